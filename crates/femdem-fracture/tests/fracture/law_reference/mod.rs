//! The cohesive joint law of the reference paper, §2.2 (Eq. 5–13, Fig. 3),
//! restated independently of the crate's code for `law_curves.rs` and
//! `law_energy.rs`: Eq. 12 (`z_ref`) and its area (`area_ref`, composite
//! Simpson), Eq. 6–7 (`dp_ref`), Eq. 10 (`dc_ref`), Eq. 11 and Eq. 13
//! (`ref_point`), the proptest parameter ranges (`case_strategy`), the
//! geometry of a test joint, and a uniform walk of one (`walk`).
//!
//! Parameter ranges, and the two choices the paper leaves open: see the
//! header of `law_curves.rs`.
#![allow(dead_code)]

use std::sync::LazyLock;

use femdem_core::{Real, Vec3};
use femdem_fracture::{Coupling, GfCalibration, Joint, JointHistory, JointParams, joint_update};
use proptest::prelude::*;

// ---------------------------------------------------------------------------
// Eq. 12, restated.

/// `a`, `b`, `c` of Eq. 12 (paper, after Eq. 12).
pub const ZA: Real = 0.63;
pub const ZB: Real = 1.8;
pub const ZC: i32 = 6;

/// Eq. 12 written as `z = g(D) q(D)`, `g = 1 − k e^{λD}`,
/// `k = (a+b−1)/(a+b)`, `λ = (a+bc)/((a+b)(1−a−b))`,
/// `q = a(1−D) + b(1−D)^c`, for `D ∈ [0, 1]`.
pub fn z_ref(d: Real) -> Real {
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
pub fn z_lipschitz() -> Real {
    let s = ZA + ZB;
    let lambda = (ZA + ZB * Real::from(ZC)) / (s * (1.0 - s));
    (s - 1.0) * lambda.abs() + ZA + ZB * Real::from(ZC)
}

/// `∫_{d0}^{d1} z_ref` by composite Simpson with `n` panels.
pub fn simpson(d0: Real, d1: Real, n: usize) -> Real {
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
pub static AREA: LazyLock<Real> = LazyLock::new(|| simpson(0.0, 1.0, 20_000));

pub fn area_ref() -> Real {
    *AREA
}

// ---------------------------------------------------------------------------
// Eq. 6, 7, 10, 11, 13, restated.

/// Peak displacement, Eq. 6–7.
pub fn dp_ref(p: &JointParams, h: Real, f: Real) -> Real {
    2.0 * f * h / p.penalty
}

/// Critical displacement, Eq. 10 (or the exact calibration); never below
/// δp (a Gf too small for the element fails at the peak).
pub fn dc_ref(p: &JointParams, f: Real, dp: Real, gf: Real) -> Real {
    let dc = match p.calibration {
        GfCalibration::Paper => 3.0 * gf / f,
        GfCalibration::Exact => dp + gf / (f * area_ref()),
    };
    dc.max(dp)
}

/// `[2r − r²] f`, the hardening branch of Eq. 11.
pub fn hard(f: Real, r: Real) -> Real {
    (2.0 * r - r * r) * f
}

/// Normalised softening displacement `(δ − δp)/(δc − δp)` in `[0, 1]`.
pub fn soft(d: Real, dp: Real, dc: Real) -> Real {
    if d <= dp {
        0.0
    } else if d >= dc {
        1.0
    } else {
        (d - dp) / (dc - dp)
    }
}

/// The reference point law for a fresh point (no history): `(σ, τ, D, f_s)`
/// at opening `dn` and slip magnitude `ds ≥ 0` (Eq. 5–7, 10, 11, 13), for
/// the joint's coupling option (`hardening_ref`).
/// Assumes `f_s > 0` (true for the parameter ranges used).
pub fn ref_point(j: &Joint, dn: Real, ds: Real) -> (Real, Real, Real, Real) {
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
        hardening_ref(p.coupling, ft, dn / dnp, zd)
    } else {
        zd * ft
    };
    let tau = if ds <= dsp { hardening_ref(p.coupling, fs, ds / dsp, zd) } else { zd * fs };
    (sigma, tau, d, fs)
}

/// The hardening branch of Eq. 11 (`0 ≤ r ≤ 1`) of a fresh point (one that
/// has never been past its peak) with damage factor `zd`, as each
/// [`Coupling`] option defines it: as printed `[2r − r²] f`; times `z(D)`;
/// capped at `z(D) f`.
pub fn hardening_ref(coupling: Coupling, f: Real, r: Real, zd: Real) -> Real {
    match coupling {
        Coupling::Printed => hard(f, r),
        Coupling::Multiplicative => zd * hard(f, r),
        Coupling::Capped => hard(f, r).min(zd * f),
    }
}

/// The three coupling options.
pub const COUPLINGS: [Coupling; 3] = [Coupling::Printed, Coupling::Multiplicative, Coupling::Capped];

/// `p` with coupling `c`.
pub fn with_coupling(p: JointParams, c: Coupling) -> JointParams {
    JointParams { coupling: c, ..p }
}

// ---------------------------------------------------------------------------
// Parameters and geometry.

#[derive(Clone, Copy, Debug)]
pub struct Case {
    pub params: JointParams,
    pub h: Real,
}

impl Case {
    pub fn joint(&self) -> Joint {
        Joint::new(self.params, self.h)
    }
}

pub fn case_strategy() -> impl Strategy<Value = Case> {
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
                    coupling: Coupling::default(),
                },
                h,
            }
        })
}

/// A granite-like joint (the crate's unit-test values): `p0 = 26e10` Pa,
/// `f_t = 3` MPa, `c = 15` MPa, `φ = 30°`, `G_ft = 50`, `G_fs = 500` J/m².
pub fn granite(calibration: GfCalibration) -> JointParams {
    JointParams {
        penalty: 26e10,
        tensile_strength: 3e6,
        cohesion: 15e6,
        friction_angle: 30f64.to_radians(),
        gf_tension: 50.0,
        gf_shear: 500.0,
        calibration,
        coupling: Coupling::default(),
    }
}

/// Mean edge of the right triangle with legs `l`: `l (2 + √2) / 3`.
pub fn mean_edge(l: Real) -> Real {
    l * (2.0 + std::f64::consts::SQRT_2) / 3.0
}

/// The joint `N1..N6` whose side a is the triangle `(0,0,0), (l,0,0),
/// (0,l,0)` and whose side b is the same triangle with node pair `k`
/// (N1–N6, N2–N5, N3–N4) moved by `d[k]`.
pub fn joint_nodes(l: Real, d: [Vec3; 3]) -> [Vec3; 6] {
    let a = [Vec3::zeros(), Vec3::new(l, 0.0, 0.0), Vec3::new(0.0, l, 0.0)];
    [a[0], a[1], a[2], a[2] + d[2], a[1] + d[1], a[0] + d[0]]
}

pub fn all_finite(ps: &femdem_fracture::PointStress) -> bool {
    ps.sigma.is_finite()
        && ps.tau.is_finite()
        && ps.damage.is_finite()
        && ps.dissipated.is_finite()
        && ps.stored.is_finite()
}

/// Work per unit area `W = ∫ t · dg` along a path of uniform side-b
/// displacements (all three node pairs alike; t the traction on side b),
/// with the joint's history and output after each step.
pub fn walk(j: &Joint, l: Real, path: &[Vec3]) -> Vec<(Real, JointHistory, Real)> {
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
