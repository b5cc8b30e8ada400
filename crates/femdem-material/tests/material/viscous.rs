//! The viscous part of Eq. 1, `η D` with `D = ½(L + Lᵀ)` (Eq. 2).
//!
//! A linear tet reproduces an affine velocity field `v = L x + w` exactly,
//! so the kernel must recover `L` and add exactly `η sym(L)` to the elastic
//! stress, whatever the deformation. A rigid motion (`L` skew) has `D = 0`
//! and is not damped. The viscous forces dissipate: their power is
//! `−Σ f_vₐ · vₐ = ∫ T_v : L dv = v η D : D ≥ 0` (v the current volume),
//! and the guarded rate used for crushed/inverted elements keeps it
//! non-negative there too (`P_v : Ḟ = η Ĵ D̂ : D̂`).
//!
//! Tolerances: `L` is recovered through `Dm⁻¹` and `cof F / J`, with
//! relative round-off ~1e-16 × cond² (≤ 1e-12 for the shapes used); the
//! elastic part is subtracted back, adding ~1e-16 of its size.

use crate::common::{good_tet, points, reference, rock, vec3};
use femdem_core::{Mat3, Real, Vec3};
use femdem_material::{Law, cauchy_stress, deformation_gradient, tet_forces};
use proptest::prelude::*;

const ETA: Real = 2.0e5;

fn viscous_forces(law: Law, x0: &[Vec3; 4], x: &[Vec3; 4], v: &[Vec3; 4]) -> [Vec3; 4] {
    let m = rock(ETA);
    let r = reference(x0);
    let with = tet_forces(law, &m, &r, x, v).forces;
    let without = tet_forces(law, &m, &r, x, &[Vec3::zeros(); 4]).forces;
    std::array::from_fn(|a| with[a] - without[a])
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    #[test]
    fn linear_velocity_field_gives_eta_d_exactly(
        x0 in good_tet(),
        d in prop::array::uniform4(vec3(0.3)),
        l in prop::array::uniform9(-10.0f64..10.0),
        w in vec3(10.0),
    ) {
        let m = rock(ETA);
        let r = reference(&x0);
        let x: [Vec3; 4] = std::array::from_fn(|a| x0[a] + d[a]);
        let f = deformation_gradient(&r, &x);
        prop_assume!(f.determinant() >= 0.2);
        let l = Mat3::from_row_slice(&l);
        let v = x.map(|p| l * p + w);
        for law in [Law::NeoHookean, Law::LinearElastic] {
            let total = tet_forces(law, &m, &r, &x, &v).stress;
            let elastic = cauchy_stress(law, &m, &f, &Mat3::zeros());
            let expected = (l + l.transpose()) * (0.5 * ETA);
            let tol = 1e-11 * ETA * l.norm() + 1e-14 * elastic.norm();
            prop_assert!(((total - elastic) - expected).norm() < tol,
                "{law:?}: η D = {}, got {}", expected, total - elastic);
        }
    }

    /// A rigid motion v = ω × (x − c) + u of a deformed tet: no viscous
    /// stress, no viscous force.
    #[test]
    fn rigid_motion_is_not_damped(
        x0 in good_tet(),
        d in prop::array::uniform4(vec3(0.3)),
        omega in vec3(10.0),
        c in vec3(1.0),
        u in vec3(10.0),
    ) {
        let m = rock(ETA);
        let r = reference(&x0);
        let x: [Vec3; 4] = std::array::from_fn(|a| x0[a] + d[a]);
        let f = deformation_gradient(&r, &x);
        prop_assume!(f.determinant() >= 0.2);
        let v = x.map(|p| omega.cross(&(p - c)) + u);
        let out = tet_forces(Law::NeoHookean, &m, &r, &x, &v);
        let elastic = cauchy_stress(Law::NeoHookean, &m, &f, &Mat3::zeros());
        prop_assert!((out.stress - elastic).norm() < 1e-11 * ETA * omega.norm() + 1e-14 * elastic.norm());
        let scale = ETA * omega.norm() * r.volume * r.inv_dm.norm();
        for fv in viscous_forces(Law::NeoHookean, &x0, &x, &v) {
            prop_assert!(fv.norm() < 1e-10 * scale + 1e-14 * elastic.norm() * r.volume * r.inv_dm.norm());
        }
    }

    /// Power of the viscous forces: exactly −v η D:D for J ≥ 0.2, and never
    /// positive (never feeds energy in) for any state, inverted included.
    #[test]
    fn viscous_forces_dissipate(
        x0 in good_tet(),
        x in points(1.5),
        v in prop::array::uniform4(vec3(10.0)),
    ) {
        let r = reference(&x0);
        let fv = viscous_forces(Law::NeoHookean, &x0, &x, &v);
        let power: Real = fv.iter().zip(&v).map(|(f, v)| f.dot(v)).sum();
        let scale: Real = fv.iter().zip(&v).map(|(f, v)| f.norm() * v.norm()).sum();
        // The viscous forces are computed as a difference of two force
        // sets; their round-off is ~1e-16 of the elastic forces.
        let m = rock(ETA);
        let elastic = tet_forces(Law::NeoHookean, &m, &r, &x, &[Vec3::zeros(); 4]).forces;
        let noise: Real = elastic.iter().zip(&v).map(|(f, v)| f.norm() * v.norm()).sum::<Real>() * 1e-14;
        prop_assert!(power <= 1e-12 * scale + noise, "viscous power {power} > 0");
        let j = deformation_gradient(&r, &x).determinant();
        if j >= 0.2 {
            let l = femdem_material::velocity_gradient(&x, &v);
            let dd = ((l + l.transpose()) * 0.5).norm_squared();
            let expected = -(j * r.volume) * ETA * dd;
            prop_assert!((power - expected).abs() <= 1e-10 * expected.abs() + noise,
                "power {power}, −v η D:D = {expected}");
        }
    }
}
