//! How the damage `D` of Eq. 13 enters the hardening branches of Eq. 11.
//!
//! Eq. 11 (and its shear counterpart, §2.2: "substituting the normal
//! displacement δn with the shear displacement δs …") has three branches:
//! `2 r f` in compression (`r = δ/δp < 0`, normal only), the hardening
//! branch `[2r − r²] f` for `0 ≤ r ≤ 1`, and the softening branch `z(D) f`
//! beyond the peak. The damage `D` of Eq. 13 couples the two directions:
//! one `D` per integration point, from both `Dn` and `Ds`. As printed, only
//! the softening branch carries `z(D)`; so when one direction has softened
//! the other still hardens to its full peak, and a direction that has
//! softened and then unloads would climb its undamaged parabola again (the
//! paper does not discuss unloading). [`Coupling`] names the three readings
//! the team is weighing; in all of them the softening branch is `z(D) f`,
//! compression (`δn < 0`) is never affected by damage, and damage is
//! irreversible: `D = max(D_now, D_hist)`.

use femdem_core::Real;

/// How the damage `D` of Eq. 13 enters the hardening branch `[2r − r²] f`
/// of Eq. 11 (`r = δ/δp`, `0 ≤ r ≤ 1`), for `σ` (`f_t`, `δnp`, Eq. 6) and
/// for `τ` (`f_s` of Eq. 5, `δsp`, Eq. 7) alike. Beyond the peak every
/// option gives `z(D) f` (Eq. 11–12); in compression every option gives
/// `σ = 2 (δn/δnp) f_t`. `D` is the coupled damage of Eq. 13 with its
/// history, `D = max(D_now, D_hist)`.
///
/// The shear strength of Eq. 5 takes the normal stress computed by the same
/// option without the shear damage (`D = max(Dn, D_hist)`; see the `law`
/// module doc).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Coupling {
    /// Eq. 11 as printed: the hardening branch carries no `z`,
    /// `σ = [2r − r²] f_t` for `0 ≤ δn ≤ δnp` whatever the shear damage, and
    /// `τ = [2r − r²] f_s` for `0 ≤ δs ≤ δsp` whatever the normal damage;
    /// `z(D) f` only beyond the peak. So with the normal direction
    /// softening at `Dn = 0.3` and the slip at `0.9 δsp`, `τ = 0.99 f_s`;
    /// and a point whose shear has failed (`D = 1`) still carries up to
    /// `f_t` in tension while `δn ≤ δnp`.
    ///
    /// Unloading and reloading: a direction that has once been past its
    /// own peak (`δn > δnp`, resp. `δs > δsp`, or both at the Mohr–Coulomb
    /// apex `f_s ≤ 0`; remembered per point and direction in [`Softened`])
    /// has its hardening branch capped
    /// at `z(D) f` from then on, as [`Coupling::Capped`] does, so it never
    /// climbs above its damaged strength again; a direction that has never
    /// been past its peak follows the printed parabola. This is the only
    /// reading in which "the hardening branch has no `z`" and "damage is
    /// irreversible" both hold *and* the stress does not depend on the time
    /// step: deciding by "`D_hist = 0`" instead would give `τ = 0.99 f_s` in
    /// the example above when the point gets there in one evaluation, but
    /// `z(0.3) f_s = 0.51 f_s` when the normal softening was reached in an
    /// earlier step.
    ///
    /// Energy: where a direction that has never softened crosses its peak
    /// while the point is damaged (`D > 0` from the other direction), its
    /// stress drops in one step from `f` to `z(D) f`. For the normal
    /// direction that raises `f_s = c − σ tan φ` (Eq. 5) by
    /// `(1 − z(D)) f_t tan φ`, and with it the stored shear plateau, with no
    /// work done: the printed law is not conservative there (measured in
    /// `tests/law_energy.rs`: 2.4 J/m² out of 495 J/m² of work to failure on
    /// a granite joint, once per point).
    ///
    /// The default: the paper's model as written. Measured on the coarse
    /// Brazilian disc (docs/fidelity.md §2) it gives the same peak as
    /// `Multiplicative` within 2% and a similar share of tensile failures
    /// in the central fracture; no measurement favoured departing from it.
    #[default]
    Printed,
    /// Munjiza's Y-code style: the hardening branch multiplied by `z(D)`,
    /// `σ = z(D) [2r − r²] f_t` for `0 ≤ δn ≤ δnp`, `z(D) f_t` beyond;
    /// `τ` likewise. Unloading at constant `D` follows the same scaled
    /// curve (a secant-like damage: the stiffness falls with `z(D)`).
    Multiplicative,
    /// The hardening branch capped at the damaged strength:
    /// `σ = min([2r − r²] f_t, z(D) f_t)` for `0 ≤ δn ≤ δnp`, `z(D) f_t`
    /// beyond; `τ` likewise. Unloading at constant `D` follows the
    /// undamaged parabola up to `z(D) f`, then the plateau. For a single
    /// mode loaded monotonically this is Eq. 11 exactly (`D = 0` while
    /// hardening); it makes `τ` continuous at `δsp` when the normal
    /// direction has softened. femdem's behaviour before the option
    /// existed (kept for comparison).
    Capped,
}

