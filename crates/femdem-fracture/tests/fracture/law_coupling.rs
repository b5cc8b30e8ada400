//! The three readings of Eq. 11's hardening branch (`Coupling`) at points
//! computed by hand (reference paper §2.2, Eq. 5–13).
//!
//! Joint: `p0 = 2e11` Pa, `f_t = 2` MPa, `c = 10` MPa, `φ = 45°`
//! (`tan φ = 1`), `G_ft = 20`, `G_fs = 100` J/m², `GfCalibration::Paper`
//! (`δc = 3 Gf / f`, Eq. 10), `h = 1` mm. So `δnp = 2 f_t h / p0 = 2e-8` m
//! (Eq. 6), `δnc = 3 × 20 / 2e6 = 3e-5` m, and for a shear strength `f_s`,
//! `δsp = 2 f_s h / p0 = f_s × 1e-14` m (Eq. 7), `δsc = 300 / f_s` m.
//!
//! Eq. 12: `z(D) = [1 − k e^{λD}] [a(1−D) + b(1−D)^6]`, `a = 0.63`,
//! `b = 1.8`, `k = (a+b−1)/(a+b) = 1.43/2.43 = 0.588477366255`,
//! `λ = (a + 6b)/((a+b)(1−a−b)) = 11.43/(2.43 × −1.43) = −3.289303289303`:
//!
//! * `D = 0.3`: `e^{λD} = 0.372771000785`, `1 − k e^{λD} = 0.780632703242`,
//!   `0.63 × 0.7 + 1.8 × 0.7⁶ = 0.441 + 0.2117682 = 0.6527682`,
//!   `z(0.3) = 0.780632703242 × 0.6527682 = 0.509572204556`;
//! * `D = 0.5`: `e^{λD} = 0.193079811465`, `1 − k e^{λD} = 0.886376901072`,
//!   `0.63 × 0.5 + 1.8 × 0.5⁶ = 0.315 + 0.028125 = 0.343125`,
//!   `z(0.5) = 0.886376901072 × 0.343125 = 0.304138074180`;
//! * `z(1) = 0` (`(1 − D) = 0`).
//!
//! The hardening branch `[2r − r²] f` at `r = 0.5` is `0.75 f`, at
//! `r = 0.9` `0.99 f`; its area `∫₀^r [2ρ − ρ²] f δp dρ = f δp (r² − r³/3)`
//! is `0.208333 f δp` at `r = 0.5`.
//!
//! Tolerance: the values above are written to 12 digits; the crate's `z`
//! agrees with Eq. 12 to 1e-15 (law_curves.rs); every expected value is a
//! product of at most four such numbers: 1e-10 relative.

use crate::law_reference::{COUPLINGS, joint_nodes};

use femdem_core::{Real, Vec3};
use femdem_fracture::{
    Coupling, FailureMode, GfCalibration, Joint, JointHistory, JointParams, Softened, joint_update, point_stress,
    point_stress_with,
};

const Z03: Real = 0.509572204556;
const Z05: Real = 0.304138074180;
const TOL: Real = 1e-10;

fn joint(coupling: Coupling) -> Joint {
    let p = JointParams {
        penalty: 2e11,
        tensile_strength: 2e6,
        cohesion: 10e6,
        friction_angle: 45f64.to_radians(),
        gf_tension: 20.0,
        gf_shear: 100.0,
        calibration: GfCalibration::Paper,
        coupling,
    };
    Joint::new(p.validate().unwrap(), 1e-3)
}

fn close(got: Real, want: Real, what: &str) {
    assert!((got - want).abs() <= TOL * want.abs().max(1.0), "{what}: {got} vs {want}");
}

const DNP: Real = 2e-8;
const DNC: Real = 3e-5;

#[test]
fn the_test_joint_is_as_computed() {
    let j = joint(Coupling::Capped);
    close(j.delta_np, DNP, "δnp");
    close(j.delta_nc, DNC, "δnc");
    close(femdem_fracture::softening::z(0.3), Z03, "z(0.3)");
    close(femdem_fracture::softening::z(0.5), Z05, "z(0.5)");
}

