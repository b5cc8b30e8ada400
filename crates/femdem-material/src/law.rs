//! The constitutive laws: stress and stored energy as functions of the
//! deformation gradient `F` and the velocity gradient `L`.
//!
//! # Laws
//!
//! [`Law::NeoHookean`] is the paper's law (§2.2, Eq. 1–2; Bonet and Wood
//! 1997), the compressible neo-Hookean solid with Kelvin–Voigt viscosity:
//!
//! - Eq. 1: `T = μ/J (B − I) + λ/J ln J I + η D`,
//! - Eq. 2: `D = ½ (L + Lᵀ)`,
//!
//! with `B = F Fᵀ`, `J = det F` and `L = ∂v/∂x` the velocity gradient with
//! respect to the **current** configuration. Its stored energy per unit
//! reference volume is `W = μ/2 (tr B − 3) − μ ln J + λ/2 (ln J)²`, and
//! `∂W/∂F = J T_el F⁻ᵀ` (the first Piola–Kirchhoff stress of the elastic
//! part of Eq. 1). It is objective: a rigid rotation of the current state
//! rotates `T` and leaves `W` unchanged.
//!
//! [`Law::LinearElastic`] is small-strain linear elasticity, for
//! verification against closed forms: `σ = λ tr ε I + 2μ ε + η D` with
//! `ε = ½(F + Fᵀ) − I`, `W = λ/2 (tr ε)² + μ ε:ε`. It is geometrically
//! linear: its first Piola–Kirchhoff stress is `σ` itself, so the tet
//! forces are linear in the nodal displacements (the classical linear FE
//! stiffness) and are the exact gradient of `W`. It is not objective; use it
//! for small rotations only.
//!
//! # Inverted and crushed elements (`J ≤` [`J_FLOOR`])
//!
//! Eq. 1 is singular at `J = 0` and undefined for `J < 0`. An explicit
//! FEMDEM run can still crush an element (a contact spike, an unstable
//! step), and one NaN would poison every node it touches. Below `J_FLOOR`
//! the laws therefore use `Ĵ = max(J, J_FLOOR)`:
//!
//! - the volumetric energy `U(J) = −μ ln J + λ/2 (ln J)²` is continued
//!   linearly, `U(J) = U(J_f) + U′(J_f)(J − J_f)` for `J < J_f`, so `W` is
//!   finite and C¹ for every `F` (no `+∞`: an energy balance summed over a
//!   mesh stays finite);
//! - [`first_piola_kirchhoff`] is the exact gradient of that `W`:
//!   `P = μ F + U′(Ĵ) cof F`, where `cof F = J F⁻ᵀ` (a polynomial in `F`)
//!   is `∂J/∂F`. Since `U′(J_f) = (λ ln J_f − μ)/J_f < 0` and large, the
//!   volumetric force always pushes the nodes towards larger `J`, also
//!   through `J = 0` and for `J < 0`;
//! - the viscous part of `P` is `η D cof F` (`= J η D F⁻ᵀ`), and
//!   [`tet_forces`](crate::tet_forces) feeds it the guarded velocity
//!   gradient `L̂ = Ḟ cof(F)ᵀ / Ĵ` (equal to `L = Ḟ F⁻¹` when `J ≥ J_f`,
//!   finite at `J = 0`); its power `P_v : Ḟ = η Ĵ D̂ : D̂`, `D̂ = sym(L̂)`,
//!   is never negative, so damping never feeds energy in;
//! - [`cauchy_stress`] is Eq. 1 evaluated with `Ĵ` in place of `J`: a
//!   finite report for output, dominated by the compressive volumetric
//!   term (no Cauchy stress exists for an inverted element).
//!
//! For `J ≥ J_FLOOR` everything is exactly Eq. 1–2. Finite inputs always
//! give finite outputs.
//!
//! # Energy at small strains
//!
//! `W = μ/2 (tr B − 3) − μ ln J + λ/2 (ln J)²` is of second order in the
//! strain, but `μ/2 (tr B − 3)` and `μ ln J` are each of first order: at a
//! strain of 10⁻⁹ they are 10⁹ times `W`, and evaluated as written their
//! difference keeps no correct digit (an elastic wave's energy came out
//! fifteen times too large). So `W` is evaluated from the Green–Lagrange
//! strain `E = ½ (FᵀF − I) = ½ (H + Hᵀ + HᵀH)`, `H = F − I`, which a
//! rotation leaves alone: `tr B − 3 = 2 tr E`, `J² = det(I + 2E) =
//! 1 + y` with `y = 2 tr E + 4 I₂(E) + 8 det E` (the characteristic
//! polynomial, `I₂ = ½((tr E)² − E:E)`), and
//! `W = μ/2 (y − ln(1 + y)) − 2μ I₂(E) − 4μ det E + λ/8 (ln(1 + y))²`,
//! with `y − ln(1 + y)` and `ln(1 + y)` from [`crate::log1p`]. Every term is
//! then of second order or is `ln J` itself, and `W` keeps its relative
//! precision: that of `E`, which `F` holds to about `ε / |E|`, and
//! `ε |H|² / |E|` more where the element is also rotated by `|H|` (the
//! rotation cancels in `H + Hᵀ + HᵀH`). This is done where `E:E < 10⁻²`;
//! at larger strains the form as written loses at most 10⁻¹⁴ and is the
//! better conditioned one for crushed elements. The stress is of first
//! order and keeps its digits as written; it is unchanged.

