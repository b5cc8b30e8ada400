//! The stress–displacement law of a joint (reference paper Fig. 3,
//! Eq. 5–13), its damage history, failure, and nodal forces.
//!
//! At each integration point, from the opening `δn` and the slip magnitude
//! `δs`:
//!
//! 1. the normal stress without shear damage gives the shear strength
//!    `f_s = c − σ tan φ` (Eq. 5; `σ ≤ f_t` makes the tension cut-off
//!    automatic), hence `δsp = 2 f_s h / p0` (Eq. 7) and `δsc` (Eq. 10 for
//!    `G_fs`); `δnp = 2 f_t h / p0` (Eq. 6) and `δnc` (Eq. 10 for `G_ft`).
//!    When `c ≤ f_t tan φ`, `f_s` reaches 0 at `σ = c / tan φ ≤ f_t`: the
//!    point has no shear strength left and breaks (`Ds = 1`, so `D = 1`)
//!    there, on the hardening branch — the tensile strength is
//!    `min(f_t, c / tan φ)` ([`crate::JointParams::effective_tensile_strength`]).
//!    An opening that jumps past `δnp` in one evaluation went over the top
//!    of the parabola on the way: if the top reached the apex, the point
//!    broke there too (the result does not depend on the step);
//! 2. the damage `D` of Eq. 13 from the normalised softening displacements
//!    `Dn = (δn − δnp)/(δnc − δnp)`, `Ds = (δs − δsp)/(δsc − δsp)`: `Dn` or
//!    `Ds` when one direction softens, `√(Dn² + Ds²)` when both do, 1 once
//!    `δn ≥ δnc` or `δs ≥ δsc`; it never decreases: `D = max(D, D_hist)`;
//! 3. the stresses of Eq. 11: `σ = 2 (δn/δnp) f_t` in compression (not
//!    affected by damage), the hardening branch for `0 ≤ δn ≤ δnp` as the
//!    joint's [`Coupling`] says — `Printed` (the default, Eq. 11 as
//!    printed): `[2r − r²] f_t`; `Multiplicative`: `z(D) [2r − r²] f_t`;
//!    `Capped`: `min([2r − r²] f_t, z(D) f_t)`, `r = δn/δnp` — and `z(D) f_t` beyond
//!    `δnp`; `τ` likewise with `f_s`, along the slip. Every option keeps a
//!    damaged point at or below its damaged strength when it unloads and
//!    reloads (`Printed`: once that direction has been past its peak,
//!    remembered in [`Softened`]; see [`Coupling::Printed`]).
//!
//! A point breaks when `D` reaches 1. Under `Capped` and `Multiplicative`
//! it then carries no tensile or shear stress; under `Printed` a direction
//! that has never been past its peak still follows its parabola (Eq. 11 as
//! printed has no `z` there). A joint fails when at least two of its three
//! points have broken (§2.2). Its failure mode is the label of the point
//! that broke last: tensile if `Dn² ≥ ¾ D²` at that evaluation (or `f_s`
//! fell to 0: the Mohr–Coulomb apex, reached only in tension), shear if
//! `Ds² ≥ ¾ D²`, mixed between (`D² = Dn² + Ds²`; [`FailureMode`]). A joint
//! whose mid-plane has collapsed (no frame: Eq. 3 cannot be evaluated)
//! fails as [`FailureMode::Collapsed`].
//!
//! Energy: the work dissipated on the softening branch is
//! `[f_t (δnc − δnp) wn + f_s (δsc − δsp) ws] (Z(D) − Z(D_hist))` per unit
//! area, with `Z(D) = ∫₀ᴰ z`, `wn = Dn/D`, `ws = Ds/D` (exact for a pure mode
//! and for a radial path in `(Dn, Ds)`; the same for every [`Coupling`]);
//! the stored energy is the area under the curve the point would unload
//! along at constant `D`, for its coupling option (`Coupling::stored`),
//! with `f_s` at its current value (Eq. 5 makes `τ` depend on `δn` while
//! `σ` does not depend on `δs`: the law has no potential, and `Printed`'s
//! jump of `σ` at `δnp` after shear damage raises the stored shear energy
//! with no work done, see [`Coupling::Printed`]);
//! when the joint fails, its stored energy is released
//! (`JointHistory::released`). Note that the shear part of it, up to
//! `2/3 f_s δsp = 4/3 f_s² h / p0`, is not small when `c ≫ f_t`. The work
//! done on the joint (`JointHistory::work`) is tracked independently;
//! `work − stored` is what the run books as fracture energy.

