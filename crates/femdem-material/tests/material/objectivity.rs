//! Objectivity (material frame indifference) of the neo-Hookean law, Eq. 1.
//!
//! Superposing a rigid motion `x′ = R x + c` on the current state gives
//! `F′ = R F`, `B′ = R B Rᵀ`, `J′ = J`, hence `T′ = R T Rᵀ` and `W′ = W`
//! (Bonet and Wood 1997, §5.5); a rigid rotation of the reference state
//! (`F = R`) is stress-free. With a spinning frame, `v′ = R v + Ω (x′ − c)`
//! with `Ω` skew, `L′ = R L Rᵀ + Ω`, so `D′ = R D Rᵀ`: the viscous part of
//! Eq. 1–2 is objective too. The tet forces, being `−v T ∇Nₐ`, rotate as
//! `f′ₐ = R fₐ`.
//!
//! Tolerances: round-off in `F` recovered from positions is ~1e-16 times
//! the condition number of `Dm` (≤ ~100 for tets of aspect ratio ≤ 6,
//! positions of order 1), so the stress of a rigid rotation is
//! ~1e-14 E; the requirement is < 1e-12 E. Rotated states compare to
//! 1e-11 relative to the stress scale.

use crate::common::{any_rotation, good_tet, map, reference, rock, rotation, skew_tet, vec3};
use femdem_core::{Mat3, Real, Vec3};
use femdem_material::{Law, deformation_gradient, strain_energy_density, tet_forces};
use proptest::prelude::*;
use std::f64::consts::{FRAC_PI_2, PI};

fn special_rotations() -> Vec<Mat3> {
    vec![
        rotation(Vec3::x(), FRAC_PI_2),
        rotation(Vec3::y(), FRAC_PI_2),
        rotation(Vec3::z(), FRAC_PI_2),
        rotation(Vec3::z(), -FRAC_PI_2),
        rotation(Vec3::new(1.0, 1.0, 0.0), PI),
        rotation(Vec3::new(1.0, -2.0, 0.5), 2.0),
    ]
}

/// Checks that rigidly rotating the reference tet `x0` by `r` gives F = R,
/// zero stress, zero forces and zero energy.
fn check_rigid_rotation(x0: &[Vec3; 4], r: &Mat3, c: &Vec3) -> Result<(), TestCaseError> {
    let m = rock(1e5);
    let reference = reference(x0);
    let x = map(x0, r, c);
    let e = m.young();
    prop_assert!((deformation_gradient(&reference, &x) - r).norm() < 1e-12);
    let out = tet_forces(Law::NeoHookean, &m, &reference, &x, &[Vec3::zeros(); 4]);
    prop_assert!(out.stress.norm() < 1e-12 * e, "stress {}", out.stress);
    // Forces scale as E V₀ |Dm⁻¹|, energy as E V₀.
    let force_scale = e * reference.volume * reference.inv_dm.norm();
    for f in out.forces {
        prop_assert!(f.norm() < 1e-12 * force_scale);
    }
    prop_assert!(out.energy.abs() < 1e-12 * e * reference.volume);
    Ok(())
}

#[test]
fn rigid_rotation_including_quarter_turns_is_stress_free() {
    for r in special_rotations() {
        check_rigid_rotation(&skew_tet(), &r, &Vec3::new(2.0, -1.0, 0.5)).unwrap();
    }
}

/// The linear law is not objective — the reason it is only for small
/// rotations: a quarter turn about z gives ε = diag(−1, −1, 0), a stress of
/// order E.
#[test]
fn linear_law_is_not_objective() {
    let m = rock(0.0);
    let x0 = skew_tet();
    let r = rotation(Vec3::z(), FRAC_PI_2);
    let out = tet_forces(Law::LinearElastic, &m, &reference(&x0), &map(&x0, &r, &Vec3::zeros()), &[Vec3::zeros(); 4]);
    assert!(out.stress.norm() > 0.5 * m.young());
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    #[test]
    fn random_rigid_rotation_is_stress_free(x0 in good_tet(), r in any_rotation(), c in vec3(1.0)) {
        check_rigid_rotation(&x0, &r, &c)?;
    }

    /// Stretch the tet by a random F (|H| ≤ 0.3 entrywise, J ≥ 0.3), give
    /// it random nodal velocities, then superpose a rigid rotation R and a
    /// spin Ω: T′ = R T Rᵀ, W′ = W, f′ₐ = R fₐ.
    #[test]
    fn rotated_stretched_state_rotates_the_stress(
        x0 in good_tet(),
        h in prop::array::uniform9(-0.3f64..0.3),
        v in prop::array::uniform4(vec3(10.0)),
        r in any_rotation(),
        c in vec3(1.0),
        w in vec3(5.0),
    ) {
        let f = Mat3::identity() + Mat3::from_row_slice(&h);
        prop_assume!(f.determinant() > 0.3);
        let m = rock(2e5);
        let reference = reference(&x0);
        let x = map(&x0, &f, &Vec3::zeros());
        let base = tet_forces(Law::NeoHookean, &m, &reference, &x, &v);

        let spin = w.cross_matrix();
        let x_rot = map(&x, &r, &c);
        let v_rot: [Vec3; 4] = std::array::from_fn(|a| r * v[a] + spin * (x_rot[a] - c));
        let rotated = tet_forces(Law::NeoHookean, &m, &reference, &x_rot, &v_rot);

        let scale = base.stress.norm().max(1e-6 * m.young());
        let expected = r * base.stress * r.transpose();
        prop_assert!((rotated.stress - expected).norm() < 1e-11 * scale,
            "T′ = {}, R T Rᵀ = {}", rotated.stress, expected);
        let w_scale = base.energy.abs().max(1e-12 * m.young() * reference.volume);
        prop_assert!((rotated.energy - base.energy).abs() < 1e-11 * w_scale);
        let force_scale = base.forces.iter().map(|f| f.norm()).fold(0.0, Real::max);
        for (a, b) in rotated.forces.iter().zip(&base.forces) {
            prop_assert!((a - r * b).norm() < 1e-11 * force_scale);
        }
        // Energy alone, through the public density: W(RF) = W(F).
        let w0 = strain_energy_density(Law::NeoHookean, &m, &f);
        let w1 = strain_energy_density(Law::NeoHookean, &m, &(r * f));
        prop_assert!((w1 - w0).abs() < 1e-11 * w0.abs().max(1e-12 * m.young()));
    }
}
