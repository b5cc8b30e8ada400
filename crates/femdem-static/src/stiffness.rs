//! Element stiffnesses at the reference state: the small-strain linear
//! elastic tet and the initial tangent of an intact joint.
//!
//! # Tet
//!
//! A linear tet of reference volume `V` has constant shape-function
//! gradients `gₐ = ∇Nₐ` (rows of `Dm⁻¹` for `a = 1, 2, 3`,
//! `g₀ = −(g₁ + g₂ + g₃)`). Small-strain linear elasticity,
//! `σ = λ tr ε I + 2 μ ε` with `ε = sym(Σ_b u_b ⊗ g_b)`, gives the force on
//! node `a`, `fₐ = −V σ gₐ = −Σ_b K_ab u_b` with the 3 × 3 blocks
//!
//! ```text
//! K_ab = V [ λ gₐ g_bᵀ + μ g_b gₐᵀ + μ (gₐ · g_b) I ].
//! ```
//!
//! It is the tangent of the neo-Hookean law of Eq. 1 at `F = I`
//! (`P = μ F + (λ ln J − μ) cof F / J` linearises to `λ tr ε I + 2 μ ε`),
//! and exactly the force of femdem's `Law::LinearElastic`; the viscous term
//! of Eq. 1 does no work at rest.
//!
//! # Joint (Eq. 3, 11)
//!
//! At a Hammer point `i` of barycentric weights `ξᵢ = (ξᵢ₁, ξᵢ₂, ξᵢ₃)`
//! the gap is `gᵢ = Σₖ ξᵢₖ (x_{b(k)} − x_k)`, `b(k) = 6 − k` pairing
//! `N1–N6`, `N2–N5`, `N3–N4` (Eq. 3: `δn = gᵢ · z′`, `δs = gᵢ − δn z′`).
//! Eq. 11 at zero opening and slip, with `δnp = 2 f_t h / p0` (Eq. 6) and
//! `δsp = 2 f_s h / p0` (Eq. 7):
//!
//! - normal, compression `σ = 2 (δn/δnp) f_t`, and the hardening branch
//!   `σ = (2r − r²) f_t`, `r = δn/δnp`: both have slope
//!   `dσ/dδn = 2 f_t / δnp = p0 / h` at `δn = 0` (damage is zero, so every
//!   coupling option of `femdem_fracture::Coupling` gives the same);
//! - shear, `τ = (2s − s²) f_s`, `s = δs/δsp`, along the slip:
//!   `dτ/dδs = 2 f_s / δsp = p0 / h`, whatever `f_s` (Eq. 5) — and at zero
//!   slip `τ` does not depend on `δn` to first order.
//!
//! The initial traction is therefore `t = (p0/h) gᵢ`, isotropic, and the
//! mid-plane frame's rotation (second order: the faces coincide at rest)
//! does not enter. With weight `A/3` per point (`A` the face area), the
//! joint's energy is `½ (p0/h) (A/3) Σᵢ |gᵢ|²`, and its stiffness couples
//! nodes `p, q` of `N1 … N6` by `(p0/h)(A/3) Σᵢ sᵢₚ sᵢ_q I`, where
//! `sᵢ = (−ξᵢ₁, −ξᵢ₂, −ξᵢ₃, ξᵢ₃, ξᵢ₂, ξᵢ₁)` are the signed weights of
//! `gᵢ` on `N1 … N6`. The explicit joints (`femdem_fracture::joint_update`)
//! exert exactly these forces to first order in the displacement.

use femdem_core::{Mat3, Real, Vec3};
use femdem_fracture::{GAUSS, Joint};
use femdem_material::{Material, TetReference};

/// The 4 × 4 blocks `K_ab` of the small-strain linear elastic stiffness of
/// one tet (module doc): the force on node `a` is `−Σ_b K_ab u_b`.
pub fn tet_stiffness(reference: &TetReference, material: &Material) -> [[Mat3; 4]; 4] {
    let (lambda, mu, v) = (material.lambda(), material.mu(), reference.volume);
    let row = |k: usize| -> Vec3 { reference.inv_dm.row(k).transpose() };
    let (g1, g2, g3) = (row(0), row(1), row(2));
    let g = [-(g1 + g2 + g3), g1, g2, g3];
    let mut k = [[Mat3::zeros(); 4]; 4];
    for a in 0..4 {
        for b in 0..4 {
            k[a][b] = (g[a] * g[b].transpose() * lambda
                + g[b] * g[a].transpose() * mu
                + Mat3::from_diagonal_element(mu * g[a].dot(&g[b])))
                * v;
        }
    }
    k
}

/// The initial tangent `p0 / h` of Eq. 11, normal and shear alike, Pa/m
/// (module doc).
#[inline]
pub fn joint_initial_stiffness(joint: &Joint) -> Real {
    joint.params.penalty / joint.h
}

/// The scalar coupling `S_pq` of the nodes `N1 … N6` of an intact joint of
/// reference face area `area` (module doc): the force on node `p` is
/// `−Σ_q S_pq u_q` in each component.
pub fn joint_stiffness(joint: &Joint, area: Real) -> [[Real; 6]; 6] {
    let k = joint_initial_stiffness(joint) * area / 3.0;
    let mut s = [[0.0; 6]; 6];
    for w in GAUSS {
        let signed = [-w[0], -w[1], -w[2], w[2], w[1], w[0]];
        for p in 0..6 {
            for q in 0..6 {
                s[p][q] += k * signed[p] * signed[q];
            }
        }
    }
    s
}