use crate::Material;
use crate::log1p::ln_1p_and_excess;
use femdem_core::{Mat3, Real};

/// The constitutive law of a tet region.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum Law {
    /// The paper's compressible neo-Hookean viscoelastic law (Eq. 1–2).
    #[default]
    NeoHookean,
    /// Small-strain, geometrically linear elasticity with the same viscous
    /// term, for verification: `σ = λ tr ε I + 2μ ε + η D`.
    LinearElastic,
}

/// The volume ratio below which the neo-Hookean law is continued
/// (see the [module documentation](self)): `J_FLOOR = 0.01`.
///
/// An element compressed to 1 % of its volume is far outside anything
/// Eq. 1 models for a quasi-brittle solid (which fails at volume changes
/// well under 1 %), so the continuation changes no physical result; it only
/// keeps crushed and inverted elements finite and restoring. Below the
/// floor the volumetric stiffness `U″` is zero, so the continuation adds no
/// stiffness that would shrink the stable time step. At the floor the restoring
/// volumetric stress is `|U′(J_f)| ≈ 460 λ + 100 μ`.
pub const J_FLOOR: Real = 1e-2;

/// Everything one law evaluation yields; the public functions pick from it.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Response {
    /// First Piola–Kirchhoff stress `P` (Pa), the force-producing stress.
    pub p: Mat3,
    /// Cauchy stress `T` (Pa), for output.
    pub cauchy: Mat3,
    /// Stored energy per unit reference volume `W` (J/m³).
    pub energy: Real,
}

/// Cofactor matrix `cof A = det(A) A⁻ᵀ`, a polynomial in `A` (defined for
/// singular `A`): its columns are `a₁ × a₂`, `a₂ × a₀`, `a₀ × a₁` for the
/// columns `aᵢ` of `A`. `∂ det A / ∂A = cof A`.
#[inline]
pub(crate) fn cofactor(a: &Mat3) -> Mat3 {
    let (c0, c1, c2) = (a.column(0), a.column(1), a.column(2));
    Mat3::from_columns(&[c1.cross(&c2), c2.cross(&c0), c0.cross(&c1)])
}

/// Symmetric part `½ (A + Aᵀ)`.
#[inline]
pub(crate) fn sym(a: &Mat3) -> Mat3 {
    (a + a.transpose()) * 0.5
}

/// The neo-Hookean stored energy per unit reference volume (module docs,
/// "Energy at small strains"). Where the Green–Lagrange strain
/// `E = ½ (H + Hᵀ + HᵀH)`, `H = F − I`, is small (`E:E < 10⁻²`) and
/// `J > 0` (so `J ≥ 0.7`), from `E`:
/// with `y = J² − 1 = det(I + 2E) − 1 = 2 tr E + 4 I₂(E) + 8 det E`,
/// `W = μ/2 (y − ln(1 + y)) − 2μ I₂(E) − 4μ det E + λ/8 (ln(1 + y))²`.
/// Elsewhere as written, `W = μ/2 (tr B − 3) + U(Ĵ) + U′(Ĵ)(J − Ĵ)`
/// (`ln_jh = ln Ĵ`, `du = U′(Ĵ)`; `Ĵ = J` above `J_FLOOR`), which loses at
/// most `ε / (E:E)`, 10⁻¹⁴, there, and keeps `ln J` from `J` itself for
/// crushed elements, where `y` would be a sum of large terms cancelling
/// to nearly −1. The two are the same function, since
/// `tr B − 3 = tr C − 3 = 2 tr E` and `ln J = ½ ln(1 + y)`.
#[inline]
fn neo_hookean_energy(lambda: Real, mu: Real, f: &Mat3, j: Real, jh: Real, ln_jh: Real, du: Real) -> Real {
    let e = green_lagrange(f);
    // C = FᵀF cannot tell a reflection from no deformation: J > 0 too.
    if j > 0.0 && e.norm_squared() < 1e-2 {
        energy_from_strain(lambda, mu, &e)
    } else {
        0.5 * mu * (f.norm_squared() - 3.0) + (0.5 * lambda * ln_jh - mu) * ln_jh + du * (j - jh)
    }
}

