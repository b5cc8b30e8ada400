//! For small strain the neo-Hookean law (Eq. 1) reduces to linear
//! elasticity, and the difference is second order.
//!
//! With `F = I + H`, `|H| = O(ε)`: `B − I = H + Hᵀ + H Hᵀ = 2 sym(H) + O(ε²)`,
//! `J = 1 + tr H + O(ε²)`, `ln J = tr sym(H) + O(ε²)`, `1/J = 1 + O(ε)`, so
//! `T = 2μ ε + λ tr ε I + O(ε²)` with `ε = sym(H) = ½(F + Fᵀ) − I`, the
//! linear law. (A rotation part of `H` also enters only at O(ε²).) The same
//! holds for the tet forces, since `P = J T F⁻ᵀ = T + O(ε²)` for the
//! neo-Hookean law and `P = σ` for the linear one.
//!
//! Check: along `F = I + ε G` for a fixed general `G` (stretch, shear and
//! rotation), halving `ε` must divide the difference by 4 (the ratio is
//! `4 (1 + O(ε))`: within [3.7, 4.3] for `ε ≤ 1e-2`). Round-off in the
//! stress is ~1e-15 E, far below the smallest difference (~1e-8 E at
//! `ε = 1e-4`).

use crate::common::{map, reference, rock, skew_tet};
use femdem_core::{Mat3, Real, Vec3};
use femdem_material::{Law, cauchy_stress, tet_forces};

fn general_direction() -> Mat3 {
    let g = Mat3::new(0.3, 0.8, -0.2, 0.1, -0.5, 0.4, -0.6, 0.2, 0.7);
    g / g.norm()
}

fn stress_gap(e: Real) -> Real {
    let m = rock(0.0);
    let f = Mat3::identity() + general_direction() * e;
    let nh = cauchy_stress(Law::NeoHookean, &m, &f, &Mat3::zeros());
    let lin = cauchy_stress(Law::LinearElastic, &m, &f, &Mat3::zeros());
    (nh - lin).norm()
}

fn force_gap(e: Real) -> Real {
    let m = rock(0.0);
    let x0 = skew_tet();
    let r = reference(&x0);
    let x = map(&x0, &(Mat3::identity() + general_direction() * e), &Vec3::zeros());
    let v = [Vec3::zeros(); 4];
    let nh = tet_forces(Law::NeoHookean, &m, &r, &x, &v).forces;
    let lin = tet_forces(Law::LinearElastic, &m, &r, &x, &v).forces;
    nh.iter().zip(&lin).map(|(a, b)| (a - b).norm_squared()).sum::<Real>().sqrt()
}

fn assert_quadratic(gap: impl Fn(Real) -> Real, scale: Real, what: &str) {
    let mut e = 1e-2;
    while e > 1.5e-4 {
        let (big, small) = (gap(e), gap(e / 2.0));
        let ratio = big / small;
        assert!((3.7..=4.3).contains(&ratio), "{what}: ε = {e}: gap ratio {ratio}");
        // The O(ε²) constant is of order E |G|² (here |G| = 1).
        assert!(big < 10.0 * scale * e * e, "{what}: ε = {e}: gap {big}");
        e /= 2.0;
    }
}

#[test]
fn neo_hookean_stress_matches_linear_law_to_second_order() {
    let m = rock(0.0);
    assert_quadratic(stress_gap, m.young(), "stress");
    // And the first-order agreement is not trivial: the stress itself is
    // O(ε), a thousand times the gap at ε = 1e-3.
    let f = Mat3::identity() + general_direction() * 1e-3;
    let lin = cauchy_stress(Law::LinearElastic, &m, &f, &Mat3::zeros());
    assert!(lin.norm() > 100.0 * stress_gap(1e-3));
}

#[test]
fn neo_hookean_forces_match_linear_forces_to_second_order() {
    let m = rock(0.0);
    let r = reference(&skew_tet());
    // Force scale E V₀ |Dm⁻¹|.
    let scale = m.young() * r.volume * r.inv_dm.norm();
    assert_quadratic(force_gap, scale, "forces");
}
