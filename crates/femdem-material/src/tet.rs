//! The force kernel of one 4-node (linear) tetrahedron.
//!
//! A linear tet maps its reference nodes `Xₐ` to current nodes `xₐ` by an
//! affine map, so the deformation gradient is constant over the element:
//! `F = Ds Dm⁻¹` with the edge matrices `Dm = [X₁−X₀, X₂−X₀, X₃−X₀]` and
//! `Ds = [x₁−x₀, x₂−x₀, x₃−x₀]` (columns). Likewise `Ḟ = Dv Dm⁻¹` with
//! `Dv = [v₁−v₀, v₂−v₀, v₃−v₀]`, and the current velocity gradient is
//! `L = Ḟ F⁻¹ = Dv Ds⁻¹`.
//!
//! # Sign convention of forces
//!
//! Every force here is the force the element exerts **on** its nodes; a
//! solver adds it to the nodal force vector (it is `−f_int` in the paper's
//! Eq. 19). With the shape-function gradients `∇Nₐ` of the current tet,
//! `fₐ = −∫ σ ∇Nₐ dv = −v σ ∇Nₐ`, equivalently `fₐ = σ nₐ Aₐ / 3` with
//! `nₐ Aₐ` the outward area vector of the face opposite node `a`. A
//! stretched element (tension) pulls its nodes together; a compressed one
//! pushes them apart. The four forces sum to zero, and for a symmetric
//! stress their torque `Σ xₐ × fₐ` vanishes.
//!
//! All functions are `#[inline]`, allocation-free and work on nalgebra stack
//! types; [`tet_forces`] is the per-element, per-step call of a solver.

use crate::Material;
use crate::law::{J_FLOOR, Law, cofactor, response};
use femdem_core::{Mat3, Real, Vec3};

/// Edge matrix `[p₁ − p₀, p₂ − p₀, p₃ − p₀]` (columns).
#[inline]
fn edge_matrix(p: &[Vec3; 4]) -> Mat3 {
    Mat3::from_columns(&[p[1] - p[0], p[2] - p[0], p[3] - p[0]])
}

/// Splits `H = [f₁ f₂ f₃]` (columns) into four nodal forces, `f₀` making
/// the sum zero.
#[inline]
fn forces_from_columns(h: &Mat3) -> [Vec3; 4] {
    let (f1, f2, f3): (Vec3, Vec3, Vec3) = (h.column(0).into(), h.column(1).into(), h.column(2).into());
    [-(f1 + f2 + f3), f1, f2, f3]
}

/// What a tet needs to remember of its reference (stress-free) shape.
///
/// Fields are public so that a solver can keep them in its own arrays; build
/// them with [`TetReference::new`], which guarantees `volume > 0` and
/// `inv_dm = Dm⁻¹`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TetReference {
    /// Inverse of the reference edge matrix `Dm = [X₁−X₀, X₂−X₀, X₃−X₀]`.
    pub inv_dm: Mat3,
    /// Reference volume `V₀ = det(Dm) / 6 > 0` (m³).
    pub volume: Real,
}

impl TetReference {
    /// The reference data of the tet with reference nodes `x0`, or `None`
    /// when its signed volume is not positive (inverted or flat) or not
    /// finite. Orientation as in [`femdem_core::tet`].
    #[inline]
    pub fn new(x0: &[Vec3; 4]) -> Option<Self> {
        let dm = edge_matrix(x0);
        let cof = cofactor(&dm);
        let det = dm.column(0).dot(&cof.column(0));
        if !(det > 0.0 && det.is_finite()) {
            return None;
        }
        let inv_dm = cof.transpose() / det;
        inv_dm.iter().all(|x| x.is_finite()).then_some(TetReference { inv_dm, volume: det / 6.0 })
    }
}

/// Deformation gradient `F = Ds Dm⁻¹` of the tet whose current nodes are
/// `x`.
#[inline]
pub fn deformation_gradient(reference: &TetReference, x: &[Vec3; 4]) -> Mat3 {
    edge_matrix(x) * reference.inv_dm
}

/// Velocity gradient with respect to the current configuration,
/// `L = ∂v/∂x = Dv Ds⁻¹`, for current nodes `x` and nodal velocities `v`.
///
/// The current tet must have non-zero volume; for a flat current tet the
/// result is non-finite. [`tet_forces`] does not call this: it uses the
/// guarded `L̂ = Ḟ cof(F)ᵀ / max(J, J_FLOOR)`, equal to `L` whenever
/// `J ≥ J_FLOOR` (see [`crate::law`]).
#[inline]
pub fn velocity_gradient(x: &[Vec3; 4], v: &[Vec3; 4]) -> Mat3 {
    let ds = edge_matrix(x);
    let cof = cofactor(&ds);
    let det = ds.column(0).dot(&cof.column(0));
    edge_matrix(v) * cof.transpose() / det
}

