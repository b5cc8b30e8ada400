//! The cohesive joint law against the reference paper, §2.2 (Eq. 5–13,
//! Fig. 3), written from the paper independently of the crate's code.
//!
//! The test restates Eq. 12 (`z_ref`), the area `∫₀¹ z dD` (`area_ref`,
//! composite Simpson on `z_ref`), Eq. 6–7 (`δp = 2 f h / p0`), Eq. 10
//! (`δc = 3 Gf / f`, or `δp + Gf / (f ∫z)` for `GfCalibration::Exact`),
//! Eq. 11 and Eq. 13 (`ref_point`), and checks the crate's `point_stress`,
//! `joint_update` and `softening` against them.
//!
//! 1. Fig. 3 curves: pure opening, pure shear, mixed mode (proptest).
//! 2. Eq. 12: ends, flat start, monotone, area 0.386 (proptest).
//! 3. Eq. 5: Mohr–Coulomb shear strength with the tension cut-off.
//! 4. Energy to open a joint to failure = area under σ–δ; softening part
//!    vs Gf for both calibrations.
//! 5. Unloading/reloading below the damaged strength; no healing
//!    (proptest).
//! 6. Failure needs two Hammer points at zero stress; failure modes.
//! 7. Energy along unloading and mixed-mode paths (the two tests at the
//!    end; they fail on the law as of b629be7 — see their docs).
//!
//! Two choices the paper leaves open are taken as the crate documents them
//! (law.rs module doc), and said so where they are used:
//! * Eq. 5 needs `σ`, which (Eq. 13) depends on the shear damage, which
//!   needs `f_s`: the circle is cut by taking `σ` without shear damage.
//! * One damage `D` per point caps both hardening branches at `z(D) f`; for
//!   a single mode loaded monotonically this is Eq. 11 exactly (`D = 0` on
//!   the hardening branch), and it makes `τ` continuous at `δs = δsp` when
//!   the normal direction has softened (test 3), where the literal Eq. 11
//!   would jump from `f_s` to `z(Dn) f_s`.
//!
//! Parameter ranges (proptest): `E ∈ [1e9, 1e11]` Pa, `p0 ∈ [E, 10 E]`
//! (Eq. 9), `f_t ∈ [1, 20]` MPa, `φ ∈ [10°, 50°]`, `c = f_t (tan φ + [0.2,
//! 4])` (so `c > f_t tan φ`: the Mohr–Coulomb apex lies beyond the tensile
//! cut-off, as for rock), `G_ft ∈ [10, 300]` J/m², `G_fs = G_ft × [1, 20]`,
//! `h` log-uniform in `[1e-4, 0.1]` m but never so large that Eq. 10 gives
//! `δc < 2 δp` in either pure mode: the mesh must resolve the cohesive
//! zone, `h ≤ 3 G_f p0 / (4 f²)`. (Where it does not, the crate clamps δc to
//! δp: `degenerate_critical_displacement_fails_at_the_peak`.)

use std::sync::LazyLock;

use femdem_core::{Real, Vec3};
use femdem_fracture::softening;
use femdem_fracture::{
    FailureMode, GfCalibration, Joint, JointHistory, JointParams, joint_kinematics, joint_update, normal_stress,
    point_stress,
};
use proptest::prelude::*;

// ---------------------------------------------------------------------------
// Eq. 12, restated.

/// `a`, `b`, `c` of Eq. 12 (paper, after Eq. 12).
const ZA: Real = 0.63;
const ZB: Real = 1.8;
const ZC: i32 = 6;

/// Eq. 12 written as `z = g(D) q(D)`, `g = 1 − k e^{λD}`,
/// `k = (a+b−1)/(a+b)`, `λ = (a+bc)/((a+b)(1−a−b))`,
/// `q = a(1−D) + b(1−D)^c`, for `D ∈ [0, 1]`.
fn z_ref(d: Real) -> Real {
    let s = ZA + ZB;
    let k = (s - 1.0) / s;
    let lambda = (ZA + ZB * Real::from(ZC)) / (s * (1.0 - s));
    let g = 1.0 - k * (lambda * d).exp();
    let q = ZA * (1.0 - d) + ZB * (1.0 - d).powi(ZC);
    g * q
}

/// A bound on `|z′|` over `[0, 1]`: with `g ∈ (0, 1]`, `|g′| ≤ k|λ|`,
/// `q ∈ [0, a+b]`, `|q′| ≤ a + bc`: `|z′| ≤ |g′| q + g |q′| ≤ (a+b−1)|λ| + a
/// + bc ≈ 16.1`.
fn z_lipschitz() -> Real {
    let s = ZA + ZB;
    let lambda = (ZA + ZB * Real::from(ZC)) / (s * (1.0 - s));
    (s - 1.0) * lambda.abs() + ZA + ZB * Real::from(ZC)
}

/// `∫_{d0}^{d1} z_ref` by composite Simpson with `n` panels.
fn simpson(d0: Real, d1: Real, n: usize) -> Real {
    let h = (d1 - d0) / n as Real;
    (0..n)
        .map(|i| {
            let a = d0 + i as Real * h;
            h / 6.0 * (z_ref(a) + 4.0 * z_ref(a + 0.5 * h) + z_ref(a + h))
        })
        .sum()
}

/// `∫₀¹ z dD` (≈ 0.386). Simpson's error `h⁴ max|z⁗| / 2880` with
/// `h = 5e-5` is below 1e-18; round-off dominates (~1e-15).
static AREA: LazyLock<Real> = LazyLock::new(|| simpson(0.0, 1.0, 20_000));

fn area_ref() -> Real {
    *AREA
}

// ---------------------------------------------------------------------------
// Eq. 6, 7, 10, 11, 13, restated.

/// Peak displacement, Eq. 6–7.
fn dp_ref(p: &JointParams, h: Real, f: Real) -> Real {
    2.0 * f * h / p.penalty
}

/// Critical displacement, Eq. 10 (or the exact calibration); never below
/// δp (a Gf too small for the element fails at the peak).
fn dc_ref(p: &JointParams, f: Real, dp: Real, gf: Real) -> Real {
    let dc = match p.calibration {
        GfCalibration::Paper => 3.0 * gf / f,
        GfCalibration::Exact => dp + gf / (f * area_ref()),
    };
    dc.max(dp)
}

/// `[2r − r²] f`, the hardening branch of Eq. 11.
fn hard(f: Real, r: Real) -> Real {
    (2.0 * r - r * r) * f
}

/// Normalised softening displacement `(δ − δp)/(δc − δp)` in `[0, 1]`.
fn soft(d: Real, dp: Real, dc: Real) -> Real {
    if d <= dp {
        0.0
    } else if d >= dc {
        1.0
    } else {
        (d - dp) / (dc - dp)
    }
}

