//! Weak cohesion, `c ≤ f_t tan φ` (reference paper §2.2, Eq. 5, and its
//! polyaxial Test 1: `c = 0.5` MPa, `φ = 33.4°`, `f_t = 1` MPa).
//!
//! Eq. 5, `f_s = c − σ tan φ`, vanishes at the Mohr–Coulomb apex
//! `σ = c / tan φ`. The paper's "automatic tension cut-off" assumes the apex
//! lies beyond `f_t`; when it does not, a point opened in pure tension
//! climbs its hardening parabola until `σ = c / tan φ`, where it has no
//! shear strength left (`Ds = 1`, Eq. 13: `D = 1`) and breaks. Its tensile
//! strength is `min(f_t, c / tan φ)` (`JointParams::effective_tensile_strength`):
//! for Test 1, `0.5 / tan 33.4° = 0.5 / 0.659379 = 0.758290` MPa.

use femdem_core::{Real, Vec3};
use femdem_fracture::{
    Coupling, FailureMode, GfCalibration, Joint, JointHistory, JointParams, joint_update, point_stress,
};

fn params(ft: Real, c: Real, phi_deg: Real, coupling: Coupling) -> JointParams {
    JointParams {
        penalty: 1e11,
        tensile_strength: ft,
        cohesion: c,
        friction_angle: phi_deg.to_radians(),
        gf_tension: 50.0,
        gf_shear: 50.0,
        calibration: GfCalibration::Paper,
        coupling,
    }
}

const COUPLINGS: [Coupling; 3] = [Coupling::Printed, Coupling::Multiplicative, Coupling::Capped];

/// The largest opening at which a fresh point in pure tension is still
/// intact, by bisection on `[0, 2 δnc]` down to adjacent floats, and the
/// normal stress there. (A fresh point is broken at any opening beyond its
/// break: in pure tension `D_now` grows with the opening, and an opening
/// past `δnp` has gone over the apex if the parabola reaches it.)
fn last_intact(j: &Joint) -> (Real, Real) {
    let (mut lo, mut hi) = (0.0, 2.0 * j.delta_nc);
    assert!(point_stress(j, hi, 0.0, 0.0).damage >= 1.0);
    loop {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if point_stress(j, mid, 0.0, 0.0).damage >= 1.0 { hi = mid } else { lo = mid }
    }
    (lo, point_stress(j, lo, 0.0, 0.0).sigma)
}

/// Weak cohesion: a point opened from 0 to `1.5 δnp` in one evaluation
/// breaks (tensile), as it does in 1,000 steps, for each coupling — the
/// parabola's top `f_t` lies beyond the apex `c / tan φ` — and a strong
/// one does not (it softens: `D = Dn` of 0.5 δnp past the peak, `< 1`).
#[test]
fn jumping_over_the_apex_breaks_the_point() {
    for coupling in COUPLINGS {
        let weak = Joint::new(params(1e6, 0.5e6, 33.4, coupling), 1e-3);
        let one = point_stress(&weak, 1.5 * weak.delta_np, 0.0, 0.0);
        assert_eq!((one.broke, one.sigma, one.damage), (Some(FailureMode::Tensile), 0.0, 1.0), "{coupling:?}");
        let (mut d, mut s, mut broke) = (0.0, femdem_fracture::Softened::default(), None);
        for i in 1..=1000 {
            let ps = femdem_fracture::point_stress_with(&weak, 1.5 * weak.delta_np * i as Real / 1000.0, 0.0, d, s);
            (d, s) = (ps.damage, ps.softened);
            broke = broke.or(ps.broke);
        }
        assert_eq!((broke, d), (Some(FailureMode::Tensile), 1.0), "{coupling:?} in 1,000 steps");
        let strong = Joint::new(params(3e6, 15e6, 30.0, coupling), 1e-3);
        let one = point_stress(&strong, 1.5 * strong.delta_np, 0.0, 0.0);
        assert!(one.broke.is_none() && one.damage < 1.0 && one.sigma > 0.0, "{coupling:?}: {one:?}");
    }
}

#[test]
fn polyaxial_test_1_parameters_are_accepted() {
    let p = params(1e6, 0.5e6, 33.4, Coupling::Capped).validate().expect("valid");
    assert!(p.cohesion_limits_tension());
    let apex = 0.5e6 / 33.4f64.to_radians().tan();
    assert!((apex - 0.758290e6).abs() < 1.0, "{apex}");
    assert_eq!(p.effective_tensile_strength(), apex);
    let strong = params(3e6, 15e6, 30.0, Coupling::Capped);
    assert!(!strong.cohesion_limits_tension());
    assert_eq!(strong.effective_tensile_strength(), 3e6);
    // φ = 0: no apex (c / 0 = ∞), f_t.
    let flat = params(3e6, 1e6, 0.0, Coupling::Capped).validate().expect("valid");
    assert_eq!(flat.effective_tensile_strength(), 3e6);
    assert!(!flat.cohesion_limits_tension());
}

