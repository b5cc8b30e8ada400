//! Single-element, patch-test-like checks against closed forms.
//!
//! A linear tet represents any homogeneous deformation exactly, so a
//! prescribed `F` imposed through the nodes (`x = F X + c`) must give the
//! closed-form stress of the law, whatever the tet's shape:
//!
//! - uniaxial strain `F = diag(1+ε, 1, 1)`: linear law
//!   `σ_xx = (λ+2μ) ε = M ε`, `σ_yy = σ_zz = λ ε`; neo-Hookean (Eq. 1 with
//!   `J = 1+ε`, `B = diag((1+ε)², 1, 1)`):
//!   `T_xx = μ((1+ε)² − 1)/J + λ ln J / J`, `T_yy = T_zz = λ ln J / J`;
//! - uniaxial stress of the linear law, `F = diag(1+ε, 1−νε, 1−νε)`:
//!   `σ_xx = E ε`, lateral stresses zero, `W = ½ E ε²`;
//! - hydrostatic stretch `F = s I` (neo-Hookean): `J = s³`,
//!   `T = [μ(s² − 1) + 3λ ln s] / s³ I`.
//!
//! The nodal forces of a constant stress are the face tractions shared
//! equally by the three nodes of each face: `fₐ = σ nₐ Aₐ / 3` with `nₐ Aₐ`
//! the outward area vector of the face opposite node `a` (Gauss's theorem
//! on `−∫σ∇Nₐ dv`, `Nₐ` vanishing on that face and `∫ N_b dA = A/3` on the
//! others).
//!
//! Tolerances: the closed forms are evaluated in the same arithmetic, and
//! `F` is recovered from positions with an absolute round-off of about
//! 1e-16 times the condition number of `Dm` (≈ 10 here), i.e. a stress
//! error of ~1e-15 E; relative to the stress scale `E |ε|` with
//! `|ε| ≥ 1e-4` that is ≤ 1e-11, so the checks use 1e-10.

use crate::common::{map, reference, rock, skew_tet};
use femdem_core::tet::FACES;
use femdem_core::{Mat3, Real, Vec3};
use femdem_material::{Law, cauchy_stress, deformation_gradient, nodal_forces, tet_forces};

fn rel_err(a: &Mat3, b: &Mat3, scale: Real) -> Real {
    (a - b).norm() / scale
}

fn stress_of(law: Law, f: &Mat3) -> (Mat3, femdem_material::TetResult) {
    let m = rock(0.0);
    let x0 = skew_tet();
    let r = reference(&x0);
    let x = map(&x0, f, &Vec3::new(0.3, -2.0, 5.0));
    let out = tet_forces(law, &m, &r, &x, &[Vec3::zeros(); 4]);
    (deformation_gradient(&r, &x), out)
}

#[test]
fn uniaxial_strain_gives_p_wave_modulus_and_lambda_laterally() {
    let m = rock(0.0);
    let (lambda, mu) = (m.lambda(), m.mu());
    for e in [1e-4, -1e-3, 0.05, -0.2] {
        let f = Mat3::from_diagonal(&Vec3::new(1.0 + e, 1.0, 1.0));
        let (_, lin) = stress_of(Law::LinearElastic, &f);
        let expected = Mat3::from_diagonal(&Vec3::new((lambda + 2.0 * mu) * e, lambda * e, lambda * e));
        assert!(rel_err(&lin.stress, &expected, m.young() * e.abs()) < 1e-10, "linear, ε = {e}");

        let (_, nh) = stress_of(Law::NeoHookean, &f);
        let j: Real = 1.0 + e;
        let lat = lambda * j.ln() / j;
        let expected = Mat3::from_diagonal(&Vec3::new(mu * (j * j - 1.0) / j + lat, lat, lat));
        assert!(rel_err(&nh.stress, &expected, m.young() * e.abs()) < 1e-10, "neo-Hookean, ε = {e}");
    }
}

#[test]
fn uniaxial_stress_recovers_young_modulus() {
    let m = rock(0.0);
    let (e, nu) = (-1e-3, m.poisson());
    let f = Mat3::from_diagonal(&Vec3::new(1.0 + e, 1.0 - nu * e, 1.0 - nu * e));
    let (_, out) = stress_of(Law::LinearElastic, &f);
    let expected = Mat3::from_diagonal(&Vec3::new(m.young() * e, 0.0, 0.0));
    assert!(rel_err(&out.stress, &expected, m.young() * e.abs()) < 1e-10);
    let v0 = reference(&skew_tet()).volume;
    let w = 0.5 * m.young() * e * e * v0;
    assert!((out.energy - w).abs() < 1e-10 * w);
}

#[test]
fn hydrostatic_stretch_has_closed_form_pressure() {
    let m = rock(0.0);
    for s in [0.9, 0.999, 1.001, 1.1] {
        let (_, out) = stress_of(Law::NeoHookean, &Mat3::from_diagonal_element(s));
        let p = (m.mu() * (s * s - 1.0) + 3.0 * m.lambda() * Real::ln(s)) / (s * s * s);
        let expected = Mat3::from_diagonal_element(p);
        assert!(rel_err(&out.stress, &expected, p.abs()) < 1e-10, "s = {s}");
    }
}

/// `nodal_forces` = face tractions σ n A / 3 (via femdem-core's outward
/// face table), for a general stress on a general tet; and for a uniform
/// state the kernel's forces are those tractions on the current shape.
#[test]
fn nodal_forces_are_shared_face_tractions() {
    let x = map(&skew_tet(), &Mat3::new(1.1, 0.2, 0.0, -0.1, 0.9, 0.1, 0.05, 0.0, 1.2), &Vec3::zeros());
    let sigma = Mat3::new(3.0, 1.0, -2.0, 1.0, -4.0, 0.5, -2.0, 0.5, 1.0) * 1e6;
    let f = nodal_forces(&sigma, &x);
    for (a, face) in FACES.iter().enumerate() {
        let [p, q, r] = face.map(|i| x[i]);
        let area_vector = (q - p).cross(&(r - p)) * 0.5;
        let expected = sigma * area_vector / 3.0;
        assert!((f[a] - expected).norm() < 1e-12 * sigma.norm(), "node {a}");
    }

    let m = rock(0.0);
    let x0 = skew_tet();
    let r = reference(&x0);
    let strain = Mat3::from_diagonal(&Vec3::new(1.002, 0.999, 0.9995));
    let x = map(&x0, &strain, &Vec3::zeros());
    let out = tet_forces(Law::NeoHookean, &m, &r, &x, &[Vec3::zeros(); 4]);
    let t = cauchy_stress(Law::NeoHookean, &m, &strain, &Mat3::zeros());
    for (a, face) in FACES.iter().enumerate() {
        let [p, q, s] = face.map(|i| x[i]);
        let expected = t * (q - p).cross(&(s - p)) * 0.5 / 3.0;
        assert!((out.forces[a] - expected).norm() < 1e-10 * t.norm(), "node {a}");
    }
}