/// The reference point law for a fresh point (no history): `(σ, τ, D, f_s)`
/// at opening `dn` and slip magnitude `ds ≥ 0` (Eq. 5–7, 10, 11, 13).
/// Assumes `f_s > 0` (true for the parameter ranges used).
fn ref_point(j: &Joint, dn: Real, ds: Real) -> (Real, Real, Real, Real) {
    let p = &j.params;
    let (ft, c) = (p.tensile_strength, p.cohesion);
    let tan_phi = p.friction_angle.tan();
    let dnp = dp_ref(p, j.h, ft);
    let dnc = dc_ref(p, ft, dnp, p.gf_tension);
    let dn_soft = soft(dn, dnp, dnc);
    // σ without shear damage, for Eq. 5.
    let sigma0 = if dn < 0.0 {
        2.0 * dn / dnp * ft
    } else if dn <= dnp {
        hard(ft, dn / dnp)
    } else {
        z_ref(dn_soft) * ft
    };
    let fs = c - sigma0 * tan_phi;
    assert!(fs > 0.0, "reference assumes f_s > 0");
    let dsp = dp_ref(p, j.h, fs);
    let dsc = dc_ref(p, fs, dsp, p.gf_shear);
    let ds_soft = soft(ds, dsp, dsc);
    // Eq. 13.
    let d = if dn >= dnc || ds >= dsc {
        1.0
    } else if dn_soft > 0.0 && ds_soft > 0.0 {
        (dn_soft * dn_soft + ds_soft * ds_soft).sqrt().min(1.0)
    } else {
        dn_soft + ds_soft
    };
    let zd = z_ref(d);
    let sigma = if dn < 0.0 {
        2.0 * dn / dnp * ft
    } else if dn <= dnp {
        hard(ft, dn / dnp).min(zd * ft)
    } else {
        zd * ft
    };
    let tau = if ds <= dsp { hard(fs, ds / dsp).min(zd * fs) } else { zd * fs };
    (sigma, tau, d, fs)
}

// ---------------------------------------------------------------------------
// Parameters and geometry.

#[derive(Clone, Copy, Debug)]
struct Case {
    params: JointParams,
    h: Real,
}

impl Case {
    fn joint(&self) -> Joint {
        Joint::new(self.params, self.h)
    }
}

fn case_strategy() -> impl Strategy<Value = Case> {
    (
        9.0..11.0f64,  // log10 E
        1.0..10.0f64,  // p0 / E
        6.0..7.3f64,   // log10 f_t
        0.2..4.0f64,   // c / f_t − tan φ
        10.0..50.0f64, // φ, degrees
        10.0..300.0f64,
        1.0..20.0f64, // G_fs / G_ft
        0.0..1.0f64,  // where h lies in its range
        any::<bool>(),
    )
        .prop_map(|(log_e, k, log_ft, c_extra, phi_deg, gft, gs, u, exact)| {
            let e = Real::powf(10.0, log_e);
            let penalty = k * e;
            let ft = Real::powf(10.0, log_ft);
            let phi = phi_deg.to_radians();
            let c = ft * (phi.tan() + c_extra);
            let gfs = gft * gs;
            let h_max = (0.1f64).min(3.0 * gft * penalty / (4.0 * ft * ft)).min(3.0 * gfs * penalty / (4.0 * c * c));
            let lo = (1e-4f64).min(h_max / 10.0);
            let h = lo * (h_max / lo).powf(u);
            Case {
                params: JointParams {
                    penalty,
                    tensile_strength: ft,
                    cohesion: c,
                    friction_angle: phi,
                    gf_tension: gft,
                    gf_shear: gfs,
                    calibration: if exact { GfCalibration::Exact } else { GfCalibration::Paper },
                },
                h,
            }
        })
}

/// A granite-like joint (the crate's unit-test values): `p0 = 26e10` Pa,
/// `f_t = 3` MPa, `c = 15` MPa, `φ = 30°`, `G_ft = 50`, `G_fs = 500` J/m².
fn granite(calibration: GfCalibration) -> JointParams {
    JointParams {
        penalty: 26e10,
        tensile_strength: 3e6,
        cohesion: 15e6,
        friction_angle: 30f64.to_radians(),
        gf_tension: 50.0,
        gf_shear: 500.0,
        calibration,
    }
}

/// Mean edge of the right triangle with legs `l`: `l (2 + √2) / 3`.
fn mean_edge(l: Real) -> Real {
    l * (2.0 + std::f64::consts::SQRT_2) / 3.0
}

/// The joint `N1..N6` whose side a is the triangle `(0,0,0), (l,0,0),
/// (0,l,0)` and whose side b is the same triangle with node pair `k`
/// (N1–N6, N2–N5, N3–N4) moved by `d[k]`.
fn joint_nodes(l: Real, d: [Vec3; 3]) -> [Vec3; 6] {
    let a = [Vec3::zeros(), Vec3::new(l, 0.0, 0.0), Vec3::new(0.0, l, 0.0)];
    [a[0], a[1], a[2], a[2] + d[2], a[1] + d[1], a[0] + d[0]]
}

fn all_finite(ps: &femdem_fracture::PointStress) -> bool {
    ps.sigma.is_finite()
        && ps.tau.is_finite()
        && ps.damage.is_finite()
        && ps.dissipated.is_finite()
        && ps.stored.is_finite()
}

// ---------------------------------------------------------------------------
// 1. Fig. 3: pure opening, pure shear, mixed mode.

/// Relative agreement with the reference law. The only differences from the
/// crate are round-off and `∫z` (Gauss–Legendre there, Simpson here; they
/// agree to ~1e-13), which moves δc by ~1e-13 relatively, D by at most
/// ~2e-13 (δc ≥ 2 δp), and z by `|z′| ≤ 16` times that: ~3e-12. Tolerance
/// 1e-9 f.
const LAW_TOL: Real = 1e-9;

