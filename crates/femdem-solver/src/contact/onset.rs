//! Energy-consistent kicks for the energy-conserving contact
//! ([`super::ContactModel::Gradient`]): the leapfrog's error where a pair's
//! energy `W` is not smooth in time — chiefly where it comes into or out of
//! contact, `W`'s curvature jumping from zero — booked back into the step
//! that made it (`docs/fidelity.md` §12).
//!
//! The leapfrog kicks the nodes at `t_{n+1}` with `Δt f_{n+1}`; the energy
//! account (`Contact::book_work`) and the velocities see half of it closing
//! the interval `[t_n, t_{n+1}]` and half opening the next, so the work of
//! a pair's normal forces over the interval is the trapezoid
//! `½ (f_n + f_{n+1}) · Δx_n`, `Δx_n = x_{n+1} − x_n` on the pair's eight
//! nodes. With `f = −∂W/∂x` this is `W_n − W_{n+1}` up to the trapezoid
//! rule's error, `O(Δt³)` per step where `W` is smooth but of the order of
//! `k δ (v Δt − δ)` in the step where a pair starts (or stops) overlapping
//! by `δ` within a step's motion `v Δt`: energy that does not come back
//! (`docs/fidelity.md` §12 measured it, 10⁻⁴–10⁻³ of a flat landing's
//! impact energy at time-step safety 0.3).
//!
//! Here each pair keeps its *debt* `R_n`: the work its applied normal
//! forces `F` have done on the nodes so far, `Σ ½ (F_m + F_{m+1}) · Δx_m`,
//! less the energy its `W` has released, `W_0 − W_n` (zero for a force
//! with a potential integrated exactly). At `t_{n+1}` the force is the
//! gradient plus half a correction `c` along the pair's deformation:
//!
//! ```text
//! E       = (W_n − W_{n+1}) − R_n − ½ (F_n + g_{n+1}) · Δx_n,      g = −∂W/∂x,
//! c       = 2 E d / |d|²,                  d = Δx_n less its rigid motion (d · Δx_n = |d|²),
//! F_{n+1} = g_{n+1} + ½ c,
//! R_{n+1} = R_n + ½ (F_n + F_{n+1}) · Δx_n − (W_n − W_{n+1}) = −E + ½ E = −½ E.
//! ```
//!
//! The half of `c` that closes the interval pays the debt and the
//! interval's own error; the other half, in the next interval's work,
//! gives back `¼ c · Δx_{n+1} ≈ ½ E`, which the debt `−½ E` expects: what
//! is left is `¼ c · (Δx_{n+1} − Δx_n)`, a step's change of velocity
//! times the correction, and the next correction takes it up too. A pair
//! that separates keeps its (small, shrinking) corrections until its debt
//! is below round-off of the largest energy it held. In a one-dimensional
//! impact on a linear spring this leaves the cycle's energy to round-off
//! (from 2.2% of it at `ωΔt = 0.3` for the worst phase with the plain
//! leapfrog); a correction of the split kick alone, without the debt,
//! leaves 4e-4 there.
//!
//! `d` is `Δx_n` less its least-squares rigid motion about the eight
//! nodes' centroid at `x_{n+1}` (`W` does not change under a rigid motion,
//! nor does `g · Δx`), so `c` has no resultant and no moment: linear and
//! angular momentum are kept.
//!
//! A pair is corrected only while its force is the gradient of its energy
//! (no Eq. 18 ramp, and not a pair that started overlapped, whatever its
//! offset, until it separates; `PairForce::exact`): a pair in contact
//! whose force is not is followed without a debt (`Held::tracked`), and
//! starts with none and no correction once it is, as every pair at the
//! first pass (a pair that stops being one drops its debt), only where `E` exceeds the round-off of the largest energy the
//! pair has held (a pair resting in contact, barely moving, would
//! otherwise divide round-off by a vanishing `|d|²`), only where `|d|` is
//! more than round-off of `|Δx|`, and never by more than four times the
//! largest force it has carried (a safety net: `|E|` is of the order of
//! `|g| |d|`, and the debt carries what is not paid).
//!
//! The debt assumes `Δx_n = Δt v_{n+½}` over the interval, which the
//! account booked half of at the last pass: an intervention between the
//! steps that changes velocities or the step (`Solver::damp`,
//! `Solver::kick`, `Solver::set_params`) leaves the debts off by
//! `½ Δt F_n · (v_old − v_new)` of that half, and contact's own account
//! no longer closes exactly (the energy balance, which books the
//! intervention, is unaffected).
//! The first pass has no interval before it: its pairs start with no
//! debt and no correction.

