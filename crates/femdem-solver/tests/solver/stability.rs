//! The stable time step estimate (power iteration for `ω_max`, see
//! `timestep.rs`): the central-difference update of an undamped mode is
//! stable for `ω Δt ≤ 2` and grows by `|λ| > 1` per step above it
//! (`λ² − (2 − ω²Δt²) λ + 1 = 0`). So a step 5% above the estimated limit
//! must blow up (at ωΔt = 2.1 the top mode's amplitude grows 1.88× per
//! step; its energy would pass ×1e9 within 20 steps, but once the joints
//! open past δp their stress is capped at the peak and the growth saturates,
//! so the test asks for ×1e3 within 100 steps — measured ×8.6e5 — while a
//! stable run changes by under 1%), and the safety step (0.9) must keep a randomly excited block
//! bounded. "Bounded" is measured on the reported energy, kinetic +
//! elastic, with the leapfrog's kinetic energy `½ Σ m v_{n−½}·v_{n+½}`:
//! for a linear system that sum is the scheme's conserved quantity
//! exactly, and for this one (neo-Hookean tets, joints) up to the
//! nonlinear terms. (When it reported `½ Σ m |v_n|²`, the rough start put a
//! fixed offset of 6% on it at 0.9 Δt_crit; the reference is still taken
//! after 100 steps.) The energy must then stay within 1% for 2000 steps.
//! Above the limit it grows: the unstable top mode opens the joints past
//! δp, where their law is no longer linear (a purely linear unstable mode
//! would keep kinetic + elastic constant, the kinetic energy going
//! negative as the elastic grows: that is the run guard's to catch, by
//! its step check and its check for non-finite values).
//!
//! Extremes: a stiff penalty (p0 = 100 E, the limit p0 → ∞ of Eq. 8) and a
//! small, badly shaped mesh (jitter 0.15) stay stable at the estimated step,
//! and with strong damping the step is shortened accordingly.

use crate::common::{at_step, box_mesh, model, rock, stable};
use femdem_core::{Real, Vec3};
use femdem_material::Law;
use femdem_solver::{Loads, Solver, StepParams, Want};

fn excited(p0_factor: f64, jitter: f64, viscosity: f64) -> (Solver, femdem_solver::StableStep) {
    let mesh = box_mesh([0.0; 3], [0.04, 0.03, 0.03], 0.01, jitter, true);
    let (_, m) = model(&mesh, Law::NeoHookean, rock(viscosity), p0_factor * 26e9);
    let stable = stable(&m, &Loads::default(), 2000);
    let mut s = at_step(m, Loads::default(), 0.9 * stable.critical);
    // Rough initial velocities excite every mode, the top one included.
    s.set_velocity(|x| {
        let k = (x.x * 1e4).sin() * (x.y * 7e3).cos() + (x.z * 9e3).sin();
        Vec3::new(k, -k, 0.5 * k) * 1e-3
    });
    (s, stable)
}

fn energy(s: &Solver) -> Real {
    s.energies().kinetic + s.energies().tet_elastic + s.energies().joint_elastic
}

/// Runs `steps` steps; returns the largest `|E/E_ref − 1|` (or growth
/// `E/E_ref`) after the reference taken at step 100.
fn run(s: &mut Solver, steps: usize) -> (Real, Real) {
    for _ in 0..100 {
        s.step(Want::default());
    }
    s.step(Want { energy: true, ..Want::default() });
    let e0 = energy(s);
    let mut worst: Real = 1.0;
    for n in 0..steps {
        s.step(Want { energy: n % 20 == 0, ..Want::default() });
        if n % 20 == 0 {
            let r = energy(s) / e0;
            if !r.is_finite() {
                return (e0, Real::INFINITY);
            }
            worst = if (r - 1.0).abs() > (worst - 1.0).abs() { r } else { worst };
        }
    }
    (e0, worst)
}

#[test]
fn step_above_the_limit_blows_up_and_safety_step_stays_bounded() {
    let (mut above, stable) = excited(10.0, 0.1, 0.0);
    above.set_params(StepParams::new(1.05 * stable.critical).unwrap());
    above.step(Want { energy: true, ..Want::default() });
    let e0 = energy(&above);
    for _ in 0..100 {
        above.step(Want::default());
    }
    above.step(Want { energy: true, ..Want::default() });
    let growth = energy(&above) / e0;
    assert!(growth > 1e3 || !growth.is_finite(), "energy grew only ×{growth} at 1.05 Δt_crit");

    let (mut safe, stable) = excited(10.0, 0.1, 0.0);
    safe.set_params(StepParams::new(0.9 * stable.critical).unwrap());
    let (_, growth) = run(&mut safe, 2000);
    assert!((growth - 1.0).abs() < 0.01, "energy changed ×{growth} at 0.9 Δt_crit");
}

#[test]
fn stiff_penalty_and_distorted_mesh_are_stable_at_the_estimate() {
    for (p0, jitter) in [(100.0, 0.15), (1.0, 0.15)] {
        let (mut s, stable) = excited(p0, jitter, 0.0);
        s.set_params(StepParams::new(0.9 * stable.critical).unwrap());
        let (_, growth) = run(&mut s, 1000);
        assert!((growth - 1.0).abs() < 0.01, "p0 = {p0} E: energy changed ×{growth}");
    }
}

#[test]
fn penalty_shortens_the_step_as_its_square_root() {
    // The top mode is a joint mode once p0 ≫ E: Δt ∝ 1/√p0.
    let (_, s100) = excited(100.0, 0.1, 0.0);
    let (_, s400) = excited(400.0, 0.1, 0.0);
    let ratio = s100.critical / s400.critical;
    assert!((ratio - 2.0).abs() < 0.1, "Δt(100E)/Δt(400E) = {ratio}");
}

#[test]
fn damping_shortens_the_step_and_stays_stable() {
    let (mut s, stable) = excited(10.0, 0.1, 2000.0);
    let (_, undamped) = excited(10.0, 0.1, 0.0);
    assert!(stable.critical < undamped.critical);
    assert!(stable.beta_max > 0.0);
    s.set_params(StepParams::new(0.9 * stable.critical).unwrap());
    let (_, growth) = run(&mut s, 1000);
    assert!(growth <= 1.0 + 1e-9, "damped energy grew ×{growth}");
    assert!(growth < 0.999, "damping must dissipate");
}
