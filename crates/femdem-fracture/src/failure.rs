//! How a joint failed: the label a broken integration point (and so a
//! failed joint) gets, from the damage contributions of Eq. 13.

use femdem_core::Real;

/// The share of `D²` one direction must hold at failure for the point to
/// be labelled by it: `Dn² ≥ ¾ (Dn² + Ds²)` is tensile, `Ds² ≥ ¾ (Dn² + Ds²)`
/// is shear. In the `(Dn, Ds)` quarter circle of failure states (`D = 1`,
/// Eq. 13) this splits the angle `θ = atan(Ds/Dn)` into three equal arcs:
/// tensile `θ ≤ 30°`, mixed `30° < θ < 60°`, shear `θ ≥ 60°`.
pub const DOMINANT_SHARE: Real = 0.75;

/// How a joint (or an integration point) failed.
///
/// A point breaks when its damage `D` of Eq. 13 reaches 1. Its label is a
/// function of the normalised softening displacements at that evaluation,
/// `Dn = (δn − δnp)/(δnc − δnp)` and `Ds = (δs − δsp)/(δsc − δsp)` (each
/// clamped to `[0, 1]`; `Dn = 1` once `δn ≥ δnc`, `Ds = 1` once `δs ≥ δsc`):
/// the share of each in `D² = Dn² + Ds²` ([`FailureMode::from_contributions`],
/// threshold [`DOMINANT_SHARE`]). A point whose shear strength `f_s = c − σ
/// tan φ` (Eq. 5) has fallen to zero failed in tension: only a tensile
/// normal stress, at the Mohr–Coulomb apex `σ = c / tan φ`, does that (see
/// [`crate::JointParams::effective_tensile_strength`]).
///
/// A joint fails when two of its three points have broken (§2.2), and takes
/// the label of the point that broke last (the last in point order when
/// several break in the same evaluation) — or [`FailureMode::Collapsed`]
/// when its mid-plane degenerates.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
pub enum FailureMode {
    /// The normal part dominates: `Dn² ≥ ¾ D²` (pure opening gives
    /// `Dn = 1`, `Ds = 0`), or the Mohr–Coulomb apex was reached (`f_s ≤ 0`).
    Tensile,
    /// The shear part dominates: `Ds² ≥ ¾ D²` (pure slip: `Ds = 1`,
    /// `Dn = 0`).
    Shear,
    /// Neither dominates: `¼ D² < Dn² < ¾ D²`.
    Mixed,
    /// The joint's mid-plane collapsed (zero area: no frame, no opening or
    /// slip can be measured, Eq. 3). Not a material failure: the joint is
    /// taken out because the law can no longer be evaluated. Its damage
    /// history is left as the points reached it, and it releases no stored
    /// energy (`JointHistory::released = 0`, see [`crate::joint_update`]).
    Collapsed,
}

impl FailureMode {
    /// A code for output: 1 tensile, 2 shear, 3 mixed, 4 collapsed.
    pub fn code(self) -> u8 {
        match self {
            FailureMode::Tensile => 1,
            FailureMode::Shear => 2,
            FailureMode::Mixed => 3,
            FailureMode::Collapsed => 4,
        }
    }

    /// The mode of a [`FailureMode::code`]; `None` for any other number.
    pub fn from_code(code: u8) -> Option<FailureMode> {
        match code {
            1 => Some(FailureMode::Tensile),
            2 => Some(FailureMode::Shear),
            3 => Some(FailureMode::Mixed),
            4 => Some(FailureMode::Collapsed),
            _ => None,
        }
    }

    /// The label of a point that broke with normal and shear contributions
    /// `dn`, `ds` (each in `[0, 1]`, see the type's doc): tensile when
    /// `dn² ≥ ¾ (dn² + ds²)`, shear when `ds² ≥ ¾ (dn² + ds²)`, mixed
    /// otherwise (and when both are zero, which a broken point never has,
    /// or not numbers).
    pub fn from_contributions(dn: Real, ds: Real) -> FailureMode {
        let (n2, s2) = (dn * dn, ds * ds);
        let total = n2 + s2;
        if total <= 0.0 {
            FailureMode::Mixed
        } else if n2 >= DOMINANT_SHARE * total {
            FailureMode::Tensile
        } else if s2 >= DOMINANT_SHARE * total {
            FailureMode::Shear
        } else {
            FailureMode::Mixed
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn codes_round_trip() {
        for m in [FailureMode::Tensile, FailureMode::Shear, FailureMode::Mixed, FailureMode::Collapsed] {
            assert_eq!(FailureMode::from_code(m.code()), Some(m));
        }
        assert_eq!(FailureMode::Collapsed.code(), 4);
        assert_eq!(FailureMode::from_code(0), None);
        assert_eq!(FailureMode::from_code(5), None);
    }

    /// The sector boundaries at 30° and 60°: `Ds/Dn = tan 30° = 1/√3` gives
    /// `Dn² = ¾ D²` exactly (tensile, the bound is inclusive); just beyond
    /// it, mixed; symmetric for shear.
    #[test]
    fn labels_split_the_quarter_circle_in_thirds() {
        assert_eq!(FailureMode::from_contributions(1.0, 0.0), FailureMode::Tensile);
        assert_eq!(FailureMode::from_contributions(0.0, 1.0), FailureMode::Shear);
        assert_eq!(FailureMode::from_contributions(0.7, 0.7), FailureMode::Mixed);
        assert_eq!(FailureMode::from_contributions(0.0, 0.0), FailureMode::Mixed);
        for (angle, expect) in [
            (29.9, FailureMode::Tensile),
            (30.1, FailureMode::Mixed),
            (59.9, FailureMode::Mixed),
            (60.1, FailureMode::Shear),
        ] {
            let t: Real = Real::to_radians(angle);
            assert_eq!(FailureMode::from_contributions(t.cos(), t.sin()), expect, "θ = {angle}°");
        }
    }
}