/// Whether each direction of an integration point has ever been past its
/// peak: `δn > δnp`; `δs > δsp`; and both at the Mohr–Coulomb apex
/// (`f_s = c − σ tan φ ≤ 0`, Eq. 5), where the point has no shear strength
/// left and its tensile strength `c / tan φ ≤ f_t` is exhausted (see
/// [`crate::JointParams::effective_tensile_strength`]). Only
/// [`Coupling::Printed`] reads it; it is recorded for every option.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
pub struct Softened {
    /// The opening has been past `δnp`, or the apex was reached.
    pub normal: bool,
    /// The slip has been past `δsp`, or the apex was reached.
    pub shear: bool,
}

impl Softened {
    /// What a point known only by its damage `d_hist` is taken to have
    /// done: nothing when undamaged, both directions past their peak when
    /// damaged (the conservative reading: every hardening branch capped at
    /// `z(D) f`).
    pub fn assumed(d_hist: Real) -> Softened {
        let damaged = d_hist > 0.0;
        Softened { normal: damaged, shear: damaged }
    }
}

/// The hardening branch of Eq. 11, `[2r − r²] f`, for `0 ≤ r ≤ 1`.
#[inline]
pub(crate) fn hardening(f: Real, r: Real) -> Real {
    (2.0 * r - r * r) * f
}

impl Coupling {
    /// The stress on the hardening branch, `0 ≤ r ≤ 1`, for peak `f`,
    /// damage factor `zd = z(D)`, and whether this direction has been past
    /// its peak before.
    #[inline]
    pub(crate) fn hardening_branch(self, f: Real, r: Real, zd: Real, softened: bool) -> Real {
        match self {
            Coupling::Printed if !softened => hardening(f, r),
            Coupling::Printed | Coupling::Capped => hardening(f, r).min(zd * f),
            Coupling::Multiplicative => zd * hardening(f, r),
        }
    }