use femdem_core::{Mat3, Real, Vec3};
use serde::{Deserialize, Serialize};

/// What a pair in contact at the last pass (or still paying its debt)
/// leaves for the next one.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub(crate) struct Held {
    /// The normal force applied to each tet's nodes, `F_n`, N.
    pub force: [[Vec3; 4]; 2],
    /// `W_n`, J.
    pub energy: Real,
    /// `R_n`, J.
    pub debt: Real,
    /// The largest energy scale of the pair's terms so far, J: what `E`
    /// is compared with.
    pub scale: Real,
    /// The largest `|g|` so far (the norm of the eight nodes' forces as
    /// one vector of 24), N: the cap.
    pub largest: Real,
    /// Whether the pair is corrected: `false` for a pair in contact whose
    /// force is not the gradient of its energy (everything else zero), which
    /// starts with no debt and no correction once it is (as at the first
    /// pass), not as a pair coming into contact.
    pub tracked: bool,
}

impl Held {
    /// The mark of a pair in contact whose force is not the gradient of its
    /// energy.
    pub(crate) fn untracked() -> Held {
        let zero = [[Vec3::zeros(); 4]; 2];
        Held { force: zero, energy: 0.0, debt: 0.0, scale: 0.0, largest: 0.0, tracked: false }
    }
}

/// The pair's gradient force on each tet's nodes and its energy at
/// `t_{n+1}`, or `None` where it is not in contact.
pub(crate) type Now<'a> = Option<(&'a [[Vec3; 4]; 2], Real)>;

/// The correction `½ c` of a pair's normal force (see the module
/// documentation) and what it leaves for the next pass, from what the last
/// pass left (`before`; `None`: not in contact, no debt), the pair's
/// gradient and energy now (`now`), its nodes' positions `x` and their
/// motion `dx` over the step. `primed`: whether a pass ran before (else
/// no correction). `None` where the pair is out of contact and has nothing
/// left to pay.
pub(crate) fn step(
    before: Option<&Held>,
    now: Now<'_>,
    x: &[[Vec3; 4]; 2],
    dx: &[[Vec3; 4]; 2],
    primed: bool,
) -> Option<([[Vec3; 4]; 2], Held)> {
    let zero = [[Vec3::zeros(); 4]; 2];
    let start = Held { tracked: true, ..Held::untracked() };
    // A pair followed but not corrected so far starts as at the first pass.
    let fresh_start = !primed || before.is_some_and(|h| !h.tracked);
    let before = before.filter(|h| h.tracked).unwrap_or(&start);
    let (g, w) = now.unwrap_or((&zero, 0.0));
    let norm = |f: &[[Vec3; 4]; 2]| f.iter().flatten().map(Vec3::norm_squared).sum::<Real>().sqrt();
    let largest = before.largest.max(norm(g));
    if fresh_start {
        let held = Held { force: *g, energy: w, debt: 0.0, scale: w.abs(), largest, tracked: true };
        return now.map(|_| (zero, held));
    }
    let dot = |f: &[[Vec3; 4]; 2]| -> (Real, Real) {
        let mut sum = (0.0, 0.0);
        for (fi, di) in f.iter().flatten().zip(dx.iter().flatten()) {
            let p = fi.dot(di);
            sum = (sum.0 + p, sum.1 + p.abs());
        }
        sum
    };
    let ((p0, a0), (p1, a1)) = (dot(&before.force), dot(g));
    let released = before.energy - w;
    let e = released - before.debt - 0.5 * (p0 + p1);
    let scale = before.scale.max(before.energy.abs() + w.abs() + before.debt.abs() + 0.5 * (a0 + a1));
    let mut kick = zero;
    if e.abs() > 1e-13 * scale && e.is_finite() {
        let d = deformation(x, dx);
        let size = d.iter().flatten().map(Vec3::norm_squared).sum::<Real>().sqrt();
        // A deformation of round-off size (the pair moving as one body) is
        // none: nothing to correct along.
        if size > 64.0 * Real::EPSILON * norm(dx) && size.is_finite() {
            // |½ c| = |E| / |d|, capped before dividing.
            let magnitude = (e.abs() / size).min(4.0 * largest);
            let along = magnitude.copysign(e) / size;
            kick = d.map(|side| side.map(|di| di * along));
        }
    } else if now.is_none() {
        // Out of contact with the debt paid to round-off.
        return None;
    }
    let mut force = *g;
    for (f, k) in force.iter_mut().flatten().zip(kick.iter().flatten()) {
        *f += k;
    }
    let debt = before.debt + 0.5 * (p0 + dot(&force).0) - released;
    if now.is_none() && kick == zero {
        return None;
    }
    Some((kick, Held { force, energy: w, debt, scale, largest, tracked: true }))
}

