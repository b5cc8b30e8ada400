//! The tet forces are minus the gradient of the tet's stored energy.
//!
//! For a hyperelastic law, `fₐ = −∂(W V₀)/∂xₐ` (principle of virtual work;
//! Bonet and Wood 1997, §7.2). For Eq. 1 this is what ties the Cauchy
//! stress `T = μ/J (B − I) + λ/J ln J I` to the energy
//! `W = μ/2 (tr B − 3) − μ ln J + λ/2 (ln J)²`: `∂W/∂F = J T F⁻ᵀ`. The same
//! check on the linear law ties `σ = λ tr ε I + 2με` to
//! `W = λ/2 (tr ε)² + μ ε:ε` (as fenris-solid's material tests do).
//!
//! The gradient is taken by central differences of
//! `strain_energy_density · V₀` with a step `h = 1e-6 ℓ` (ℓ the longest
//! reference edge) on each of the 12 coordinates. Error budget, with the
//! force scale `S = E V₀ |Dm⁻¹|`: truncation `h² ∂³(W V₀)/6 ~ h² E V₀
//! |Dm⁻¹|³ ≲ 1e-12 · 1e2 S`; round-off `ε_mach |W V₀| / h` where `W`
//! carries terms of size ~E (`tr B − 3`, `ln J` cancel), so
//! `~1e-16 E V₀ / (1e-6 ℓ) ≈ 1e-10 S`. Tolerance `1e-6 S`, which still
//! exposes any error in a stress term (an O(strain) = O(1e-2..1) fraction
//! of S).
//!
//! The neo-Hookean check covers ordinary states (J ≥ 0.2) and, separately,
//! crushed and inverted ones (J ≤ −0.05, below the continuation floor, where
//! W is smooth again), which proves the continued energy and the restoring
//! forces are consistent too. Velocities are zero (the viscous part stores
//! nothing). Also: the kernel's reference-volume integration and
//! `nodal_forces` of the Cauchy stress agree for positive elements.

use crate::common::{any_rotation, good_tet, max_edge, reference, rock, vec3};
use femdem_core::{Real, Vec3};
use femdem_material::{
    Law, Material, TetReference, deformation_gradient, nodal_forces, strain_energy_density, tet_forces,
    velocity_gradient,
};
use proptest::prelude::*;

fn stored_energy(law: Law, m: &Material, r: &TetReference, x: &[Vec3; 4]) -> Real {
    strain_energy_density(law, m, &deformation_gradient(r, x)) * r.volume
}

fn check_forces_are_energy_gradient(law: Law, x0: &[Vec3; 4], x: &[Vec3; 4]) -> Result<(), TestCaseError> {
    // Viscosity present but velocities zero: no viscous force.
    let m = rock(1e5);
    let r = reference(x0);
    let out = tet_forces(law, &m, &r, x, &[Vec3::zeros(); 4]);
    prop_assert!((out.energy - stored_energy(law, &m, &r, x)).abs() <= 1e-12 * out.energy.abs());
    let h = 1e-6 * max_edge(x0);
    let scale = m.young() * r.volume * r.inv_dm.norm();
    for a in 0..4 {
        for i in 0..3 {
            let (mut xp, mut xm) = (*x, *x);
            xp[a][i] += h;
            xm[a][i] -= h;
            let grad = (stored_energy(law, &m, &r, &xp) - stored_energy(law, &m, &r, &xm)) / (2.0 * h);
            prop_assert!(
                (out.forces[a][i] + grad).abs() < 1e-6 * scale,
                "{law:?}, node {a}, axis {i}: f = {}, −∂E/∂x = {}, scale {scale}",
                out.forces[a][i],
                -grad
            );
        }
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    /// Random positive tet, random nodal displacements up to 0.3 of the
    /// cube size (moderate, large strains included) and a random rigid
    /// rotation of the result.
    #[test]
    fn neo_hookean_forces_are_minus_energy_gradient(
        x0 in good_tet(),
        d in prop::array::uniform4(vec3(0.3)),
        rot in any_rotation(),
    ) {
        let r = reference(&x0);
        let x: [Vec3; 4] = std::array::from_fn(|a| rot * (x0[a] + d[a]));
        prop_assume!(deformation_gradient(&r, &x).determinant() >= 0.2);
        check_forces_are_energy_gradient(Law::NeoHookean, &x0, &x)?;
    }

    /// Crushed through and inverted: node 3 pushed past the opposite face.
    #[test]
    fn continued_neo_hookean_forces_are_minus_energy_gradient_when_inverted(
        x0 in good_tet(),
        d in prop::array::uniform4(vec3(0.2)),
        depth in 1.05f64..2.0,
    ) {
        // Reflect node 3 through the plane of face (0, 1, 2) by `depth`
        // times its height, giving J = 1 − depth ∈ (−1, −0.05) before `d`.
        let n = (x0[1] - x0[0]).cross(&(x0[2] - x0[0])).normalize();
        let height = (x0[3] - x0[0]).dot(&n);
        let mut x: [Vec3; 4] = std::array::from_fn(|a| x0[a] + d[a] * 0.1);
        x[3] -= n * (depth * height);
        let r = reference(&x0);
        prop_assume!(deformation_gradient(&r, &x).determinant() <= -0.05);
        check_forces_are_energy_gradient(Law::NeoHookean, &x0, &x)?;
    }

    /// The linear law, over the same states (no rotation needed: it is
    /// quadratic in the displacements, any state is fair).
    #[test]
    fn linear_forces_are_minus_energy_gradient(
        x0 in good_tet(),
        d in prop::array::uniform4(vec3(0.3)),
    ) {
        let x: [Vec3; 4] = std::array::from_fn(|a| x0[a] + d[a]);
        check_forces_are_energy_gradient(Law::LinearElastic, &x0, &x)?;
    }

    /// For J ≥ J_FLOOR the kernel's `−V₀ P Dm⁻ᵀ` equals `−v T ∇Nₐ` of
    /// `nodal_forces` with the returned Cauchy stress, velocities included,
    /// and the stress equals Eq. 1–2 at `velocity_gradient(x, v)`.
    #[test]
    fn reference_and_current_force_routes_agree(
        x0 in good_tet(),
        d in prop::array::uniform4(vec3(0.3)),
        v in prop::array::uniform4(vec3(10.0)),
    ) {
        let m = rock(2e5);
        let r = reference(&x0);
        let x: [Vec3; 4] = std::array::from_fn(|a| x0[a] + d[a]);
        let f = deformation_gradient(&r, &x);
        prop_assume!(f.determinant() >= 0.2);
        let out = tet_forces(Law::NeoHookean, &m, &r, &x, &v);
        let t = femdem_material::cauchy_stress(Law::NeoHookean, &m, &f, &velocity_gradient(&x, &v));
        prop_assert!((out.stress - t).norm() < 1e-11 * t.norm());
        let g = nodal_forces(&out.stress, &x);
        let scale = out.forces.iter().map(|f| f.norm()).fold(0.0, Real::max);
        for (a, b) in out.forces.iter().zip(&g) {
            prop_assert!((a - b).norm() < 1e-11 * scale);
        }
    }
}
