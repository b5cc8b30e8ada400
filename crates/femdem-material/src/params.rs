//! Material parameters of the tets: what a user writes ([`ElasticParams`])
//! and the validated form the laws use ([`Material`]).
//!
//! Validation happens once, when a case is built; the laws and the tet
//! kernel then trust a [`Material`] and never check again.

use femdem_core::Real;
use thiserror::Error;

/// Why a set of material parameters was rejected.
///
/// Each error names the parameter as it appears in [`ElasticParams`] (and in
/// case files): `young`, `poisson`, `density` or `viscosity`.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum MaterialError {
    /// A parameter is NaN or infinite.
    #[error("material parameter `{name}` must be finite, got {value}")]
    NotFinite {
        /// Parameter name.
        name: &'static str,
        /// The rejected value.
        value: Real,
    },
    /// A parameter is finite but outside its physical range.
    #[error("material parameter `{name}` = {value} is out of range: {reason}")]
    OutOfRange {
        /// Parameter name.
        name: &'static str,
        /// The rejected value.
        value: Real,
        /// The range it must lie in, and why.
        reason: &'static str,
    },
}

impl MaterialError {
    /// The name of the rejected parameter (`young`, `poisson`, `density` or
    /// `viscosity`).
    pub fn name(&self) -> &'static str {
        match self {
            MaterialError::NotFinite { name, .. } | MaterialError::OutOfRange { name, .. } => name,
        }
    }
}

/// Elastic and viscous parameters of a tet material, as a user gives them
/// (SI units).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ElasticParams {
    /// Young's modulus `E` (Pa), `E > 0`.
    pub young: Real,
    /// Poisson's ratio `ν` (–), `−1 < ν < 0.5`.
    pub poisson: Real,
    /// Mass density `ρ` (kg/m³), `ρ > 0`.
    pub density: Real,
    /// Viscous damping parameter `η` of Eq. 1 (Pa·s), `η ≥ 0`. See
    /// [`critical_viscosity`] for how to choose it.
    pub viscosity: Real,
}

impl ElasticParams {
    /// Checks every parameter and derives the Lamé constants.
    ///
    /// Parameters are checked in the order `young`, `poisson`, `density`,
    /// `viscosity`; the first bad one is reported. Rejected: non-finite
    /// values, `E ≤ 0`, `ν ∉ (−1, 0.5)` (the bulk modulus
    /// `K = E / (3(1 − 2ν))` must be positive and finite, the shear modulus
    /// `μ = E / (2(1 + ν))` positive), `ρ ≤ 0` and `η < 0`.
    pub fn validate(self) -> Result<Material, MaterialError> {
        let ElasticParams { young, poisson, density, viscosity } = self;
        check("young", young, young > 0.0, "Young's modulus must be > 0 Pa")?;
        check(
            "poisson",
            poisson,
            poisson > -1.0 && poisson < 0.5,
            "Poisson's ratio must lie in the open interval (-1, 0.5) for positive, finite shear and bulk moduli",
        )?;
        check("density", density, density > 0.0, "density must be > 0 kg/m³")?;
        check(
            "viscosity",
            viscosity,
            viscosity >= 0.0,
            "viscosity must be >= 0 Pa·s (a negative value would feed energy in)",
        )?;
        let mu = young / (2.0 * (1.0 + poisson));
        let lambda = young * poisson / ((1.0 + poisson) * (1.0 - 2.0 * poisson));
        Ok(Material { young, poisson, density, viscosity, lambda, mu })
    }
}

fn check(name: &'static str, value: Real, in_range: bool, reason: &'static str) -> Result<(), MaterialError> {
    if !value.is_finite() {
        Err(MaterialError::NotFinite { name, value })
    } else if !in_range {
        Err(MaterialError::OutOfRange { name, value, reason })
    } else {
        Ok(())
    }
}

