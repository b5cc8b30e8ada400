//! The elastic shortening of a disc pressed between two flat rigid
//! platens: the closed form a Brazilian run's load–strain curve (Eq. 21–22)
//! is compared with before anything fails.
//!
//! A disc of radius R and thickness t carries the load F, P = F/t per unit
//! length, on two contact strips of half-width b (two-dimensional Hertz
//! contact of a cylinder on a rigid flat; Johnson, *Contact Mechanics*,
//! 1985, §5.6):
//!
//! b = √(4 P R / (π E′))
//!
//! Along the loaded diameter the stress is, while b ≪ R, the Hertz
//! (McEwen) field of each strip as if on a half-plane, plus Frocht's
//! uniform tension P/(πR) that frees the rim (the superposition of
//! [`crate::hondros`], with each point load spread over its strip). At
//! depth z below a strip, with p₀ = 2P/(πb):
//!
//! σ_z = −p₀ b / √(b² + z²),  σ_x = −p₀ b³ / (s (b² + 2z² + 2zs)), s = √(b² + z²)
//!
//! Integrating the strain along the diameter (z from 0 to 2R, for b ≪ R:
//! ∫σ_z dz = −(2P/π) ln(4R/b), ∫σ_x dz = −P/π, so the two σ_x strips
//! cancel the uniform tension's share and only σ_y is left):
//!
//! Δ = (2P / (π E′)) [2 ln(4R/b) − 1],  ε_yy = Δ / (2R) (Eq. 22)
//!
//! with E′ = E/(1 − ν²) in plane strain and E′ = E in plane stress. A disc
//! 15 mm thick and 40 mm across is neither; the two bound it within a
//! factor 1 − ν² (4% at ν = 0.2), plane strain the stiffer. Δ is the
//! approach of the platens when they are rigid and the disc is the only
//! compliance: a run's own strain adds the joints' penalty compliance and
//! the contact's penetration to it. The strain grows more slowly than the
//! load (the strip widens as the load rises, and a wider strip presses the
//! disc less deep), so the load–strain curve steepens even while
//! everything is elastic.

use std::f64::consts::PI;

use crate::brazilian::Disc;

/// Which two-dimensional idealisation of the disc.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Plane {
    /// Thin disc: σ_z = 0 through the thickness; E′ = E.
    Stress,
    /// Long cylinder: ε_z = 0; E′ = E / (1 − ν²).
    Strain,
}

/// An isotropic elastic disc.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Elastic {
    /// Young's modulus E, Pa.
    pub young: f64,
    /// Poisson's ratio ν.
    pub poisson: f64,
}

impl Elastic {
    /// The plane modulus E′ of `plane`, Pa.
    pub fn plane_modulus(self, plane: Plane) -> f64 {
        match plane {
            Plane::Stress => self.young,
            Plane::Strain => self.young / (1.0 - self.poisson * self.poisson),
        }
    }
}

/// Half-width b of each contact strip under load `f` (N), m:
/// `b = √(4 P R / (π E′))`, P = f/t.
pub fn half_width(disc: Disc, material: Elastic, plane: Plane, f: f64) -> f64 {
    let p = f / disc.thickness;
    (4.0 * p * 0.5 * disc.diameter / (PI * material.plane_modulus(plane))).sqrt()
}

/// The platens' approach Δ (m) that shortens the disc elastically under
/// load `f` (N): `Δ = (2P/(π E′)) [2 ln(4R/b) − 1]`.
pub fn shortening(disc: Disc, material: Elastic, plane: Plane, f: f64) -> f64 {
    if f <= 0.0 {
        return 0.0;
    }
    let p = f / disc.thickness;
    let b = half_width(disc, material, plane, f);
    2.0 * p / (PI * material.plane_modulus(plane)) * (2.0 * (2.0 * disc.diameter / b).ln() - 1.0)
}

/// The strain ε_yy = Δ/d of Eq. 22 under load `f` (N).
pub fn strain(disc: Disc, material: Elastic, plane: Plane, f: f64) -> f64 {
    shortening(disc, material, plane, f) / disc.diameter
}

#[cfg(test)]
mod tests {
    use super::*;

    const DISC: Disc = Disc { diameter: 0.04, thickness: 0.015 };
    const ROCK: Elastic = Elastic { young: 26.0e9, poisson: 0.2 };

    /// Composite Simpson's rule over z = b sinh u, u in [0, asinh(z_max/b)],
    /// which spreads the points where the strip's field varies (z ≲ b).
    fn integral(b: f64, z_max: f64, g: impl Fn(f64) -> f64) -> f64 {
        let n = 20_000;
        let top = (z_max / b).asinh();
        let h = top / n as f64;
        let f = |u: f64| g(b * u.sinh()) * b * u.cosh();
        let mut sum = f(0.0) + f(top);
        for i in 1..n {
            sum += if i % 2 == 1 { 4.0 } else { 2.0 } * f(i as f64 * h);
        }
        sum * h / 3.0
    }