/// The Green–Lagrange strain `E = ½ (FᵀF − I)`, as `½ (H + Hᵀ + HᵀH)`,
/// `H = F − I`, so that a small strain keeps its digits.
#[inline]
fn green_lagrange(f: &Mat3) -> Mat3 {
    let h = f - Mat3::identity();
    (h + h.transpose() + h.transpose() * h) * 0.5
}

/// `W` from the Green–Lagrange strain `e`, for `J > 0`
/// ([`neo_hookean_energy`]).
#[inline]
fn energy_from_strain(lambda: Real, mu: Real, e: &Mat3) -> Real {
    let tr = e.trace();
    let i2 = 0.5 * (tr * tr - e.norm_squared());
    let det = e.column(0).dot(&e.column(1).cross(&e.column(2)));
    let (ln_c, excess) = ln_1p_and_excess(2.0 * tr + 4.0 * i2 + 8.0 * det);
    0.5 * mu * excess - 2.0 * mu * i2 - 4.0 * mu * det + 0.125 * lambda * ln_c * ln_c
}

/// Evaluates `law` at deformation gradient `f`, velocity gradient `l` and
/// `cof = cof f`, `j = det f` (computed once by the caller).
#[inline]
pub(crate) fn response(law: Law, m: &Material, f: &Mat3, l: &Mat3, cof: &Mat3, j: Real) -> Response {
    let (lambda, mu, eta) = (m.lambda(), m.mu(), m.viscosity());
    let d = sym(l);
    match law {
        Law::NeoHookean => {
            // Ĵ and the continued volumetric energy U, U′ (module docs).
            let jh = j.max(J_FLOOR);
            let ln_jh = jh.ln();
            let du = (lambda * ln_jh - mu) / jh;
            let energy = neo_hookean_energy(lambda, mu, f, j, jh, ln_jh, du);
            // P = μF + U′(Ĵ) cof F + η D cof F  (= J T F⁻ᵀ for J ≥ J_f).
            let p = f * mu + (Mat3::identity() * du + d * eta) * cof;
            // Eq. 1 with Ĵ: T = (μ (B − I) + λ ln Ĵ I)/Ĵ + η D.
            let b = f * f.transpose();
            let cauchy = b * (mu / jh) + Mat3::from_diagonal_element((lambda * ln_jh - mu) / jh) + d * eta;
            Response { p, cauchy, energy }
        }
        Law::LinearElastic => {
            let eps = sym(f) - Mat3::identity();
            let tr = eps.trace();
            let cauchy = Mat3::from_diagonal_element(lambda * tr) + eps * (2.0 * mu) + d * eta;
            let energy = 0.5 * lambda * tr * tr + mu * eps.norm_squared();
            Response { p: cauchy, cauchy, energy }
        }
    }
}

/// Cauchy stress `T` (Pa) of `law` at deformation gradient `f` and
/// current-configuration velocity gradient `l`.
///
/// - [`Law::NeoHookean`], Eq. 1–2: `T = μ/J (B − I) + λ/J ln J I + η D`,
///   `B = F Fᵀ`, `J = det F`, `D = ½(L + Lᵀ)`; for `J < J_FLOOR` evaluated
///   at `Ĵ = J_FLOOR` (module docs).
/// - [`Law::LinearElastic`]: `σ = λ tr ε I + 2μ ε + η D`,
///   `ε = ½(F + Fᵀ) − I`.
///
/// Symmetric whenever `l` is any matrix (only `sym(l)` enters).
#[inline]
pub fn cauchy_stress(law: Law, material: &Material, f: &Mat3, l: &Mat3) -> Mat3 {
    let cof = cofactor(f);
    let j = f.column(0).dot(&cof.column(0));
    response(law, material, f, l, &cof, j).cauchy
}

