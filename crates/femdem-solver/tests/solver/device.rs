//! The step on a device (`Solver::use_device`), both residencies, against
//! the CPU: a jointed bar pulled to failure under gravity, bare and with a
//! pressure and a traction on two of its sides (faces whose edges are the
//! pulled ends' nodes too), and the interventions and checkpoints that move
//! the state between host and device.
//!
//! Where no Vulkan device with 64-bit floats exists these tests say so and
//! pass, unless `FEMDEM_GPU_REQUIRED` is set (CI sets it).
//!
//! Tolerance: the device's stage 1 agrees with the CPU's to round-off per
//! element (`femdem-gpu`'s tests) and the update is the same arithmetic,
//! so until the first failure positions agree to round-off carried over
//! the steps: `10⁻¹²` of the bar's width (10⁻¹⁴ m; coordinates of 10⁻² m
//! carry 2·10⁻¹⁸ m of rounding, so the steps here may amplify it a
//! thousandfold), and velocities, which are position differences over a
//! step, to that over `Δt`. After
//! failures begin a failure a step earlier or later is allowed to move the
//! course, so there the same joints must fail.

use femdem_core::Vec3;
use femdem_material::Law;
use femdem_mesh::insert_joints;
use femdem_solver::{ContactSettings, Gpu, Model, RegionBehaviour, Residency, Solver, SurfaceKind, SurfaceLoad, Want};

use crate::common::{at_step, box_mesh, joints, pulled_bar_loads, rock, stable};

const W: f64 = 0.01;
/// The pull's speed, m/s.
const V: f64 = 0.5;

/// The device, or `None` where the machine has none and
/// `FEMDEM_GPU_REQUIRED` is not set.
fn gpu() -> Option<Gpu> {
    Gpu::for_tests()
}

/// The pulled bar (10 × 10 × 20 mm, viscous, weak joints so that it breaks
/// within the steps below), under gravity, with a pressure on its x = 0
/// face and a traction on its y = W face when `pressed`.
fn bar(pressed: bool) -> Solver {
    let mesh = box_mesh([0.0; 3], [W, W, 0.02], 0.0025, 0.1, true);
    let jointed = insert_joints(&mesh).unwrap();
    let mut params = joints(26e10);
    params.tensile_strength = 3e5;
    params.cohesion = 1.5e6;
    params.gf_tension = 0.5;
    params.gf_shear = 0.5;
    let behaviour = RegionBehaviour::Deformable { law: Law::NeoHookean, material: rock(2e3), joints: Some(params) };
    let model = Model::new(&jointed, &[behaviour], 1.0).unwrap();
    let mut loads = pulled_bar_loads(&jointed, W, V);
    loads.gravity = Vec3::new(0.0, -9.81, -9.81);
    if pressed {
        let faces = femdem_solver::select::group_faces(&jointed, "xmin").unwrap();
        loads.surfaces.push(SurfaceLoad {
            name: "side".into(),
            faces,
            kind: SurfaceKind::Pressure(2e5),
            ramp: femdem_solver::Ramp { ramp_time: 1e-5, stop_time: None },
        });
        let faces = femdem_solver::select::group_faces(&jointed, "ymax").unwrap();
        loads.surfaces.push(SurfaceLoad {
            name: "shear".into(),
            faces,
            kind: SurfaceKind::Traction(Vec3::new(5e4, -1e5, 2e4)),
            // Removed within the first 400 steps (Δt ≈ 43 ns): the device's
            // zero-factor path before the comparison.
            ramp: femdem_solver::Ramp { ramp_time: 5e-6, stop_time: Some(1.2e-5) },
        });
    }
    let dt = 0.5 * stable(&model, &loads, 300).critical;
    at_step(model, loads, dt)
}

/// Steps `s` `n` times, asking for energies every 10th step and stresses
/// every 25th, as a run's output would; returns the joints failed.
fn run(s: &mut Solver, n: usize) -> usize {
    let mut failed = 0;
    for k in 0..n {
        let want = Want { stress: k % 25 == 0, energy: k % 10 == 0 };
        failed += s.step(want).new_failures.len();
    }
    failed
}

