//! The cohesive joint law's energy along mixed paths with unloading, for
//! each `Coupling` option (reference paper §2.2, Eq. 5–13; the restatement
//! and the `walk` helper are in `law_reference`, the other energy tests in
//! `law_energy.rs`).

use crate::law_reference::*;

use femdem_core::{Real, Vec3};
use femdem_fracture::{Coupling, GfCalibration, Joint};

/// Mixed paths with unloading, for each `Coupling`: the energy account
/// closes. Side b moves uniformly through waypoints `(δs along x, δn)`,
/// `n` steps per leg:
///
/// * "shear first": slip into the shear softening (`Ds ≈ 0.4`) while the
///   opening rises to `0.8 δnp` (its hardening branch: the options differ
///   most here, Printed `σ = 0.96 f_t`, Capped `z(D) f_t ≈ 0.37 f_t`,
///   Multiplicative `0.96 z(D) f_t`); slip back to 0; close to
///   `−0.5 δnp`; reopen to `0.8 δnp`; slip again to just short of the first
///   point (`0.99` of it: the Eq. 5 shear strength uses the damage of the
///   previous evaluation, so a reload to the very same point can add ~1e-6
///   to D); then on past `δnp` to failure.
/// * "normal first": open into the normal softening (`Dn = 0.3`), slip to
///   `0.9 δsp` (shear hardening), unload the slip, then the opening, reload
///   both, and slip on to failure.
///
/// With `W` the work per unit area done on side b (trapezoid on the
/// tractions read from the nodal forces) and `E` the stored energy the
/// joint reports: `history.work = W`; on the unloading and reloading legs
/// (damage checked constant) `W − E` stays constant — the work given back
/// or taken is the change of the stored energy, so `E` is the area under
/// the curve the point unloads and reloads along; and `W − E` (the fracture
/// energy the solver books) never decreases — except under `Printed`, once,
/// where the shear-first path's opening crosses `δnp` with the shear
/// softened: the printed `σ` drops there from the parabola's `f_t` to
/// `z(D) f_t` in one step, so `f_s = c − σ tan φ` (Eq. 5) jumps up by
/// `(1 − z(D)) f_t tan φ` and with it the stored shear plateau
/// `z(D) f_s δs`, with no work done: the printed law (discontinuous there)
/// is not conservative. That fall is checked to happen at that step only,
/// and to stay below `z(D) (1 − z(D)) f_t tan φ δs` (the plateau's jump with
/// `D` of the step before; the damage grows in the step, which lowers it).
///
/// Tolerance 1e-4 of the final work: the trapezoid error is
/// `Σ Δ² |t″| / 12` per leg, with 40,000 steps per leg and the stiffest
/// branch (`2 f/δp` in slope, curvature `2 f/δp²`), ~1e-9 of W; the kinks
/// where a branch changes within a step add `≤ slope jump × Δ²`, ~1e-8 of
/// W; the lag of the Eq. 5 strength on the damage (see above) moves `E` by
/// ~5e-7 of W at the first step of an unloading (measured).
#[test]
fn mixed_unloading_closes_the_energy_account() {
    let l = 1e-3;
    let area = 0.5 * l * l;
    let n = 40_000;
    for coupling in COUPLINGS {
        let p = with_coupling(granite(GfCalibration::Exact), coupling);
        let j = Joint::new(p, mean_edge(l));
        let (ft, c, tan_phi) = (p.tensile_strength, p.cohesion, p.friction_angle.tan());
        let (dnp, dnc) = (j.delta_np, j.delta_nc);
        // Shear first: at δn = 0.8 δnp the normal stress without shear
        // damage is [2r − r²] f_t = 0.96 f_t for a fresh point.
        let fs = c - 0.96 * ft * tan_phi;
        let (dsp, dsc) = (dp_ref(&p, j.h, fs), dc_ref(&p, fs, dp_ref(&p, j.h, fs), p.gf_shear));
        let s1 = dsp + 0.4 * (dsc - dsp);
        let shear_first = [
            (s1, 0.8 * dnp),
            (0.0, 0.8 * dnp),
            (0.0, -0.5 * dnp),
            (0.0, 0.8 * dnp),
            (0.99 * s1, 0.8 * dnp),
            (1.2 * dsc, 0.5 * dnc),
        ];
        // Normal first: Dn = 0.3, σ = z(0.3) f_t, f_s from it.
        let n1 = dnp + 0.3 * (dnc - dnp);
        let fs = c - z_ref(0.3) * ft * tan_phi;
        let s2 = 0.9 * dp_ref(&p, j.h, fs);
        let normal_first = [(0.0, n1), (s2, n1), (0.0, n1), (0.0, 0.0), (0.0, n1), (s2, n1), (1.2 * dsc, n1)];
        // Legs at constant damage: 1–4 (shear first), 2–5 (normal first).
        for (name, points, elastic) in
            [("shear first", &shear_first[..], 1..5), ("normal first", &normal_first[..], 2..6)]
        {
            let mut path = vec![Vec3::zeros()];
            let mut leg_of = vec![0];
            let mut from = Vec3::zeros();
            for (k, &(s, d)) in points.iter().enumerate() {
                let to = Vec3::new(s, 0.0, d);
                path.extend((1..=n).map(|i| from + (to - from) * (i as Real / n as Real)));
                leg_of.extend(std::iter::repeat_n(k, n));
                from = to;
            }
            let states = walk(&j, l, &path);
            let (w_end, h_end, _) = *states.last().unwrap();
            assert!(h_end.failed, "{coupling:?} {name}: fails on the last leg");
            let tol = 1e-4 * w_end;
            let (mut worst_elastic, mut worst_fall) = (0.0f64, 0.0f64);
            let mut falls = Vec::new();
            for i in 1..states.len() {
                let ((w0, h0, e0), (w, h, e)) = (states[i - 1], states[i]);
                assert!((h.work / area - w).abs() <= tol, "{coupling:?} {name}: work {} vs ∫t·dg {w}", h.work / area);
                // Once failed, everything done on the joint is lost (E = 0).
                let fall = (w0 - e0) - (w - e);
                worst_fall = worst_fall.max(fall);
                if fall > tol {
                    falls.push((i, fall));
                }
                if elastic.contains(&leg_of[i]) {
                    assert_eq!(h.damage, h0.damage, "{coupling:?} {name}: damage changed on leg {}", leg_of[i]);
                    // W − E at the start of this leg.
                    let start = leg_of[i] * n;
                    let (ws, _, es) = states[start];
                    worst_elastic = worst_elastic.max(((w - e) - (ws - es)).abs());
                }
            }
            println!(
                "{coupling:?} {name}: W at failure {w_end:.4} J/m², largest change of W − E at constant damage \
                 {worst_elastic:.2e}, largest fall of W − E {worst_fall:.2e} J/m²"
            );
            assert!(worst_elastic <= tol, "{coupling:?} {name}: W − E moved by {worst_elastic} at constant damage");
            if coupling == Coupling::Printed && name == "shear first" {
                assert_eq!(falls.len(), 1, "{coupling:?} {name}: W − E falls at {falls:?}");
                let (i, fall) = falls[0];
                let (h0, h) = (states[i - 1].1, states[i].1);
                assert!(!h0.softened[0].normal && h.softened[0].normal, "the fall is where δn passes δnp");
                let zd = z_ref(h0.damage[0]);
                let bound = zd * (1.0 - zd) * ft * tan_phi * path[i].x;
                println!("  the fall, at δn = {:.4} δnp: {fall:.4} J/m² (bound {bound:.4})", path[i].z / dnp);
                assert!(fall <= bound, "{coupling:?}: fall {fall} above {bound}");
            } else {
                assert!(falls.is_empty(), "{coupling:?} {name}: W − E falls at {falls:?}");
            }
        }
    }
}
