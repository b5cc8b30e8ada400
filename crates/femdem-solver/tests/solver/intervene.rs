//! Changing the state between steps through the solver's API
//! (`Solver::damp`, `Solver::kick`): what each removes or adds is booked
//! so that the energy balance holds to the account's own accuracy (the
//! identity in `step/intervene.rs`), and bad arguments change nothing.

use femdem_core::Vec3;
use femdem_material::Law;
use femdem_mesh::insert_joints;
use femdem_solver::select::{NodeSelection, select_nodes};
use femdem_solver::{Fixed, Loads, Solver, Want};

use crate::common::{box_mesh, model, rock, solver};

/// An elastic cube (no joints, no viscosity) in free space, shaken by an
/// initial velocity field that stretches and shears it.
fn shaken_cube() -> Solver {
    let mesh = box_mesh([0.0; 3], [0.1, 0.1, 0.1], 0.05, 0.1, false);
    let (_, m) = model(&mesh, Law::NeoHookean, rock(0.0), 0.0);
    let mut s = solver(m, Loads::default(), 0.5);
    s.set_velocity(|x| Vec3::new(0.0, 2.0 * (x.x - 0.05), 1.0 * (x.y - 0.05)));
    s
}

/// The same cube standing on its fixed base (`zmin`) under gravity, so
/// that loads and reactions hold work over between steps.
fn standing_cube() -> (Solver, Vec<u32>) {
    let mesh = box_mesh([0.0; 3], [0.1, 0.1, 0.1], 0.05, 0.1, false);
    let (_, m) = model(&mesh, Law::NeoHookean, rock(0.0), 0.0);
    let jointed = insert_joints(&mesh).unwrap();
    let base = select_nodes(&jointed, &NodeSelection { group: Some("zmin".into()), ..Default::default() }).unwrap();
    let loads = Loads {
        fixed: vec![Fixed { nodes: base.clone(), components: [true; 3] }],
        gravity: Vec3::new(0.0, 0.0, -9.81e3),
        ..Loads::default()
    };
    let mut s = solver(m, loads, 0.5);
    s.set_velocity(|x| Vec3::new(0.0, 2.0 * (x.x - 0.05), 0.0));
    (s, base)
}

/// Steps `n` times, calling `between` after each step; returns the largest
/// `|B_k − B_0|` over the steps (energies evaluated at every step).
fn drift(s: &mut Solver, n: usize, mut between: impl FnMut(&mut Solver)) -> f64 {
    let b0 = s.step(Want { energy: true, stress: false }).energies.balance();
    between(s);
    let mut worst: f64 = 0.0;
    for _ in 1..n {
        worst = worst.max((s.step(Want { energy: true, stress: false }).energies.balance() - b0).abs());
        between(s);
    }
    worst
}

#[test]
fn damping_books_what_it_removes_and_the_balance_holds() {
    let mut free = shaken_cube();
    let k0 = free.step(Want { energy: true, stress: false }).energies.kinetic;
    let undamped = drift(&mut shaken_cube(), 400, |_| {});
    let mut removed = 0.0;
    let mut s = shaken_cube();
    let damped = drift(&mut s, 400, |s| removed += s.damp(0.99).unwrap());
    let e = *s.energies();
    // The damping took most of the motion's energy, and booked all of it.
    assert!(removed > 0.5 * k0, "removed {removed:e} J of {k0:e} J");
    assert!((e.damping - removed).abs() <= 1e-12 * removed, "{} vs {removed}", e.damping);
    // The balance moved no more than without damping (the neo-Hookean
    // truncation), and by a tiny part of what was removed: unbooked, the
    // removal would have moved it by `removed` itself.
    eprintln!("damping: drift {damped:e} J (undamped {undamped:e} J), removed {removed:e} J of {k0:e} J");
    assert!(damped <= 2.0 * undamped + 1e-12 * k0, "damped {damped:e} J, undamped {undamped:e} J");
    assert!(damped < 1e-6 * removed, "drift {damped:e} J against {removed:e} J removed");
}

