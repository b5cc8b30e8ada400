//! Each surface load's work (`StepRecord::surface_work`) and each drive's
//! (`StepRecord::drive_work`), booked as the external work is (the
//! trapezoidal rule centred on `t_n`).
//!
//! - Each load keeps its own: two pressures on one column both do work.
//!   (That the loads', the drives' and gravity's work add up to the
//!   external work is the ledger's construction, `Ledger::close`: the
//!   external work is their sum, not a second computation to compare.)
//! - On a column fixed at its base and pressed slowly on its top alone, the
//!   load's work is that of a linear spring, `∫ F dδ = ½ F δ` (δ the
//!   mean displacement of the top face): the ramp lasts 20 periods of the
//!   column's first mode (estimated as a bar's, `4 l / c`), which leaves
//!   an oscillation of at most `T / (π T_ramp) = 1.6%` of the static
//!   displacement (the upper envelope of a linear ramp's response); the
//!   work integrates over it, `½ F δ` at the ramp's end does not, so the
//!   two agree to that bound (0.32% measured).
//! - Started from a displaced state at rest (a static start), each load's
//!   work starts at its Clapeyron share `½ f · u`, the external work at the
//!   stored energy, and the shares add up to the stored energy to the same
//!   bound when the state is the slowly pressed column's.
//! - A solver restored from a snapshot continues the loads' work bit for
//!   bit.
//! - With a drive pressing the top and a pressure on a side, both do work;
//!   pressed slowly, the drive's work is `½ F δ` of its
//!   reaction `F` and its prescribed displacement `δ`, to the same ramp
//!   bound; and a restored solver continues it bit for bit.

use crate::common::{box_mesh, model, rock, solver};
use femdem_core::Vec3;
use femdem_material::Law;
use femdem_mesh::JointedMesh;
use femdem_solver::select::{NodeSelection, group_faces, select_nodes};
use femdem_solver::{Fixed, Loads, Model, Ramp, Solver, SurfaceKind, SurfaceLoad, VelocityDrive, Want};

/// A 10 × 10 × 40 mm column fixed at its base, pressed on its top by `p`
/// and on its `xmax` side by `p_side`, both ramped over `periods` periods
/// of its first axial mode; returns the solver, the top's faces and the
/// ramp time.
fn column(p: f64, p_side: f64, periods: f64) -> (Solver, Vec<[u32; 3]>, f64) {
    column_ramped(p, p_side, periods, false)
}

/// The 10 × 10 × 40 mm jointed column of rock and the period of its first
/// axial mode when fixed at one end, `4 l / c` (s).
fn column_model() -> (JointedMesh, Model, f64) {
    let (w, l) = (0.01, 0.04);
    let mesh = box_mesh([0.0; 3], [w, w, l], 0.005, 0.1, false);
    let mat = rock(0.0);
    let (jointed, m) = model(&mesh, Law::NeoHookean, mat, 0.0);
    (jointed, m, 4.0 * l / (mat.young() / mat.density()).sqrt())
}

/// The nodes of `group` of `jointed`.
fn nodes(jointed: &JointedMesh, group: &str) -> Vec<u32> {
    select_nodes(jointed, &NodeSelection { group: Some(group.into()), ..Default::default() }).unwrap()
}

/// [`column`], its loads ramped or (`step`) at full value from the start.
fn column_ramped(p: f64, p_side: f64, periods: f64, step: bool) -> (Solver, Vec<[u32; 3]>, f64) {
    let (jointed, m, period) = column_model();
    let t_ramp = periods * period;
    let sel = |g: &str| nodes(&jointed, g);
    let ramp = if step { Ramp::STEP } else { Ramp { ramp_time: t_ramp, stop_time: None } };
    let load = |name: &str, group: &str, p: f64| SurfaceLoad {
        name: name.into(),
        faces: group_faces(&jointed, group).unwrap(),
        kind: SurfaceKind::Pressure(p),
        ramp,
    };
    let loads = Loads {
        fixed: vec![Fixed { nodes: sel("zmin"), components: [true; 3] }],
        surfaces: vec![load("top", "zmax", p), load("side", "xmax", p_side)],
        ..Loads::default()
    };
    (solver(m, loads, 0.9), group_faces(&jointed, "zmax").unwrap(), t_ramp)
}

#[test]
fn each_load_keeps_its_own_work() {
    let (mut s, _, t_ramp) = column(10e6, 3e6, 2.0);
    let mut work = [0.0; 2];
    while s.state().time < t_ramp {
        let r = s.step(Want::default());
        work = [r.surface_work[0], r.surface_work[1]];
    }
    assert!(work[0] > 0.0 && work[1] > 0.0, "both pressures do work on the body they press: {work:?} J");
}

