//! The joint kernel of the force pass: the law of `law.rs` (Eq. 3–13)
//! evaluated with the same arithmetic, operation for operation, but without
//! the work a step does not need.
//!
//! [`joint_update`](crate::joint_update) is the readable reference: it
//! evaluates every term of the law at every point. Per integration point
//! that is two or three calls of Munjiza's softening curve `z(D)` (Eq. 12:
//! an `exp` and a `powf` each), the stored energy of both directions, and a
//! failure label — although in an intact step the damage does not change
//! and nobody reads the energy. [`joint_update_fast`] gives the same forces,
//! history and output, bit for bit, and:
//!
//! - evaluates `z` only where the damage is not zero, and `z(D)` after the
//!   update only when `D` grew (`z(0)` is a constant, [`KernelConsts::z0`];
//!   `z(D)` of an unchanged `D` is the `z(D_hist)` already in hand): an
//!   intact joint calls no transcendental function at all;
//! - labels a point ([`crate::FailureMode`]) only when it breaks;
//! - sums the stored energy (`Coupling::stored`, Eq. 11 integrated) only
//!   when it is asked for or the joint fails (then it is
//!   `JointHistory::released`);
//! - computes the shear traction `τ δs/|δs|` once for the work and the
//!   force.
//!
//! Since every value that is computed is computed as in `law.rs`, a
//! comparison of the two paths can demand bit equality
//! (`tests/fracture/kernel_matches_law.rs`).

use femdem_core::{Real, Vec3};

use crate::softening::{z, z_integral};
use crate::{Coupling, FailureMode, GAUSS, Joint, JointHistory, JointOutput, Softened, joint_kinematics};

/// Constants the kernel shares across joints, computed once per pass.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct KernelConsts {
    /// `z(0)` of Eq. 12 (1 up to round-off), the softening factor of every
    /// undamaged point.
    pub z0: Real,
}

impl KernelConsts {
    /// The constants (one evaluation of Eq. 12).
    pub fn new() -> KernelConsts {
        KernelConsts { z0: z(0.0) }
    }

    /// `z(d)` of Eq. 12, without evaluating it for an undamaged point.
    #[inline]
    fn z(&self, d: Real) -> Real {
        if d == 0.0 { self.z0 } else { z(d) }
    }
}

impl Default for KernelConsts {
    fn default() -> Self {
        KernelConsts::new()
    }
}

/// What a point's evaluation leaves for the stored energy, summed only
/// when needed (see `Coupling::stored`).
#[derive(Clone, Copy, Default)]
struct ForStored {
    rn: Real,
    zd: Real,
    fs: Real,
    dsp: Real,
    rs: Real,
    softened: Softened,
}

impl ForStored {
    /// The stored energy per unit area of the point, as `point_stress_with`
    /// computes it.
    #[inline]
    fn stored(&self, joint: &Joint) -> Real {
        let coupling: Coupling = joint.params.coupling;
        coupling.stored(joint.params.tensile_strength, joint.delta_np, self.rn, self.zd, self.softened.normal)
            + if self.fs > 0.0 {
                coupling.stored(self.fs, self.dsp, self.rs, self.zd, self.softened.shear)
            } else {
                0.0
            }
    }
}

/// The result of one point (the parts of `PointStress` the kernel uses).
#[derive(Clone, Copy)]
struct Point {
    sigma: Real,
    tau: Real,
    damage: Real,
    broke: Option<FailureMode>,
    dissipated: Real,
    softened: Softened,
    for_stored: ForStored,
}

/// One integration point: `point_stress_with` (Eq. 5–7, 11–13) with `z`
/// evaluated only where the damage is not zero and not known already, and
/// the failure label only when the point breaks.
#[inline(always)]
fn point(c: &KernelConsts, joint: &Joint, dn: Real, ds: Real, d_hist: Real, softened: Softened) -> Point {
    let p = &joint.params;
    let coupling: Coupling = p.coupling;
    let ft = p.tensile_strength;
    let (dnp, dnc) = (joint.delta_np, joint.delta_nc);
    let z_hist = c.z(d_hist);
    let rn = dn / dnp;
    let dn_soft = if dn > dnp { ((dn - dnp) / (dnc - dnp)).min(1.0) } else { 0.0 };
    let sigma_trial = if rn < 0.0 {
        2.0 * rn * ft
    } else if rn <= 1.0 {
        coupling.hardening_branch(ft, rn, z_hist, softened.normal)
    } else {
        let d = dn_soft.max(d_hist);
        (if d == d_hist { z_hist } else { z(d) }) * ft
    };
    let over_the_apex = rn > 1.0
        && !softened.normal
        && p.cohesion <= ft * joint.tan_phi
        && p.cohesion - coupling.hardening_branch(ft, 1.0, z_hist, false) * joint.tan_phi <= 0.0;
    let fs = if over_the_apex { 0.0 } else { p.cohesion - sigma_trial * joint.tan_phi };
    let (dsp, dsc) = if fs > 0.0 {
        let dsp = 2.0 * fs * joint.h / p.penalty;
        (dsp, p.critical_displacement(fs, dsp, p.gf_shear))
    } else {
        (0.0, 0.0)
    };
    let ds_soft = if fs <= 0.0 {
        1.0
    } else if ds > dsp {
        ((ds - dsp) / (dsc - dsp)).min(1.0)
    } else {
        0.0
    };
    // Eq. 13.
    let d_now = if dn >= dnc || (fs > 0.0 && ds >= dsc) {
        1.0
    } else if dn_soft > 0.0 && ds_soft > 0.0 {
        (dn_soft * dn_soft + ds_soft * ds_soft).sqrt().min(1.0)
    } else {
        dn_soft + ds_soft
    };
    let damage = d_now.max(d_hist);
    let zd = if damage == d_hist { z_hist } else { z(damage) };
    let rs = if fs > 0.0 { ds / dsp } else { 0.0 };
    let now_softened =
        Softened { normal: softened.normal || rn > 1.0 || fs <= 0.0, shear: softened.shear || fs <= 0.0 || rs > 1.0 };
    // Eq. 11.
    let sigma = if rn < 0.0 {
        2.0 * rn * ft
    } else if rn <= 1.0 {
        coupling.hardening_branch(ft, rn, zd, now_softened.normal)
    } else {
        zd * ft
    };
    let tau = if fs <= 0.0 {
        0.0
    } else if rs <= 1.0 {
        coupling.hardening_branch(fs, rs, zd, now_softened.shear)
    } else {
        zd * fs
    };
    let broke = (d_hist < 1.0 && damage >= 1.0)
        .then(|| if fs <= 0.0 { FailureMode::Tensile } else { FailureMode::from_contributions(dn_soft, ds_soft) });
    let dissipated = if damage > d_hist {
        let norm = (dn_soft * dn_soft + ds_soft * ds_soft).sqrt();
        let (wn, ws) = if norm > 0.0 { (dn_soft / norm, ds_soft / norm) } else { (1.0, 0.0) };
        let scale = ft * (dnc - dnp) * wn + if fs > 0.0 { fs * (dsc - dsp) * ws } else { 0.0 };
        scale * z_integral(d_hist, damage)
    } else {
        0.0
    };
    Point {
        sigma,
        tau,
        damage,
        broke,
        dissipated,
        softened: now_softened,
        for_stored: ForStored { rn, zd, fs, dsp, rs, softened: now_softened },
    }
}