/// Positions and velocities of `a` and `b` within the module's tolerance;
/// the energies of their last records, and each surface load's force and
/// work, within `10⁻⁹` of the work and of the largest load's force: sums
/// over thousands of terms in different orders (the device sums a load
/// face by face, the CPU node by node), of terms that agree to round-off.
fn assert_close(a: &Solver, b: &Solver, what: &str) {
    let dx = a.state().x.iter().zip(&b.state().x).map(|(p, q)| (p - q).norm()).fold(0.0, f64::max);
    let dv = a.state().v.iter().zip(&b.state().v).map(|(p, q)| (p - q).norm()).fold(0.0, f64::max);
    println!("{what}: positions {dx:.2e} m, velocities {dv:.2e} m/s apart");
    assert!(dx <= 1e-12 * W, "{what}: positions {dx:e} m apart");
    assert!(dv <= 1e-12 * W / a.dt(), "{what}: velocities {dv:e} m/s apart");
    let (ea, eb) = (a.record().energies, b.record().energies);
    let scale = ea.external_work.abs().max(1e-12);
    for (x, y, name) in [
        (ea.kinetic, eb.kinetic, "kinetic"),
        (ea.external_work, eb.external_work, "external work"),
        (ea.damping, eb.damping, "damping"),
        (ea.joint_elastic, eb.joint_elastic, "joint elastic"),
    ] {
        assert!((x - y).abs() <= 1e-9 * scale, "{what}: {name} {x} vs {y}");
    }
    let (ra, rb) = (a.record(), b.record());
    let force = ra.surface_forces.iter().map(|f| f.norm()).fold(1e-12, f64::max);
    for (k, (fa, fb)) in ra.surface_forces.iter().zip(&rb.surface_forces).enumerate() {
        assert!((fa - fb).norm() <= 1e-9 * force, "{what}: load {k}'s force {fa} vs {fb}");
    }
    for (k, (wa, wb)) in ra.surface_work.iter().zip(&rb.surface_work).enumerate() {
        assert!((wa - wb).abs() <= 1e-9 * scale, "{what}: load {k}'s work {wa} vs {wb}");
    }
}

/// The checkpoint `saved` resumed on a solver from `make` on the CPU, and
/// on another with the device attached first.
fn resumed(g: &Gpu, saved: &[u8], make: impl Fn() -> Solver) -> (Solver, Solver) {
    let mut on_cpu = make();
    on_cpu.restore(saved).unwrap();
    let mut on_device = make();
    on_device.use_device(g, Residency::Auto).unwrap();
    on_device.restore(saved).unwrap();
    (on_cpu, on_device)
}

/// Both residencies against the CPU before any failure, then the same
/// failures once the bar breaks.
#[test]
fn the_device_steps_as_the_cpu_with_and_without_surface_loads() {
    let Some(g) = gpu() else { return };
    for (pressed, residency) in [(false, Residency::Auto), (true, Residency::Auto), (true, Residency::ForcesOnly)] {
        let mut cpu = bar(pressed);
        let mut dev = bar(pressed);
        dev.use_device(&g, residency).unwrap();
        let stages = dev.device_stages().unwrap();
        assert_eq!(stages.starts_with("stages 1 and 5"), residency == Residency::Auto, "{stages}");
        // While the traction acts (it stops at 12 µs, step 280), then after.
        for (steps, traction_on) in [(200, true), (200, false)] {
            assert_eq!(run(&mut cpu, steps), 0, "no failure yet");
            assert_eq!(run(&mut dev, steps), 0);
            dev.sync_device();
            let t = cpu.record().time;
            let what = format!("{residency:?}, {}, t = {t:.3e} s", if pressed { "pressed" } else { "bare" });
            assert_close(&cpu, &dev, &what);
            let r = cpu.record();
            assert!(!pressed || r.surface_work.iter().all(|&w| w != 0.0), "the loads work");
            assert!(!pressed || (r.surface_forces[1] != Vec3::zeros()) == traction_on, "the traction at {t:e} s");
        }
        // The kernels' timings leave the device's state as it was.
        dev.sync_device();
        let (joints, x) = (dev.state().joints.clone(), dev.state().x.clone());
        assert!(dev.device_timings(2).is_some_and(|t| t.len() >= 6), "timings of the round trips and kernels");
        dev.sync_device();
        assert!(dev.state().joints == joints && dev.state().x == x, "{residency:?}: the timings change nothing");
        let (fc, fd) = (run(&mut cpu, 1500), run(&mut dev, 1500));
        assert!(fc > 5, "the bar breaks ({fc})");
        let joints = |s: &Solver| s.failures().iter().map(|f| (f.joint, f.mode)).collect::<Vec<_>>();
        assert_eq!(joints(&cpu), joints(&dev), "the same joints fail the same way");
        assert_eq!(fc, fd);
    }
}