/// The force the update applies is the loads' recorded totals. With the
/// loads at full value from the start, step 0 starts at rest in the
/// reference configuration, where the internal forces are zero: its
/// momentum `Σ m v_{½} / Δt` is what the loads pushed with (the base,
/// fixed, is off the pressed top), against `StepRecord::surface_forces`,
/// which each load sums from its own nodal forces: to round-off of the
/// force (1e-12 relative, some thousand nodes summed in two orders).
#[test]
fn the_loads_recorded_forces_are_the_forces_applied() {
    let (mut s, _, _) = column_ramped(10e6, 0.0, 2.0, true);
    let r = s.step(Want::default()).clone();
    let recorded: Vec3 = r.surface_forces.iter().sum();
    let dt = s.dt();
    let momentum: Vec3 = s.state().v.iter().zip(&s.model().mass).map(|(v, &m)| v * (m / dt)).sum();
    assert!(recorded.z < 0.0, "the top is pressed down: {recorded:?}");
    assert!((momentum - recorded).norm() <= 1e-12 * recorded.norm(), "applied {momentum:?}, recorded {recorded:?}");
}

#[test]
fn a_slowly_pressed_column_takes_half_f_delta_from_its_load() {
    let periods = 20.0;
    let (mut s, top, t_ramp) = column(10e6, 0.0, periods);
    // The top's mean displacement weighted as a pressure spreads over its
    // faces (a third of each face's area to each of its nodes), so that
    // F δ is the load's `Σ f_i · u_i`.
    let area = |f: &[u32; 3], s: &Solver| {
        let x = f.map(|i| s.model().x0[i as usize]);
        0.5 * (x[1] - x[0]).cross(&(x[2] - x[0])).norm()
    };
    let mean_top_z = |s: &Solver| {
        let uz = |i: u32| s.recorded_position(i as usize).z - s.model().x0[i as usize].z;
        let weighted: f64 = top.iter().map(|f| area(f, s) * f.iter().map(|&i| uz(i)).sum::<f64>() / 3.0).sum();
        weighted / top.iter().map(|f| area(f, s)).sum::<f64>()
    };
    let (mut work, mut force, mut delta) = (0.0, 0.0, 0.0);
    while s.state().time < t_ramp {
        let r = s.step(Want::default());
        (work, force) = (r.surface_work[0], r.surface_forces[0].z);
        delta = mean_top_z(&s);
    }
    assert_spring_work("the load", work, force, delta, periods);
}

/// Asserts that `who`'s `work` (J) is a linear spring's `½ F δ` within the
/// upper envelope `T / (π T_ramp)` of a linear ramp's oscillation, the
/// ramp lasting `periods` periods `T` of the first mode.
fn assert_spring_work(who: &str, work: f64, force: f64, delta: f64, periods: f64) {
    let spring = 0.5 * force * delta;
    let bound = 1.0 / (std::f64::consts::PI * periods);
    let error = (work - spring).abs() / spring;
    eprintln!("{who}: work {work:e} J, ½ F δ {spring:e} J, {:.3}% apart", 100.0 * error);
    assert!(spring > 0.0, "{who} pushes and moves the same way: F = {force:e} N, δ = {delta:e} m");
    assert!(
        error < bound,
        "{who}'s work {work:e} J, ½ F δ = {spring:e} J (F = {force:e} N, δ = {delta:e} m): {:.2}% apart, \
         the ramp's oscillation up to {:.2}%",
        100.0 * error,
        100.0 * bound
    );
}

#[test]
fn a_restored_solver_continues_the_loads_work_bit_for_bit() {
    let (mut a, _, _) = column(10e6, 3e6, 2.0);
    for _ in 0..150 {
        a.step(Want::default());
    }
    let snap = a.snapshot();
    let (mut b, _, _) = column(10e6, 3e6, 2.0);
    b.restore(&snap).unwrap();
    for _ in 0..150 {
        a.step(Want::default());
        b.step(Want::default());
    }
    assert!(a.record().surface_work.iter().all(|&w| w > 0.0), "{:?}", a.record().surface_work);
    assert_eq!(a.record().surface_work, b.record().surface_work);
}