/// Checks one pure-mode curve `s(δ)` (peak `f` at `dp`, zero from `dc`):
/// the peak, zero at and beyond δc, and continuity at 0, δp, δc. The law is
/// Lipschitz with constant `K = f max(2/δp, L/(δc − δp))` (`2f/δp` is the
/// steepest hardening and compression slope, `L ≥ |z′|`), so just below and
/// just above each branch boundary, `ε` apart, the values may differ by at
/// most `2εK`, plus round-off `1e-12 f`; a jump anywhere would exceed it.
fn check_pure_curve(
    s: &dyn Fn(Real) -> (Real, Real, Option<FailureMode>),
    f: Real,
    dp: Real,
    dc: Real,
    mode: FailureMode,
) -> Result<(), TestCaseError> {
    let (peak, _, _) = s(dp);
    prop_assert!((peak - f).abs() <= 1e-12 * f, "peak {peak} ≠ f {f}");
    for d in [dc, dc * (1.0 + 1e-9), 1.5 * dc, 2.0 * dc, 1e3, 1e300] {
        let (v, dmg, broke) = s(d);
        prop_assert!(v == 0.0, "stress {v} at δ = {d} ≥ δc = {dc}");
        prop_assert!(dmg == 1.0);
        prop_assert_eq!(broke, Some(mode));
    }
    let k = f * (2.0 / dp).max(z_lipschitz() / (dc - dp));
    // ε below each boundary's neighbouring branch widths.
    let eps_at = [1e-9 * dp, 1e-9 * dp.min(dc - dp), 1e-9 * (dc - dp)];
    for (x, eps) in [0.0, dp, dc].into_iter().zip(eps_at) {
        let (lo, _, _) = s(x - eps);
        let (hi, _, _) = s(x + eps);
        prop_assert!((hi - lo).abs() <= 2.0 * eps * k + 1e-12 * f, "jump {} at δ = {x} (δp {dp}, δc {dc})", hi - lo);
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// Pure opening (δs = 0): Eq. 11 with `f = f_t`, `δnp = 2 f_t h / p0`
    /// (Eq. 6), `δnc` from Eq. 10 — `σ = 2(δ/δp) f_t` in compression,
    /// `[2δ/δp − (δ/δp)²] f_t` up to the peak `f_t` at δp, `z(D) f_t` with
    /// `D = (δ − δp)/(δc − δp)` after it, 0 from δc on (tensile failure).
    /// The curve is also checked for Lipschitz continuity between random
    /// pairs of openings (`|σ(x) − σ(y)| ≤ K |x − y|`, K as above).
    #[test]
    fn pure_opening_follows_fig3(
        case in case_strategy(),
        xs in prop::collection::vec(-2.0..2.0f64, 32),
    ) {
        let j = case.joint();
        let p = &case.params;
        let ft = p.tensile_strength;
        let dp = dp_ref(p, case.h, ft);
        let dc = dc_ref(p, ft, dp, p.gf_tension);
        prop_assert!((j.delta_np - dp).abs() <= 1e-14 * dp, "Eq. 6");
        prop_assert!((j.delta_nc - dc).abs() <= 1e-11 * dc, "Eq. 10: {} vs {dc}", j.delta_nc);
        let s = |d: Real| {
            let ps = point_stress(&j, d, 0.0, 0.0);
            (ps.sigma, ps.damage, ps.broke)
        };
        check_pure_curve(&s, ft, dp, dc, FailureMode::Tensile)?;
        let k = ft * (2.0 / dp).max(z_lipschitz() / (dc - dp));
        let mut prev: Option<(Real, Real)> = None;
        for x in xs {
            let d = x * dc;
            let ps = point_stress(&j, d, 0.0, 0.0);
            prop_assert!(all_finite(&ps));
            let (sigma, tau, dmg, _) = ref_point(&j, d, 0.0);
            prop_assert!((ps.sigma - sigma).abs() <= LAW_TOL * ft, "σ({d}) = {} vs {sigma}", ps.sigma);
            prop_assert!((ps.sigma - normal_stress(&j, d)).abs() == 0.0);
            prop_assert!(ps.tau == 0.0 && tau == 0.0);
            prop_assert!((ps.damage - dmg).abs() <= 1e-9);
            prop_assert!(ps.sigma <= ft, "above the peak");
            if let Some((x0, s0)) = prev {
                prop_assert!((ps.sigma - s0).abs() <= k * (d - x0).abs() * (1.0 + 1e-9) + 1e-12 * ft);
            }
            prev = Some((d, ps.sigma));
        }
    }

    /// Pure shear (δn = 0, so σ = 0 and `f_s = c`, Eq. 5): the same curve
    /// with `f_s`, `δsp = 2 c h / p0` (Eq. 7), `δsc` from `G_fs` (Eq. 10),
    /// failing in shear; σ stays 0.
    #[test]
    fn pure_shear_follows_fig3(
        case in case_strategy(),
        xs in prop::collection::vec(0.0..2.0f64, 32),
    ) {
        let j = case.joint();
        let p = &case.params;
        let c = p.cohesion;
        let dp = dp_ref(p, case.h, c);
        let dc = dc_ref(p, c, dp, p.gf_shear);
        let s = |d: Real| {
            let ps = point_stress(&j, 0.0, d.abs(), 0.0);
            (ps.tau, ps.damage, ps.broke)
        };
        // Continuity at δs = 0 is checked on the odd extension
        // τ(−δ) = −τ(δ) (the slip is a magnitude; its traction reverses).
        let odd = |d: Real| {
            let (t, dmg, b) = s(d);
            (t * d.signum(), dmg, b)
        };
        check_pure_curve(&odd, c, dp, dc, FailureMode::Shear)?;
        for x in xs {
            let d = x * dc;
            let ps = point_stress(&j, 0.0, d, 0.0);
            prop_assert!(all_finite(&ps));
            let (sigma, tau, dmg, fs) = ref_point(&j, 0.0, d);
            prop_assert!(fs == c && sigma == 0.0 && ps.sigma == 0.0);
            prop_assert!((ps.tau - tau).abs() <= LAW_TOL * c, "τ({d}) = {} vs {tau}", ps.tau);
            prop_assert!((ps.damage - dmg).abs() <= 1e-9);
            prop_assert!(ps.tau <= c);
        }
    }

    /// Mixed mode: random (δn, δs) with `δn ∈ [−3 δnp, 1.2 δnc]`,
    /// `δs ∈ [0, 1.2 δsc(c)]`; σ, τ and D as Eq. 5, 11 and 13 give them
    /// (`ref_point`), to `LAW_TOL f`. Plus: everything finite for huge, zero
    /// and negative openings and slips (|δ| up to 1e3 m, and +1e300 m).
    #[test]
    fn mixed_mode_follows_eq11_and_eq13(
        case in case_strategy(),
        pts in prop::collection::vec((-1.0..1.2f64, 0.0..1.2f64), 32),
    ) {
        let j = case.joint();
        let p = &case.params;
        let (ft, c) = (p.tensile_strength, p.cohesion);
        let dnp = dp_ref(p, case.h, ft);
        let dnc = dc_ref(p, ft, dnp, p.gf_tension);
        let dsc = dc_ref(p, c, dp_ref(p, case.h, c), p.gf_shear);
        for (a, b) in pts {
            let dn = if a < 0.0 { 3.0 * a * dnp } else { a * dnc };
            let ds = b * dsc;
            let ps = point_stress(&j, dn, ds, 0.0);
            prop_assert!(all_finite(&ps));
            let (sigma, tau, dmg, fs) = ref_point(&j, dn, ds);
            prop_assert!((ps.sigma - sigma).abs() <= LAW_TOL * ft, "σ({dn}, {ds}) = {} vs {sigma}", ps.sigma);
            prop_assert!((ps.tau - tau).abs() <= LAW_TOL * fs, "τ({dn}, {ds}) = {} vs {tau}", ps.tau);
            prop_assert!((ps.damage - dmg).abs() <= 1e-9, "D({dn}, {ds}) = {} vs {dmg}", ps.damage);
        }
        let odd = [0.0, 1e-300, -1e-300, 1e-30, -1e-30, 1e3, -1e3, dnp, dnc, 1e300];
        for dn in odd {
            for ds in [0.0, 1e-300, 1e-30, 1e3, 1e300, dsc] {
                let ps = point_stress(&j, dn, ds, 0.0);
                prop_assert!(all_finite(&ps), "({dn}, {ds}): {ps:?}");
                let ps = point_stress(&j, dn, ds, 0.5);
                prop_assert!(all_finite(&ps), "({dn}, {ds}, D 0.5): {ps:?}");
            }
        }
        let zero = point_stress(&j, 0.0, 0.0, 0.0);
        prop_assert!(zero.sigma == 0.0 && zero.tau == 0.0 && zero.damage == 0.0 && zero.stored == 0.0);
        // The joint kernel on wild positions: finite forces that sum to zero.
        let l = case.h * 3.0 / (2.0 + std::f64::consts::SQRT_2);
        for d in [Vec3::new(1e3, -1e3, 1e3), Vec3::new(0.0, 0.0, -1e3), Vec3::new(-1e-30, 0.0, 1e-30)] {
            let x = joint_nodes(l, [d, Vec3::zeros(), d * 0.5]);
            let mut hist = JointHistory::default();
            let out = joint_update(&j, &mut hist, &x, true);
            prop_assert!(out.forces.iter().all(|f| f.iter().all(|v| v.is_finite())));
            prop_assert!(out.energy.is_finite() && hist.dissipated.is_finite());
            let sum: Vec3 = out.forces.iter().sum();
            let scale = out.forces.iter().map(|f| f.norm()).fold(0.0, Real::max);
            prop_assert!(sum.norm() <= 1e-12 * scale.max(1e-300));
        }
    }
}

/// A Gf too small for the element (Eq. 10 gives δc < δp: `h` exceeds the
/// cohesive-zone length): the crate documents δc clamped to δp, so the
/// point carries the peak at δp and fails just beyond it — no snap-back,
/// no negative softening length.
#[test]
fn degenerate_critical_displacement_fails_at_the_peak() {
    let mut p = granite(GfCalibration::Paper);
    p.gf_tension = 1e-3; // 3 Gf / f_t = 1e-9 m
    let j = Joint::new(p, 1e-2); // δnp = 2.6e-7 m
    assert!(3.0 * p.gf_tension / p.tensile_strength < j.delta_np);
    let peak = point_stress(&j, j.delta_np, 0.0, 0.0);
    assert!((peak.sigma - p.tensile_strength).abs() <= 1e-12 * p.tensile_strength);
    let past = point_stress(&j, j.delta_np * (1.0 + 1e-9), 0.0, 0.0);
    assert_eq!(past.sigma, 0.0);
    assert_eq!(past.broke, Some(FailureMode::Tensile));
}

// ---------------------------------------------------------------------------
// 2. Eq. 12.

/// The ends: `z(0) = (1 − k)(a + b) = (1/(a+b))(a+b) = 1`, `z(1) = 0`
/// (q(1) = 0). The slope at 0 is zero exactly: `z′(0) = −kλ(a+b) −
/// (1−k)(a+bc) = (a+bc)/(a+b) − (a+bc)/(a+b) = 0` — the exponent of Eq. 12
/// is chosen so that the softening curve leaves the peak flat, as the
/// hardening branch arrives there (slope `2f(1 − r)/δp = 0` at r = 1):
/// Fig. 3 is C¹ at δp. A forward difference with step η has error
/// `|z″| η / 2 ≲ 100 η`; η = 1e-7 gives 1e-5.
#[test]
fn eq12_ends_and_flat_start() {
    assert!((z_ref(0.0) - 1.0).abs() < 1e-15);
    assert_eq!(z_ref(1.0), 0.0);
    assert!((softening::z(0.0) - 1.0).abs() < 1e-15);
    assert!(softening::z(1.0).abs() < 1e-15);
    let eta = 1e-7;
    let slope = (softening::z(eta) - softening::z(0.0)) / eta;
    assert!(slope.abs() < 1e-5, "z′(0) ≈ {slope}");
    // The crate clamps D to [0, 1].
    assert_eq!(softening::z(-0.5), softening::z(0.0));
    assert_eq!(softening::z(1.5), softening::z(1.0));
}

/// `∫₀¹ z dD`: the crate's Gauss–Legendre value against Simpson on the
/// restated Eq. 12 (both ~1e-14 accurate; tolerance 1e-12), and the
/// issue's 0.386 (to its three digits: ±5e-4).
#[test]
fn softening_area_is_0_386() {
    let a = softening::softening_area();
    println!("∫₀¹ z dD: crate {a:.15}, Simpson {:.15}", area_ref());
    assert!((a - area_ref()).abs() < 1e-12);
    assert!((a - 0.386).abs() < 5e-4);
    assert!((softening::z_integral(0.0, 1.0) - a).abs() < 1e-15);
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// `softening::z` equals the restated Eq. 12 to 1e-12 (both are a few
    /// flops on numbers ≤ 2.43: round-off ~1e-15), lies in [0, 1] and never
    /// increases; `z_integral` agrees with Simpson (2,000 panels per unit
    /// length, error < 1e-14) to 1e-12.
    #[test]
    fn z_matches_eq12_and_is_monotone(a in 0.0..=1.0f64, b in 0.0..=1.0f64) {
        prop_assert!((softening::z(a) - z_ref(a)).abs() <= 1e-12, "z({a})");
        prop_assert!((softening::z(b) - z_ref(b)).abs() <= 1e-12, "z({b})");
        let (lo, hi) = if a <= b { (a, b) } else { (b, a) };
        prop_assert!(softening::z(lo) >= softening::z(hi));
        prop_assert!(z_ref(lo) >= z_ref(hi));
        prop_assert!((0.0..=1.0).contains(&softening::z(a)));
        let n = ((hi - lo) * 2000.0).ceil().max(1.0) as usize;
        prop_assert!((softening::z_integral(lo, hi) - simpson(lo, hi, n)).abs() <= 1e-12);
    }
}

// ---------------------------------------------------------------------------
// 3. Eq. 5.

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// Shear strength under several normal states, compressive and tensile:
    /// `δn/δnp ∈ {−10, −3, −1, −0.25, 0, 0.25, 0.5, 0.9, 1}`. With `σ` the
    /// normal stress of Eq. 11, `f_s = c − σ tan φ` (Eq. 5) and
    /// `δsp = 2 f_s h / p0` (Eq. 7), `τ(δsp) = f_s`, `τ(δsp/2) = 3/4 f_s`
    /// (hardening branch), and `τ ≤ f_s` just past δsp. σ never exceeds
    /// `f_t` (reached at δnp), so `f_s ≥ c − f_t tan φ`: the cut-off, with
    /// equality at δnp. Beyond δnp the normal damage `Dn` caps τ at
    /// `z(Dn) f_s` (see the file doc): `τ(δsp) = z(Dn) f_s` and τ is
    /// continuous across δsp (Lipschitz bound as in test 1, slope
    /// `≤ 2 f_s/δsp`). Tolerances: 1e-12 relative for closed forms (a few
    /// flops), LAW_TOL where ∫z enters.
    ///
    /// Under strong compression `f_s` grows and, with `Paper`, Eq. 10's
    /// `δsc = 3 G_fs / f_s` can fall below Eq. 7's `δsp = 2 f_s h / p0`
    /// (once `f_s > √(3 G_fs p0 / (2h))`); the crate then clamps δsc to δsp
    /// (documented), and the check becomes: `f_s` just below δsp, shear
    /// failure just past it.
    #[test]
    fn shear_strength_follows_mohr_coulomb(case in case_strategy(), xs in prop::collection::vec(-5.0..5.0f64, 16)) {
        let j = case.joint();
        let p = &case.params;
        let (ft, c) = (p.tensile_strength, p.cohesion);
        let tan_phi = p.friction_angle.tan();
        let dnp = dp_ref(p, case.h, ft);
        let dnc = dc_ref(p, ft, dnp, p.gf_tension);
        let floor = c - ft * tan_phi;
        for r in [-10.0, -3.0, -1.0, -0.25, 0.0, 0.25, 0.5, 0.9, 1.0] {
            let dn = r * dnp;
            let sigma = if r < 0.0 { 2.0 * r * ft } else { hard(ft, r) };
            prop_assert!((normal_stress(&j, dn) - sigma).abs() <= 1e-12 * ft * (1.0 + r.abs()));
            let fs = c - sigma * tan_phi;
            prop_assert!(fs >= floor * (1.0 - 1e-12));
            let dsp = 2.0 * fs * case.h / p.penalty;
            if dc_ref(p, fs, dsp, p.gf_shear) <= dsp * (1.0 + 1e-6) {
                // Confinement raised f_s so far that Eq. 10 gives δsc ≤ δsp
                // (Paper: 3 G_fs / f_s falls as δsp = 2 f_s h / p0 grows):
                // the peak is reached, then the point fails at once.
                let below = point_stress(&j, dn, dsp * (1.0 - 1e-9), 0.0);
                prop_assert!((below.tau - fs).abs() <= 1e-12 * fs, "r {r}: τ {} vs f_s {fs}", below.tau);
                let past = point_stress(&j, dn, dsp * (1.0 + 1e-9), 0.0);
                prop_assert!(past.tau == 0.0 && past.broke == Some(FailureMode::Shear));
                continue;
            }
            let at_peak = point_stress(&j, dn, dsp, 0.0);
            prop_assert!((at_peak.tau - fs).abs() <= 1e-12 * fs, "r {r}: τ {} vs f_s {fs}", at_peak.tau);
            prop_assert!(at_peak.damage <= 1e-12, "at the peak, not past it");
            let half = point_stress(&j, dn, 0.5 * dsp, 0.0).tau;
            prop_assert!((half - 0.75 * fs).abs() <= 1e-12 * fs);
            for k in [1e-6, 1e-3, 0.1] {
                prop_assert!(point_stress(&j, dn, dsp * (1.0 + k), 0.0).tau <= fs * (1.0 + 1e-12));
            }
            if r == 1.0 {
                prop_assert!((fs - floor).abs() <= 1e-12 * c, "the cut-off is reached at δnp");
            }
        }
        // σ ≤ f_t for any opening, so f_s ≥ c − f_t tan φ everywhere.
        for x in xs {
            let dn = x * dnc;
            prop_assert!(normal_stress(&j, dn) <= ft);
        }
        // Softened normal direction: the peak of τ still sits at
        // δsp(f_s(σ)), is z(Dn) f_s, and τ is continuous across it.
        for dn_frac in [0.2, 0.6] {
            let dn = dnp + dn_frac * (dnc - dnp);
            let sigma = z_ref(dn_frac) * ft;
            prop_assert!((normal_stress(&j, dn) - sigma).abs() <= LAW_TOL * ft);
            let fs = c - sigma * tan_phi;
            let dsp = 2.0 * fs * case.h / p.penalty;
            let tau = point_stress(&j, dn, dsp, 0.0).tau;
            prop_assert!((tau - z_ref(dn_frac) * fs).abs() <= LAW_TOL * fs);
            let eps = 1e-9 * dsp;
            let jump = point_stress(&j, dn, dsp + eps, 0.0).tau - point_stress(&j, dn, dsp - eps, 0.0).tau;
            let dsc = dc_ref(p, fs, dsp, p.gf_shear);
            let k = fs * (2.0 / dsp).max(z_lipschitz() / (dsc - dsp));
            prop_assert!(jump.abs() <= 2.0 * eps * k + 1e-12 * fs, "τ jumps by {jump} at δsp");
        }
    }
}

