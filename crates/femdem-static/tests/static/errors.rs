//! What the static start refuses, the hand-over's checks, and determinism.

use femdem_core::Vec3;
use femdem_solver::{Loads, Ramp, SolverError, SurfaceKind, Want};
use femdem_static::{StaticError, StaticOptions, static_solve};

use crate::common::{fixed, jointed_box, limestone, model, pressures, solver, surface};

#[test]
fn initial_contacts_are_refused() {
    let mesh = jointed_box([0.01; 3], 0.005);
    let m = model(&mesh, limestone(0.0));
    let err = static_solve(&m, &Loads::default(), &[(0, 1)], &StaticOptions::default()).unwrap_err();
    assert_eq!(err, StaticError::InitialContact { pairs: 1 });
    assert!(err.to_string().contains("pre-existing fracture faces"), "{err}");
}

#[test]
fn bad_options_are_refused() {
    let mesh = jointed_box([0.01; 3], 0.005);
    let m = model(&mesh, limestone(0.0));
    let options = StaticOptions { tolerance: 0.0, ..Default::default() };
    assert!(matches!(static_solve(&m, &Loads::default(), &[], &options), Err(StaticError::Options(_))));
}

/// Without loads the answer is zero, at once.
#[test]
fn no_load_no_displacement() {
    let mesh = jointed_box([0.01; 3], 0.005);
    let m = model(&mesh, limestone(0.0));
    let s = static_solve(&m, &Loads::default(), &[], &StaticOptions::default()).unwrap();
    assert!(s.displacement.iter().all(|u| *u == Vec3::zeros()) && s.iterations == 0 && s.residual == 0.0);
}

/// A displaced start is for the start of a run, moves no held component,
/// and takes a finite field of the model's size.
#[test]
fn the_hand_over_checks_its_displacement() {
    let mesh = jointed_box([0.01; 3], 0.005);
    let loads = Loads { fixed: vec![fixed(&mesh, "zmin")], ..Default::default() };
    let held = loads.fixed[0].nodes[0] as usize;
    let mut s = solver(model(&mesh, limestone(0.0)), loads, 0.9);
    let n = s.model().num_nodes();
    let bad = |r: Result<f64, SolverError>| matches!(r, Err(SolverError::InitialDisplacement(_)));
    assert!(bad(s.start_displaced(&vec![Vec3::zeros(); n - 1])));
    let mut u = vec![Vec3::zeros(); n];
    u[held].x = 1e-9;
    assert!(bad(s.start_displaced(&u)));
    u[held].x = 0.0;
    u[(held + 1) % n].y = f64::NAN;
    assert!(bad(s.start_displaced(&u)));
    s.step(Want::default());
    assert!(bad(s.start_displaced(&vec![Vec3::zeros(); n])));
}

/// The solve is sequential: one thread or two, the same bits.
#[test]
fn the_solution_does_not_depend_on_the_thread_count() {
    let mesh = jointed_box([0.02, 0.02, 0.03], 0.005);
    let m = model(&mesh, limestone(0.0));
    let mut loads = Loads {
        surfaces: pressures(&mesh, [1e6, 2e6, 3e6], Ramp::STEP),
        gravity: Vec3::new(0.0, -9.8, 0.0),
        ..Default::default()
    };
    loads.surfaces.push(surface(&mesh, "xmax", SurfaceKind::Traction(Vec3::new(0.0, 1e5, 0.0)), Ramp::STEP));
    let solve = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
        pool.install(|| static_solve(&m, &loads, &[], &StaticOptions::default()).unwrap())
    };
    let (one, two) = (solve(1), solve(2));
    assert!(
        one.displacement
            .iter()
            .zip(&two.displacement)
            .all(|(a, b)| a.iter().zip(b).all(|(p, q)| p.to_bits() == q.to_bits()))
    );
    assert_eq!(one.residual.to_bits(), two.residual.to_bits());
}