/// The peak normal stress under pure opening is `min(f_t, c / tan φ)`, for
/// weak cohesion (Test 1), for a strong one (the paper's granite), and at
/// `c = 1.5 f_t tan φ`, each coupling option. Tolerance 1e-12 relative: the
/// bisection brackets the failure opening between adjacent floats, the
/// parabola's slope is at most `2 f_t/δnp`, so σ at the last intact float
/// is within `2 f_t × 2⁻⁵²` (~4e-16 f_t) of the strength, plus the rounding
/// of `c − σ tan φ` (a few ulp of c), where the decision is taken.
///
/// Weak cohesion: the point breaks on the hardening branch (`δ < δnp`) and
/// the label is tensile (`f_s ≤ 0` only happens at the apex, in tension);
/// no softening branch, so nothing is booked in `dissipated` and the
/// stored energy at the break is 0 (`D = 1`). Strong: the break is at δnc
/// as usual.
#[test]
fn peak_normal_stress_is_the_effective_tensile_strength() {
    for coupling in COUPLINGS {
        let cases = [
            ("Test 1", params(1e6, 0.5e6, 33.4, coupling)),
            ("granite", params(3e6, 15e6, 30.0, coupling)),
            ("c = 1.5 f_t tan φ", params(2e6, 1.5 * 2e6 * 40f64.to_radians().tan(), 40.0, coupling)),
        ];
        for (name, p) in cases {
            let j = Joint::new(p.validate().unwrap(), 1e-3);
            let strength = p.effective_tensile_strength();
            let (at, sigma) = last_intact(&j);
            // The largest σ on the way: at the break (weak) or at δnp
            // (strong); a grid of 10,000 openings finds nothing above.
            let grid = (0..=10_000).map(|i| point_stress(&j, at * i as Real / 10_000.0, 0.0, 0.0).sigma);
            let top = if at > j.delta_np { point_stress(&j, j.delta_np, 0.0, 0.0).sigma } else { sigma };
            let peak = grid.fold(top, Real::max);
            println!(
                "{coupling:?} {name}: peak {peak:.6e} Pa at δn/δnp = {:.6}, strength {strength:.6e}",
                at / j.delta_np
            );
            assert!((peak - strength).abs() <= 1e-12 * strength, "{coupling:?} {name}: {peak} vs {strength}");
            let past = point_stress(&j, at * (1.0 + 1e-12), 0.0, 0.0);
            assert_eq!((past.sigma, past.tau, past.damage), (0.0, 0.0, 1.0), "{coupling:?} {name}");
            assert_eq!(past.broke, Some(FailureMode::Tensile), "{coupling:?} {name}");
            if p.cohesion_limits_tension() {
                assert!(at < j.delta_np, "breaks on the hardening branch");
                assert_eq!((past.dissipated, past.stored), (0.0, 0.0));
            } else {
                assert!((at - j.delta_nc).abs() <= 1e-12 * j.delta_nc, "breaks at δnc");
            }
        }
    }
}

/// At the apex and beyond, with slips, damage histories and huge openings:
/// every number finite (no `0/0` from `δsp = 0` when `f_s ≤ 0`). The exact
/// case `f_s = 0`: `c = f_t tan φ` computed in floating point, at `δnp`
/// (`σ = f_t`, so `c − σ tan φ = 0` exactly).
#[test]
fn no_nan_at_or_beyond_the_apex() {
    let phi: Real = 45.0;
    let exact = params(2e6, 2e6 * phi.to_radians().tan(), phi, Coupling::Capped);
    assert!(exact.cohesion_limits_tension());
    for coupling in COUPLINGS {
        for p in [params(1e6, 0.5e6, 33.4, coupling), JointParams { coupling, ..exact }] {
            let j = Joint::new(p.validate().unwrap(), 1e-3);
            let at_peak = point_stress(&j, j.delta_np, 0.0, 0.0);
            assert_eq!(at_peak.damage, 1.0, "{coupling:?}: f_s ≤ 0 at δnp breaks the point");
            for dn in [0.5, 0.9, 1.0, 1.5, 1e3, 1e300].map(|r| r * j.delta_np) {
                for ds in [0.0, 1e-12, 1e-6, 1.0, 1e300] {
                    for d_hist in [0.0, 0.5, 1.0] {
                        let ps = point_stress(&j, dn, ds, d_hist);
                        let v = [ps.sigma, ps.tau, ps.damage, ps.dissipated, ps.stored];
                        assert!(v.iter().all(|x| x.is_finite()), "{coupling:?} ({dn}, {ds}, {d_hist}): {ps:?}");
                    }
                }
            }
        }
    }
}

/// A whole Test-1 joint opened in pure tension (n = 100,000 steps to
/// `δnp`): the traction read from its forces peaks at `c / tan φ` — above
/// `c / tan φ − 2 f_t / n` (the grid spacing times the steepest slope of the
/// parabola) and not above it (1e-12) — and the joint fails tensile there.
#[test]
fn a_weak_joint_fails_in_tension_at_the_apex() {
    let p = params(1e6, 0.5e6, 33.4, Coupling::Capped).validate().unwrap();
    let l = 1e-3 * 3.0 / (2.0 + std::f64::consts::SQRT_2);
    let j = Joint::new(p, 1e-3);
    let area = 0.5 * l * l;
    let a = [Vec3::zeros(), Vec3::new(l, 0.0, 0.0), Vec3::new(0.0, l, 0.0)];
    let n = 100_000;
    let mut h = JointHistory::default();
    let mut peak = 0.0f64;
    let mut failed = None;
    for i in 1..=n {
        let d = Vec3::new(0.0, 0.0, j.delta_np * i as Real / n as Real);
        let out = joint_update(&j, &mut h, &[a[0], a[1], a[2], a[2] + d, a[1] + d, a[0] + d], true);
        if out.failed.is_some() {
            failed = out.failed;
            break;
        }
        peak = peak.max(-out.forces[3..].iter().sum::<Vec3>().z / area);
    }
    let apex = p.effective_tensile_strength();
    assert_eq!(failed, Some(FailureMode::Tensile));
    assert!(peak <= apex * (1.0 + 1e-12) && peak >= apex - 2.0 * p.tensile_strength / n as Real, "{peak} vs {apex}");
}