// ---------------------------------------------------------------------------
// 4. Energy to open a joint to failure.

/// A joint opened monotonically along `dir` (side b translated: every point
/// has the same opening or slip `δ`) on the grid `δp i/n1` (i ≤ n1), then
/// `δp + (1.002 δc − δp) i/n2`. Returns the grid, the stress on side b
/// along `dir` (`−ΣF_b · dir / A`), the index where the joint failed and
/// how, and the energies the joint reports, per unit area.
struct Opening {
    delta: Vec<Real>,
    stress: Vec<Real>,
    failed_at: usize,
    mode: FailureMode,
    /// `history.dissipated / A`: the softening work.
    dissipated: Real,
    /// `history.released / A`: the stored energy lost at failure.
    released: Real,
    /// `history.work / A`: the work the joint counted.
    work: Real,
    n1: usize,
}

fn open_to_failure(j: &Joint, l: Real, dir: Vec3, dp: Real, dc: Real) -> Opening {
    let (n1, n2) = (2_000, 40_000);
    let area = 0.5 * l * l;
    let mut delta = Vec::with_capacity(n1 + n2 + 1);
    delta.extend((0..=n1).map(|i| dp * (i as Real / n1 as Real)));
    delta.extend((1..=n2).map(|i| dp + (1.002 * dc - dp) * (i as Real / n2 as Real)));
    let mut hist = JointHistory::default();
    let mut stress = Vec::with_capacity(delta.len());
    let mut failed = None;
    for (i, &d) in delta.iter().enumerate() {
        let x = joint_nodes(l, [dir * d; 3]);
        let out = joint_update(j, &mut hist, &x, true);
        let fb: Vec3 = out.forces[3..].iter().sum();
        stress.push(-fb.dot(&dir) / area);
        if let Some(m) = out.failed {
            assert!(failed.is_none(), "fails once");
            failed = Some((i, m));
        }
        if failed.is_some() {
            assert!(out.forces.iter().all(|f| f.norm() == 0.0), "a failed joint exerts nothing");
            break;
        }
    }
    let (failed_at, mode) = failed.expect("the joint fails by 1.002 δc");
    Opening {
        delta,
        stress,
        failed_at,
        mode,
        dissipated: hist.dissipated / area,
        released: hist.released / area,
        work: hist.work / area,
        n1,
    }
}

