//! Joint parameters and their validation.

use femdem_core::Real;
use thiserror::Error;

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
}

impl JointParams {
    /// Checks every parameter: `p0 > 0`, `f_t > 0`, `c > 0`,
    /// `0 ≤ φ < π/2`, all finite.
    ///
    /// # Errors
    /// The first parameter out of range, with the reason.
    pub fn validate(self) -> Result<Self, JointError> {
        let positive = |name, value: Real| {
            if value.is_finite() && value > 0.0 {
                Ok(())
            } else {
                Err(JointError {
                    name,
                    value,
                    reason: "must be finite and > 0",
                })
            }
        };
        positive("penalty", self.penalty)?;
        positive("tensile_strength", self.tensile_strength)?;
        positive("cohesion", self.cohesion)?;
        if !(self.friction_angle.is_finite()
            && (0.0..std::f64::consts::FRAC_PI_2).contains(&self.friction_angle))
        {
            return Err(JointError {
                name: "friction_angle",
                value: self.friction_angle,
                reason: "must lie in [0°, 90°)",
            });
        }
        Ok(self)
    }

    /// Normal stiffness per unit area of the intact joint, `p0 / h`: the
    /// initial slope `2 f_t / δ_np` of Eq. 11 with `δ_np = 2 f_t h / p0`
    /// (Eq. 6). The shear slope `2 f_s / δ_sp` is the same (Eq. 7).
    pub fn stiffness(&self, h: Real) -> Real {
        self.penalty / h
    }
}
