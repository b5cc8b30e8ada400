//! `[[output.probes]]`: named points whose displacement, velocity and
//! stress a run records in its history (a P-wave arrival, a crack-mouth
//! opening, the stress at a gauge).
//!
//! A probe is placed once, in the reference configuration: in the tet that
//! contains its point (the lowest-numbered one when the point lies on a
//! face, edge or node several tets share), with the point's barycentric
//! coordinates `λ_k` in it. It then moves with that tet: its displacement
//! and velocity are `u = Σ λ_k u_k` and `v = Σ λ_k v_k` over the tet's four
//! nodes, and its stress is the tet's Cauchy stress (constant in a linear
//! tet). In a jointed region every tet has its own nodes, so the probe
//! follows one side of a crack that passes through its point.

use femdem_core::{Mat3, Real, Vec3};
use femdem_solver::{Loads, Model};

use super::{CaseError, LoadedCase};

/// Barycentric coordinates may be this far below zero (relative) for a
/// point on a tet's boundary to count as inside it: rounding of the
/// coordinates of a point typed on a face or node.
const ON_BOUNDARY: Real = 1e-9;

/// A probe, placed.
#[derive(Clone, Debug, PartialEq)]
pub struct Probe {
    /// Its name, the prefix of its history columns.
    pub name: String,
    /// The tet it lies in.
    pub tet: u32,
    /// Its barycentric coordinates in that tet (reference configuration).
    pub weights: [Real; 4],
}

impl Probe {
    /// The history columns of a probe named `name`: displacement (m),
    /// velocity (m/s) and stress (Pa, tension positive, Voigt order).
    pub fn columns(name: &str) -> [String; 12] {
        ["ux", "uy", "uz", "vx", "vy", "vz", "sxx", "syy", "szz", "syz", "sxz", "sxy"].map(|c| format!("{name}_{c}"))
    }

    /// Its row values, in the order of [`Probe::columns`], from node
    /// displacements `u(n)`, velocities `v(n)` and the tet stresses
    /// `stress`.
    pub fn values(
        &self,
        tets: &[[u32; 4]],
        u: impl Fn(usize) -> Vec3,
        v: impl Fn(usize) -> Vec3,
        stress: &[Mat3],
    ) -> [Real; 12] {
        let nodes = tets[self.tet as usize];
        let at = |f: &dyn Fn(usize) -> Vec3| -> Vec3 {
            nodes.iter().zip(self.weights).map(|(&n, w)| f(n as usize) * w).sum()
        };
        let (du, dv) = (at(&u), at(&v));
        let s = stress.get(self.tet as usize).copied().unwrap_or_else(Mat3::zeros);
        [du.x, du.y, du.z, dv.x, dv.y, dv.z, s[(0, 0)], s[(1, 1)], s[(2, 2)], s[(1, 2)], s[(0, 2)], s[(0, 1)]]
    }
}

/// The barycentric coordinates of `p` in the tet with corners `x`, or
/// `None` for a degenerate tet.
fn barycentric(x: &[Vec3; 4], p: &Vec3) -> Option<[Real; 4]> {
    let m = Mat3::from_columns(&[x[1] - x[0], x[2] - x[0], x[3] - x[0]]);
    let l = m.try_inverse()? * (p - x[0]);
    Some([1.0 - l.x - l.y - l.z, l.x, l.y, l.z])
}

/// The lowest-numbered tet of `model` containing `p` in the reference
/// configuration, with `p`'s coordinates in it.
pub fn locate(model: &Model, p: &Vec3) -> Option<(u32, [Real; 4])> {
    model.tets.iter().enumerate().find_map(|(t, nodes)| {
        let x = nodes.map(|n| model.x0[n as usize]);
        let lam = barycentric(&x, p)?;
        lam.iter().all(|&l| l >= -ON_BOUNDARY).then_some((t as u32, lam))
    })
}