/// Trapezoid ∫σ dδ over grid segments `[lo, hi)` of an opening.
fn trapezoid(o: &Opening, lo: usize, hi: usize) -> Real {
    (lo..hi).map(|i| 0.5 * (o.stress[i] + o.stress[i + 1]) * (o.delta[i + 1] - o.delta[i])).sum()
}

/// Opening one joint monotonically to failure, in pure tension (side b
/// translated along the normal) and in pure shear (along x′), for both
/// calibrations, on a fine and a coarse element. All per unit mid-plane
/// area.
///
/// (a) The work done, `W = ∫₀^δc σ dδ` (trapezoid on the σ–δ curve read
/// from the joint's nodal forces), equals what the joint reports as lost
/// when it fails: `history.dissipated` (softening work) + `history.released`
/// (the stored energy it held at failure; the crate keeps the two apart
/// and the solver's balance adds them). Closed form:
/// `W = ⅔ f δp + f (δc − δp) ∫₀¹ z`, with the hardening area
/// `∫₀^δp [2δ/δp − δ²/δp²] f dδ = ⅔ f δp` = `released`.
///
/// (b) The softening part `∫_δp^δc σ dδ = f (δc − δp) ∫₀¹ z` (trapezoid,
/// and `history.dissipated`) is, for `Paper` (δc = 3Gf/f),
/// `∫z (3 Gf − f δp)` = 3 × 0.386 Gf less the correction `∫z f δp` — about
/// 1.16 Gf when δp ≪ δc — and for `Exact` (δc − δp = Gf/(f ∫z)) exactly Gf.
///
/// Tolerance 1e-4 relative (the brief's acceptance bound is 2%): the
/// trapezoid error is `(b−a) Δ² max|σ″| / 12` — on the hardening branch
/// `f δp/(6 n1²)`, ~4e-8 of W; on the softening branch
/// `f (δc−δp) max|z″| /(12 n2²)` with `|z″| ≲ 100`, ~1e-8 of W — plus the
/// failing segment, where σ drops to 0 at δc inside the step:
/// `≤ f L Δ² / (δc − δp)`, ~1e-8 of W. 1e-4 still catches a 2% or even a
/// 0.1% error in ∫z, δc or the released stored energy.
#[test]
fn energy_to_failure_matches_the_curve_and_gf() {
    const TOL: Real = 1e-4;
    println!(
        "{:<6} {:<6} {:>8} {:>8} {:>11} {:>9} {:>9} {:>9} {:>9} {:>9}",
        "mode", "calib", "l (m)", "δp/δc", "W/(dis+rel)", "soft/Gf", "expect", "dis/Gf", "rel/Gf", "W/Gf"
    );
    for calibration in [GfCalibration::Paper, GfCalibration::Exact] {
        let p = granite(calibration);
        // l = 1 mm: δp ≪ δc (δnp/δnc = 5e-4 with Paper); l = 0.4 m:
        // δnp/δnc ≈ 0.24 and δsp/δsc ≈ 0.52, a large δp correction.
        for l in [1e-3, 0.4] {
            let j = Joint::new(p, mean_edge(l));
            let tension = ("normal", Vec3::z(), p.tensile_strength, p.gf_tension, FailureMode::Tensile);
            let shear = ("shear", Vec3::x(), p.cohesion, p.gf_shear, FailureMode::Shear);
            for (name, dir, f, gf, mode) in [tension, shear] {
                let dp = dp_ref(&p, j.h, f);
                let dc = dc_ref(&p, f, dp, gf);
                assert!(dc > 1.5 * dp);
                let o = open_to_failure(&j, l, dir, dp, dc);
                assert_eq!(o.mode, mode);
                // It fails at the first grid point at or beyond δc.
                assert!(o.delta[o.failed_at] >= dc && o.delta[o.failed_at - 1] < dc);
                let work = trapezoid(&o, 0, o.failed_at);
                let hardening = trapezoid(&o, 0, o.n1);
                let soft = trapezoid(&o, o.n1, o.failed_at);
                // Once broken, a point's unloading curve stores nothing: the
                // hardening area is lost too (not in `dissipated`, which is
                // the softening branch, nor in `released`, which is ≈ 0).
                let lost = o.dissipated + o.released + hardening;
                let w_closed = 2.0 / 3.0 * f * dp + f * (dc - dp) * area_ref();
                let soft_expected = match calibration {
                    GfCalibration::Paper => area_ref() * (3.0 * gf - f * dp),
                    GfCalibration::Exact => gf,
                };
                println!(
                    "{name:<6} {:<6} {l:>8.1e} {:>8.4} {:>11.8} {:>9.6} {:>9.6} {:>9.6} {:>9.6} {:>9.6}",
                    format!("{calibration:?}"),
                    dp / dc,
                    work / lost,
                    soft / gf,
                    soft_expected / gf,
                    o.dissipated / gf,
                    o.released / gf,
                    work / gf,
                );
                let ctx = format!("{name} {calibration:?} l {l}");
                // (a), and the joint's own work count (a backward
                // rectangle rule: error ≤ 2 f Δδ, ≤ 1e-4 W here).
                assert!((o.work - work).abs() <= 1e-3 * work, "{ctx}: history.work {} vs ∫σdδ {work}", o.work);
                assert!((work - lost).abs() <= TOL * lost, "{ctx}: ∫σdδ {work} vs dissipated + released {lost}");
                assert!((lost - w_closed).abs() <= TOL * w_closed, "{ctx}: {lost} vs {w_closed}");
                assert!(o.released <= TOL * work, "{ctx}: released {} though every point broke", o.released);
                // (b)
                assert!(
                    (soft - soft_expected).abs() <= TOL * soft_expected,
                    "{ctx}: softening {soft} vs {soft_expected}"
                );
                assert!(
                    (o.dissipated - soft_expected).abs() <= TOL * soft_expected,
                    "{ctx}: dissipated {} vs {soft_expected}",
                    o.dissipated
                );
                if calibration == GfCalibration::Paper && l == 1e-3 {
                    // δp ≪ δc: the "≈ 1.16 Gf" (3 × 0.386, ±3e-3
                    // for the δp correction, here < 0.2%).
                    assert!((soft / gf - 3.0 * 0.386).abs() < 3e-3, "{}", soft / gf);
                }
            }
        }
    }
}