    /// Stored (recoverable) energy per unit area of one direction at ratio
    /// `r = δ/δp`, peak `f`, damage factor `zd = z(D)`, and whether the
    /// direction has been past its peak (after this evaluation): the area
    /// under the curve the point would unload along at constant `D`, down
    /// to `δ = 0`.
    ///
    /// * Compression (`r < 0`, normal only): `f δp r²` (the line `2 r f`).
    /// * `Capped`, and `Printed` once softened: the parabola capped at
    ///   `zd f`, which it meets at `r* = 1 − √(1 − zd)`:
    ///   `f δp (r² − r³/3)` up to `r*`, then
    ///   `f δp (r*² − r*³/3) + zd f δp (r − r*)` (undamaged: `r* = 1`).
    /// * `Printed` never softened (then `r ≤ 1`): `f δp (r² − r³/3)`.
    /// * `Multiplicative`: `zd f δp (r² − r³/3)` for `r ≤ 1`, then
    ///   `zd f δp (r − 1/3)` (the scaled parabola, area `⅔ zd f δp`, and the
    ///   plateau `zd f`).
    #[inline]
    pub(crate) fn stored(self, f: Real, dp: Real, r: Real, zd: Real, softened: bool) -> Real {
        if r < 0.0 {
            return f * dp * r * r;
        }
        match self {
            Coupling::Printed if !softened && r <= 1.0 => f * dp * (r * r - r * r * r / 3.0),
            Coupling::Printed | Coupling::Capped => capped_stored(f, dp, r, zd),
            Coupling::Multiplicative => {
                if r <= 1.0 {
                    zd * f * dp * (r * r - r * r * r / 3.0)
                } else if zd > 0.0 {
                    zd * f * dp * (r - 1.0 / 3.0)
                } else {
                    0.0 // broken: nothing stored, even at r = ∞ (0 × ∞ is NaN)
                }
            }
        }
    }
}

/// The stored energy under the capped curve, `r ≥ 0` (see
/// [`Coupling::stored`]).
#[inline]
fn capped_stored(f: Real, dp: Real, r: Real, zd: Real) -> Real {
    let rs = 1.0 - (1.0 - zd.clamp(0.0, 1.0)).sqrt();
    if r <= rs {
        f * dp * (r * r - r * r * r / 3.0)
    } else if zd > 0.0 {
        f * dp * (rs * rs - rs * rs * rs / 3.0 + zd * (r - rs))
    } else {
        0.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::softening::z;

    /// The stored energy is the integral of the unloading curve: checked
    /// against a midpoint rule on the branch functions themselves (20,000
    /// panels: error `≤ f δp max|σ″| h² / 24 ≈ 1e-9 f δp` on the parabola,
    /// the kink at `r*` adds `≤ f δp × slope × h² ≈ 1e-8`); tolerance
    /// 1e-7 f δp.
    #[test]
    fn stored_is_the_area_under_the_unloading_curve() {
        let (f, dp) = (2.0, 0.5);
        for coupling in [Coupling::Printed, Coupling::Multiplicative, Coupling::Capped] {
            for softened in [false, true] {
                for d in [0.0, 0.3, 0.7, 1.0] {
                    let zd = z(d);
                    for r in [0.0, 0.2, 0.6, 1.0, 1.5, 3.0] {
                        if coupling == Coupling::Printed && !softened && r > 1.0 {
                            continue; // a direction past its peak has softened
                        }
                        let curve = |rho: Real| {
                            if rho <= 1.0 { coupling.hardening_branch(f, rho, zd, softened) } else { zd * f }
                        };
                        let n = 20_000;
                        let h = r / n as Real;
                        let area: Real = (0..n).map(|i| curve((i as Real + 0.5) * h) * h * dp).sum();
                        let s = coupling.stored(f, dp, r, zd, softened);
                        assert!((s - area).abs() < 1e-7 * f * dp, "{coupling:?} {softened} D {d} r {r}: {s} vs {area}");
                    }
                }
            }
        }
        // A broken point (z = 0) stores nothing, even slipped without bound
        // (regression: Multiplicative gave 0 × ∞ = NaN).
        for coupling in [Coupling::Printed, Coupling::Multiplicative, Coupling::Capped] {
            assert_eq!(coupling.stored(f, dp, Real::INFINITY, 0.0, true), 0.0, "{coupling:?}");
        }
        // Compression: the line 2 r f, area f δp r², whatever the damage.
        for coupling in [Coupling::Printed, Coupling::Multiplicative, Coupling::Capped] {
            assert_eq!(coupling.stored(f, dp, -0.5, 0.0, true), f * dp * 0.25);
        }
    }
}
