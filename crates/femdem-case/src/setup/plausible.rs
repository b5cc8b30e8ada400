//! Warnings for material values that are legal but lie outside what any
//! quasi-brittle solid has: the marks of a unit slip (g/cm³ for kg/m³, MPa
//! or GPa for Pa, radians for degrees, N/mm for J/m²). A case may mean
//! them (a scaled model, a numerical experiment), so they warn, never
//! refuse.

use crate::format::MaterialSpec;

/// Densities of solids, kg/m³: below the lightest rocks (pumice, ~250) and
/// foamed concretes (~300) by a margin, above osmium (22,590).
pub const DENSITY: (f64, f64) = (100.0, 25_000.0);

/// Young's moduli of solids, Pa: from soft rubber (~10⁶) to diamond
/// (~1.2·10¹²).
pub const YOUNG: (f64, f64) = (1.0e6, 2.0e12);

/// Fracture energies, J/m²: from glass and silicon (a few J/m²) to tough
/// metals' (~10⁵); rocks and concretes lie at 10–500.
pub const FRACTURE_ENERGY: (f64, f64) = (1.0, 1.0e5);

/// A strength above this fraction of E would put the peak at a strain of
/// more than 10%, which no brittle material reaches.
pub const STRENGTH_OVER_YOUNG: f64 = 0.1;

/// A strength below this fraction of E would put the peak at a strain
/// below 10⁻⁶ (3 Pa for 3 MPa against a rock's tens of GPa).
pub const STRENGTH_OVER_YOUNG_MIN: f64 = 1e-6;

/// A joint penalty below E: a joint's compliance `h/p₀` then exceeds its
/// tets' `h/E`, and the jointed body is far softer than E says (the
/// paper's default is 10 E, Eq. 9).
pub const PENALTY_OVER_YOUNG_MIN: f64 = 1.0;

/// Poisson's ratios above this are nearly incompressible: the bulk
/// modulus is more than 50 times the shear modulus, and the stable step
/// shrinks with the dilatational wave speed (ν = 0.4999999 made it 400
/// times smaller).
pub const POISSON_MAX: f64 = 0.49;

/// A `damping_ratio` above 1 damps the element's top mode beyond critical,
/// and the stable step shrinks as `2/(√(ω²+β²/4)+β/2)` (5 made it 17 times
/// smaller): a percentage given as a fraction?
pub const DAMPING_RATIO_MAX: f64 = 1.0;

/// Coulomb coefficients of rock and concrete surfaces lie at 0.3–1 (up to
/// about 1.5 for rough joints); far above is an angle given for μ = tan φ.
pub const FRICTION_MAX: f64 = 2.0;

/// The warning for a Coulomb coefficient `mu` of `key` above
/// [`FRICTION_MAX`].
pub fn friction_warning(key: &str, mu: f64) -> Option<String> {
    (mu.is_finite() && mu > FRICTION_MAX).then(|| {
        format!(
            "`{key}` = {mu} is a Coulomb coefficient far above rock's 0.3–1 (> {FRICTION_MAX}); if {mu} is a \
             friction angle in degrees, μ = tan φ = {:.3}",
            mu.to_radians().tan()
        )
    })
}