/// A validated material: the parameters of [`ElasticParams`] plus the
/// constants the laws use.
///
/// Only [`ElasticParams::validate`] builds one, so every `Material` has
/// `E > 0`, `−1 < ν < 0.5`, `ρ > 0`, `η ≥ 0`, all finite.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Material {
    young: Real,
    poisson: Real,
    density: Real,
    viscosity: Real,
    lambda: Real,
    mu: Real,
}

impl Material {
    /// Young's modulus `E` (Pa).
    #[inline]
    pub fn young(&self) -> Real {
        self.young
    }

    /// Poisson's ratio `ν`.
    #[inline]
    pub fn poisson(&self) -> Real {
        self.poisson
    }

    /// Mass density `ρ` (kg/m³).
    #[inline]
    pub fn density(&self) -> Real {
        self.density
    }

    /// Viscous damping parameter `η` of Eq. 1 (Pa·s).
    #[inline]
    pub fn viscosity(&self) -> Real {
        self.viscosity
    }

    /// First Lamé constant `λ = E ν / ((1 + ν)(1 − 2ν))` (Pa).
    #[inline]
    pub fn lambda(&self) -> Real {
        self.lambda
    }

    /// Shear modulus (second Lamé constant) `μ = E / (2(1 + ν))` (Pa).
    #[inline]
    pub fn mu(&self) -> Real {
        self.mu
    }

    /// P-wave (constrained, oedometric) modulus `M = λ + 2μ` (Pa): the
    /// stiffness of uniaxial strain, which sets the fastest wave and hence
    /// the explicit time step.
    #[inline]
    pub fn p_wave_modulus(&self) -> Real {
        self.lambda + 2.0 * self.mu
    }

    /// P-wave speed `c_p = √(M / ρ)` (m/s).
    #[inline]
    pub fn p_wave_speed(&self) -> Real {
        (self.p_wave_modulus() / self.density).sqrt()
    }

    /// [`critical_viscosity`] of this material for element size `h` (m).
    #[inline]
    pub fn critical_viscosity(&self, h: Real) -> Real {
        critical_viscosity(h, self.young, self.density)
    }

    /// The parameters this material was validated from.
    pub fn params(&self) -> ElasticParams {
        ElasticParams { young: self.young, poisson: self.poisson, density: self.density, viscosity: self.viscosity }
    }
}