/// The first check: normal softening at `Dn = 0.3`, slip `0.9 δsp`.
/// `δn = δnp + 0.3 (δnc − δnp)`, so `σ = z(0.3) f_t = 1.019144409112` MPa
/// in every option (softening branch), `f_s = c − σ tan φ =
/// 8.980855590888` MPa, `δsp = 8.980855590888e-8` m, `δs = 0.9 δsp`:
/// `Ds = 0`, `D = 0.3`.
/// * Printed: `τ = 0.99 f_s = 8.891047034979` MPa;
/// * Multiplicative: `τ = z(0.3) × 0.99 f_s = 0.504476482510 f_s =
///   4.530630438421` MPa;
/// * Capped: `τ = min(0.99, z(0.3)) f_s = 0.509572204556 f_s =
///   4.576394382248` MPa — the 0.51 f_s.
#[test]
fn softened_normal_and_slip_at_0_9_dsp() {
    let fs = 10e6 - Z03 * 2e6;
    close(fs, 8.980855590888e6, "f_s");
    let dn = DNP + 0.3 * (DNC - DNP);
    let ds = 0.9 * fs * 1e-14;
    for (c, tau) in [
        (Coupling::Printed, 8.891047034979e6),
        (Coupling::Multiplicative, 4.530630438421e6),
        (Coupling::Capped, 4.576394382248e6),
    ] {
        let ps = point_stress(&joint(c), dn, ds, 0.0);
        close(ps.sigma, 1.019144409112e6, &format!("{c:?} σ"));
        close(ps.damage, 0.3, &format!("{c:?} D"));
        close(ps.tau, tau, &format!("{c:?} τ"));
        assert_eq!(ps.softened, Softened { normal: true, shear: false });
        assert_eq!(ps.broke, None);
    }
}

/// The same state reached in 1,000 steps of opening at zero slip, then
/// 1,000 steps of slip at fixed opening, carrying the history as
/// `joint_update` does: the normal softening (`D_hist = 0.3`) is then in the
/// history before the slip starts. Printed still gives `0.99 f_s` (the
/// shear has never been past its peak), Capped `z(0.3) f_s`: the stress
/// does not depend on how many steps reached the state. (Deciding Printed
/// by "`D_hist = 0`" would give 0.99 f_s in one step and 0.51 f_s here.)
#[test]
fn printed_does_not_depend_on_the_number_of_steps() {
    let fs = 10e6 - Z03 * 2e6;
    let (dn1, ds1) = (DNP + 0.3 * (DNC - DNP), 0.9 * fs * 1e-14);
    for (c, tau) in [(Coupling::Printed, 0.99 * fs), (Coupling::Capped, Z03 * fs)] {
        let j = joint(c);
        let (mut d, mut s) = (0.0, Softened::default());
        let n = 1000;
        let path = (1..=n).map(|i| (dn1 * i as Real / n as Real, 0.0));
        let path = path.chain((1..=n).map(|i| (dn1, ds1 * i as Real / n as Real)));
        let mut last = None;
        for (dn, ds) in path {
            let ps = point_stress_with(&j, dn, ds, d, s);
            (d, s) = (ps.damage, ps.softened);
            last = Some(ps);
        }
        let ps = last.unwrap();
        close(ps.damage, 0.3, &format!("{c:?} D"));
        close(ps.tau, tau, &format!("{c:?} τ after 2,000 steps"));
    }
}

