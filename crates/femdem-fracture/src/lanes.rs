//! Four joints at a time: the intact, elastic regime of the joint law
//! (Eq. 3, 5–7, 11) in SIMD lanes ([`F4`], four `f64` a lane group), with
//! no branch in the lane arithmetic.
//!
//! In a step most joints are intact and stay so: no point damaged before
//! or after, every point below its peaks (`δn < δnp`, `δs < δsp`, `f_s > 0`,
//! so `D = 0` by Eq. 13 and `z(0)` is the softening factor of Eq. 12). For
//! such a point the law reduces to Eq. 11's compression line or hardening
//! parabola in `σ`, Eq. 5 for `f_s`, Eq. 7 for `δsp` and the hardening
//! parabola in `τ`. [`joint_update_lanes`] evaluates that for four joints
//! together, with every operation of [`crate::joint_update`] in the same
//! order (branches become selects: both sides are computed, one is kept),
//! so its forces and history are the scalar law's bit for bit. Where any
//! of the four leaves the regime — a point damaged, reaching a peak, a
//! collapsed mid-plane, a failed joint, mixed couplings — it writes nothing
//! and says so, and the caller evaluates the four with
//! [`crate::joint_update_fast`]. It never computes energies: a step that
//! asks for them uses the scalar kernel.

use femdem_core::lanes::{F4, F4x3 as V3};
use femdem_core::{Real, Vec3};

use crate::{Coupling, GAUSS, Joint, JointHistory, KernelConsts};

/// Joints per lane group.
pub const LANES: usize = 4;

type V = F4;

/// A lane of one value per joint.
#[inline(always)]
fn per_joint(joints: &[&Joint; LANES], f: impl Fn(&Joint) -> Real) -> V {
    V::from([f(joints[0]), f(joints[1]), f(joints[2]), f(joints[3])])
}

/// The hardening branch of Eq. 11 for a direction that has not softened
/// and an undamaged point (`Coupling::hardening_branch` with `z(0)`).
#[inline(always)]
fn hardening_branch(coupling: Coupling, f: V, r: V, z0: V) -> V {
    let h = (V::splat(2.0) * r - r * r) * f;
    match coupling {
        Coupling::Printed => h,
        Coupling::Capped => h.simd_lt(z0 * f).select(h, z0 * f),
        Coupling::Multiplicative => z0 * h,
    }
}