use femdem_core::{Real, Vec3};

use crate::softening::{z, z_integral};
use crate::{Coupling, FailureMode, GAUSS, JointParams, Softened, joint_kinematics};

/// A joint: parameters, its reference mean edge length `h`, and what
/// follows from them alone (precomputed: the kernel runs for every joint at
/// every step).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Joint {
    /// The law's parameters.
    pub params: JointParams,
    /// Mean length of the joint's edges in the reference configuration, m.
    pub h: Real,
    /// `δ_np = 2 f_t h / p0` (Eq. 6), m.
    pub delta_np: Real,
    /// `δ_nc` (Eq. 10 with `G_ft`), m.
    pub delta_nc: Real,
    /// `tan φ`.
    pub tan_phi: Real,
}

impl Joint {
    /// The joint of parameters `params` and reference mean edge `h`.
    pub fn new(params: JointParams, h: Real) -> Joint {
        let delta_np = 2.0 * params.tensile_strength * h / params.penalty;
        Joint {
            params,
            h,
            delta_np,
            delta_nc: params.critical_displacement(params.tensile_strength, delta_np, params.gf_tension),
            tan_phi: params.friction_angle.tan(),
        }
    }
}

/// What a joint remembers between steps.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct JointHistory {
    /// The largest damage `D` reached at each integration point.
    pub damage: [Real; 3],
    /// Energy dissipated on the softening branches so far, J (the
    /// Eq. 10–12 part: exact for pure modes and radial paths in
    /// `(Dn, Ds)`; the hardening energy a broken point can no longer give
    /// back is not in it). The authoritative total is `work`.
    pub dissipated: Real,
    /// Stored energy the joint held when it failed, J (lost with it).
    pub released: Real,
    /// Work done on the joint by its nodes since the start, J: the sum over
    /// steps of `A/3 (σ̄ Δδn + τ̄·Δδs)` at each point, `σ̄` and `τ̄` the means
    /// of the last and the new traction (trapezoid rule: exact on an
    /// elastic branch, where the rectangle rule would book `k Δδ²/2` per
    /// step as spurious dissipation whenever the joint vibrates). On the
    /// step that fails it the joint exerts no force, so that step's
    /// trapezoid ends on a zero traction: `A/3 (σ_last Δδn + τ_last·Δδs)/2`
    /// (the work its nodes did on it, as the solver's nodal account sees
    /// it; ending on the tractions it no longer exerts booked `½ σ Δδ` of
    /// work that no node did, measured as the larger part of the energy
    /// error of the bundled Brazilian run's shear failures under the
    /// platen). `work − stored energy` is what the joint has dissipated,
    /// whatever the path, so the run's energy account closes.
    pub work: Real,
    /// Opening and slip vector of each point at the last evaluation.
    pub last: [[Real; 4]; 3],
    /// Normal stress and shear stress magnitude of each point at the last
    /// evaluation, Pa (the shear along the last slip).
    pub last_stress: [[Real; 2]; 3],
    /// Which directions of each point have been past their peak (read by
    /// [`Coupling::Printed`] only).
    pub softened: [Softened; 3],
    /// Whether the joint has failed (it then exerts no force).
    pub failed: bool,
}

impl JointHistory {
    /// The energy held by the joint's compression at its last evaluation,
    /// J, for mid-plane area `area`: `A/3 Σ ½ σ δn` over the points with
    /// `δn < 0`. There Eq. 11 is the linear branch `σ = 2 f_t δn / δnp`,
    /// whatever the damage, which holds `f_t δnp (δn/δnp)² = ½ σ δn` per
    /// unit area (the compressive part of `Coupling::stored`). When a joint
    /// fails closed its two tets overlap by that opening, and contact's
    /// penalty takes the compression over: the solver books what contact
    /// gives back of such overlaps, up to this energy, as handed over from
    /// the joint rather than dissipated by fracture.
    pub fn compression_energy(&self, area: Real) -> Real {
        let mut held = 0.0;
        for (last, stress) in self.last.iter().zip(&self.last_stress) {
            let (dn, sigma) = (last[0], stress[0]);
            if dn < 0.0 && sigma < 0.0 {
                held += 0.5 * sigma * dn;
            }
        }
        area / 3.0 * held
    }
}