/// The second check: shear failed (`D = 1`) while the opening is on
/// its hardening branch. At `δn = 0.5 δnp = 1e-8` m: `σ` without shear
/// damage `= 0.75 f_t = 1.5` MPa, `f_s = 10 − 1.5 = 8.5` MPa,
/// `δsc = 300 / 8.5e6 = 3.529e-5` m; slip `2 δsc`: `Ds = 1`, `D = 1`,
/// `z = 0`. Capped `σ = min(0.75 f_t, 0) = 0`, Multiplicative
/// `σ = 0 × 0.75 f_t = 0`, Printed `σ = 0.75 f_t = 1.5` MPa; `τ = 0` in all.
/// At `δn = δnp`: `f_s = 8` MPa, `δsc = 3.75e-5` m, slip `1e-4` m: Printed
/// carries the full `f_t = 2` MPa. The point broke in shear (`Dn = 0`).
#[test]
fn failed_shear_with_hardening_normal() {
    for (c, s_half, s_peak) in
        [(Coupling::Printed, 1.5e6, 2e6), (Coupling::Multiplicative, 0.0, 0.0), (Coupling::Capped, 0.0, 0.0)]
    {
        let j = joint(c);
        let half = point_stress(&j, 0.5 * DNP, 2.0 * 300.0 / 8.5e6, 0.0);
        close(half.sigma, s_half, &format!("{c:?} σ at δnp/2"));
        assert_eq!((half.tau, half.damage, half.broke), (0.0, 1.0, Some(FailureMode::Shear)), "{c:?}");
        let peak = point_stress(&j, DNP, 1e-4, 0.0);
        close(peak.sigma, s_peak, &format!("{c:?} σ at δnp"));
        assert_eq!((peak.tau, peak.damage, peak.broke), (0.0, 1.0, Some(FailureMode::Shear)), "{c:?}");
    }
}

/// Partial shear softening with the opening on its hardening branch:
/// `δn = 0.5 δnp`, so `f_s = 8.5` MPa (as above), `δsp = 8.5e-8` m,
/// `δsc = 3.529411764706e-5` m, and `δs = δsp + 0.5 (δsc − δsp)`:
/// `Ds = 0.5 = D`. `τ = z(0.5) f_s = 2.585173630531` MPa in all options.
/// `σ`: Printed `0.75 f_t = 1.5` MPa; Multiplicative `z(0.5) × 0.75 f_t =
/// 0.456207111271` MPa; Capped `min(0.75, z(0.5)) f_t = 0.608276148361`
/// MPa. At `δn = 0.1 δnp` (`[2r − r²] = 0.19`, `f_s = 10 − 0.38 = 9.62`
/// MPa): Printed and Capped `0.19 f_t = 0.38` MPa (below the cap),
/// Multiplicative `z(0.5) × 0.38 = 0.115572468188` MPa.
#[test]
fn shear_softening_with_hardening_normal() {
    for (r, fs, expect) in
        [(0.5, 8.5e6, [1.5e6, 0.456207111271e6, 0.608276148361e6]), (0.1, 9.62e6, [0.38e6, 0.115572468188e6, 0.38e6])]
    {
        let (dsp, dsc) = (fs * 1e-14, 300.0 / fs);
        let ds = dsp + 0.5 * (dsc - dsp);
        for (c, sigma) in COUPLINGS.into_iter().zip(expect) {
            let ps = point_stress(&joint(c), r * DNP, ds, 0.0);
            close(ps.damage, 0.5, &format!("{c:?} r {r} D"));
            close(ps.tau, Z05 * fs, &format!("{c:?} r {r} τ"));
            close(ps.sigma, sigma, &format!("{c:?} r {r} σ"));
        }
    }
}