    /// The strip's field on its axis at depth z under the line load p
    /// spread over half-width b: (σ_z, σ_x), Pa.
    fn strip(p: f64, b: f64, z: f64) -> (f64, f64) {
        let p0 = 2.0 * p / (PI * b);
        let s = (b * b + z * z).sqrt();
        (-p0 * b / s, -p0 * b.powi(3) / (s * (b * b + 2.0 * z * z + 2.0 * z * s)))
    }

    /// The closed form's logarithm and constant are the asymptotics of the
    /// superposed fields for b ≪ R: integrating those fields' strain along
    /// the diameter numerically, without the asymptotics, must give the
    /// same shortening up to the neglected terms, O((b/R)²): allowed
    /// (b/R)²/20 (7e-6 of 2.4e-5 at the largest load here, b/R = 0.022;
    /// Simpson's rule with 20,000 intervals adds < 1e-9).
    #[test]
    fn the_closed_form_is_the_integral_of_the_superposed_fields() {
        for plane in [Plane::Strain, Plane::Stress] {
            for f in [100.0, 1000.0, 3000.0] {
                let p = f / DISC.thickness;
                let r = 0.5 * DISC.diameter;
                let b = half_width(DISC, ROCK, plane, f);
                // Each strip's field over the whole diameter (depth 0 to
                // 2R), twice, plus the uniform tension P/(πR) over 2R.
                let sz = 2.0 * integral(b, 2.0 * r, |z| strip(p, b, z).0) + 2.0 * p / PI;
                let sx = 2.0 * integral(b, 2.0 * r, |z| strip(p, b, z).1) + 2.0 * p / PI;
                let nu = ROCK.poisson;
                let numeric = match plane {
                    Plane::Strain => -(1.0 + nu) / ROCK.young * ((1.0 - nu) * sz - nu * sx),
                    Plane::Stress => -(sz - nu * sx) / ROCK.young,
                };
                let closed = shortening(DISC, ROCK, plane, f);
                let rel = (numeric / closed - 1.0).abs();
                assert!(
                    rel < (b / r).powi(2) / 20.0,
                    "{plane:?}, F = {f} N: numeric {numeric:e}, closed {closed:e} ({rel:e})"
                );
            }
        }
    }

    /// Far from the strips the superposed field is Hondros' point-load
    /// field ([`crate::hondros::point_load`]): on the loaded diameter at
    /// the centre and halfway out, within O((b/z)²).
    #[test]
    fn far_from_the_strips_the_field_is_hondros() {
        let f = 2000.0;
        let p = f / DISC.thickness;
        let r = 0.5 * DISC.diameter;
        let b = half_width(DISC, ROCK, Plane::Strain, f);
        for y in [0.0, 0.5 * r, -0.5 * r] {
            let (top, bottom) = (strip(p, b, r - y), strip(p, b, r + y));
            let sy = top.0 + bottom.0 + p / (PI * r);
            let sx = top.1 + bottom.1 + p / (PI * r);
            let (hx, hy) = crate::hondros::point_load(DISC, f, 0.0, y);
            let depth = r - y.abs();
            let tol = 4.0 * (b / depth).powi(2);
            assert!((sy / hy - 1.0).abs() < tol, "σy at y = {y}: {sy:e} vs {hy:e}");
            assert!((sx / hx - 1.0).abs() < tol, "σx at y = {y}: {sx:e} vs {hx:e}");
        }
    }

    /// The strip holds the load: Hertz's half-ellipse of peak p₀ = 2P/(πb)
    /// over 2b integrates to P; b grows as √F, so doubling F takes ln 2
    /// off the bracket L = 2 ln(4R/b) − 1 and the strain grows by
    /// 2 (L − ln 2) / L, less than 2 (the curve steepens).
    #[test]
    fn the_strip_carries_the_load_and_the_curve_bends() {
        let f = 1500.0;
        let p = f / DISC.thickness;
        let b = half_width(DISC, ROCK, Plane::Stress, f);
        let p0 = 2.0 * p / (PI * b);
        let n = 100_000;
        let load: f64 = (0..n)
            .map(|i| {
                let x = -b + (i as f64 + 0.5) * 2.0 * b / n as f64;
                p0 * (1.0 - (x / b).powi(2)).sqrt() * 2.0 * b / n as f64
            })
            .sum();
        assert!((load / p - 1.0).abs() < 1e-6, "{load} vs {p}");
        let b4 = half_width(DISC, ROCK, Plane::Stress, 4.0 * f);
        assert!((b4 / b - 2.0).abs() < 1e-12);
        let (e1, e2) = (strain(DISC, ROCK, Plane::Stress, f), strain(DISC, ROCK, Plane::Stress, 2.0 * f));
        let l = 2.0 * (2.0 * DISC.diameter / b).ln() - 1.0;
        assert!((e2 / e1 - 2.0 * (l - 2f64.ln()) / l).abs() < 1e-12, "{e1:e} {e2:e}");
        assert!(e2 < 2.0 * e1);
        assert!(strain(DISC, ROCK, Plane::Strain, f) < e1);
        assert_eq!(strain(DISC, ROCK, Plane::Stress, 0.0), 0.0);
    }
}