/// The state of one integration point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PointStress {
    /// Normal stress, Pa (tension positive).
    pub sigma: Real,
    /// Shear stress magnitude, Pa, along the slip.
    pub tau: Real,
    /// Damage after this evaluation (≥ the history).
    pub damage: Real,
    /// Set when the point reaches `D = 1` in this evaluation.
    pub broke: Option<FailureMode>,
    /// Energy dissipated per unit area by the damage increment, J/m².
    pub dissipated: Real,
    /// Stored energy per unit area, J/m² (see `Coupling::stored`).
    pub stored: Real,
    /// Which directions have been past their peak, this evaluation included.
    pub softened: Softened,
    /// The normalised softening displacements of Eq. 13 at this evaluation,
    /// `[Dn, Ds]`, each in `[0, 1]` (`Ds = 1` when `f_s ≤ 0`): what the
    /// failure label is made of ([`FailureMode`]).
    pub contributions: [Real; 2],
}

/// Evaluates one integration point at opening `dn` and slip magnitude
/// `ds ≥ 0` with damage history `d_hist` (see the module doc), for a point
/// known by its damage alone: [`Softened::assumed`] (under
/// [`Coupling::Printed`] a damaged point is taken to have been past its
/// peak in both directions; the other options do not read it).
/// [`joint_update`] keeps the full history and calls [`point_stress_with`].
#[inline]
pub fn point_stress(joint: &Joint, dn: Real, ds: Real, d_hist: Real) -> PointStress {
    point_stress_with(joint, dn, ds, d_hist, Softened::assumed(d_hist))
}

/// Evaluates one integration point at opening `dn` and slip magnitude
/// `ds ≥ 0` with damage history `d_hist` and the directions that have been
/// past their peak before, `softened` (see the module doc and
/// [`Coupling`]).
#[inline]
pub fn point_stress_with(joint: &Joint, dn: Real, ds: Real, d_hist: Real, softened: Softened) -> PointStress {
    let p = &joint.params;
    let coupling: Coupling = p.coupling;
    let ft = p.tensile_strength;
    let (dnp, dnc) = (joint.delta_np, joint.delta_nc);
    let rn = dn / dnp;
    // Normal softening displacement, and the normal stress without shear
    // damage, which sets the shear strength (Eq. 5).
    let dn_soft = if dn > dnp { ((dn - dnp) / (dnc - dnp)).min(1.0) } else { 0.0 };
    let sigma_trial = if rn < 0.0 {
        2.0 * rn * ft
    } else if rn <= 1.0 {
        coupling.hardening_branch(ft, rn, z(d_hist), softened.normal)
    } else {
        z(dn_soft.max(d_hist)) * ft
    };
    // Weak cohesion (c ≤ f_t tan φ): an opening that passes δnp for the
    // first time in this evaluation went over the top of the parabola, where
    // σ was its value at r = 1; if that reached the apex c / tan φ, f_s fell
    // to 0 on the way and the point broke there, however long the step.
    let over_the_apex = rn > 1.0
        && !softened.normal
        && p.cohesion <= ft * joint.tan_phi
        && p.cohesion - coupling.hardening_branch(ft, 1.0, z(d_hist), false) * joint.tan_phi <= 0.0;
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
    let zd = z(damage);
    let rs = if fs > 0.0 { ds / dsp } else { 0.0 };
    // Past the peak: beyond δp, or (both directions) at the Mohr–Coulomb
    // apex, `f_s ≤ 0`, which exhausts the tensile strength `c / tan φ` too.
    let now_softened =
        Softened { normal: softened.normal || rn > 1.0 || fs <= 0.0, shear: softened.shear || fs <= 0.0 || rs > 1.0 };
    // Eq. 11, with the hardening branches as `coupling` says.
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
    // Labels: see `FailureMode`. `f_s ≤ 0` only at the Mohr–Coulomb apex.
    let mode = if fs <= 0.0 { FailureMode::Tensile } else { FailureMode::from_contributions(dn_soft, ds_soft) };
    let broke = (d_hist < 1.0 && damage >= 1.0).then_some(mode);
    let dissipated = if damage > d_hist {
        // Along a radial path in (Dn, Ds), dDn = (Dn/D) dD and dDs = (Ds/D) dD.
        let norm = (dn_soft * dn_soft + ds_soft * ds_soft).sqrt();
        let (wn, ws) = if norm > 0.0 { (dn_soft / norm, ds_soft / norm) } else { (1.0, 0.0) };
        let scale = ft * (dnc - dnp) * wn + if fs > 0.0 { fs * (dsc - dsp) * ws } else { 0.0 };
        scale * z_integral(d_hist, damage)
    } else {
        0.0
    };
    let stored = coupling.stored(ft, dnp, rn, zd, now_softened.normal)
        + if fs > 0.0 { coupling.stored(fs, dsp, rs, zd, now_softened.shear) } else { 0.0 };
    PointStress {
        sigma,
        tau,
        damage,
        broke,
        dissipated,
        stored,
        softened: now_softened,
        contributions: [dn_soft, ds_soft],
    }
}