// ---------------------------------------------------------------------------
// 5. Unloading, reloading, irreversibility.

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// One point driven along a random path of targets (fractions of δc,
    /// with returns below δp and into compression), in 8 sub-steps per leg,
    /// purely normal, purely shear, or mixed. At every evaluation:
    /// the damage never decreases (and stays ≤ 1); σ ≤ z(D) f_t and
    /// τ ≤ z(D) f_s, D the damage reached so far, with `f_s ≤ c` for
    /// δn ≥ 0 and `f_s = c − σ tan φ` with σ = 2(δn/δnp) f_t in compression
    /// (round-off: 1e-12 f); in a pure mode, no damage grows while the
    /// displacement stays at or below the largest reached before; once
    /// D = 1, no tension and no shear ever again (compression, i.e.
    /// interpenetration resistance, stays).
    #[test]
    fn unloading_never_exceeds_damaged_strength(
        case in case_strategy(),
        mode in 0..3u8,
        targets in prop::collection::vec((-0.3..1.3f64, 0.0..1.3f64), 2..12),
    ) {
        let j = case.joint();
        let p = &case.params;
        let (ft, c) = (p.tensile_strength, p.cohesion);
        let tan_phi = p.friction_angle.tan();
        let dnp = dp_ref(p, case.h, ft);
        let dnc = dc_ref(p, ft, dnp, p.gf_tension);
        let dsc = dc_ref(p, c, dp_ref(p, case.h, c), p.gf_shear);
        let map = |(a, b): (Real, Real)| match mode {
            0 => (a * dnc, 0.0),
            1 => (0.0, b * dsc),
            _ => (a * dnc, b * dsc),
        };
        let mut d_hist = 0.0;
        let mut max_reached = 0.0f64;
        let mut at = (0.0, 0.0);
        for t in targets {
            let to = map(t);
            for k in 1..=8 {
                let s = k as Real / 8.0;
                let (dn, ds) = (at.0 + (to.0 - at.0) * s, at.1 + (to.1 - at.1) * s);
                let ps = point_stress(&j, dn, ds, d_hist);
                prop_assert!(all_finite(&ps));
                prop_assert!(ps.damage >= d_hist && ps.damage <= 1.0, "D {} after {d_hist}", ps.damage);
                let zd = z_ref(ps.damage);
                prop_assert!(ps.sigma <= zd * ft + 1e-12 * ft, "σ {} > z(D) f_t = {}", ps.sigma, zd * ft);
                let fs_bound = if dn < 0.0 { c - 2.0 * dn / dnp * ft * tan_phi } else { c };
                prop_assert!(ps.tau >= 0.0);
                prop_assert!(ps.tau <= zd * fs_bound * (1.0 + 1e-12) + 1e-12 * c, "τ {} > z(D) f_s", ps.tau);
                let reached = match mode { 0 => dn, 1 => ds, _ => Real::NAN };
                if mode < 2 && reached <= max_reached {
                    prop_assert!(ps.damage == d_hist, "damage grew on reloading below the envelope");
                }
                if d_hist >= 1.0 {
                    prop_assert!(ps.sigma <= 0.0 && ps.tau == 0.0, "a broken point heals");
                    prop_assert!(ps.dissipated == 0.0);
                }
                if mode < 2 {
                    max_reached = max_reached.max(reached);
                }
                d_hist = ps.damage;
            }
            at = to;
        }
    }

    /// A whole joint along a random path of node-pair displacements
    /// (openings in [−0.3, 1.5] δnc, slips in ±δsc, each node pair its own,
    /// so the joint opens unevenly and rotates), 6 sub-steps per leg,
    /// through `joint_update`: the damage at each point and the dissipated
    /// energy never decrease; the joint is failed exactly when two or more
    /// points have D = 1; once failed it exerts no force, reports no new
    /// failure and its history stays frozen, whatever the nodes do —
    /// including closing back to the reference position.
    #[test]
    fn a_joint_never_heals(
        case in case_strategy(),
        legs in prop::collection::vec(
            prop::collection::vec((-0.3..1.5f64, -1.0..1.0f64, -1.0..1.0f64), 3),
            2..10,
        ),
    ) {
        let j = case.joint();
        let p = &case.params;
        let dnc = dc_ref(p, p.tensile_strength, dp_ref(p, case.h, p.tensile_strength), p.gf_tension);
        let dsc = dc_ref(p, p.cohesion, dp_ref(p, case.h, p.cohesion), p.gf_shear);
        let l = case.h * 3.0 / (2.0 + std::f64::consts::SQRT_2);
        let mut hist = JointHistory::default();
        let mut at = [Vec3::zeros(); 3];
        let mut path: Vec<[Vec3; 3]> = Vec::new();
        for leg in &legs {
            let to: Vec<Vec3> = leg.iter().map(|&(n, sx, sy)| Vec3::new(sx * dsc, sy * dsc, n * dnc)).collect();
            for k in 1..=6 {
                let s = k as Real / 6.0;
                path.push([0, 1, 2].map(|i| at[i] + (to[i] - at[i]) * s));
            }
            at = [to[0], to[1], to[2]];
        }
        path.push([Vec3::zeros(); 3]);
        for d in path {
            let before = hist;
            let out = joint_update(&j, &mut hist, &joint_nodes(l, d), true);
            prop_assert!(out.forces.iter().all(|f| f.iter().all(|v| v.is_finite())));
            prop_assert!(hist.dissipated >= before.dissipated && hist.dissipated.is_finite());
            for i in 0..3 {
                prop_assert!(hist.damage[i] >= before.damage[i] && hist.damage[i] <= 1.0);
            }
            let broken = hist.damage.iter().filter(|&&d| d >= 1.0).count();
            prop_assert_eq!(hist.failed, broken >= 2, "failed {} with {} broken points", hist.failed, broken);
            if before.failed {
                prop_assert!(out.forces.iter().all(|f| f.norm() == 0.0), "a failed joint pulls");
                prop_assert!(out.failed.is_none() && out.energy == 0.0);
                prop_assert_eq!(hist, before);
            } else if out.failed.is_some() {
                prop_assert!(hist.failed && out.forces.iter().all(|f| f.norm() == 0.0));
            } else {
                let sum: Vec3 = out.forces.iter().sum();
                let scale = out.forces.iter().map(|f| f.norm()).fold(0.0, Real::max);
                prop_assert!(sum.norm() <= 1e-12 * scale.max(1e-300));
            }
        }
    }
}