/// The pulled bar with contact (its outer surface and, as joints fail,
/// the tets around the cracks; friction 0.5), contact on the CPU beside
/// both residencies: the same course as the CPU before the first failure,
/// the same failures and the same candidate pairs after it (each failure
/// makes tets contactable, whose nodes the device then sends back every
/// step), and a checkpoint taken on the device resumed on the CPU and on
/// the device. The bar is pulled apart, so no pair comes into contact
/// here: contact forces with the bulk on the device are checked by the
/// decree test below, the closed cycles (`contact_cycle.rs`) and the
/// README run (`femdem-cli`'s `device.rs`).
#[test]
fn contact_on_the_host_beside_the_device_steps_as_the_cpu() {
    let Some(g) = gpu() else { return };
    let with_contact = || {
        let mut s = bar(true);
        s.enable_contact(ContactSettings { friction: 0.5, ..ContactSettings::new(26e9) }, &[]);
        s
    };
    for residency in [Residency::Auto, Residency::ForcesOnly] {
        let mut cpu = with_contact();
        let mut dev = with_contact();
        dev.use_device(&g, residency).unwrap();
        assert!(dev.device_stages().unwrap().contains("contact") || residency == Residency::ForcesOnly);
        let start = std::time::Instant::now();
        assert_eq!(run(&mut cpu, 400), 0, "no failure yet");
        let on_cpu = start.elapsed();
        let start = std::time::Instant::now();
        assert_eq!(run(&mut dev, 400), 0);
        let on_dev = start.elapsed();
        // Every step timed by stage; the pairs asked of the device only
        // where the step is resident.
        for (s, on_device, wall) in [(&cpu, false, on_cpu), (&dev, residency == Residency::Auto, on_dev)] {
            let times = s.stage_times().expect("steps are timed");
            // Each stretch of a step in one stage at most: nothing counted
            // twice.
            assert!(times.total() <= wall, "{:?} of stages in {wall:?} of steps", times.total());
            assert_eq!(times.steps, 400);
            let stages = times.per_step_ms();
            for stage in ["forces", "detection", "pair loop", "update"] {
                assert!(stages.iter().any(|&(name, _)| name == stage), "{stage} in {stages:?}");
            }
            assert!(times.geometry_device <= times.geometry, "the device's part is within its stage");
            assert_eq!(times.geometry_device.is_zero(), !on_device, "{residency:?}");
        }
        dev.sync_device();
        assert_close(&cpu, &dev, &format!("{residency:?} with contact"));
        // The kernels' timings leave the device's state as it was.
        dev.sync_device();
        let (joints, x) = (dev.state().joints.clone(), dev.state().x.clone());
        assert!(dev.device_timings(2).is_some_and(|t| t.len() >= 6), "timings of the round trips and kernels");
        dev.sync_device();
        assert!(dev.state().joints == joints && dev.state().x == x, "{residency:?}: the timings change nothing");
        let (fc, fd) = (run(&mut cpu, 1500), run(&mut dev, 1500));
        assert!(fc > 5, "the bar breaks ({fc})");
        let joints = |s: &Solver| s.failures().iter().map(|f| (f.joint, f.mode)).collect::<Vec<_>>();
        assert_eq!(joints(&cpu), joints(&dev), "{residency:?}: the same joints fail the same way");
        assert_eq!(fc, fd);
        let pairs = |s: &Solver| s.contact().unwrap().candidates().to_vec();
        let contactable = |s: &Solver| s.contact().unwrap().contactable().len();
        assert!(contactable(&cpu) > contactable(&with_contact()), "the cracks make tets contactable");
        assert!(!pairs(&cpu).is_empty(), "contact has candidates");
        assert_eq!(pairs(&cpu), pairs(&dev), "{residency:?}: the same candidate pairs");
    }
    // A checkpoint of a device run past its failures, resumed on both.
    let mut dev = with_contact();
    dev.use_device(&g, Residency::Auto).unwrap();
    run(&mut dev, 1200);
    dev.sync_device();
    let (mut on_cpu, mut again) = resumed(&g, &dev.snapshot(), with_contact);
    run(&mut dev, 50);
    run(&mut on_cpu, 50);
    run(&mut again, 50);
    dev.sync_device();
    again.sync_device();
    assert_close(&on_cpu, &dev, "resumed on the CPU");
    assert_close(&dev, &again, "resumed on the device");
}