/// The normal stress of a point with no slip and no history (Fig. 3, the
/// normal curve): for plotting and tests.
pub fn normal_stress(joint: &Joint, dn: Real) -> Real {
    point_stress(joint, dn, 0.0, 0.0).sigma
}

/// What a joint evaluation returns.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct JointOutput {
    /// Force on `N1 … N6`, N. They sum to zero; zero for a failed joint.
    pub forces: [Vec3; 6],
    /// Stored (elastic) energy, J, when asked for (else 0).
    pub energy: Real,
    /// Mean normal stress over the three points, Pa (tension positive).
    pub normal_stress: Real,
    /// Set when the joint failed in this evaluation.
    pub failed: Option<FailureMode>,
}

/// Evaluates a joint at current positions `x = [N1 … N6]` and updates its
/// history: at each Hammer point the traction `t = σ z′ + τ δs/|δs|` acts on
/// side a (pulling it towards b when the joint is open) and `−t` on side b;
/// each is integrated with weight `A/3` (mid-plane area) and shared among
/// the face's nodes by the point's barycentric coordinates.
///
/// A failed joint exerts no force. On failure the joint's stored energy is
/// kept in `history.released`.
///
/// A joint whose mid-plane has collapsed (zero area: [`joint_kinematics`]
/// finds no frame, so no opening or slip exists) fails at once as
/// [`FailureMode::Collapsed`], with no force. Its `released` is 0: the
/// stored energy is an integral over the mid-plane, whose area is now 0,
/// and the last evaluation's value cannot be rebuilt (the history keeps
/// each point's last opening, slip and stresses but not the area). Nothing
/// is lost from the run's account for it: once a joint has failed the
/// solver books all of `history.work` as fracture energy, the energy the
/// joint held included. The work of this last step is not added (no
/// traction can be evaluated); damage, `last` and `last_stress` keep their
/// values from the last evaluation.
#[inline]
pub fn joint_update(joint: &Joint, history: &mut JointHistory, x: &[Vec3; 6], with_energy: bool) -> JointOutput {
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
    let mut stored_total = 0.0;
    for (i, w) in GAUSS.iter().enumerate() {
        let ds = k.slip[i].norm();
        let ps = point_stress_with(joint, k.opening[i], ds, history.damage[i], history.softened[i]);
        history.damage[i] = ps.damage;
        history.softened[i] = ps.softened;
        let [ln, lx, ly, lz] = history.last[i];
        let [sigma_last, tau_last] = history.last_stress[i];
        let slip_last = Vec3::new(lx, ly, lz);
        let d_slip = k.slip[i] - slip_last;
        // Trapezoid rule on the tractions (see `JointHistory::work`).
        let mut traction = if ds > 0.0 { k.slip[i] * (ps.tau / ds) } else { Vec3::zeros() };
        let ds_last = slip_last.norm();
        if ds_last > 0.0 {
            traction += slip_last * (tau_last / ds_last);
        }
        let normal_work = 0.5 * (sigma_last + ps.sigma) * (k.opening[i] - ln);
        history.work += weight * (normal_work + 0.5 * traction.dot(&d_slip));
        let shear_now = if ds > 0.0 { k.slip[i] * (ps.tau / ds) } else { Vec3::zeros() };
        ending += weight * 0.5 * (ps.sigma * (k.opening[i] - ln) + shear_now.dot(&d_slip));
        history.last[i] = [k.opening[i], k.slip[i].x, k.slip[i].y, k.slip[i].z];
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
            t += k.slip[i] * (ps.tau / ds);
        }
        let f = t * weight;
        for (node_a, node_b, xi) in [(0, 5, w[0]), (1, 4, w[1]), (2, 3, w[2])] {
            out.forces[node_a] += f * xi;
            out.forces[node_b] -= f * xi;
        }
        stored_total += weight * ps.stored;
        out.normal_stress += ps.sigma / 3.0;
    }
    if broken_points >= 2 {
        history.failed = true;
        history.work -= ending;
        history.released = stored_total;
        out.failed = Some(mode.unwrap_or(FailureMode::Mixed));
        out.forces = [Vec3::zeros(); 6];
        return out;
    }
    if with_energy {
        out.energy = stored_total;
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::GfCalibration;

    fn params() -> JointParams {
        JointParams {
            penalty: 26e10,
            tensile_strength: 3e6,
            cohesion: 15e6,
            friction_angle: 30f64.to_radians(),
            gf_tension: 50.0,
            gf_shear: 500.0,
            calibration: GfCalibration::Paper,
            coupling: Coupling::default(),
        }
    }

    #[test]
    fn initial_slopes_equal_p0_over_h() {
        let j = Joint::new(params(), 1e-3);
        let k = j.params.penalty / j.h;
        // At r = δ/δp the secant slope of the hardening branch is (1 − r/2)·k.
        let d = 1e-3 * j.delta_np;
        assert!((normal_stress(&j, d) / d / k - (1.0 - 0.5e-3)).abs() < 1e-9);
        assert!((normal_stress(&j, -d) / -d / k - 1.0).abs() < 1e-12);
        let dsp = 2.0 * j.params.cohesion * j.h / j.params.penalty;
        let ds = 1e-3 * dsp;
        assert!((point_stress(&j, 0.0, ds, 0.0).tau / ds / k - (1.0 - 0.5e-3)).abs() < 1e-9);
    }

    #[test]
    fn shear_strength_follows_mohr_coulomb_with_tension_cut_off() {
        let j = Joint::new(params(), 1e-3);
        for dn in [-1e-6, -1e-7, 0.0, 0.5 * j.delta_np] {
            let sigma = normal_stress(&j, dn);
            let fs = j.params.cohesion - sigma * j.tan_phi;
            let dsp = 2.0 * fs * j.h / j.params.penalty;
            let at_peak = point_stress(&j, dn, dsp, 0.0).tau;
            assert!((at_peak - fs).abs() < 1e-9 * fs, "δn = {dn}: τ = {at_peak}, f_s = {fs}");
        }
    }

    /// The kernel's forces carry the point law's stresses.
    #[test]
    fn kernel_forces_match_point_stresses() {
        let j = Joint::new(params(), 1e-3);
        let base = [Vec3::zeros(), Vec3::new(1e-3, 0.0, 0.0), Vec3::new(0.0, 1e-3, 0.0)];
        for (dn, ds) in [(-3e-8, 2e-8), (1e-8, 5e-8), (4e-9, 1e-9)] {
            let d = Vec3::new(ds, 0.0, dn);
            let x = [base[0], base[1], base[2], base[2] + d, base[1] + d, base[0] + d];
            let mut h = JointHistory::default();
            let f = joint_update(&j, &mut h, &x, false);
            let ps = point_stress(&j, dn, ds, 0.0);
            let area = 0.5e-6;
            let fb: Vec3 = f.forces[3..].iter().sum();
            assert!((fb.z + ps.sigma * area).abs() < 1e-9 * (ps.sigma.abs() * area).max(1e-12));
            assert!((fb.x + ps.tau * area).abs() < 1e-9 * (ps.tau.abs() * area).max(1e-12));
            let sum: Vec3 = f.forces.iter().sum();
            assert!(sum.norm() < 1e-12 * fb.norm().max(1e-12));
        }
    }

    #[test]
    fn a_failed_joint_exerts_nothing() {
        let j = Joint::new(params(), 1e-3);
        let base = [Vec3::zeros(), Vec3::new(1e-3, 0.0, 0.0), Vec3::new(0.0, 1e-3, 0.0)];
        let d = Vec3::new(0.0, 0.0, 2.0 * j.delta_nc);
        let x = [base[0], base[1], base[2], base[2] + d, base[1] + d, base[0] + d];
        let mut h = JointHistory::default();
        let out = joint_update(&j, &mut h, &x, true);
        assert_eq!(out.failed, Some(FailureMode::Tensile));
        assert!(h.failed && out.forces.iter().all(|f| f.norm() == 0.0));
        // Closing it again does not heal it.
        let closed = [base[0], base[1], base[2], base[2], base[1], base[0]];
        let again = joint_update(&j, &mut h, &closed, true);
        assert!(again.failed.is_none() && again.forces.iter().all(|f| f.norm() == 0.0));
    }

    /// A joint whose mid-plane collapses (all six nodes on one line: zero
    /// area, no frame) fails at once as `Collapsed` (code 4), exerts
    /// nothing, releases no stored energy (documented on `joint_update`),
    /// keeps its damage and work, and stays failed.
    #[test]
    fn a_collapsed_joint_fails_as_collapsed() {
        let j = Joint::new(params(), 1e-3);
        let base = [Vec3::zeros(), Vec3::new(1e-3, 0.0, 0.0), Vec3::new(0.0, 1e-3, 0.0)];
        let d = Vec3::new(0.0, 0.0, 0.5 * j.delta_np);
        let x = [base[0], base[1], base[2], base[2] + d, base[1] + d, base[0] + d];
        let mut h = JointHistory::default();
        let loaded = joint_update(&j, &mut h, &x, true);
        assert!(loaded.energy > 0.0 && h.work > 0.0);
        let before = h;
        let line = [0.0, 1.0, 2.0, 3.0, 4.0, 5.0].map(|t| Vec3::new(t * 1e-4, 0.0, 0.0));
        assert!(joint_kinematics(&line).is_none());
        let out = joint_update(&j, &mut h, &line, true);
        assert_eq!(out.failed, Some(FailureMode::Collapsed));
        assert_eq!(out.failed.unwrap().code(), 4);
        assert!(out.forces.iter().all(|f| f.norm() == 0.0) && out.energy == 0.0);
        assert!(h.failed && h.released == 0.0);
        assert_eq!((h.damage, h.work, h.last), (before.damage, before.work, before.last));
        // Restoring the geometry does not revive it, nor fail it again.
        let again = joint_update(&j, &mut h, &x, true);
        assert!(again.failed.is_none() && again.forces.iter().all(|f| f.norm() == 0.0));
    }

    /// A joint vibrating in compression (the linear branch, `σ = 2 r f_t`,
    /// no damage) stores what is done on it: after 200 random closings and
    /// reopenings `work − stored` is round-off. The rectangle rule booked
    /// `k Δδ²/2` per step here as dissipation (a spurious fracture energy
    /// that grew with every vibration of an intact mesh).
    #[test]
    fn elastic_vibration_books_no_dissipation() {
        let j = Joint::new(params(), 1e-3);
        let base = [Vec3::zeros(), Vec3::new(1e-3, 0.0, 0.0), Vec3::new(0.0, 1e-3, 0.0)];
        let mut h = JointHistory::default();
        let mut seed = 7u64;
        let mut stored = 0.0;
        for _ in 0..200 {
            seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            let u = (seed >> 11) as Real / (1u64 << 53) as Real;
            let d = Vec3::new(0.0, 0.0, -u * j.delta_np);
            let x = [base[0], base[1], base[2], base[2] + d, base[1] + d, base[0] + d];
            stored = joint_update(&j, &mut h, &x, true).energy;
        }
        assert!(stored > 0.0 && h.damage == [0.0; 3]);
        assert!((h.work - stored).abs() < 1e-9 * stored, "work {} vs stored {stored}", h.work);
    }
    /// `compression_energy` is the compressive part of the stored energy:
    /// all of it for a joint closed with no slip (the mid-plane area of the
    /// test face is 0.5 mm²), none of it for one opened, and under slip
    /// only the normal part, `f_t δnp r²` per unit area (Eq. 11 linear branch).
    #[test]
    fn compression_energy_is_the_stored_energy_of_closing() {
        let j = Joint::new(params(), 1e-3);
        let base = [Vec3::zeros(), Vec3::new(1e-3, 0.0, 0.0), Vec3::new(0.0, 1e-3, 0.0)];
        let area = 0.5e-6;
        let at = |d: Vec3| {
            let x = [base[0], base[1], base[2], base[2] + d, base[1] + d, base[0] + d];
            let mut h = JointHistory::default();
            let stored = joint_update(&j, &mut h, &x, true).energy;
            (stored, h.compression_energy(area))
        };
        let closed = Vec3::new(0.0, 0.0, -0.3 * j.delta_np);
        let (stored, held) = at(closed);
        assert!(stored > 0.0 && (held - stored).abs() < 1e-12 * stored, "held {held} vs stored {stored}");
        let (stored, held) = at(-closed);
        assert!(stored > 0.0 && held == 0.0);
        let slip = Vec3::new(0.2 * 2.0 * j.params.cohesion * j.h / j.params.penalty, 0.0, 0.0);
        let (stored, held) = at(closed + slip);
        let normal = j.params.tensile_strength * j.delta_np * 0.3 * 0.3 * area;
        assert!(stored > held && (held - normal).abs() < 1e-12 * normal, "held {held} vs f_t δnp r² A = {normal}");
    }
}