/// Nodal forces of a constant Cauchy `stress` over the current tet `x`:
/// `fₐ = −v σ ∇Nₐ` (the forces **on** the nodes, see the
/// [module documentation](self)); they sum to zero.
///
/// Computed as `[f₁ f₂ f₃] = −σ cof(Ds) / 6` (`v ∇Nₐ` is column `a` of
/// `cof(Ds)/6`, a polynomial in `x`), so no inverse is taken and the result
/// is finite for any finite input. For an element of positive current
/// volume it equals the forces of [`tet_forces`] for the same state; for an
/// inverted one (`J ≤ 0`) it pulls the wrong way, which is why
/// [`tet_forces`] integrates over the reference volume instead.
#[inline]
pub fn nodal_forces(stress: &Mat3, x: &[Vec3; 4]) -> [Vec3; 4] {
    let h = stress * cofactor(&edge_matrix(x)) * (-1.0 / 6.0);
    forces_from_columns(&h)
}

/// Everything one tet evaluation yields.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TetResult {
    /// Forces on the four nodes (N), to be added to the nodal force vector;
    /// they sum to zero.
    pub forces: [Vec3; 4],
    /// Cauchy stress (Pa), Eq. 1–2 (for output and failure checks).
    pub stress: Mat3,
    /// Stored elastic energy `W · V₀` (J).
    pub energy: Real,
}

