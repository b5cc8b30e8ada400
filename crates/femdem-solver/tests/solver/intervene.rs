//! Changing the state between steps through the solver's API
//! (`Solver::damp`, `Solver::kick`): what each removes or adds is booked
//! so that the energy balance holds to the account's own accuracy (the
//! identity in `step/intervene.rs`), and bad arguments change nothing.

use femdem_core::Vec3;
use femdem_material::Law;
use femdem_solver::{Loads, Solver, Want};

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
        }
    });
    // Unbooked, the balance would move by the kicks' work itself. Booked,
    // what is left is the neo-Hookean truncation of the sharper motion a
    // kicked node makes: measured 1.6e-6 of the kicks' work (the account's
    // accuracy on the bundled cases is 1e-4 of their scale,
    // docs/reliability.md).
    eprintln!("kicks: drift {drift:e} J, kicks {w:e} J");
    assert!(w.abs() > 1e-2, "{w:e}");
    assert!(drift < 1e-5 * w.abs(), "drift {drift:e} J against kicks {w:e} J");
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