/// `dx` less its least-squares rigid motion (a translation and a small
/// rotation about the centroid of `x`): what is left has zero sum and zero
/// moment `Σ (x_i − x̄) × d_i`.
fn deformation(x: &[[Vec3; 4]; 2], dx: &[[Vec3; 4]; 2]) -> [[Vec3; 4]; 2] {
    let centre = x.iter().flatten().sum::<Vec3>() / 8.0;
    let shift = dx.iter().flatten().sum::<Vec3>() / 8.0;
    let r = x.map(|side| side.map(|p| p - centre));
    let mut inertia = Mat3::zeros();
    let mut moment = Vec3::zeros();
    for (ri, di) in r.iter().flatten().zip(dx.iter().flatten()) {
        inertia += Mat3::identity() * ri.norm_squared() - ri * ri.transpose();
        moment += ri.cross(&(di - shift));
    }
    let spin = inertia.try_inverse().map_or_else(Vec3::zeros, |inv| inv * moment);
    let mut d = [[Vec3::zeros(); 4]; 2];
    for s in 0..2 {
        for k in 0..4 {
            d[s][k] = dx[s][k] - shift - spin.cross(&r[s][k]);
        }
    }
    d
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pair() -> [[Vec3; 4]; 2] {
        let a =
            [Vec3::new(0.0, 0.0, 0.0), Vec3::new(1.0, 0.0, 0.0), Vec3::new(0.0, 1.0, 0.0), Vec3::new(0.2, 0.3, 1.0)];
        let b =
            [Vec3::new(0.1, 0.2, 0.9), Vec3::new(1.1, 0.3, 1.8), Vec3::new(0.3, 1.2, 1.9), Vec3::new(0.4, 0.1, 2.0)];
        [a, b]
    }

    /// A pair coming into contact: the correction leaves the debt `−½ E`
    /// the module documentation derives, and has no resultant and no moment
    /// about the origin.
    #[test]
    fn an_onset_is_corrected_without_moving_momentum() {
        let x = pair();
        let mut dx = [[Vec3::zeros(); 4]; 2];
        for (i, d) in dx.iter_mut().flatten().enumerate() {
            let f = i as Real;
            *d = Vec3::new((0.7 * f).sin(), (1.3 * f).cos(), 0.1 * f - 0.3) * 1e-3;
        }
        let mut g = [[Vec3::zeros(); 4]; 2];
        for (i, gi) in g.iter_mut().flatten().enumerate() {
            *gi = Vec3::new(1.0, -2.0, 0.5) * (i as Real - 3.5);
        }
        let w = 2e-3;
        let (kick, held) = step(None, Some((&g, w)), &x, &dx, true).expect("an onset to correct");
        let plain: Real = g.iter().flatten().zip(dx.iter().flatten()).map(|(f, d)| 0.5 * f.dot(d)).sum();
        let e = -w - plain;
        assert!((held.debt + 0.5 * e).abs() <= 1e-15, "debt {:e} against −½E {:e}", held.debt, -0.5 * e);
        let sum: Vec3 = kick.iter().flatten().sum();
        let moment: Vec3 = x.iter().flatten().zip(kick.iter().flatten()).map(|(p, c)| p.cross(c)).sum();
        assert!(sum.norm() <= 1e-15 && moment.norm() <= 1e-15, "resultant {sum:?}, moment {moment:?}");
    }

    /// A rigid motion changes neither `W` nor `g · Δx`: its deformation
    /// part is zero.
    #[test]
    fn a_rigid_motion_has_no_deformation() {
        let x = pair();
        let (t, w) = (Vec3::new(1e-3, -2e-3, 5e-4), Vec3::new(0.01, 0.02, -0.03));
        let dx = x.map(|side| side.map(|p| t + w.cross(&p)));
        let d = deformation(&x, &dx);
        // Round-off of the fit: a few ulps of the motion.
        let largest = dx.iter().flatten().map(Vec3::norm).fold(0.0, Real::max);
        assert!(d.iter().flatten().all(|v| v.norm() <= 16.0 * Real::EPSILON * largest), "{d:?}");
    }

    /// Two tets, each moving as a block, meet on a one-sided spring
    /// `W = ½ k s²`, `s` the overlap of their mean heights (`s > 0`), under
    /// the leapfrog: the kinetic energy they leave with against what they
    /// brought. Returns that share with and without the corrections, over
    /// entry phases spread across a step at `ω Δt = 0.3`.
    fn bounce(corrected: bool, phase: Real) -> Real {
        let (k, m, dt, v0) = (1.0, 0.25, 0.3 / 2.0_f64.sqrt(), 1.0);
        // Tet A at rest below, B falling onto it; 4 nodes each of mass m.
        let mut x = pair();
        let lift = 1.0 - phase * v0 * dt;
        for p in x[1].iter_mut() {
            p.z += lift;
        }
        let overlap = |x: &[[Vec3; 4]; 2]| {
            let mean = |s: usize| x[s].iter().map(|p| p.z).sum::<Real>() / 4.0;
            mean(0) - mean(1) + 1.0
        };
        let forces = |x: &[[Vec3; 4]; 2]| -> Option<([[Vec3; 4]; 2], Real)> {
            let s = overlap(x);
            (s > 0.0).then(|| {
                let f = Vec3::new(0.0, 0.0, 0.25 * k * s);
                ([[-f; 4], [f; 4]], 0.5 * k * s * s)
            })
        };
        let mut v = [[Vec3::zeros(); 4], [Vec3::new(0.0, 0.0, -v0); 4]];
        let ke = |v: &[[Vec3; 4]; 2]| 0.5 * m * v.iter().flatten().map(Vec3::norm_squared).sum::<Real>();
        let brought = ke(&v);
        let mut held: Option<Held> = None;
        let mut force = [[Vec3::zeros(); 4]; 2];
        for _ in 0..400 {
            // v_{n+½} = v_{n−½} + Δt F_n / m; x_{n+1} = x_n + Δt v_{n+½}.
            for (vi, fi) in v.iter_mut().flatten().zip(force.iter().flatten()) {
                *vi += fi * (dt / m);
            }
            let dx = v.map(|side| side.map(|vi| vi * dt));
            for (p, d) in x.iter_mut().flatten().zip(dx.iter().flatten()) {
                *p += d;
            }
            let now = forces(&x);
            force = now.map_or([[Vec3::zeros(); 4]; 2], |(g, _)| g);
            if corrected {
                let next = step(held.as_ref(), now.as_ref().map(|(g, w)| (g, *w)), &x, &dx, true);
                held = next.map(|(kick, h)| {
                    for (f, c) in force.iter_mut().flatten().zip(kick.iter().flatten()) {
                        *f += c;
                    }
                    h
                });
            }
        }
        ke(&v) / brought - 1.0
    }

    /// The plain leapfrog leaves percents of the energy in an impact on a
    /// one-sided spring at `ω Δt = 0.3` (the phase of the onset decides);
    /// with the corrections the cycle closes to round-off (`10⁻¹²`: the
    /// debt is paid to `10⁻¹³` of the largest energy term, then dropped).
    #[test]
    fn a_one_sided_spring_closes_its_cycle() {
        let phases: Vec<Real> = (0..13).map(|i| (Real::from(i) + 0.5) / 13.0).collect();
        let plain = phases.iter().map(|&p| bounce(false, p).abs()).fold(0.0, Real::max);
        let fixed = phases.iter().map(|&p| bounce(true, p).abs()).fold(0.0, Real::max);
        eprintln!("largest share of the energy left: {plain:.3e} plain, {fixed:.3e} corrected");
        assert!(plain > 1e-3, "the plain leapfrog's error, {plain:e}");
        assert!(fixed < 1e-12, "{fixed:e}");
    }
}