/// Forces, stress and stored energy of one tet under `law`, for current
/// nodes `x` and nodal velocities `v`.
///
/// The forces are `[f₁ f₂ f₃] = −V₀ P Dm⁻ᵀ`, `f₀ = −(f₁ + f₂ + f₃)`, with
/// `P` the [`first_piola_kirchhoff`](crate::first_piola_kirchhoff) stress.
/// For the neo-Hookean law and `J ≥ J_FLOOR` this is exactly
/// `fₐ = −v T ∇Nₐ` of [`nodal_forces`] with `T` of Eq. 1 (`J T F⁻ᵀ = P`,
/// `v = J V₀`); below the floor it stays finite and restoring (see
/// [`crate::law`]). For [`Law::LinearElastic`] it is the classical linear
/// FE force `−V₀ σ Dm⁻ᵀ`. In both cases the elastic forces are minus the
/// gradient of `energy` with respect to `x`.
///
/// `stress` is [`cauchy_stress`](crate::cauchy_stress) at `F` and the
/// (guarded) current velocity gradient; `energy = W(F) V₀`.
#[inline]
pub fn tet_forces(law: Law, material: &Material, reference: &TetReference, x: &[Vec3; 4], v: &[Vec3; 4]) -> TetResult {
    let f = deformation_gradient(reference, x);
    let cof = cofactor(&f);
    let j = f.column(0).dot(&cof.column(0));
    let f_dot = edge_matrix(v) * reference.inv_dm;
    // L = Ḟ F⁻¹ = Ḟ cof(F)ᵀ / J, guarded at the floor.
    let l = f_dot * cof.transpose() / j.max(J_FLOOR);
    let r = response(law, material, &f, &l, &cof, j);
    let h = r.p * reference.inv_dm.transpose() * (-reference.volume);
    TetResult { forces: forces_from_columns(&h), stress: r.cauchy, energy: r.energy * reference.volume }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{ElasticParams, cauchy_stress};

    fn corner() -> [Vec3; 4] {
        [Vec3::zeros(), Vec3::x(), Vec3::y(), Vec3::z()]
    }

    fn material(viscosity: Real) -> Material {
        ElasticParams { young: 1e9, poisson: 0.25, density: 2500.0, viscosity }.validate().unwrap()
    }

    /// The unit corner tet has Dm = I, V₀ = 1/6; swapping two nodes inverts
    /// it and a flat tet has zero volume: both are rejected.
    #[test]
    fn reference_rejects_inverted_and_flat_tets() {
        let r = TetReference::new(&corner()).unwrap();
        assert_eq!(r.inv_dm, Mat3::identity());
        assert!((r.volume - 1.0 / 6.0).abs() < 1e-16);
        let mut inverted = corner();
        inverted.swap(1, 2);
        assert_eq!(TetReference::new(&inverted), None);
        let flat = [Vec3::zeros(), Vec3::x(), Vec3::y(), Vec3::new(1.0, 1.0, 0.0)];
        assert_eq!(TetReference::new(&flat), None);
        let nan = [Vec3::zeros(), Vec3::x(), Vec3::y(), Vec3::new(0.0, 0.0, Real::NAN)];
        assert_eq!(TetReference::new(&nan), None);
    }

    /// A linear tet reproduces affine fields exactly: x = A X + c gives
    /// F = A, and v = L x + w gives velocity_gradient = L (round-off only,
    /// amplified by the condition number of Dm, ≈ 10 here).
    #[test]
    fn affine_fields_give_their_own_gradients() {
        let x0 =
            [Vec3::new(0.1, 0.0, 0.2), Vec3::new(1.3, 0.1, 0.0), Vec3::new(0.2, 0.9, 0.1), Vec3::new(0.4, 0.3, 1.1)];
        let r = TetReference::new(&x0).unwrap();
        let a = Mat3::new(1.1, 0.2, -0.1, 0.05, 0.95, 0.3, -0.2, 0.1, 1.05);
        let c = Vec3::new(3.0, -1.0, 2.0);
        let x = x0.map(|p| a * p + c);
        assert!((deformation_gradient(&r, &x) - a).norm() < 1e-14);
        let l = Mat3::new(0.3, -1.0, 2.0, 0.5, 0.1, -0.7, 1.5, 0.2, -0.4);
        let w = Vec3::new(0.5, 0.0, -2.0);
        let v = x.map(|p| l * p + w);
        assert!((velocity_gradient(&x, &v) - l).norm() < 1e-13);
    }

    /// Uniaxial tension σ = s e_x ⊗ e_x on the unit corner tet: only the
    /// face x = 0 (area ½, outward normal −e_x, opposite node 1) carries
    /// traction, so f₁ = σ n A / 3 = −(s/6) e_x pulls node 1 back towards
    /// that face, f₀ = +(s/6) e_x, f₂ = f₃ = 0.
    #[test]
    fn tension_pulls_the_nodes_together() {
        let s = 6.0e6;
        let stress = Mat3::from_diagonal(&Vec3::new(s, 0.0, 0.0));
        let f = nodal_forces(&stress, &corner());
        let tol = 1e-15 * s;
        assert!((f[1] + Vec3::x() * (s / 6.0)).norm() < tol);
        assert!((f[0] - Vec3::x() * (s / 6.0)).norm() < tol);
        assert!(f[2].norm() < tol && f[3].norm() < tol);
    }

    /// For a positive element, the reference-volume integration of
    /// tet_forces equals −v T ∇Nₐ of nodal_forces with the same Cauchy
    /// stress (P = J T F⁻ᵀ, v = J V₀), with velocities too.
    #[test]
    fn kernel_forces_match_the_current_configuration_route() {
        let m = material(2e5);
        let x0 = corner();
        let r = TetReference::new(&x0).unwrap();
        let a = Mat3::new(1.2, 0.1, -0.2, 0.15, 0.8, 0.3, -0.1, 0.2, 1.1);
        let x = x0.map(|p| a * p);
        let v =
            [Vec3::new(1.0, 2.0, 0.0), Vec3::new(-1.0, 0.5, 3.0), Vec3::new(0.0, 0.0, -2.0), Vec3::new(2.0, -1.0, 1.0)];
        let out = tet_forces(Law::NeoHookean, &m, &r, &x, &v);
        let expected = cauchy_stress(Law::NeoHookean, &m, &a, &velocity_gradient(&x, &v));
        assert!((out.stress - expected).norm() < 1e-12 * expected.norm());
        let g = nodal_forces(&out.stress, &x);
        let scale = out.forces.iter().map(|f| f.norm()).fold(0.0, Real::max);
        for (a, b) in out.forces.iter().zip(&g) {
            assert!((a - b).norm() < 1e-12 * scale);
        }
    }

    /// The reference state with zero velocity gives zero forces, stress
    /// and energy (exactly: F = I is exact for the corner tet).
    #[test]
    fn reference_state_gives_no_forces() {
        let m = material(1e5);
        let x = corner();
        let r = TetReference::new(&x).unwrap();
        for law in [Law::NeoHookean, Law::LinearElastic] {
            let out = tet_forces(law, &m, &r, &x, &[Vec3::zeros(); 4]);
            assert_eq!(out.forces, [Vec3::zeros(); 4]);
            assert_eq!(out.stress, Mat3::zeros());
            assert_eq!(out.energy, 0.0);
        }
    }

    /// An element flattened (J = 0) or turned inside out (J < 0) gets
    /// finite forces whose power against "re-inflating" it (moving node 3
    /// back along +e_z) is positive: the element pushes itself back out.
    #[test]
    fn inverted_element_pushes_back() {
        let m = material(1e5);
        let x0 = corner();
        let r = TetReference::new(&x0).unwrap();
        for z in [0.0, -0.5, -2.0] {
            let mut x = x0;
            x[3].z = z;
            let out = tet_forces(Law::NeoHookean, &m, &r, &x, &[Vec3::zeros(); 4]);
            assert!(out.forces.iter().all(|f| f.iter().all(|c| c.is_finite())));
            assert!(out.energy.is_finite() && out.stress.iter().all(|c| c.is_finite()));
            assert!(out.forces[3].z > 0.0, "z = {z}: {:?}", out.forces[3]);
        }
    }
}