/// A pressed column whose closed mid-plane joints are broken by decree
/// on the device (`contact_pressed.rs`): the mid-plane's tets become
/// contactable between steps (their nodes are watched from the next step
/// on), and contact takes the load across the cut as on the CPU. (The
/// column is settled, so nodes of those tets that are not in contact barely
/// move: the test would not see them left unwatched.)
#[test]
fn joints_broken_by_decree_hand_their_load_to_contact_on_the_device() {
    let Some(g) = gpu() else { return };
    let (mut cpu, mid) = crate::contact_pressed::pressed_column(|c| c);
    let (mut dev, _) = crate::contact_pressed::pressed_column(|c| c);
    dev.use_device(&g, Residency::Auto).unwrap();
    let before = dev.contact().unwrap().contactable().len();
    for s in [&mut cpu, &mut dev] {
        s.break_joints(&mid);
        // No output between: nothing brings the whole state back.
        for _ in 0..300 {
            s.step(Want::default());
        }
    }
    let after = dev.contact().unwrap().contactable().len();
    assert!(after > before, "the break makes the mid-plane's tets contactable ({before} -> {after})");
    dev.sync_device();
    assert_close(&cpu, &dev, "broken under pressure");
    let pairs = |s: &Solver| s.contact().unwrap().active_pairs;
    assert!(pairs(&cpu) > 0, "contact carries the load across the cut");
    assert_eq!(pairs(&cpu), pairs(&dev), "the same pairs in contact");
}

/// Damping, a kick and joints broken by decree between steps, then a
/// checkpoint of the device run resumed on the CPU: the same as the CPU
/// doing all of it.
#[test]
fn interventions_and_checkpoints_cross_between_host_and_device() {
    let Some(g) = gpu() else { return };
    let mut cpu = bar(false);
    let mut dev = bar(false);
    dev.use_device(&g, Residency::Auto).unwrap();
    for s in [&mut cpu, &mut dev] {
        run(s, 150);
        s.damp(0.9).unwrap();
        s.kick(7, Vec3::new(0.0, 0.01, 0.0)).unwrap();
        s.break_joints(&[3, 4, 5]);
        run(s, 100);
    }
    dev.sync_device();
    assert_close(&cpu, &dev, "after the interventions");
    assert_eq!(cpu.state().joints.iter().filter(|j| j.failed).count(), 3, "the decreed failures");
    assert_eq!(dev.state().joints.iter().filter(|j| j.failed).count(), 3);
    // A checkpoint of the device run, resumed on the CPU and on the device.
    let (mut back_on_cpu, mut again) = resumed(&g, &dev.snapshot(), || bar(false));
    run(&mut cpu, 50);
    run(&mut back_on_cpu, 50);
    run(&mut again, 50);
    again.sync_device();
    assert_close(&cpu, &back_on_cpu, "resumed on the CPU");
    assert_close(&cpu, &again, "resumed on the device");
}