/// The area of the face `N1 N2 N3` at the reference positions `x0`.
#[inline]
pub fn face_area(x0: &[Vec3], nodes: &[u32; 6]) -> Real {
    let [a, b, c] = [nodes[0], nodes[1], nodes[2]].map(|n| x0[n as usize]);
    0.5 * (b - a).cross(&(c - a)).norm()
}

#[cfg(test)]
mod tests {
    use super::*;
    use femdem_fracture::{Coupling, GfCalibration, JointHistory, JointParams, joint_update, point_stress};
    use femdem_material::{ElasticParams, Law, tet_forces};

    fn material() -> Material {
        ElasticParams { young: 30e9, poisson: 0.27, density: 2700.0, viscosity: 0.0 }.validate().unwrap()
    }

    fn joint(coupling: Coupling) -> Joint {
        let p = JointParams {
            penalty: 3e11,
            tensile_strength: 1e6,
            cohesion: 0.5e6,
            friction_angle: 33.4f64.to_radians(),
            gf_tension: 60.0,
            gf_shear: 60.0,
            calibration: GfCalibration::Paper,
            coupling,
        };
        Joint::new(p, 0.02)
    }

    /// `Law::LinearElastic` is linear in the displacement: its forces are
    /// `−K u` to round-off, for any displacement.
    #[test]
    fn tet_stiffness_gives_the_linear_law_forces() {
        let x0 =
            [Vec3::new(0.1, 0.0, 0.2), Vec3::new(1.3, 0.1, 0.0), Vec3::new(0.2, 0.9, 0.1), Vec3::new(0.4, 0.3, 1.1)];
        let r = TetReference::new(&x0).unwrap();
        let m = material();
        let k = tet_stiffness(&r, &m);
        let u = [
            Vec3::new(1e-3, -2e-3, 0.5e-3),
            Vec3::new(0.0, 1e-3, 2e-3),
            Vec3::new(-1e-3, 0.0, 0.0),
            Vec3::new(3e-3, 1e-3, -1e-3),
        ];
        let x = [0, 1, 2, 3].map(|a| x0[a] + u[a]);
        let f = tet_forces(Law::LinearElastic, &m, &r, &x, &[Vec3::zeros(); 4]).forces;
        for a in 0..4 {
            let ku: Vec3 = (0..4).map(|b| k[a][b] * u[b]).sum();
            assert!((f[a] + ku).norm() < 1e-12 * f[a].norm().max(1.0), "node {a}: {} vs {}", f[a], -ku);
            for b in 0..4 {
                assert!((k[a][b] - k[b][a].transpose()).norm() < 1e-9 * k[a][a].norm());
            }
        }
    }

    /// The Eq. 11 branches of femdem-fracture have the slope `p0/h` at zero
    /// opening and slip (one-sided differences into tension, compression
    /// and slip; the hardening branch's curvature makes the error
    /// `O(δ/δp)`), for every coupling option.
    #[test]
    fn joint_slope_is_that_of_eq_11() {
        for coupling in [Coupling::Capped, Coupling::Printed, Coupling::Multiplicative] {
            let j = joint(coupling);
            let k = joint_initial_stiffness(&j);
            let d = 1e-7 * j.delta_np;
            for (dn, ds) in [(d, 0.0), (-d, 0.0), (0.0, d)] {
                let ps = point_stress(&j, dn, ds, 0.0);
                let slope = if ds > 0.0 { ps.tau / ds } else { ps.sigma / dn };
                assert!((slope / k - 1.0).abs() < 1e-6, "{coupling:?} ({dn}, {ds}): {slope} vs {k}");
            }
        }
    }

    /// The joint's forces at a small displacement of its six nodes are
    /// `−S u` to first order (relative error `O(|u|/δp)`).
    #[test]
    fn joint_stiffness_gives_the_joint_forces_at_small_displacement() {
        let j = joint(Coupling::default());
        let base = [Vec3::zeros(), Vec3::new(0.02, 0.0, 0.001), Vec3::new(0.003, 0.018, -0.002)];
        let x0 = [base[0], base[1], base[2], base[2], base[1], base[0]];
        let nodes = [0, 1, 2, 3, 4, 5];
        let s = joint_stiffness(&j, face_area(&x0, &nodes));
        let scale = 1e-6 * j.delta_np;
        let u: [Vec3; 6] = std::array::from_fn(|p| {
            let t = p as Real;
            Vec3::new((1.3 * t).sin(), (0.7 * t + 1.0).cos(), (2.1 * t).sin()) * scale
        });
        let x = std::array::from_fn(|p| x0[p] + u[p]);
        let f = joint_update(&j, &mut JointHistory::default(), &x, false).forces;
        let norm: Real = f.iter().map(|v| v.norm()).fold(0.0, Real::max);
        for p in 0..6 {
            let su: Vec3 = (0..6).map(|q| u[q] * s[p][q]).sum();
            assert!((f[p] + su).norm() < 1e-4 * norm, "node {p}: {} vs {}", f[p], -su);
        }
    }
}
