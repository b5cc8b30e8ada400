//! Linear and angular momentum balance of the tet forces.
//!
//! Internal forces of a body can neither push nor spin it: `Σ fₐ = 0` and
//! `Σ xₐ × fₐ = 0`. For `fₐ = −v σ ∇Nₐ`: `Σ ∇Nₐ = 0` gives the first, and
//! `Σ xₐ ⊗ ∇Nₐ = I` makes the torque the axial vector of `−v σᵀ`, zero for
//! symmetric `σ`. For the kernel, `Σ xₐ ⊗ fₐ = −V₀ F Pᵀ`, and the
//! neo-Hookean `P = μF + U′ cof F + η D̂ cof F` gives
//! `F Pᵀ = μ B + J U′ I + η J D̂` (using `F cof(F)ᵀ = J I`), symmetric for
//! **every** `F` — also crushed and inverted elements, where the law is
//! continued (see `femdem_material::law`). The geometrically linear law
//! balances torque only about the reference configuration.
//!
//! Tolerances: the sum is exact up to a few ulps (`f₀` is built as
//! `−(f₁+f₂+f₃)`): 1e-13 of `Σ|fₐ|`. The torque is a sum of products of
//! quantities with relative round-off ~1e-16 × cond(Dm) (≤ ~100): 1e-12 of
//! `Σ |xₐ| |fₐ|`.

use crate::common::{good_tet, points, reference, rock, vec3};
use femdem_core::{Mat3, Real, Vec3};
use femdem_material::{Law, nodal_forces, tet_forces};
use proptest::prelude::*;

fn check_balance(x: &[Vec3; 4], f: &[Vec3; 4], torque_too: bool) -> Result<(), TestCaseError> {
    let size: Real = f.iter().map(|f| f.norm()).sum();
    let sum: Vec3 = f.iter().sum();
    prop_assert!(sum.norm() <= 1e-13 * size, "Σf = {sum}, Σ|f| = {size}");
    if torque_too {
        let torque: Vec3 = x.iter().zip(f).map(|(x, f)| x.cross(f)).sum();
        let scale: Real = x.iter().zip(f).map(|(x, f)| x.norm() * f.norm()).sum();
        prop_assert!(torque.norm() <= 1e-12 * scale, "torque {torque}, scale {scale}");
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    /// Any current positions (inverted, flat and crushed included) and any
    /// velocities: the neo-Hookean forces sum to zero and exert no torque.
    #[test]
    fn neo_hookean_forces_balance_momentum_in_any_state(
        x0 in good_tet(),
        x in points(1.5),
        v in prop::array::uniform4(vec3(10.0)),
    ) {
        let out = tet_forces(Law::NeoHookean, &rock(1e5), &reference(&x0), &x, &v);
        check_balance(&x, &out.forces, true)?;
    }

    /// The linear law's forces always sum to zero; their torque vanishes in
    /// the reference configuration (any velocities).
    #[test]
    fn linear_forces_balance_momentum(
        x0 in good_tet(),
        x in points(1.5),
        v in prop::array::uniform4(vec3(10.0)),
    ) {
        let m = rock(1e5);
        let r = reference(&x0);
        check_balance(&x, &tet_forces(Law::LinearElastic, &m, &r, &x, &v).forces, false)?;
        check_balance(&x0, &tet_forces(Law::LinearElastic, &m, &r, &x0, &v).forces, true)?;
    }

    /// `nodal_forces` of any symmetric stress on any tet balances momentum.
    #[test]
    fn nodal_forces_of_symmetric_stress_balance_momentum(
        x in points(1.5),
        s in prop::array::uniform6(-1e8f64..1e8),
    ) {
        let sigma = Mat3::new(s[0], s[3], s[4], s[3], s[1], s[5], s[4], s[5], s[2]);
        check_balance(&x, &nodal_forces(&sigma, &x), true)?;
    }
}