/// The warnings for material `s` (empty when every value is plausible),
/// each naming the key, the value with its unit, the range and the slip
/// it suggests.
pub fn material_warnings(s: &MaterialSpec) -> Vec<String> {
    let mut out = Vec::new();
    let mut outside = |key: &str, v: f64, (lo, hi): (f64, f64), unit: &str, low: &str| {
        if v.is_finite() && !(lo..=hi).contains(&v) {
            // Below the range a common slip is named; above it, none is.
            let hint = if v < lo { low } else { "check its unit" };
            out.push(format!(
                "`{key}` = {v:e} {unit} lies outside [{lo:e}, {hi:e}] {unit}, the range of solids; {hint}"
            ));
        }
    };
    outside("density", s.density, DENSITY, "kg/m³", "is it in g/cm³ (× 1000 for kg/m³)?");
    outside("young", s.young, YOUNG, "Pa", "is it in MPa or GPa (× 10⁶ or × 10⁹ for Pa)?");
    for (key, v) in [("fracture_energy", s.fracture_energy), ("fracture_energy_shear", s.fracture_energy_shear)] {
        if let Some(v) = v {
            outside(key, v, FRACTURE_ENERGY, "J/m²", "is it in N/mm (× 1000 for J/m² = N/m)?");
        }
    }
    for (key, v) in [("tensile_strength", s.tensile_strength), ("cohesion", s.cohesion)] {
        if let Some(v) = v.filter(|v| s.young > 0.0 && *v > STRENGTH_OVER_YOUNG * s.young) {
            out.push(format!(
                "`{key}` = {v:e} Pa is more than {STRENGTH_OVER_YOUNG} × young ({:e} Pa): the joints would peak at \
                 a strain above 10%; are both in Pa?",
                s.young
            ));
        }
    }
    for (key, v) in [("tensile_strength", s.tensile_strength), ("cohesion", s.cohesion)] {
        if let Some(v) = v.filter(|v| *v > 0.0 && *v < STRENGTH_OVER_YOUNG_MIN * s.young) {
            out.push(format!(
                "`{key}` = {v:.4e} Pa is less than {STRENGTH_OVER_YOUNG_MIN:e} × young ({:e} Pa): the joints \
                 would peak at a strain below 10⁻⁶; is it in MPa (× 10⁶ for Pa)?",
                s.young
            ));
        }
    }
    if let Some(p) = s.penalty.filter(|p| p.is_finite() && *p > 0.0 && *p < PENALTY_OVER_YOUNG_MIN * s.young) {
        out.push(format!(
            "`penalty` = {p:e} Pa is below young ({:e} Pa): each joint's compliance h/p₀ then exceeds its tets' \
             h/E and the jointed body is far softer than E says (the default is 10 E, Eq. 9); is it in MPa or GPa?",
            s.young
        ));
    }
    if s.poisson > POISSON_MAX && s.poisson < 0.5 {
        out.push(format!(
            "`poisson` = {} is nearly incompressible (> {POISSON_MAX}): the bulk modulus is {:.0} times the shear \
             modulus, and the stable step shrinks with the dilatational wave speed",
            s.poisson,
            2.0 * (1.0 + s.poisson) / (3.0 * (1.0 - 2.0 * s.poisson))
        ));
    }
    if let Some(r) = s.damping_ratio.filter(|r| r.is_finite() && *r > DAMPING_RATIO_MAX) {
        out.push(format!(
            "`damping_ratio` = {r} damps the element's top mode beyond critical (> {DAMPING_RATIO_MAX}), and the \
             stable step shrinks with it; is it a percentage (0.05 for 5%)?"
        ));
    }
    if let Some(phi) = s.friction_angle.filter(|phi| *phi > 0.0 && *phi < std::f64::consts::FRAC_PI_2) {
        out.push(format!(
            "`friction_angle` = {phi}° is below π/2 ≈ 1.571, as if given in radians ({:.1}°); the key is in degrees",
            phi.to_degrees()
        ));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn granite() -> MaterialSpec {
        MaterialSpec {
            region: "rock".into(),
            law: "neo-hookean".into(),
            density: 2700.0,
            young: 60.0e9,
            poisson: 0.25,
            viscosity: None,
            damping_ratio: None,
            penalty: None,
            tensile_strength: Some(8.0e6),
            cohesion: Some(25.0e6),
            friction_angle: Some(35.0),
            fracture_energy: Some(100.0),
            fracture_energy_shear: None,
            gf_calibration: None,
            joint_coupling: None,
        }
    }

    #[test]
    fn a_rock_in_si_units_gives_no_warning() {
        assert!(material_warnings(&granite()).is_empty(), "{:?}", material_warnings(&granite()));
        let glued = MaterialSpec { tensile_strength: None, cohesion: None, friction_angle: None, ..granite() };
        assert!(material_warnings(&glued).is_empty());
    }

    #[test]
    fn each_unit_slip_is_named_by_its_key() {
        let cases: [(MaterialSpec, &str); 13] = [
            (MaterialSpec { tensile_strength: Some(8.0), ..granite() }, "`tensile_strength` = 8.0000e0 Pa is less"),
            (MaterialSpec { cohesion: Some(25.0), ..granite() }, "is it in MPa (× 10⁶ for Pa)?"),
            (MaterialSpec { penalty: Some(6.0e4), ..granite() }, "`penalty` = 6e4 Pa is below young (6e10 Pa)"),
            (MaterialSpec { poisson: 0.4999999, ..granite() }, "`poisson` = 0.4999999 is nearly incompressible"),
            (MaterialSpec { damping_ratio: Some(5.0), ..granite() }, "`damping_ratio` = 5 damps the element's"),
            (
                MaterialSpec { density: 2.7, ..granite() },
                "`density` = 2.7e0 kg/m³ lies outside [1e2, 2.5e4] kg/m³, the range of solids; is it in g/cm³",
            ),
            (MaterialSpec { young: 60.0e3, ..granite() }, "`young` = 6e4 Pa"),
            (
                MaterialSpec { young: 60.0e18, ..granite() },
                "`young` = 6e19 Pa lies outside [1e6, 2e12] Pa, the range of solids; check its unit",
            ),
            (MaterialSpec { fracture_energy: Some(0.1), ..granite() }, "`fracture_energy` = 1e-1 J/m²"),
            (MaterialSpec { fracture_energy_shear: Some(2e6), ..granite() }, "`fracture_energy_shear` = 2e6 J/m²"),
            (
                MaterialSpec { density: 2.7e5, ..granite() },
                "2.7e5 kg/m³ lies outside [1e2, 2.5e4] kg/m³, the range of solids; check its unit",
            ),
            (MaterialSpec { tensile_strength: Some(8.0e9), ..granite() }, "`tensile_strength` = 8e9 Pa"),
            (MaterialSpec { friction_angle: Some(0.61), ..granite() }, "as if given in radians (35.0°)"),
        ];
        for (spec, words) in cases {
            // A modulus in kPa also makes the strengths too large for it.
            let w = material_warnings(&spec);
            assert!(w.iter().any(|w| w.contains(words)), "{words} not in {w:?}");
        }
    }

    #[test]
    fn plausible_neighbours_of_the_new_bounds_give_no_warning() {
        for spec in [
            MaterialSpec { penalty: Some(60.0e9), poisson: 0.45, damping_ratio: Some(1.0), ..granite() },
            MaterialSpec { tensile_strength: Some(0.1e6), cohesion: Some(0.0), ..granite() },
        ] {
            assert!(material_warnings(&spec).is_empty(), "{:?}", material_warnings(&spec));
        }
        assert_eq!(friction_warning("contact.friction", 1.5), None);
        let w = friction_warning("contact.friction", 30.0).expect("a warning");
        assert!(w.contains("μ = tan φ = 0.577"), "{w}");
    }

    #[test]
    fn frictionless_joints_are_not_taken_for_radians() {
        let spec = MaterialSpec { friction_angle: Some(0.0), ..granite() };
        assert!(material_warnings(&spec).is_empty());
    }
}
