//! Joint parameters and their validation.

use femdem_core::Real;
use thiserror::Error;

use crate::Coupling;

/// A bad joint parameter.
#[derive(Debug, Error, Clone, PartialEq)]
#[error("invalid joint parameter `{name}` = {value}: {reason}")]
pub struct JointError {
    /// Parameter name as in a case file.
    pub name: &'static str,
    /// The value given.
    pub value: Real,
    /// Why it was rejected.
    pub reason: &'static str,
}

/// How the critical displacement δc follows from the fracture energy.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum GfCalibration {
    /// The paper's Eq. 10: `δc = 3 Gf / f` (the area under a parabola). With
    /// the softening curve of Eq. 12 a joint then dissipates
    /// `f (δc − δp) ∫₀¹ z dD ≈ 3 × 0.386 Gf ≈ 1.16 Gf` per unit area
    /// (slightly less, since δp > 0).
    #[default]
    Paper,
    /// `δc = δp + Gf / (f ∫₀¹ z dD)`: the softening branch dissipates exactly
    /// Gf per unit area.
    Exact,
}

/// Parameters of the cohesive law. SI units.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct JointParams {
    /// Penalty `p0`, Pa (Eq. 6–9; the paper advises `E ≤ p0 ≤ 10 E`).
    pub penalty: Real,
    /// Tensile strength `f_t`, Pa.
    pub tensile_strength: Real,
    /// Cohesion `c`, Pa (Eq. 5).
    pub cohesion: Real,
    /// Internal friction angle `φ`, radians (Eq. 5).
    pub friction_angle: Real,
    /// Fracture energy in tension `G_ft`, J/m² (Eq. 10).
    pub gf_tension: Real,
    /// Fracture energy in shear `G_fs`, J/m² (Eq. 10).
    pub gf_shear: Real,
    /// How δc follows from Gf.
    pub calibration: GfCalibration,
    /// How the damage of Eq. 13 enters the hardening branches of Eq. 11
    /// (default [`Coupling::Printed`], Eq. 11 as printed).
    pub coupling: Coupling,
}

impl JointParams {
    /// Checks every parameter: `p0, f_t, c, G_ft, G_fs > 0`, `0 ≤ φ < 90°`,
    /// all finite.
    ///
    /// `c ≤ f_t tan φ` is accepted (the paper's polyaxial Test 1 has
    /// `c = 0.5` MPa, `φ = 33.4°`, `f_t = 1` MPa): Eq. 5 with its tension
    /// cut-off then caps the tensile strength at `c / tan φ`
    /// ([`JointParams::effective_tensile_strength`]); callers that want to
    /// warn can ask [`JointParams::cohesion_limits_tension`].
    ///
    /// # Errors
    /// The first parameter out of range, with the reason.
    pub fn validate(self) -> Result<Self, JointError> {
        let positive = |name, value: Real| {
            if value.is_finite() && value > 0.0 {
                Ok(())
            } else {
                Err(JointError { name, value, reason: "must be finite and > 0" })
            }
        };
        positive("penalty", self.penalty)?;
        positive("tensile_strength", self.tensile_strength)?;
        positive("cohesion", self.cohesion)?;
        positive("fracture_energy_tension", self.gf_tension)?;
        positive("fracture_energy_shear", self.gf_shear)?;
        if !(self.friction_angle.is_finite() && (0.0..std::f64::consts::FRAC_PI_2).contains(&self.friction_angle)) {
            return Err(JointError {
                name: "friction_angle",
                value: self.friction_angle,
                reason: "must lie in [0°, 90°)",
            });
        }
        Ok(self)
    }

    /// The largest normal stress a joint can carry under pure opening,
    /// `min(f_t, c / tan φ)` (`f_t` when `φ = 0`). Eq. 5 gives the shear
    /// strength `f_s = c − σ tan φ`, which vanishes at the Mohr–Coulomb apex
    /// `σ = c / tan φ`; when that lies below `f_t` the point loses all
    /// strength there (Eq. 13: `D = 1`), on the hardening branch, before
    /// reaching `f_t`.
    pub fn effective_tensile_strength(&self) -> Real {
        self.tensile_strength.min(self.cohesion / self.friction_angle.tan())
    }

    /// Whether the cohesion limits the tensile strength: `c ≤ f_t tan φ`,
    /// so that [`JointParams::effective_tensile_strength`] is
    /// `c / tan φ ≤ f_t`. Such a joint fails brittly in tension: at the apex
    /// `f_s = 0` gives `D = 1` at once, before `δnp`, so the tensile
    /// softening branch (and `G_ft`) is never used. Valid, but worth a
    /// warning from a caller that has a terminal.
    pub fn cohesion_limits_tension(&self) -> bool {
        self.cohesion <= self.tensile_strength * self.friction_angle.tan()
    }

    /// Normal stiffness per unit area of the intact joint, `p0 / h`: the
    /// initial slope `2 f_t / δ_np` of Eq. 11 with `δ_np = 2 f_t h / p0`
    /// (Eq. 6). The shear slope `2 f_s / δ_sp` is the same (Eq. 7).
    pub fn stiffness(&self, h: Real) -> Real {
        self.penalty / h
    }

    /// The critical displacement for peak `f`, peak displacement `dp` and
    /// fracture energy `gf` (Eq. 10, or its exact calibration). Never less
    /// than `dp` (a tiny Gf gives immediate failure at the peak).
    pub fn critical_displacement(&self, f: Real, dp: Real, gf: Real) -> Real {
        let dc = match self.calibration {
            GfCalibration::Paper => 3.0 * gf / f,
            GfCalibration::Exact => dp + gf / (f * crate::softening::softening_area()),
        };
        dc.max(dp * (1.0 + 1e-12))
    }
}