// ---------------------------------------------------------------------------
// 6. Failure needs two points.

/// Drives a joint of granite (`h` = mean edge of legs `l`) through `steps`
/// node-pair displacements, returning the history and the last output.
fn drive(j: &Joint, l: Real, steps: &[[Vec3; 3]]) -> (JointHistory, Option<FailureMode>, [Vec3; 6]) {
    let mut hist = JointHistory::default();
    let mut failed = None;
    let mut forces = [Vec3::zeros(); 6];
    for d in steps {
        let out = joint_update(j, &mut hist, &joint_nodes(l, *d), false);
        if out.failed.is_some() {
            assert!(failed.is_none());
            failed = out.failed;
        }
        forces = out.forces;
    }
    (hist, failed, forces)
}

/// Linear ramp of node-pair displacements from `from` to `to` in `n` steps.
fn ramp(from: [Vec3; 3], to: [Vec3; 3], n: usize) -> Vec<[Vec3; 3]> {
    (1..=n)
        .map(|k| {
            let s = k as Real / n as Real;
            [0, 1, 2].map(|i| from[i] + (to[i] - from[i]) * s)
        })
        .collect()
}

/// §2.2: "A joint element is labelled as failed when at least two
/// integration points have zero stress components."
///
/// Opening only node pair N1–N6 by W gives the Hammer points (barycentric
/// weights 2/3, 1/6, 1/6) openings ≈ 2W/3, W/6, W/6: with W = 1.8 δnc point
/// A is at 1.2 δnc (zero stress) and B, C at 0.3 δnc — one point broken,
/// the joint holds and still carries force. Then opening N2–N5 by 1.5 δnc
/// puts B at ≈ 1.3 δnc (C at ≈ 0.55 δnc): two points, tensile failure. The
/// midplane tilts by ~W/(2l) = 5e-4 rad, so the openings differ from the
/// numbers above by ~1e-7 relatively and a slip ~W²/l ≈ 1e-8 m ≪ δsp
/// appears; the preconditions (which points are beyond δnc) are asserted
/// from the crate's kinematics, with margins ≥ 0.2 δnc.
///
/// The same in-plane (slip along x, openings exactly zero): Shear. And a
/// uniform mixed displacement with `Dn = Ds = 0.8` (neither reaches δc,
/// but `√(Dn² + Ds²) > 1`, Eq. 13): Mixed, in one step and along a ramp.
#[test]
fn failure_needs_two_points_at_zero_stress() {
    let p = granite(GfCalibration::Paper);
    let l = 0.1;
    let j = Joint::new(p, mean_edge(l));
    let dnc = j.delta_nc;
    let dsc = dc_ref(&p, p.cohesion, dp_ref(&p, j.h, p.cohesion), p.gf_shear);
    for (dir, crit, mode) in [(Vec3::z(), dnc, FailureMode::Tensile), (Vec3::x(), dsc, FailureMode::Shear)] {
        let zero = [Vec3::zeros(); 3];
        let one = [dir * (1.8 * crit), Vec3::zeros(), Vec3::zeros()];
        let two = [dir * (1.8 * crit), dir * (1.5 * crit), Vec3::zeros()];
        // Preconditions from the kinematics: only A, then A and B, beyond δc.
        let measure = |d: &[Vec3; 3]| {
            let k = joint_kinematics(&joint_nodes(l, *d)).unwrap();
            [0, 1, 2].map(|i| k.opening[i].abs().max(k.slip[i].norm()) / crit)
        };
        let m1 = measure(&one);
        assert!(m1[0] > 1.15 && m1[1] < 0.35 && m1[2] < 0.35, "{m1:?}");
        let m2 = measure(&two);
        assert!(m2[0] > 1.15 && m2[1] > 1.25 && m2[2] < 0.6, "{m2:?}");

        let stage1 = ramp(zero, one, 200);
        let (hist, failed, forces) = drive(&j, l, &stage1);
        assert_eq!(failed, None, "{mode:?}: one broken point must not fail the joint");
        assert!(!hist.failed);
        assert_eq!(hist.damage[0], 1.0);
        assert!(hist.damage[1] < 1.0 && hist.damage[2] < 1.0, "{:?}", hist.damage);
        assert!(forces.iter().any(|f| f.norm() > 0.0), "B and C still carry load");
        let mut steps = stage1;
        steps.extend(ramp(one, two, 200));
        let (hist, failed, forces) = drive(&j, l, &steps);
        assert_eq!(failed, Some(mode));
        assert!(hist.failed && forces.iter().all(|f| f.norm() == 0.0));
        assert!(hist.damage[0] == 1.0 && hist.damage[1] == 1.0 && hist.damage[2] < 1.0);
    }
    // Mixed: uniform (all points alike) Dn = Ds = 0.8.
    let ft = p.tensile_strength;
    let dnp = j.delta_np;
    let dn = dnp + 0.8 * (dnc - dnp);
    let fs = p.cohesion - z_ref(0.8) * ft * p.friction_angle.tan();
    let dsp = dp_ref(&p, j.h, fs);
    let ds = dsp + 0.8 * (dc_ref(&p, fs, dsp, p.gf_shear) - dsp);
    let target = [Vec3::new(ds, 0.0, dn); 3];
    let (_, failed, _) = drive(&j, l, &[target]);
    assert_eq!(failed, Some(FailureMode::Mixed), "in one step");
    let (_, failed, _) = drive(&j, l, &ramp([Vec3::zeros(); 3], target, 400));
    assert_eq!(failed, Some(FailureMode::Mixed), "along a ramp");
}

// ---------------------------------------------------------------------------
// Energy along general paths.
//
// Test 4 covers pure-mode monotonic loading. A joint in a simulation also
// unloads after softening, and opens in mixed mode. Since 86e716f the
// solver books a joint's fracture energy as `history.work − out.energy`
// (work done on it less what it stores) while intact and `history.work`
// once failed, and `out.energy` as joint elastic energy. Statements that do
// not depend on how the law is written:
// * `history.work` is the work done on the joint (checked against the
//   trapezoid `W = ∫ t · dg` of the traction read from the nodal forces);
// * at constant damage nothing is dissipated: the work done between two
//   states of equal damage is the change of the stored energy, so the
//   fracture energy `work − stored` never decreases;
// * a failed joint holds nothing: all the work done on it is lost, and
//   `history.dissipated` ("energy dissipated on the softening branches")
//   + `history.released` (the stored energy at failure) should say so.
//
// Tolerance 1e-3 of the work scale: the trapezoid on ≥ 20,000 steps per
// leg is accurate to ~1e-6 (measured on monotonic loading, test 4, where
// all three statements hold to 1e-6); the crate's `work` is a backward
// rectangle rule, off by at most `max Δδ × total variation of σ ≤ 2 f Δδ`,
// i.e. ≤ 1e-4 of W on these grids.