/// Evaluates a joint at current positions `x = [N1 … N6]` and updates its
/// history: [`crate::joint_update`] (Eq. 3–13, its doc says what is
/// computed), bit for bit, with the shortcuts of the module doc. `c` from
/// [`KernelConsts::new`].
#[inline]
pub fn joint_update_fast(
    c: &KernelConsts,
    joint: &Joint,
    history: &mut JointHistory,
    x: &[Vec3; 6],
    with_energy: bool,
) -> JointOutput {
    let mut out = JointOutput { forces: [Vec3::zeros(); 6], energy: 0.0, normal_stress: 0.0, failed: None };
    if history.failed {
        return out;
    }
    let Some(k) = joint_kinematics(x) else {
        history.failed = true;
        history.released = 0.0;
        out.failed = Some(FailureMode::Collapsed);
        return out;
    };
    let weight = k.frame.area / 3.0;
    let mut broken_points = 0;
    let mut mode = None;
    // The halves of this step's work that end on this evaluation's
    // tractions: taken back if the joint fails now (`JointHistory::work`).
    let mut ending = 0.0;
    let mut for_stored = [ForStored::default(); 3];
    for (i, w) in GAUSS.iter().enumerate() {
        let slip = k.slip[i];
        let ds = slip.norm();
        let ps = point(c, joint, k.opening[i], ds, history.damage[i], history.softened[i]);
        history.damage[i] = ps.damage;
        history.softened[i] = ps.softened;
        let [ln, lx, ly, lz] = history.last[i];
        let [sigma_last, tau_last] = history.last_stress[i];
        let slip_last = Vec3::new(lx, ly, lz);
        let d_slip = slip - slip_last;
        // Trapezoid rule on the tractions (see `JointHistory::work`); the
        // shear traction of this evaluation serves the force below too.
        let shear = if ds > 0.0 { slip * (ps.tau / ds) } else { Vec3::zeros() };
        let mut traction = shear;
        let ds_last = slip_last.norm();
        if ds_last > 0.0 {
            traction += slip_last * (tau_last / ds_last);
        }
        let normal_work = 0.5 * (sigma_last + ps.sigma) * (k.opening[i] - ln);
        history.work += weight * (normal_work + 0.5 * traction.dot(&d_slip));
        ending += weight * 0.5 * (ps.sigma * (k.opening[i] - ln) + shear.dot(&d_slip));
        history.last[i] = [k.opening[i], slip.x, slip.y, slip.z];
        history.last_stress[i] = [ps.sigma, ps.tau];
        history.dissipated += weight * ps.dissipated;
        if ps.damage >= 1.0 {
            broken_points += 1;
        }
        if ps.broke.is_some() {
            mode = ps.broke;
        }
        let mut t = k.frame.z * ps.sigma;
        if ds > 0.0 {
            t += shear;
        }
        let f = t * weight;
        for (node_a, node_b, xi) in [(0, 5, w[0]), (1, 4, w[1]), (2, 3, w[2])] {
            out.forces[node_a] += f * xi;
            out.forces[node_b] -= f * xi;
        }
        for_stored[i] = ps.for_stored;
        out.normal_stress += ps.sigma / 3.0;
    }
    let stored_total = |out_of: &[ForStored; 3]| {
        let mut total = 0.0;
        for s in out_of {
            total += weight * s.stored(joint);
        }
        total
    };
    if broken_points >= 2 {
        history.failed = true;
        history.work -= ending;
        history.released = stored_total(&for_stored);
        out.failed = Some(mode.unwrap_or(FailureMode::Mixed));
        out.forces = [Vec3::zeros(); 6];
        return out;
    }
    if with_energy {
        out.energy = stored_total(&for_stored);
    }
    out
}
