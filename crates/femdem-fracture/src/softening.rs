//! Munjiza's softening curve (reference paper Eq. 12; Munjiza, Andrews &
//! White 1999, after Evans & Marathe's concrete data):
//!
//! ```text
//! z(D) = [1 − (a+b−1)/(a+b) · exp(D (a + b c) / ((a+b)(1 − a − b)))] · [a (1−D) + b (1−D)^c]
//! ```
//!
//! with `a = 0.63`, `b = 1.8`, `c = 6.0`; `z(0) = 1`, `z(1) = 0`, decreasing.
//! The area under it, `∫₀¹ z dD ≈ 0.386` ([`softening_area`]), is what
//! relates the critical opening to the fracture energy (Eq. 10).

use std::sync::LazyLock;

use femdem_core::Real;

/// `a` of Eq. 12.
pub const A: Real = 0.63;
/// `b` of Eq. 12.
pub const B: Real = 1.8;
/// `c` of Eq. 12.
pub const C: Real = 6.0;

/// The softening factor `z(D)` of Eq. 12, for `D` clamped to `[0, 1]`.
#[inline]
pub fn z(d: Real) -> Real {
    let d = d.clamp(0.0, 1.0);
    let ab = A + B;
    let e = (d * (A + B * C) / (ab * (1.0 - ab))).exp();
    let one_minus = 1.0 - d;
    (1.0 - (ab - 1.0) / ab * e) * (A * one_minus + B * one_minus.powf(C))
}

/// Nodes and weights of 8-point Gauss–Legendre quadrature on `[−1, 1]`.
const GL8: [(Real, Real); 8] = [
    (-0.960_289_856_497_536_2, 0.101_228_536_290_376_26),
    (-0.796_666_477_413_626_7, 0.222_381_034_453_374_47),
    (-0.525_532_409_916_329, 0.313_706_645_877_887_3),
    (-0.183_434_642_495_649_8, 0.362_683_783_378_362),
    (0.183_434_642_495_649_8, 0.362_683_783_378_362),
    (0.525_532_409_916_329, 0.313_706_645_877_887_3),
    (0.796_666_477_413_626_7, 0.222_381_034_453_374_47),
    (0.960_289_856_497_536_2, 0.101_228_536_290_376_26),
];

/// `∫_{d0}^{d1} z(D) dD` by 8-point Gauss–Legendre on each of `panels`
/// equal sub-intervals (z is smooth: a polynomial of degree 6 times an
/// exponential).
pub fn z_integral(d0: Real, d1: Real) -> Real {
    let (d0, d1) = (d0.clamp(0.0, 1.0), d1.clamp(0.0, 1.0));
    if d1 <= d0 {
        return 0.0;
    }
    let panels = 4;
    let h = (d1 - d0) / panels as Real;
    let mut sum = 0.0;
    for p in 0..panels {
        let mid = d0 + h * (p as Real + 0.5);
        for (x, w) in GL8 {
            sum += w * z(mid + 0.5 * h * x);
        }
    }
    sum * 0.5 * h
}

static AREA: LazyLock<Real> = LazyLock::new(|| z_integral(0.0, 1.0));

/// `∫₀¹ z(D) dD`, the area under the normalised softening curve (≈ 0.386).
pub fn softening_area() -> Real {
    *AREA
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    #[test]
    fn ends_are_one_and_zero() {
        assert!((z(0.0) - 1.0).abs() < 1e-15);
        assert!(z(1.0).abs() < 1e-15);
    }

    #[test]
    fn area_is_about_0_386() {
        // Independent check: composite Simpson with 20,000 panels.
        let n = 20_000;
        let h = 1.0 / n as Real;
        let simpson: Real = (0..n)
            .map(|i| {
                let a = i as Real * h;
                h / 6.0 * (z(a) + 4.0 * z(a + 0.5 * h) + z(a + h))
            })
            .sum();
        assert!((softening_area() - simpson).abs() < 1e-10, "{} vs {simpson}", softening_area());
        assert!((softening_area() - 0.386).abs() < 0.001);
    }

    proptest! {
        #[test]
        fn z_is_monotone_and_bounded(a in 0.0f64..1.0, b in 0.0f64..1.0) {
            let (lo, hi) = if a < b { (a, b) } else { (b, a) };
            prop_assert!(z(lo) >= z(hi));
            prop_assert!((0.0..=1.0).contains(&z(a)));
        }

        #[test]
        fn integral_is_additive(a in 0.0f64..1.0, b in 0.0f64..1.0, c in 0.0f64..1.0) {
            let mut v = [a, b, c];
            v.sort_by(|x, y| x.partial_cmp(y).unwrap());
            let whole = z_integral(v[0], v[2]);
            let parts = z_integral(v[0], v[1]) + z_integral(v[1], v[2]);
            prop_assert!((whole - parts).abs() < 1e-9);
        }
    }
}