/// Evaluates the four joints `joints` at positions `x` with histories
/// `history` (each `[N1 … N6]`, as [`crate::joint_update`]) when all four
/// are intact and every point stays in the elastic regime of the module
/// doc: writes the new histories and the nodal forces into `forces` and
/// returns `true`, the scalar law's results bit for bit. Otherwise returns
/// `false` and writes nothing.
#[inline(always)]
pub fn joint_update_lanes(
    c: &KernelConsts,
    joints: [&Joint; LANES],
    history: &mut [JointHistory; LANES],
    x: &[[Vec3; 6]; LANES],
    forces: &mut [[Vec3; 6]; LANES],
) -> bool {
    let coupling = joints[0].params.coupling;
    if joints.iter().any(|j| j.params.coupling != coupling)
        || history.iter().any(|h| h.failed || h.damage != [0.0; 3] || h.softened.iter().any(|s| s.normal || s.shear))
    {
        return false;
    }
    // Eq. 3: the frame through N16, N25, N34 (`joint_kinematics`).
    let node = |k: usize| V3::gather([x[0][k], x[1][k], x[2][k], x[3][k]]);
    let n = [node(0), node(1), node(2), node(3), node(4), node(5)];
    let half = V::splat(0.5);
    let m16 = n[0].add(n[5]).scale(half);
    let m25 = n[1].add(n[4]).scale(half);
    let m34 = n[2].add(n[3]).scale(half);
    let e1 = m25.sub(m16);
    let normal = e1.cross(m34.sub(m16));
    let twice_area = normal.norm();
    let len1 = e1.norm();
    let mut ok = twice_area.simd_gt(V::ZERO) & len1.simd_gt(V::ZERO) & twice_area.simd_lt(V::splat(Real::INFINITY));
    let z = normal.div(twice_area);
    let weight = half * twice_area / V::splat(3.0);
    // The joints' constants.
    let ft = per_joint(&joints, |j| j.params.tensile_strength);
    let cohesion = per_joint(&joints, |j| j.params.cohesion);
    let tan_phi = per_joint(&joints, |j| j.tan_phi);
    let h = per_joint(&joints, |j| j.h);
    let penalty = per_joint(&joints, |j| j.params.penalty);
    let dnp = per_joint(&joints, |j| j.delta_np);
    let z0 = V::splat(c.z0);
    let two = V::splat(2.0);
    let mut work = V::from([history[0].work, history[1].work, history[2].work, history[3].work]);
    let mut out = [V3::zero(); 6];
    // Each point in turn, keeping what its history will keep: `[δn, δs]`
    // and `[σ, τ]`. (A loop, not `array::from_fn`, whose closure the
    // compiler keeps out of line, i.e. out of a dispatched caller's
    // instruction set.)
    let mut points = [([V::ZERO; 4], [V::ZERO; 2]); 3];
    for (i, point) in points.iter_mut().enumerate() {
        let w = &GAUSS[i];
        let (w0, w1, w2) = (V::splat(w[0]), V::splat(w[1]), V::splat(w[2]));
        let pa = n[0].scale(w0).add(n[1].scale(w1)).add(n[2].scale(w2));
        let pb = n[5].scale(w0).add(n[4].scale(w1)).add(n[3].scale(w2));
        let g = pb.sub(pa);
        let dn = g.dot(z);
        let slip = g.sub(z.scale(dn));
        // Eq. 11 below the peak, Eq. 5, Eq. 7 (`point_stress_with` at D = 0).
        let rn = dn / dnp;
        let sigma = rn.simd_lt(V::ZERO).select(two * rn * ft, hardening_branch(coupling, ft, rn, z0));
        let fs = cohesion - sigma * tan_phi;
        let dsp = two * fs * h / penalty;
        let ds = slip.norm();
        let rs = ds / dsp;
        let tau = hardening_branch(coupling, fs, rs, z0);
        ok = ok & dn.simd_lt(dnp) & fs.simd_gt(V::ZERO) & ds.simd_lt(dsp);
        // The work, trapezoid rule (see `JointHistory::work`).
        let lane_last = |k: usize| V::from([0, 1, 2, 3].map(|l| history[l].last[i][k]));
        let lane_stress = |k: usize| V::from([0, 1, 2, 3].map(|l| history[l].last_stress[i][k]));
        let (ln, sigma_last, tau_last) = (lane_last(0), lane_stress(0), lane_stress(1));
        let slip_last = V3 { x: lane_last(1), y: lane_last(2), z: lane_last(3) };
        let d_slip = slip.sub(slip_last);
        let slipping = ds.simd_gt(V::ZERO);
        let shear = V3::select(slipping, slip.scale(tau / ds), V3::zero());
        let ds_last = slip_last.norm();
        let traction = V3::select(ds_last.simd_gt(V::ZERO), shear.add(slip_last.scale(tau_last / ds_last)), shear);
        let normal_work = half * (sigma_last + sigma) * (dn - ln);
        work += weight * (normal_work + half * traction.dot(d_slip));
        // Forces: the traction on side a, its opposite on side b.
        let t = z.scale(sigma);
        let t = V3::select(slipping, t.add(shear), t);
        let f = t.scale(weight);
        for (node_a, node_b, xi) in [(0, 5, w0), (1, 4, w1), (2, 3, w2)] {
            out[node_a] = out[node_a].add(f.scale(xi));
            out[node_b] = out[node_b].sub(f.scale(xi));
        }
        *point = ([dn, slip.x, slip.y, slip.z], [sigma, tau]);
    }
    if !ok.all() {
        return false;
    }
    let weight = weight.as_array();
    for (l, hist) in history.iter_mut().enumerate() {
        for (i, (last, stress)) in points.iter().enumerate() {
            hist.damage[i] = 0.0f64.max(hist.damage[i]);
            hist.last[i] = last.map(|v| v.as_array()[l]);
            hist.last_stress[i] = stress.map(|v| v.as_array()[l]);
            hist.dissipated += weight[l] * 0.0;
        }
        hist.work = work.as_array()[l];
        forces[l] = [0, 1, 2, 3, 4, 5].map(|k| out[k].lane(l));
    }
    true
}
