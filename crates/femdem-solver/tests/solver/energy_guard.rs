//! The energy account, centred on `t_n` (`femdem-solver` `step/mod.rs`),
//! and the guard that watches it (`Solver::check_energy`, `ledger.rs`).
//!
//! 1. **Exact for a linear body.** The leapfrog's kinetic energy
//!    `½ Σ m v_{n−½}·v_{n+½}` changes by exactly the trapezoidal work of
//!    the total force, and for the small-strain linear law (forces linear
//!    in `x`, energy quadratic) the trapezoidal work of the internal forces
//!    is exactly the change of strain energy. So a linear, undamped,
//!    unjointed block under everything that is booked as work — a piston
//!    that starts and stops abruptly (velocity jumps), a follower pressure
//!    (not conservative), gravity, a base held fixed, an initial velocity
//!    field — keeps `B_n − B_0` at round-off. What round-off: the strains
//!    (about 10⁻³ here) are differences of positions, so each tet's energy
//!    carries a relative error of order `ε / 10⁻³` ≈ 10⁻¹³, summed over
//!    1,280 tets and compared after 3000 steps of booked work: 10⁻¹⁰
//!    bounds it with a margin and is still 10⁸ below the guard's default.
//!    Measured: 7.7·10⁻¹² (growing while the piston pushes, flat after).
//!    The old account (work through `t_{n+½}` against the kinetic energy of
//!    `v_n`) was 53% off on the bundled elastic bar at its first step.
//! 2. **Honest nonlinear runs stay quiet with margin.** The damped,
//!    jointed bar of `bar_fracture.rs`, crushed at 1 m/s until 140 joints
//!    have failed, with contact and Coulomb friction (μ = 0.6) on the crack
//!    faces: neo-Hookean tets, softening and failing joints, viscous
//!    damping, the Eq. 18 ramp, sliding. What is left of the account's
//!    error is the truncation of the nonlinear laws and the viscous
//!    operator taken on `x_n` for the whole interval
//!    (`femdem_solver::Dissipation`). The default tolerance must have a
//!    margin of 10 over such a run: the error must stay below
//!    `ENERGY_TOLERANCE / 10` = 10⁻³ at every check. Measured: worst
//!    3.7·10⁻⁵ (the bundled runs, evaluated at every step: at most
//!    1.2·10⁻⁴).
//! 3. **Energy no force accounts for trips it.** `Solver::set_velocity`
//!    called in the middle of a run (a legal call, physically wrong: a
//!    kick no force gave) on a free block squeezed between two equal
//!    pressures. It replaces the block's velocities by a rigid `u` = 1 m/s,
//!    so the next evaluation must find `B_n − B_0 = ½ M |u|²` up to what
//!    the block held before (the vibration's kinetic energy the kick
//!    replaced, and one step of its elastic motion, which the account
//!    books with the new velocities): `|error − ½ M |u|²| ≤ K + U` of the
//!    last evaluation before the kick. The step after it moves the block
//!    rigidly and the loads are balanced: they add nothing. And
//!    `check_energy` must stop the run naming the step, the time, the
//!    error and its scale.

use femdem_core::{Real, Vec3};
use femdem_material::Law;
use femdem_solver::select::{NodeSelection, select_nodes};
use femdem_solver::{
    ContactSettings, ENERGY_TOLERANCE, Fixed, Loads, Ramp, Solver, SurfaceKind, SurfaceLoad, Trouble, VelocityDrive,
    Want, held_nodes,
};

use crate::common::{at_step, box_mesh, model, pulled_bar_loads, rock, stable};

/// The worst `|B_n − B_0| / scale_n` over `steps` steps, the energies
/// evaluated every `every` steps; `check_energy` with the default
/// tolerance must stay quiet at each.
fn worst_imbalance(s: &mut Solver, steps: usize, every: usize) -> Real {
    let mut worst: Real = 0.0;
    for n in 0..steps {
        let want = n % every == every - 1;
        s.step(Want { energy: want, ..Want::default() });
        if want {
            let i = s.imbalance().expect("evaluated");
            assert_eq!(i.step + 1, s.state().step, "the watch reads the step just taken");
            worst = worst.max(i.relative());
            assert_eq!(s.check_energy(ENERGY_TOLERANCE), Ok(()), "step {n}");
        }
    }
    worst
}