/// Resolves `[[output.probes]]` against the model and the loads (whose
/// names also prefix history columns).
///
/// # Errors
/// A located [`CaseError`] naming `output.probes[i]` when a name is empty,
/// has other characters than letters, digits, `_`, `-` and `.`, is used
/// twice or by a load, or a point is not finite or lies in no tet.
pub fn probes(case: &LoadedCase, model: &Model, loads: &Loads) -> Result<Vec<Probe>, CaseError> {
    let Some(specs) = case.case.output.as_ref().and_then(|o| o.get_ref().probes.as_ref()) else {
        return Ok(Vec::new());
    };
    let mut placed: Vec<Probe> = Vec::with_capacity(specs.len());
    for (i, spec) in specs.iter().enumerate() {
        let s = spec.get_ref();
        let at = |msg: String| case.error_at(spec.span(), format!("output.probes[{i}]: {msg}"));
        let name = s.name.as_str();
        if name.is_empty() || !name.chars().all(|c| c.is_ascii_alphanumeric() || "_-.".contains(c)) {
            return Err(at(format!(
                "name `{name}` must be letters, digits, `_`, `-` or `.` (it prefixes history columns)"
            )));
        }
        if placed.iter().any(|p| p.name == name) {
            return Err(at(format!("name `{name}` is used by another probe")));
        }
        if loads.drives.iter().map(|d| &d.name).chain(loads.surfaces.iter().map(|s| &s.name)).any(|n| n == name) {
            return Err(at(format!("name `{name}` is already a load's; history columns would repeat")));
        }
        let p = Vec3::from(s.at);
        if !p.iter().all(|c| c.is_finite()) {
            return Err(at(format!("`at` must be finite, got {:?} m", s.at)));
        }
        let Some((tet, weights)) = locate(model, &p) else {
            return Err(at(format!("`at` {:?} m lies in no tet of the mesh", s.at)));
        };
        placed.push(Probe { name: name.to_string(), tet, weights });
    }
    Ok(placed)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn unit() -> [Vec3; 4] {
        [Vec3::zeros(), Vec3::new(1.0, 0.0, 0.0), Vec3::new(0.0, 1.0, 0.0), Vec3::new(0.0, 0.0, 1.0)]
    }

    #[test]
    fn barycentric_coordinates_rebuild_the_point() {
        let x = unit().map(|p| p * 2.0 + Vec3::new(1.0, -1.0, 0.5));
        let p = Vec3::new(1.3, -0.6, 0.9);
        let l = barycentric(&x, &p).unwrap();
        let back: Vec3 = x.iter().zip(l).map(|(xk, lk)| xk * lk).sum();
        assert!((back - p).norm() < 1e-14, "{back} vs {p}");
        assert!((l.iter().sum::<Real>() - 1.0).abs() < 1e-15);
        let flat = [Vec3::zeros(), Vec3::new(1.0, 0.0, 0.0), Vec3::new(2.0, 0.0, 0.0), Vec3::new(0.0, 1.0, 0.0)];
        assert!(barycentric(&flat, &p).is_none());
    }

    #[test]
    fn a_probe_interpolates_linear_fields_exactly() {
        // u = A x + b is linear, so its interpolation at the probe is exact.
        let tets = [[0, 1, 2, 3]];
        let x = unit();
        let probe = Probe { name: "g".into(), tet: 0, weights: [0.1, 0.2, 0.3, 0.4] };
        let a = Mat3::new(1.0, 2.0, 3.0, -1.0, 0.5, 0.0, 0.25, 0.0, -2.0);
        let b = Vec3::new(0.1, 0.2, 0.3);
        let p: Vec3 = x.iter().zip(probe.weights).map(|(xk, w)| xk * w).sum();
        let s = Mat3::new(1.0, 6.0, 5.0, 6.0, 2.0, 4.0, 5.0, 4.0, 3.0);
        let row = probe.values(&tets, |n| a * x[n] + b, |n| a * x[n] * 2.0, &[s]);
        let (u, v) = (a * p + b, a * p * 2.0);
        for k in 0..3 {
            assert!((row[k] - u[k]).abs() < 1e-14 && (row[3 + k] - v[k]).abs() < 1e-14, "{row:?}");
        }
        assert_eq!(&row[6..], &[1.0, 2.0, 3.0, 4.0, 5.0, 6.0], "Voigt order xx yy zz yz xz xy");
        assert_eq!(Probe::columns("g")[0], "g_ux");
        assert_eq!(Probe::columns("g")[11], "g_sxy");
    }
}