#[test]
fn a_kick_books_its_work_and_the_balance_holds() {
    let mut s = shaken_cube();
    let mut w = 0.0;
    let mut kicked = 0.0;
    let mut step = 0;
    let node = 5;
    let drift = drift(&mut s, 300, |s| {
        step += 1;
        if step % 50 == 0 {
            let v = s.state().v[node];
            let m = s.model().mass[node];
            let dv = Vec3::new(0.3, -0.2, 0.1);
            let work = s.kick(node, dv).unwrap();
            // ½ m (|v + dv|² − |v|²), up to the internal-force term.
            let kinetic = 0.5 * m * ((v + dv).norm_squared() - v.norm_squared());
            assert!((work - kinetic).abs() <= 0.1 * kinetic.abs(), "{work:e} vs {kinetic:e}");
            assert_eq!(s.state().v[node], v + dv);
            w += work;
            kicked += work.abs();
        }
    });
    // Unbooked, the balance would move by the kicks' work itself. Booked,
    // what is left is the neo-Hookean truncation of the sharper motion a
    // kicked node makes: measured 1.6e-6 of the kicks' work (the account's
    // accuracy on the bundled cases is 1e-4 of their scale,
    // docs/reliability.md).
    eprintln!("kicks: drift {drift:e} J, kicks {w:e} J (Σ|work| {kicked:e} J)");
    assert!(kicked > 1e-2, "{kicked:e}");
    assert!(drift < 1e-5 * kicked, "drift {drift:e} J against kicks of {kicked:e} J");
}

#[test]
fn bad_interventions_are_refused_and_change_nothing() {
    let mut s = shaken_cube();
    s.step(Want::default());
    let (v, e) = (s.state().v.clone(), *s.energies());
    for keep in [-0.1, 1.5, f64::NAN] {
        let err = s.damp(keep).unwrap_err().to_string();
        assert!(err.contains("keep must lie in [0, 1]"), "{err}");
    }
    let n = s.state().v.len();
    assert!(s.kick(n, Vec3::new(1.0, 0.0, 0.0)).unwrap_err().to_string().contains(&format!("node {n} of {n}")));
    assert!(s.kick(0, Vec3::new(f64::INFINITY, 0.0, 0.0)).unwrap_err().to_string().contains("not finite"));
    assert_eq!(s.state().v, v);
    assert_eq!(s.energies().balance().to_bits(), e.balance().to_bits());
}

#[test]
fn with_gravity_and_a_fixed_base_the_booking_holds_and_fixed_components_stay() {
    // Gravity's and the base's reactions hold work over between steps: it
    // was computed with the old velocities, and the booking accounts for it.
    let (mut s, base) = standing_cube();
    let undamped = drift(&mut standing_cube().0, 300, |_| {});
    let mut removed = 0.0;
    let damped = drift(&mut s, 300, |s| removed += s.damp(0.98).unwrap());
    eprintln!("standing: drift {damped:e} J (undamped {undamped:e} J), removed {removed:e} J");
    assert!(removed > 0.0);
    assert!(damped < 1e-6 * removed && damped <= 2.0 * undamped + 1e-9 * removed, "{damped:e} {undamped:e}");
    // A fixed node does not move: a kick leaves it at rest and books nothing.
    let fixed = base[0] as usize;
    assert_eq!(s.kick(fixed, Vec3::new(1.0, 1.0, 1.0)).unwrap(), 0.0);
    assert_eq!(s.state().v[fixed], Vec3::zeros());
}

#[test]
fn before_the_first_step_only_the_velocity_changes_and_after_a_restore_a_step_comes_first() {
    let mut s = shaken_cube();
    let x0 = s.state().x.clone();
    let v = s.state().v[3];
    s.kick(3, Vec3::new(0.0, 0.0, 0.5)).unwrap();
    s.damp(0.5).unwrap();
    assert_eq!(s.state().x, x0, "the reference positions stay");
    assert_eq!(s.state().v[3], (v + Vec3::new(0.0, 0.0, 0.5)) * 0.5);
    // The balance of step 0 starts from the changed velocities: the run
    // drifts as one started with them does (nodes of this unjointed mesh
    // have positions of their own).
    let v_start = s.state().v.clone();
    let mut same = shaken_cube();
    let x_ref = same.model().x0.clone();
    same.set_velocity(|p| v_start[x_ref.iter().position(|q| q == p).unwrap()]);
    assert_eq!(same.state().v, v_start);
    let (changed, started) = (drift(&mut s, 100, |_| {}), drift(&mut same, 100, |_| {}));
    assert!((changed - started).abs() <= 1e-3 * started.max(1e-15), "{changed:e} vs {started:e}");

    let snapshot = s.snapshot();
    let mut restored = shaken_cube();
    restored.restore(&snapshot).unwrap();
    let err = restored.damp(0.9).unwrap_err().to_string();
    assert!(err.contains("take a step first"), "{err}");
    restored.step(Want::default());
    assert!(restored.damp(0.9).is_ok());
}