/// Work per unit area `W = ∫ t · dg` along a path of uniform side-b
/// displacements (all three node pairs alike; t the traction on side b),
/// with the joint's history and output after each step.
fn walk(j: &Joint, l: Real, path: &[Vec3]) -> Vec<(Real, JointHistory, Real)> {
    let area = 0.5 * l * l;
    let mut hist = JointHistory::default();
    let mut w = 0.0;
    let mut prev: Option<(Vec3, Vec3)> = None;
    let mut out_path = Vec::with_capacity(path.len());
    for g in path {
        let out = joint_update(j, &mut hist, &joint_nodes(l, [*g; 3]), true);
        let t = -out.forces[3..].iter().sum::<Vec3>() / area;
        if let Some((g0, t0)) = prev {
            w += 0.5 * (t + t0).dot(&(g - g0));
        }
        prev = Some((*g, t));
        out_path.push((w, hist, out.energy / area));
        if hist.failed {
            break;
        }
    }
    out_path
}

/// Load in pure tension (then, separately, pure shear) to `D ∈ {0.1, 0.5,
/// 0.9}` on the softening branch, unload to zero opening and reload to the
/// same point. The damage stays constant on the way down and back (checked),
/// so the work the joint gives back must equal the drop of its stored
/// energy, and its fracture energy `work − stored` must not fall. The law
/// keeps the plateau `z(D) f` from δ1 back to δp and then the capped
/// hardening curve, so the joint gives back
/// `z(D) f (δ1 − δp) + ∫₀^δp min([2r − r²] f, z f)`, while its stored
/// energy (the hardening area `⅔ f δp`, whatever D) drops to 0: the
/// difference, about `z(D) f (δ1 − δp)`, is energy that had been booked as
/// fracture on the way up and comes back out of it.
#[test]
fn stored_energy_is_the_unloading_work() {
    let p = granite(GfCalibration::Exact);
    let l = 1e-3;
    let area = 0.5 * l * l;
    let j = Joint::new(p, mean_edge(l));
    let dsp = dp_ref(&p, j.h, p.cohesion);
    let dsc = dc_ref(&p, p.cohesion, dsp, p.gf_shear);
    let n = 20_000;
    let mut failures = Vec::new();
    for (name, dir, dp, dc) in [("tension", Vec3::z(), j.delta_np, j.delta_nc), ("shear", Vec3::x(), dsp, dsc)] {
        for d_frac in [0.1, 0.5, 0.9] {
            let d1 = dp + d_frac * (dc - dp);
            let up = (0..=n).map(|i| dir * (d1 * i as Real / n as Real));
            let path: Vec<Vec3> = up.clone().chain(up.clone().rev()).chain(up).collect();
            let states = walk(&j, l, &path);
            assert_eq!(states.len(), path.len(), "no failure");
            let (w1, h1, e1) = states[n];
            let mut worst = (0.0, n);
            for (k, (w, h, e)) in states.iter().enumerate() {
                assert!((h.work / area - w).abs() <= 1e-3 * w1, "{name}: work {} vs ∫t·dg {w}", h.work / area);
                if k < n {
                    continue;
                }
                assert_eq!(h.damage, h1.damage, "damage constant while unloading");
                // Work given back since δ1 vs the drop of stored energy.
                let err = ((w1 - w) - (e1 - e)).abs() / w1;
                if err > worst.0 {
                    worst = (err, k);
                }
            }
            let (_, k) = worst;
            let (w, h, e) = states[k];
            println!(
                "{name} D {d_frac}: at δ/δ1 {:.2} the joint gave back {:.4} J/m² while its stored energy fell by \
                 {:.4} J/m²; fracture energy (work − stored) {:.4} → {:.4} J/m²",
                path[k].norm() / d1,
                w1 - w,
                e1 - e,
                (h1.work / area) - e1,
                (h.work / area) - e,
            );
            if worst.0 > 1e-3 {
                failures.push(format!("{name} D {d_frac}: {:.3e} of W", worst.0));
            }
        }
    }
    assert!(failures.is_empty(), "work at constant damage ≠ change of stored energy: {failures:?}");
}

/// Proportional mixed loading to failure: side b moves along
/// `(b δsc, 0, a δnc)` until the joint fails (Mixed). `history.work`
/// must be the work done (to 1e-3, the rectangle rule of the joint's own
/// count). The softening increment `[Sn wn + Ss ws] (Z(D) − Z(D_hist))`
/// (`Sn = f_t (δnc − δnp)`, `Ss = f_s (δsc − δsp)`) with `wn = Dn/D`,
/// `ws = Ds/D` is the work `z(D) (Sn dDn + Ss dDs)` on radial paths in
/// `(Dn, Ds)`; on these rays it is an approximation (this test found the
/// earlier weights `Dn²/D²`, which undercounted by up to 55%).
#[test]
fn energy_lost_at_mixed_mode_failure_is_the_work() {
    let mut failures = Vec::new();
    for calibration in [GfCalibration::Paper, GfCalibration::Exact] {
        let p = granite(calibration);
        let l = 1e-3;
        let area = 0.5 * l * l;
        let j = Joint::new(p, mean_edge(l));
        let dsc = dc_ref(&p, p.cohesion, dp_ref(&p, j.h, p.cohesion), p.gf_shear);
        for (a, b) in [(1.0, 0.05), (1.0, 0.3), (1.0, 1.0), (0.2, 1.0)] {
            let dir = Vec3::new(b * dsc, 0.0, a * j.delta_nc);
            let n = 200_000;
            let path: Vec<Vec3> = (0..=n).map(|i| dir * (1.5 * i as Real / n as Real)).collect();
            let states = walk(&j, l, &path);
            let (w, h, _) = *states.last().unwrap();
            assert!(h.failed, "fails by 1.5× the ray");
            let work = h.work / area;
            assert!((work - w).abs() <= 1e-3 * w, "{calibration:?} ({a}, {b}): work {work} vs ∫t·dg {w}");
            let lost = (h.dissipated + h.released) / area;
            println!(
                "{calibration:?} (a, b) = ({a}, {b}): failed at t = {:.4}: ∫t·dg {w:.4}, history.work {work:.4}, \
                 dissipated + released {lost:.4} J/m² ({:+.1}%)",
                1.5 * (states.len() - 1) as Real / n as Real,
                100.0 * (lost - w) / w
            );
            // `dissipated` is the softening branch with weights Dn/D, Ds/D:
            // exact on radial paths in (Dn, Ds). This ray in δ is not one (Dn
            // and Ds start at different displacements), so the formula is an
            // approximation here, held to 5% (measured: ≤ 3.5% over); and it
            // leaves out the hardening areas that broken points can no longer
            // give back, at most 2/3 (f_t δnp + f_s δsp) with f_s ≤ c here
            // (tension). The run's energy account uses `work`, asserted above.
            let dsp_max = 2.0 * p.cohesion * j.h / p.penalty;
            let hardening_max = 2.0 / 3.0 * (p.tensile_strength * j.delta_np + p.cohesion * dsp_max);
            if lost > 1.05 * w || lost < 0.95 * w - hardening_max {
                failures.push(format!("{calibration:?} ({a}, {b}): {:+.3e}", (lost - w) / w));
            }
        }
    }
    assert!(failures.is_empty(), "history.dissipated + released off the work at mixed-mode failure: {failures:?}");
}