/// First Piola–Kirchhoff stress `P` (Pa): force per unit reference area,
/// the stress a reference-configuration force integration uses.
///
/// - [`Law::NeoHookean`]: `P = μ F + U′(Ĵ) cof F + η D cof F`, which is
///   `J T F⁻ᵀ` of Eq. 1 for `J ≥ J_FLOOR`, and whose elastic part is
///   `∂W/∂F` for every `F` (module docs).
/// - [`Law::LinearElastic`]: `P = σ` (geometrically linear).
#[inline]
pub fn first_piola_kirchhoff(law: Law, material: &Material, f: &Mat3, l: &Mat3) -> Mat3 {
    let cof = cofactor(f);
    let j = f.column(0).dot(&cof.column(0));
    response(law, material, f, l, &cof, j).p
}

/// Stored (elastic) energy per unit **reference** volume `W` (J/m³),
/// consistent with the elastic part of the stress (`P_el = ∂W/∂F`):
///
/// - [`Law::NeoHookean`]: `W = μ/2 (tr B − 3) − μ ln J + λ/2 (ln J)²`,
///   continued linearly in `J` below `J_FLOOR`, so it is finite (and C¹)
///   for inverted elements too (module docs);
/// - [`Law::LinearElastic`]: `W = λ/2 (tr ε)² + μ ε:ε`.
///
/// `W = 0` at `F = I`, and `W > 0` for any other stretch.
#[inline]
pub fn strain_energy_density(law: Law, material: &Material, f: &Mat3) -> Real {
    let cof = cofactor(f);
    let j = f.column(0).dot(&cof.column(0));
    response(law, material, f, &Mat3::zeros(), &cof, j).energy
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ElasticParams;

    fn material(viscosity: Real) -> Material {
        ElasticParams { young: 26e9, poisson: 0.2, density: 2340.0, viscosity }.validate().unwrap()
    }

    const LAWS: [Law; 2] = [Law::NeoHookean, Law::LinearElastic];

    /// `cof A = det(A) A⁻ᵀ` for an invertible A; `Aᵀ cof A = det(A) I`.
    #[test]
    fn cofactor_is_determinant_times_inverse_transpose() {
        let a = Mat3::new(1.2, 0.3, -0.1, 0.05, 0.9, 0.2, -0.3, 0.1, 1.1);
        let expected = a.try_inverse().unwrap().transpose() * a.determinant();
        assert!((cofactor(&a) - expected).norm() < 1e-14);
        let singular = Mat3::new(1.0, 2.0, 3.0, 2.0, 4.0, 6.0, 0.0, 1.0, 1.0);
        assert!((singular.transpose() * cofactor(&singular)).norm() < 1e-14);
    }

    /// Eq. 1 at F = I, L = 0: B − I = 0 and ln 1 = 0, so T = 0; likewise
    /// ε = 0 for the linear law. The energy vanishes too.
    #[test]
    fn reference_state_is_stress_and_energy_free() {
        let m = material(1e5);
        for law in LAWS {
            let s = cauchy_stress(law, &m, &Mat3::identity(), &Mat3::zeros());
            assert_eq!(s, Mat3::zeros(), "{law:?}");
            assert_eq!(first_piola_kirchhoff(law, &m, &Mat3::identity(), &Mat3::zeros()), Mat3::zeros());
            assert_eq!(strain_energy_density(law, &m, &Mat3::identity()), 0.0);
        }
    }

    /// Simple shear F = I + γ e_x ⊗ e_y has J = 1 and
    /// B = [[1+γ², γ, 0], [γ, 1, 0], [0, 0, 1]], so Eq. 1 gives exactly
    /// T_xy = μγ, T_xx = μγ² (the Poynting effect), T_yy = T_zz = 0.
    #[test]
    fn neo_hookean_simple_shear_has_closed_form() {
        let m = material(0.0);
        let g = 0.3;
        let mut f = Mat3::identity();
        f[(0, 1)] = g;
        let t = cauchy_stress(Law::NeoHookean, &m, &f, &Mat3::zeros());
        let mu = m.mu();
        let tol = 1e-14 * mu;
        assert!((t[(0, 1)] - mu * g).abs() < tol && (t[(1, 0)] - mu * g).abs() < tol);
        assert!((t[(0, 0)] - mu * g * g).abs() < tol);
        assert!(t[(1, 1)].abs() < tol && t[(2, 2)].abs() < tol);
        assert!(t[(0, 2)].abs() < tol && t[(1, 2)].abs() < tol);
    }

    /// Only sym(L) enters: a spin L = −Lᵀ gives no viscous stress, and
    /// any L gives a symmetric stress.
    #[test]
    fn spin_is_not_damped() {
        let m = material(1e6);
        let w = Mat3::new(0.0, -2.0, 1.0, 2.0, 0.0, -3.0, -1.0, 3.0, 0.0);
        for law in LAWS {
            assert_eq!(cauchy_stress(law, &m, &Mat3::identity(), &w), Mat3::zeros());
            let l = Mat3::new(1.0, 2.0, 3.0, -4.0, 5.0, 6.0, 7.0, 8.0, -9.0);
            let t = cauchy_stress(law, &m, &Mat3::identity(), &l);
            assert_eq!(t, t.transpose());
        }
    }

    /// The continuation below J_FLOOR: W is C¹ across the floor (values
    /// and slopes along F = diag(J, 1, 1) match at J_f from both sides to
    /// the finite-difference error), and crushed/inverted states give finite
    /// energy, finite stress and a compressive mean Cauchy stress.
    #[test]
    fn crushed_and_inverted_elements_stay_finite_and_restoring() {
        let m = material(1e5);
        let w = |j: Real| {
            strain_energy_density(Law::NeoHookean, &m, &Mat3::from_diagonal(&femdem_core::Vec3::new(j, 1.0, 1.0)))
        };
        let h = 1e-9;
        let (below, at, above) = (w(J_FLOOR - h), w(J_FLOOR), w(J_FLOOR + h));
        let slope_below = (at - below) / h;
        let slope_above = (above - at) / h;
        // One-sided slopes of a C¹ function differ by ≈ h W''/2 with
        // W'' = (λ(1 − ln J_f) + μ)/J_f² ≈ 5e14 Pa just above the floor
        // (0 below), i.e. ≈ 2.5e5 Pa against |W'| ≈ 4.4e12 Pa (6e-8
        // relative); round-off adds ~1e-16 · W / h ≈ 13 Pa. A kink would
        // show as an O(1) relative jump.
        assert!((slope_below - slope_above).abs() < 1e-6 * slope_above.abs(), "{slope_below} vs {slope_above}");
        for j in [J_FLOOR / 2.0, 0.0, -0.5, -3.0] {
            let f = Mat3::from_diagonal(&femdem_core::Vec3::new(j, 1.0, 1.0));
            let l = Mat3::from_diagonal(&femdem_core::Vec3::new(-1.0, 0.0, 0.0));
            let t = cauchy_stress(Law::NeoHookean, &m, &f, &l);
            let p = first_piola_kirchhoff(Law::NeoHookean, &m, &f, &l);
            assert!(t.iter().chain(p.iter()).all(|x| x.is_finite()), "J = {j}");
            assert!(w(j).is_finite());
            assert!(t.trace() < 0.0, "J = {j}: mean stress must be compressive");
            // The force-producing P pushes towards larger J: P : cof F < 0
            // means the energy decreases as J grows (dW = P : dF).
            let cof = cofactor(&f);
            let elastic = first_piola_kirchhoff(Law::NeoHookean, &m, &f, &Mat3::zeros());
            assert!((elastic - f * m.mu()).component_mul(&cof).sum() < 0.0);
        }
    }

    /// At small strains the neo-Hookean energy is the linear law's,
    /// `λ/2 (tr ε)² + μ ε:ε`, up to terms of relative order `|H|`: checked
    /// on uniaxial stress, pure shear and a general gradient, from
    /// `|H| = 10⁻³` down to 10⁻¹¹, within `4 |H|` plus 10⁻¹³ (both laws
    /// read the same `F`, so what `F` has lost of `H` is common to both;
    /// the 10⁻¹³ is a few hundred ulps of the terms' round-off). The same
    /// strains rotated by one radian (`R F`, against the linear law of `F`:
    /// `W` is objective) within `4 |H|` plus `16 ε / |H|`: `R F` rounds
    /// each entry by about `ε`, which the strain, of size `|H|`, carries at
    /// `ε / |H|` relative, doubled in `W`, and again in the rotation's
    /// cancellation in `H + Hᵀ + HᵀH` (`|R − I|² ≈ 1.8`). Evaluated as
    /// `μ/2 (tr B − 3) − μ ln J + …` the energy at `|H| = 10⁻⁹` has no
    /// correct digit (module docs, "Energy at small strains").
    #[test]
    fn energy_at_small_strains_is_the_linear_laws() {
        let m = material(0.0);
        let nu = m.poisson();
        let general = Mat3::new(0.3, -0.7, 0.2, 0.5, -0.4, 0.9, -0.1, 0.6, 0.8);
        for size in [1e-3, 1e-5, 1e-7, 1e-9, 3e-10, 1e-11] {
            let shapes = [
                Mat3::from_diagonal(&femdem_core::Vec3::new(1.0, -nu, -nu)),
                Mat3::new(0.0, 1.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0),
                general,
            ];
            for shape in shapes {
                let f = Mat3::identity() + shape * size;
                let nh = strain_energy_density(Law::NeoHookean, &m, &f);
                let lin = strain_energy_density(Law::LinearElastic, &m, &f);
                assert!(lin > 0.0);
                let err = (nh / lin - 1.0).abs();
                assert!(err < 4.0 * size * shape.norm() + 1e-13, "|H| = {size:e}, {shape}: {nh:e} vs {lin:e}");
                let turn = nalgebra::Rotation3::from_axis_angle(&femdem_core::Vec3::y_axis(), 1.0);
                let turned = strain_energy_density(Law::NeoHookean, &m, &(turn.matrix() * f));
                let err = (turned / lin - 1.0).abs();
                let allowed = 4.0 * size * shape.norm() + 16.0 * Real::EPSILON / (size * shape.norm());
                assert!(err < allowed, "turned, |H| = {size:e}, {shape}: {turned:e} vs {lin:e}");
            }
        }
    }

    /// The energy's two forms are one function: at strains above the
    /// switch (`E:E` from about 0.01 to 0.4), plain and rotated, the form
    /// from `E` and the form as written agree within 10⁻¹³ of `W` (both
    /// keep 14 digits or more there).
    #[test]
    fn the_energys_two_forms_agree_where_both_keep_their_digits() {
        let m = material(0.0);
        let general = Mat3::new(0.3, -0.7, 0.2, 0.5, -0.4, 0.9, -0.1, 0.6, 0.8);
        let turn = nalgebra::Rotation3::from_axis_angle(&femdem_core::Vec3::x_axis(), 0.7);
        for size in [0.07, 0.1, 0.2, 0.4] {
            for f in [Mat3::identity() + general * size, turn.matrix() * (Mat3::identity() + general * size)] {
                let e = green_lagrange(&f);
                let written = strain_energy_density(Law::NeoHookean, &m, &f);
                let j = f.determinant();
                let from_strain = energy_from_strain(m.lambda(), m.mu(), &e);
                assert!(j > J_FLOOR && written > 0.0);
                assert!((from_strain - written).abs() < 1e-13 * written, "{size}: {from_strain:e} vs {written:e}");
            }
        }
    }

    /// Linear law, uniaxial stress: F = diag(1+ε, 1−νε, 1−νε) gives
    /// σ_xx = E ε and σ_yy = σ_zz = 0, since λ(1−2ν) − 2μν = 0 and
    /// λ(1−2ν) + 2μ = E (exact up to round-off).
    #[test]
    fn linear_uniaxial_stress_recovers_young_modulus() {
        let m = material(0.0);
        let (e, nu) = (1e-3, m.poisson());
        let f = Mat3::from_diagonal(&femdem_core::Vec3::new(1.0 + e, 1.0 - nu * e, 1.0 - nu * e));
        let s = cauchy_stress(Law::LinearElastic, &m, &f, &Mat3::zeros());
        let tol = 1e-12 * m.young() * e;
        assert!((s[(0, 0)] - m.young() * e).abs() < tol);
        assert!(s[(1, 1)].abs() < tol && s[(2, 2)].abs() < tol);
        // W = ½ σ:ε = ½ E ε² for uniaxial stress.
        let w = strain_energy_density(Law::LinearElastic, &m, &f);
        assert!((w - 0.5 * m.young() * e * e).abs() < 1e-12 * w);
    }
}