/// Unloading and reloading with history `D_hist`, zero slip (so the shear
/// stores nothing) at `δn = 0.5 δnp`:
/// * after the normal direction softened to `D = 0.3` and came back:
///   Printed and Capped `z(0.3) f_t = 1.019144409112` MPa (the cap: no
///   healing), Multiplicative `z(0.3) × 0.75 f_t = 0.764358306834` MPa;
/// * after only the shear softened, `D = 0.5`: Printed `0.75 f_t = 1.5` MPa
///   (the normal direction never passed its peak), Multiplicative
///   `z(0.5) × 1.5 = 0.456207111271` MPa, Capped `z(0.5) f_t =
///   0.608276148361` MPa.
///
/// Stored energy in the second case, per unit area, `f_t δnp = 0.04` J/m²
/// times: Printed `r² − r³/3 = 0.208333333333` (8.333333333e-3 J/m²);
/// Multiplicative `z(0.5) × 0.208333333333 = 0.063362098788`
/// (2.534483951e-3 J/m²); Capped: the parabola meets `z(0.5)` at
/// `r* = 1 − √(1 − z(0.5)) = 0.165816611398`, area
/// `r*² − r*³/3 + z(0.5)(0.5 − r*) = 0.027495 − 0.001520 + 0.101637 =
/// 0.127613323390` (5.104532936e-3 J/m²).
#[test]
fn unloading_and_reloading_with_history() {
    let normal_first = Softened { normal: true, shear: false };
    let shear_first = Softened { normal: false, shear: true };
    let cases = [
        (Coupling::Printed, 1.019144409112e6, 1.5e6, 8.333333333333e-3),
        (Coupling::Multiplicative, 0.764358306834e6, 0.456207111271e6, 2.534483951503e-3),
        (Coupling::Capped, 1.019144409112e6, 0.608276148361e6, 5.104532935609e-3),
    ];
    for (c, after_normal, after_shear, stored) in cases {
        let j = joint(c);
        let ps = point_stress_with(&j, 0.5 * DNP, 0.0, 0.3, normal_first);
        close(ps.sigma, after_normal, &format!("{c:?} after normal softening"));
        assert_eq!(ps.damage, 0.3, "no damage on reloading");
        let ps = point_stress_with(&j, 0.5 * DNP, 0.0, 0.5, shear_first);
        close(ps.sigma, after_shear, &format!("{c:?} after shear softening"));
        close(ps.stored, stored, &format!("{c:?} stored"));
        // Compression is never affected by damage: σ = 2 (δn/δnp) f_t.
        for s in [normal_first, shear_first] {
            assert_eq!(point_stress_with(&j, -0.5 * DNP, 0.0, 1.0, s).sigma, -2e6, "{c:?}");
        }
    }
}

/// `point_stress` (damage history only) takes a damaged point as having
/// passed both peaks; `joint_update` keeps the directions apart. A joint
/// slipped uniformly to `Ds = 0.5` at zero opening, then opened to
/// `0.5 δnp` with the slip held: Printed carries `0.75 f_t` there (its
/// normal direction never softened); Capped `z(0.5) f_t` — read from the
/// nodal forces.
#[test]
fn the_joint_remembers_which_direction_softened() {
    // Side a: right triangle with legs l; mean edge h = l (2 + √2)/3 = 1 mm.
    let l = 3e-3 / (2.0 + std::f64::consts::SQRT_2);
    let area = 0.5 * l * l;
    // At zero opening f_s = c = 10 MPa: δsp = 1e-7 m, δsc = 3e-5 m.
    let ds = 1e-7 + 0.5 * (3e-5 - 1e-7);
    for (c, sigma) in [(Coupling::Printed, 1.5e6), (Coupling::Capped, 0.608276148361e6)] {
        let j = joint(c);
        let mut h = JointHistory::default();
        let slipped = [Vec3::new(ds, 0.0, 0.0); 3];
        joint_update(&j, &mut h, &joint_nodes(l, slipped), false);
        close(h.damage[0], 0.5, "D after slip");
        assert_eq!(h.softened, [Softened { normal: false, shear: true }; 3]);
        let opened = [Vec3::new(ds, 0.0, 0.5 * DNP); 3];
        let out = joint_update(&j, &mut h, &joint_nodes(l, opened), false);
        let fb: Vec3 = out.forces[3..].iter().sum();
        close(-fb.z / area, sigma, &format!("{c:?} σ from the forces"));
        close(out.normal_stress, sigma, &format!("{c:?} mean σ"));
    }
}