/// Munjiza's estimate of the viscosity that critically damps the highest
/// mode of an element of size `h`: `η_crit = 2 h √(E ρ)` (Pa·s; `h` in m,
/// `E` in Pa, `ρ` in kg/m³). Munjiza (2004), *The combined finite-discrete
/// element method*, Wiley.
///
/// # What it means
///
/// In a Kelvin–Voigt bar, `ρ ü = E u″ + η u̇″`, a mode of wavenumber `k`
/// has frequency `ω = k √(E/ρ)` and damping ratio
///
/// `ξ(k) = η k / (2 √(E ρ))`.
///
/// At `k = 1/h` this is `ξ ≈ η / (2 h √(E ρ)) = η / η_crit`: the damping
/// ratio of a mode of wavelength ~`h` for this element size. The ratio grows
/// linearly with `k`: the shortest wave a mesh of size `h` carries
/// (wavelength ≈ 2h, `k = π/h`) is damped about π times more, and a
/// structural mode of wavelength `Λ ≫ h` only gets `ξ ≈ (η/η_crit) · 2πh/Λ`.
/// The viscous term therefore kills element-scale ringing (the numerical
/// noise of explicit FEMDEM) while leaving the response of the specimen
/// nearly undamped. (In 3D the longitudinal waves see the P-wave modulus
/// `M = λ + 2μ` rather than `E`, which lowers `ξ` by `√(E/M)`; the estimate
/// keeps Munjiza's `E`.)
///
/// # Choosing `η`
///
/// A case gives either
/// - `η` directly (Pa·s), used as is; or
/// - a damping ratio `ξ_h` for the element scale, with `h` a typical
///   element size (e.g. the mean edge length of the mesh):
///   `η = ξ_h · critical_viscosity(h, E, ρ)`. `ξ_h = 1` is Munjiza's
///   usual choice for quasi-static loading; use `ξ_h ≪ 1` where wave
///   propagation matters.
///
/// Viscosity also shortens the stable explicit time step (for central
/// differences `Δt ≤ (2/ω_max)(√(1 + ξ²) − ξ)`); the solver must account
/// for it.
#[inline]
pub fn critical_viscosity(h: Real, young: Real, density: Real) -> Real {
    2.0 * h * (young * density).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rock() -> ElasticParams {
        // Table 1 of the reference paper (Brazilian test).
        ElasticParams { young: 26e9, poisson: 0.2, density: 2340.0, viscosity: 0.0 }
    }

    fn rel(a: Real, b: Real) -> Real {
        (a - b).abs() / b.abs()
    }

    /// E = 1, ν = 1/4 gives the textbook λ = μ = 2/5, M = 6/5 (exact in
    /// binary up to one rounding each).
    #[test]
    fn quarter_poisson_gives_equal_lame_constants() {
        let m = ElasticParams { young: 1.0, poisson: 0.25, density: 1.0, viscosity: 0.0 }.validate().unwrap();
        assert!(rel(m.lambda(), 0.4) < 1e-15);
        assert!(rel(m.mu(), 0.4) < 1e-15);
        assert!(rel(m.p_wave_modulus(), 1.2) < 1e-15);
    }

    /// Lamé constants reproduce E and ν through the inverse relations
    /// E = μ(3λ + 2μ)/(λ + μ), ν = λ / (2(λ + μ)) (round-off only).
    #[test]
    fn lame_constants_invert_to_young_and_poisson() {
        let m = rock().validate().unwrap();
        let (l, mu) = (m.lambda(), m.mu());
        assert!(rel(mu * (3.0 * l + 2.0 * mu) / (l + mu), m.young()) < 1e-14);
        assert!(rel(l / (2.0 * (l + mu)), m.poisson()) < 1e-14);
        assert_eq!(m.params(), rock());
    }

    /// c_p = √(E(1−ν)/((1+ν)(1−2ν)ρ)); for the paper's rock (E = 26 GPa,
    /// ν = 0.2, ρ = 2340 kg/m³) that is √(10/9 · 26e9 / 2340) ≈ 3513.6 m/s.
    #[test]
    fn p_wave_speed_of_paper_rock() {
        let m = rock().validate().unwrap();
        let expected = (26e9 * 0.8 / (1.2 * 0.6) / 2340.0_f64).sqrt();
        assert!(rel(m.p_wave_speed(), expected) < 1e-14);
        assert!((m.p_wave_speed() - 3513.642).abs() < 1e-3);
    }

    /// η_crit = 2h√(Eρ): for h = 1 mm and the paper's rock,
    /// 2e-3 · √(26e9 · 2340) ≈ 1.5600e4 Pa·s; and the damping ratio of
    /// the k = 1/h mode, η k / (2√(Eρ)), is exactly 1 at η = η_crit.
    #[test]
    fn critical_viscosity_critically_damps_the_element_mode() {
        let m = rock().validate().unwrap();
        let h = 1e-3;
        let eta = m.critical_viscosity(h);
        assert!(rel(eta, 2e-3 * (26e9_f64 * 2340.0).sqrt()) < 1e-15);
        assert!((eta - 1.56e4).abs() < 1.0);
        let xi = eta * (1.0 / h) / (2.0 * (m.young() * m.density()).sqrt());
        assert!((xi - 1.0).abs() < 1e-15);
    }

    #[test]
    fn error_names_the_parameter_and_reason() {
        let err = ElasticParams { poisson: 0.5, ..rock() }.validate().unwrap_err();
        assert_eq!(err.name(), "poisson");
        let msg = err.to_string();
        assert!(msg.contains("`poisson`") && msg.contains("(-1, 0.5)"), "{msg}");
    }
}
