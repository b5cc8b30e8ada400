//! Parameter validation: every bad parameter is rejected with its name and
//! the reason, good and bad inputs side by side.
//!
//! Ranges (any linear elasticity text, e.g. Bonet and Wood 1997 §6.5):
//! `E > 0`; `μ = E/(2(1+ν)) > 0` needs `ν > −1` and the bulk modulus
//! `K = E/(3(1−2ν)) > 0` finite needs `ν < 1/2`; `ρ > 0`; `η ≥ 0` (a
//! negative viscosity injects energy). NaN and ±∞ are rejected before the
//! range check.

use femdem_material::{ElasticParams, MaterialError};

const GOOD: ElasticParams = ElasticParams { young: 26e9, poisson: 0.2, density: 2340.0, viscosity: 1.0e4 };

/// (description, params, expected parameter name, expected message).
fn bad_cases() -> Vec<(&'static str, ElasticParams, &'static str, &'static str)> {
    let nan = f64::NAN;
    let inf = f64::INFINITY;
    vec![
        (
            "zero E",
            ElasticParams { young: 0.0, ..GOOD },
            "young",
            "material parameter `young` = 0 is out of range: Young's modulus must be > 0 Pa",
        ),
        (
            "negative E",
            ElasticParams { young: -1e9, ..GOOD },
            "young",
            "material parameter `young` = -1000000000 is out of range: Young's modulus must be > 0 Pa",
        ),
        ("NaN E", ElasticParams { young: nan, ..GOOD }, "young", "material parameter `young` must be finite, got NaN"),
        (
            "infinite E",
            ElasticParams { young: inf, ..GOOD },
            "young",
            "material parameter `young` must be finite, got inf",
        ),
        (
            "ν = 0.5 (incompressible)",
            ElasticParams { poisson: 0.5, ..GOOD },
            "poisson",
            "material parameter `poisson` = 0.5 is out of range: Poisson's ratio must lie in the open interval (-1, 0.5) for positive, finite shear and bulk moduli",
        ),
        (
            "ν > 0.5",
            ElasticParams { poisson: 0.7, ..GOOD },
            "poisson",
            "material parameter `poisson` = 0.7 is out of range: Poisson's ratio must lie in the open interval (-1, 0.5) for positive, finite shear and bulk moduli",
        ),
        (
            "ν = −1",
            ElasticParams { poisson: -1.0, ..GOOD },
            "poisson",
            "material parameter `poisson` = -1 is out of range: Poisson's ratio must lie in the open interval (-1, 0.5) for positive, finite shear and bulk moduli",
        ),
        (
            "NaN ν",
            ElasticParams { poisson: nan, ..GOOD },
            "poisson",
            "material parameter `poisson` must be finite, got NaN",
        ),
        (
            "zero ρ",
            ElasticParams { density: 0.0, ..GOOD },
            "density",
            "material parameter `density` = 0 is out of range: density must be > 0 kg/m³",
        ),
        (
            "negative ρ",
            ElasticParams { density: -2.0, ..GOOD },
            "density",
            "material parameter `density` = -2 is out of range: density must be > 0 kg/m³",
        ),
        (
            "infinite ρ",
            ElasticParams { density: inf, ..GOOD },
            "density",
            "material parameter `density` must be finite, got inf",
        ),
        (
            "negative η",
            ElasticParams { viscosity: -1e-9, ..GOOD },
            "viscosity",
            "material parameter `viscosity` = -0.000000001 is out of range: viscosity must be >= 0 Pa·s (a negative value would feed energy in)",
        ),
        (
            "NaN η",
            ElasticParams { viscosity: nan, ..GOOD },
            "viscosity",
            "material parameter `viscosity` must be finite, got NaN",
        ),
        (
            "−∞ η",
            ElasticParams { viscosity: -inf, ..GOOD },
            "viscosity",
            "material parameter `viscosity` must be finite, got -inf",
        ),
    ]
}

#[test]
fn each_bad_parameter_is_rejected_with_its_name_and_reason() {
    for (what, params, name, message) in bad_cases() {
        let err = params.validate().expect_err(what);
        assert_eq!(err.name(), name, "{what}");
        assert_eq!(err.to_string(), message, "{what}");
    }
}

#[test]
fn the_first_bad_parameter_is_reported() {
    let err = ElasticParams { young: -1.0, poisson: 2.0, density: -1.0, viscosity: -1.0 }.validate().unwrap_err();
    assert!(matches!(err, MaterialError::OutOfRange { name: "young", .. }));
}

/// Edges of the admissible set are accepted: ν just inside (−1, 0.5),
/// η = 0 (no damping), tiny but positive E and ρ.
#[test]
fn limits_inside_the_ranges_are_accepted() {
    for p in [
        GOOD,
        ElasticParams { poisson: 0.499_999, ..GOOD },
        ElasticParams { poisson: -0.999_999, ..GOOD },
        ElasticParams { poisson: 0.0, ..GOOD },
        ElasticParams { viscosity: 0.0, ..GOOD },
        ElasticParams { young: 1e-300, density: 1e-300, ..GOOD },
    ] {
        let m = p.validate().unwrap_or_else(|e| panic!("{p:?}: {e}"));
        assert!(m.lambda().is_finite() && m.mu() > 0.0 && m.p_wave_speed().is_finite());
        assert_eq!(m.params(), p);
    }
}