#[test]
fn a_linear_elastic_run_balances_to_round_off() {
    let mesh = box_mesh([0.0; 3], [0.02, 0.02, 0.04], 0.005, 0.1, false);
    let (jointed, m) = model(&mesh, Law::LinearElastic, rock(0.0), 0.0);
    let sel = |g: &str| select_nodes(&jointed, &NodeSelection { group: Some(g.into()), ..Default::default() }).unwrap();
    let faces = femdem_solver::select::group_faces(&jointed, "xmax").unwrap();
    let loads = Loads {
        gravity: Vec3::new(0.0, 0.0, -9.81e3),
        fixed: vec![Fixed { nodes: sel("zmin"), components: [true; 3] }],
        drives: vec![VelocityDrive {
            name: "piston".into(),
            nodes: sel("zmax"),
            velocity: Vec3::new(0.0, 0.0, -0.5),
            components: [false, false, true],
            ramp: Ramp { ramp_time: 0.0, stop_time: Some(1e-4) },
            start_time: None,
        }],
        surfaces: vec![SurfaceLoad {
            name: "side".into(),
            faces,
            kind: SurfaceKind::Pressure(2e6),
            ramp: Ramp { ramp_time: 5e-5, stop_time: None },
        }],
    };
    assert!(held_nodes(&m, &loads).unwrap().iter().any(|&h| !h));
    let dt = 0.9 * stable(&m, &loads, 400).critical;
    let mut s = at_step(m, loads, dt);
    s.set_velocity(|x| Vec3::new((x.z * 90.0).sin(), 0.0, (x.x * 70.0).cos()) * (0.2 * x.z / 0.04));
    let steps = 3000;
    let worst = worst_imbalance(&mut s, steps, 1);
    let e = *s.energies();
    eprintln!(
        "linear: worst |B − B0| / scale {worst:.2e} over {steps} steps of {dt:.3e} s (drive stopped at step {}); \
         work {:.4e} J, kinetic {:.4e} J, elastic {:.4e} J",
        (1e-4 / dt).ceil(),
        e.external_work,
        e.kinetic,
        e.tet_elastic
    );
    assert!(s.state().time > 2e-4, "the run must go past the drive's stop");
    assert!(e.external_work > 0.0 && e.tet_elastic > 0.0);
    assert!(worst < 1e-10, "the account of a linear run is exact up to round-off: {worst:e}");
}

#[test]
fn a_damped_crushed_bar_with_friction_stays_within_a_tenth_of_the_default() {
    const V: f64 = -1.0;
    const END: f64 = 1.5e-4;
    let (w, len, h) = (0.01, 0.02, 0.0025);
    let mesh = box_mesh([0.0; 3], [w, w, len], h, 0.1, true);
    let viscosity = femdem_material::critical_viscosity(h, 26e9, 2340.0) * 0.1;
    let (jointed, m) = model(&mesh, Law::NeoHookean, rock(viscosity), 10.0 * 26e9);
    let loads = pulled_bar_loads(&jointed, w, V);
    let dt = 0.9 * stable(&m, &loads, 300).critical;
    let mut s = at_step(m, loads, dt);
    s.enable_contact(ContactSettings { surfaces: false, friction: 0.6, ..ContactSettings::new(26e9) }, &[]);
    let steps = (END / dt).ceil() as usize;
    let worst = worst_imbalance(&mut s, steps, 10);
    let e = *s.energies();
    eprintln!(
        "crushed bar: worst |B − B0| / scale {worst:.2e} over {steps} steps; {} joints failed; work {:.3e} J, damping \
         {:.3e} J, fracture {:.3e} J, contact {:.3e} J, friction {:.3e} J",
        s.failures().len(),
        e.external_work,
        e.damping,
        e.fracture,
        e.contact,
        e.friction
    );
    assert!(s.failures().len() > 100, "the bar must crush");
    assert!(e.damping > 0.0 && e.fracture > 0.0 && e.friction > 0.0 && e.contact != 0.0);
    assert!(worst < 0.1 * ENERGY_TOLERANCE, "worst {worst:e}: less than 10× margin below the default tolerance");
}

#[test]
fn a_kick_no_force_gave_trips_the_energy_check() {
    let mesh = box_mesh([0.0; 3], [0.02, 0.02, 0.02], 0.005, 0.1, false);
    let (jointed, m) = model(&mesh, Law::NeoHookean, rock(0.0), 0.0);
    let total: Real = m.mass.iter().sum();
    let squeeze = |name: &str| SurfaceLoad {
        name: name.into(),
        faces: femdem_solver::select::group_faces(&jointed, name).unwrap(),
        kind: SurfaceKind::Pressure(1e6),
        ramp: Ramp { ramp_time: 2e-5, stop_time: None },
    };
    let loads = Loads { surfaces: vec![squeeze("zmin"), squeeze("zmax")], ..Loads::default() };
    let dt = 0.9 * stable(&m, &loads, 400).critical;
    let mut s = at_step(m, loads, dt);
    let quiet = worst_imbalance(&mut s, 200, 10);
    assert!(quiet < 1e-3, "before the kick: {quiet:e}");
    let before = *s.energies();
    assert!(s.record().energies_current, "step 199 evaluated the energies");
    let held = before.kinetic + before.tet_elastic;
    let u = Vec3::new(1.0, 0.0, 0.0);
    s.set_velocity(|_| u);
    let kick = 0.5 * total * u.norm_squared();
    s.step(Want { energy: true, ..Want::default() });
    let i = s.imbalance().unwrap();
    eprintln!(
        "kick: ½M|u|² = {kick:.4e} J, held before {held:.3e} J; error {:.4e} J of scale {:.4e} J ({:.3}) at step {}",
        i.error,
        i.scale,
        i.relative(),
        i.step
    );
    assert!(held < 0.05 * kick, "the block held {held:e} J before a kick of {kick:e} J");
    assert!((i.error - kick).abs() <= held, "error {:e} J, kick {kick:e} J, held before {held:e} J", i.error);
    match s.check_energy(ENERGY_TOLERANCE) {
        Err(t @ Trouble::EnergyBalance { step, time, error, scale, tolerance }) => {
            assert_eq!((step, time), (200, s.record().time));
            assert!(error > 0.0 && error > tolerance * scale);
            let message = t.to_string();
            assert!(
                message.starts_with("step 200, t = ") && message.contains("gained") && message.contains("energy scale"),
                "{message}"
            );
        }
        other => panic!("expected the energy check to trip, got {other:?}"),
    }
}
