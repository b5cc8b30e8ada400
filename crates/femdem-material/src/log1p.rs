//! `ln(1 + x)` and `x − ln(1 + x)` for small `x`, without cancellation.
//!
//! The neo-Hookean energy (`law`) needs `ln J²` and `2 tr E − ln J²`
//! (`E` the Green–Lagrange strain) at strains down to round-off: an
//! elastic wave of strain 10⁻⁹ stores `W ≈ μ 10⁻¹⁸`, while `ln J` and
//! `tr E` are each `≈ 10⁻⁹`. Computed as `x − ln(1.0 + x)` the difference
//! keeps no correct digit, and as `x − ln_1p(x)` about half of them. With
//! `s = x / (2 + x)`,
//!
//! - `ln(1 + x) = 2 atanh s = 2 s (1 + z P(z))`, `z = s²`,
//!   `P(z) = 1/3 + z/5 + z²/7 + …`;
//! - `x = 2 s / (1 − s)`, so `x − 2 s = s x` and
//!   `x − ln(1 + x) = s x − 2 s z P(z)`, two terms of order `x²/2` and
//!   `x³/12`: no cancellation.
//!
//! For `|s| ≤ (√2 − 1)/(√2 + 1) = 0.1716` (`−0.2929 ≤ x ≤ 0.4142`) the
//! series to `z¹¹` leaves less than 2·10⁻¹⁷ of the result (the same series
//! and bound as the device's `ln64`, `femdem-gpu/src/wgsl/math.wgsl`).
//! Outside that range the plain forms are used: `ln(1 + x)` (libm's
//! `ln_1p`) loses nothing, and `x − ln(1 + x)` at most a factor of 6.5 of
//! `ln(1 + x)`'s rounding (at `x = −0.2929`, where the difference is
//! 0.155 of `ln(1 + x)`; 0.16 of it at `x = 0.4142`, and more beyond): a
//! few ulps.

use femdem_core::Real;

/// `|s|` up to which the series is used: `(√2 − 1)/(√2 + 1)`.
const S_MAX: Real = 0.171_572_875_253_809_9;

/// `P(z) = Σ_{k≥0} z^k / (2k + 3)`, to `z¹⁰`, by Horner's rule.
#[inline]
fn atanh_tail(z: Real) -> Real {
    let mut p = 1.0 / 23.0;
    for d in [21.0, 19.0, 17.0, 15.0, 13.0, 11.0, 9.0, 7.0, 5.0, 3.0] {
        p = p * z + 1.0 / d;
    }
    p
}

/// `(ln(1 + x), x − ln(1 + x))` for `x > −1`, each to a few ulps of its
/// own size (module docs).
#[inline]
pub fn ln_1p_and_excess(x: Real) -> (Real, Real) {
    let s = x / (2.0 + x);
    if s.abs() <= S_MAX {
        let z = s * s;
        let tail = 2.0 * s * z * atanh_tail(z);
        (2.0 * s + tail, s * x - tail)
    } else {
        let ln = x.ln_1p();
        (ln, x - ln)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Against the CPU's `ln_1p` (correctly rounded to within an ulp or
    /// so) over the series' range and beyond: within 4 ulps of it.
    #[test]
    fn ln_1p_matches_libm() {
        let mut x = -0.9;
        while x < 3.0 {
            for v in [x, x * 1e-3, x * 1e-9, x * 1e-200] {
                let (ln, _) = ln_1p_and_excess(v);
                let want = v.ln_1p();
                assert!((ln - want).abs() <= 4.0 * Real::EPSILON * want.abs(), "{v}: {ln} vs {want}");
            }
            x += 0.0137;
        }
        assert_eq!(ln_1p_and_excess(0.0), (0.0, 0.0));
    }

    /// `x − ln(1 + x)` against its series in `s = x / (2 + x)`,
    /// `s x − 2 s³ Σ_k s^{2k} / (2k + 3)`, summed to convergence (every term
    /// of one sign for `x > 0`, alternating in sign of `s` otherwise, none
    /// cancelling the first): an independent reference wherever it
    /// converges fast, here `|s| ≤ 0.6` (`−0.75 ≤ x ≤ 3`). Within 8 ulps
    /// in the series' range, and within 8 ulps of `ln(1 + x)` where the
    /// difference is taken plainly (module docs: it loses up to a factor
    /// 6.5 of `ln(1 + x)`'s rounding there). `x − ln(1.0 + x)` at
    /// `x = 10⁻⁹` has no correct digit; this has 15.
    #[test]
    fn excess_keeps_its_digits_at_small_x() {
        let reference = |x: Real| {
            let s = x / (2.0 + x);
            let z = s * s;
            let (mut sum, mut power) = (0.0, 1.0);
            for k in 0..400 {
                sum += power / Real::from(2 * k + 3);
                power *= z;
            }
            s * x - 2.0 * s * z * sum
        };
        let mut xs = vec![0.05, -0.05, 1e-3, -1e-3, 1e-6, 1e-9, -3e-9, 1e-12, 1e-150, 0.4142, -0.2929];
        let mut x = -0.75;
        while x < 3.0 {
            xs.push(x);
            x += 0.0173;
        }
        for x in xs {
            let (ln, g) = ln_1p_and_excess(x);
            let want = reference(x);
            let scale = if (x / (2.0 + x)).abs() <= S_MAX { want.abs() } else { ln.abs() };
            assert!((g - want).abs() <= 8.0 * Real::EPSILON * scale, "{x}: {g} vs {want}");
        }
    }
}