#[test]
fn a_static_start_gives_each_load_its_share_of_the_stored_energy() {
    let (p, periods) = (10e6, 20.0);
    let (mut a, _, t_ramp) = column_ramped(p, 0.3 * p, periods, false);
    while a.state().time < t_ramp {
        a.step(Want::default());
    }
    let u: Vec<Vec3> = (0..a.state().x.len()).map(|i| a.recorded_position(i) - a.model().x0[i]).collect();
    let (mut b, top, _) = column_ramped(p, 0.3 * p, periods, true);
    // A kick before the start: the start sets every velocity to zero, and
    // the kick's work goes with it.
    let kicked = b.kick(top[0][0] as usize, Vec3::new(0.0, 0.0, 1.0)).unwrap();
    assert!(kicked > 0.0);
    let stored = b.start_displaced(&u).unwrap();
    let shares = b.record().surface_work.clone();
    assert!(shares.iter().all(|&w| w > 0.0), "{shares:?}");
    // The ledger books the stored energy as the shares plus the rest
    // (`start`) and sums them again: two roundings.
    let external = b.energies().external_work;
    assert!(
        (external - stored).abs() <= 2.0 * f64::EPSILON * stored,
        "the external work {external:e} J starts at the stored energy {stored:e} J"
    );
    let sum: f64 = shares.iter().sum();
    let bound = 1.0 / (std::f64::consts::PI * periods);
    assert!(
        (sum - stored).abs() / stored < bound,
        "shares {shares:?} J add up to {sum:e} J, the stored energy is {stored:e} J"
    );
    // The first step books on from the shares: at rest, the half step
    // before t_0 adds nothing to them.
    let r = b.step(Want::default());
    assert_eq!(r.surface_work, shares);
}

/// The column of [`column`] with its top driven down at `speed` (m/s, z
/// only, ramped over `periods` periods of its first axial mode) instead of
/// pressed, and `p_side` on its `xmax` side; returns the solver and the
/// ramp time.
fn driven_column(speed: f64, p_side: f64, periods: f64) -> (Solver, f64) {
    let (jointed, m, period) = column_model();
    let t_ramp = periods * period;
    let ramp = Ramp { ramp_time: t_ramp, stop_time: None };
    let sel = |g: &str| nodes(&jointed, g);
    let loads = Loads {
        fixed: vec![Fixed { nodes: sel("zmin"), components: [true; 3] }],
        drives: vec![VelocityDrive {
            name: "press".into(),
            nodes: sel("zmax"),
            velocity: Vec3::new(0.0, 0.0, -speed),
            components: [false, false, true],
            ramp,
            start_time: None,
        }],
        surfaces: vec![SurfaceLoad {
            name: "side".into(),
            faces: group_faces(&jointed, "xmax").unwrap(),
            kind: SurfaceKind::Pressure(p_side),
            ramp,
        }],
        ..Loads::default()
    };
    (solver(m, loads, 0.9), t_ramp)
}

#[test]
fn a_drive_and_a_load_both_do_work() {
    let (mut s, t_ramp) = driven_column(0.5, 3e6, 2.0);
    let mut work = (0.0, 0.0);
    while s.state().time < 2.0 * t_ramp {
        let r = s.step(Want::default());
        work = (r.drive_work[0], r.surface_work[0]);
    }
    assert!(work.0 > 0.0 && work.1 > 0.0, "the drive and the pressure both do work on the column: {work:?} J");
}

#[test]
fn a_slowly_driven_column_takes_half_f_delta_from_its_drive() {
    // Driven at a speed that rises linearly over 20 periods: the top moves
    // by `v t² / (2 T_ramp)`, a start smoother than the pressed column's
    // force ramp, so the same bound on the oscillation holds; the column's
    // kinetic energy is about 10⁻⁴ of what it stores.
    let periods = 20.0;
    let (mut s, t_ramp) = driven_column(0.05, 0.0, periods);
    let (mut work, mut force, mut delta) = (0.0, 0.0, 0.0);
    while s.state().time < t_ramp {
        let r = s.step(Want::default());
        (work, force, delta) = (r.drive_work[0], r.drive_forces[0].z, r.drive_displacements[0].z);
    }
    assert_spring_work("the drive", work, force, delta, periods);
}

#[test]
fn a_restored_solver_continues_the_drives_work_bit_for_bit() {
    let (mut a, _) = driven_column(0.5, 3e6, 2.0);
    for _ in 0..150 {
        a.step(Want::default());
    }
    let snap = a.snapshot();
    let (mut b, _) = driven_column(0.5, 3e6, 2.0);
    b.restore(&snap).unwrap();
    for _ in 0..150 {
        a.step(Want::default());
        b.step(Want::default());
    }
    assert!(a.record().drive_work[0] > 0.0, "{:?}", a.record().drive_work);
    assert_eq!(a.record().drive_work, b.record().drive_work);
    assert_eq!(a.record().surface_work, b.record().surface_work);
}
