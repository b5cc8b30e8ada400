//! The run guard (`Solver::check`): a crushed element trips the time-step
//! check before the run loses meaning; a NaN is reported with its node.
//!
//! Crushing case: an unbreakable 20 mm rock cube (5 mm lattice) on a held
//! base, its top face driven down at 200 m/s (a strain rate of 1e4 /s, far
//! beyond anything quasi-static, so that elements flatten within a few
//! hundred steps). The step is the usual 0.9 of the reference critical
//! step. As the cube is crushed its tets lose altitude and, being
//! neo-Hookean, stiffen (`c(J)² ∝ λ + 2μ − λ ln J`), so the critical step
//! falls below the step in use: the guard must say so, naming a tet, before
//! any value becomes non-finite, and the run it stops must really have been
//! heading for an instability.

use femdem_core::Vec3;
use femdem_material::Law;
use femdem_solver::select::{NodeSelection, select_nodes};
use femdem_solver::{Loads, Ramp, Solver, Trouble, VelocityDrive, Want};

use crate::common::{at_step, box_mesh, model, rock, stable};

fn crushed_cube() -> (Solver, f64) {
    let mesh = box_mesh([0.0; 3], [0.02, 0.02, 0.02], 0.005, 0.1, false);
    let (jointed, m) = model(&mesh, Law::NeoHookean, rock(0.0), 0.0);
    let sel = |g: &str| select_nodes(&jointed, &NodeSelection { group: Some(g.into()), ..Default::default() }).unwrap();
    let drive = |name: &str, nodes, vz| VelocityDrive {
        name: name.into(),
        nodes,
        velocity: Vec3::new(0.0, 0.0, vz),
        components: [true; 3],
        ramp: Ramp::STEP,
        start_time: None,
    };
    let loads = Loads {
        drives: vec![drive("base", sel("zmin"), 0.0), drive("press", sel("zmax"), -200.0)],
        ..Default::default()
    };
    let critical = stable(&m, &loads, 300).critical;
    (at_step(m, loads, 0.9 * critical), critical)
}

#[test]
fn crushing_trips_the_step_check_before_anything_is_non_finite() {
    let (mut s, critical) = crushed_cube();
    let mut tripped = None;
    for n in 0..20_000 {
        s.step(Want::default());
        if n % 10 == 0 {
            match s.check(critical) {
                Ok(()) => {}
                Err(t) => {
                    tripped = Some(t);
                    break;
                }
            }
        }
    }
    let Some(Trouble::StepTooLarge { step, j, shrink, estimate, dt, .. }) = tripped else {
        panic!("expected the step check to trip, got {tripped:?}");
    };
    let strain = 200.0 * s.state().time / 0.02;
    eprintln!(
        "tripped at step {step}, nominal strain {strain:.3}: J = {j:.3}, altitude ×{shrink:.3}, estimate {estimate:.3e} s < dt {dt:.3e} s"
    );
    assert!(s.state().x.iter().chain(&s.state().v).all(|p| p.iter().all(|c| c.is_finite())));
    assert!(estimate < dt && (j < 1.0 || shrink < 1.0));
    // The instability it warns of is real: run on unguarded and the energy
    // account explodes (measured: at a nominal strain of 0.47, 40 steps
    // after the trip at 0.13, kinetic energy 1e25 J against 2.5e4 J of work).
    let blew_up = (0..400).any(|_| {
        let e = s.step(Want { energy: true, stress: false }).energies;
        let (imbalance, work) = (e.balance().abs(), e.external_work.abs());
        imbalance.is_nan() || imbalance >= work
    });
    assert!(blew_up, "the crushed cube was expected to go unstable past the trip");
}

#[test]
fn a_non_finite_velocity_is_reported_with_its_node() {
    let (mut s, critical) = crushed_cube();
    s.step(Want::default());
    assert_eq!(s.check(critical), Ok(()));
    // A node whose reference position no other node shares (split nodes
    // share theirs), given a non-finite velocity through the API.
    let x0 = s.model().x0.clone();
    let node = (0..x0.len()).find(|&i| x0.iter().filter(|p| **p == x0[i]).count() == 1).expect("a node of its own");
    s.set_velocity(|p| if *p == x0[node] { Vec3::new(0.0, f64::NAN, 0.0) } else { Vec3::zeros() });
    match s.check(critical) {
        Err(Trouble::NonFinite { node: n, .. }) if n == node => {}
        other => panic!("expected node {node} reported, got {other:?}"),
    }
}
