//! Closed contact cycles (issue 30, item 2): a frictionless, undamped
//! elastic cube lands on a plane and leaves it again. A force with a
//! potential gives back exactly what it absorbed, so after separation the
//! work the normal contact forces absorbed (`Solver::contact_normal_work`) is zero
//! up to the integrator's error; Eq. 17's potential force is not the
//! gradient of an energy (its two one-sided integrals differ), and what it
//! leaves is the cycle's *residual*, here as a share of the impact's
//! kinetic energy.
//!
//! The cases: face to face, edge to face, vertex to face, oblique with
//! spin, and sliding across the crack between two jointed blocks. Each
//! asserts its residual against the value measured on this build (the
//! solver is deterministic: the same input gives the same bits on every
//! machine with IEEE doubles and the same thread-count-independent sums),
//! raised by a quarter so that a change of the kernel that moves it by
//! round-off passes and one that changes it materially fails; the sweep
//! over penalty, speed, mesh and time step (`closed_cycle_sweep`, ignored:
//! `cargo test --release -p femdem-solver --test solver contact_cycle --
//! --ignored --nocapture`) is written up in `docs/fidelity.md` §10. Three
//! of the cycles run again with the bulk of the step on the test device
//! (lavapipe in CI) and contact on the CPU beside it, and must leave the
//! CPU's residual to round-off.

use femdem_core::Vec3;
use femdem_material::Law;
use femdem_mesh::generate::{BoxSpec, generate_box};
use femdem_mesh::{Region, TetMesh, insert_joints};
use femdem_solver::{
    ContactModel, ContactSettings, Loads, Model, Ramp, RegionBehaviour, Solver, StepParams, VelocityDrive, Want,
    contact_omega, held_nodes, stable_time_step,
};

use crate::common::{joints, nodes_in_box, rock};

/// Cube edge, m.
const SIZE: f64 = 0.04;

/// What the ground is.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Ground {
    /// A rigid plate.
    Plate,
    /// Two jointed (unbreakable in practice: strong joints) deformable
    /// blocks side by side, held at their base, the crack between them at
    /// `x = SIZE / 2` under the cube's landing.
    Cracked,
}

/// One impact.
#[derive(Clone, Copy, Debug)]
struct Impact {
    /// Rotation of the cube (axis × angle, rad) before it falls.
    tilt: [f64; 3],
    /// Velocity of its centre, m/s.
    velocity: [f64; 3],
    /// Spin about its centre, rad/s.
    spin: [f64; 3],
    ground: Ground,
    /// Element size, m.
    h: f64,
    /// Contact penalty over E.
    penalty: f64,
    /// Time step over the contact-aware critical step.
    safety: f64,
    /// The normal force.
    model: ContactModel,
    /// With the bulk of the step on the test device (contact on the CPU
    /// beside it).
    device: bool,
}

impl Impact {
    fn flat() -> Impact {
        Impact {
            tilt: [0.0; 3],
            velocity: [0.0, 0.0, -1.0],
            spin: [0.0; 3],
            ground: Ground::Plate,
            h: 0.01,
            penalty: 1.0,
            safety: 0.3,
            model: ContactModel::Potential,
            device: false,
        }
    }
}

/// The outcome of a cycle.
#[derive(Debug)]
struct Cycle {
    /// Kinetic energy the cube brought, J.
    brought: f64,
    /// The normal contact work after separation over `brought`.
    residual: f64,
    /// The bodies' energy after separation (kinetic, elastic in tets and
    /// joints, and what pairs still in contact hold) over `brought`, less
    /// one: what the cycle created (positive) or lost, the contact's
    /// residual and the leapfrog's own error together.
    mechanical: f64,
    /// Steps taken.
    steps: u64,
}

fn block(min: [f64; 3], max: [f64; 3], h: f64, name: &str, breakable: bool) -> TetMesh {
    generate_box(&BoxSpec {
        min,
        max,
        element_size: h,
        jitter: 0.0,
        seed: 1,
        region: Region { name: name.into(), breakable },
    })
    .unwrap()
}

/// Rotates `r` by the rotation vector `w` (Rodrigues).
fn rotate(w: Vec3, r: Vec3) -> Vec3 {
    let angle = w.norm();
    if angle == 0.0 {
        return r;
    }
    let k = w / angle;
    r * angle.cos() + k.cross(&r) * angle.sin() + k * (k.dot(&r) * (1.0 - angle.cos()))
}

/// The solver of `impact`, the cube thrown.
fn thrown(impact: &Impact) -> Solver {
    let h = impact.h;
    // Tilt about the centre, then lift the lowest node to a gap of h/1000
    // above the ground's top at z = 0.
    let (centre, tilt) = (Vec3::repeat(0.5 * SIZE), Vec3::from(impact.tilt));
    let mut cube_mesh = block([0.0, 0.0, 0.0], [SIZE; 3], h, "cube", false);
    for p in cube_mesh.coords.iter_mut() {
        *p = (centre + rotate(tilt, Vec3::from(*p) - centre)).into();
    }
    let low = cube_mesh.coords.iter().map(|p| p[2]).fold(f64::INFINITY, f64::min);
    for p in cube_mesh.coords.iter_mut() {
        p[2] += 1e-3 * h - low;
    }
    let mut mesh = cube_mesh;
    let behaviour = match impact.ground {
        Ground::Plate => {
            mesh.append(&block([-SIZE, -SIZE, -h], [2.0 * SIZE, 2.0 * SIZE, 0.0], h, "ground", false));
            vec![RegionBehaviour::Rigid]
        }
        Ground::Cracked => {
            let half = 0.5 * SIZE;
            mesh.append(&block([-SIZE, -half, -2.0 * h], [half, 1.5 * SIZE, 0.0], h, "ground", true));
            let gap = 1e-3 * h;
            mesh.append(&block([half + gap, -half, -2.0 * h], [2.0 * SIZE, 1.5 * SIZE, 0.0], h, "ground", true));
            let mut strong = joints(10.0 * 26e9);
            (strong.tensile_strength, strong.cohesion) = (1e12, 1e12);
            vec![RegionBehaviour::Deformable { law: Law::NeoHookean, material: rock(0.0), joints: Some(strong) }]
        }
    };
    let jointed = insert_joints(&mesh).unwrap();
    let mut regions = vec![RegionBehaviour::Deformable { law: Law::NeoHookean, material: rock(0.0), joints: None }];
    regions.extend(behaviour);
    let model = Model::new(&jointed, &regions, 1.0).unwrap();
    let below = nodes_in_box(&model, [-1.0, -1.0, -1.0], [1.0, 1.0, -2.0 * h + 1e-9]);
    let held = match impact.ground {
        Ground::Plate => nodes_in_box(&model, [-1.0, -1.0, -1.0], [1.0, 1.0, 0.0]),
        Ground::Cracked => below,
    };
    let loads = Loads {
        drives: vec![VelocityDrive {
            name: "ground".into(),
            nodes: held,
            velocity: Vec3::zeros(),
            components: [true; 3],
            ramp: Ramp::STEP,
            start_time: None,
        }],
        ..Loads::default()
    };
    let penalty = impact.penalty * 26e9;
    let omega = stable_time_step(&model, &held_nodes(&model, &loads).unwrap(), 300).omega_max;
    let omega_c = contact_omega(&model, penalty);
    let dt = impact.safety * 2.0 / (omega * omega + omega_c * omega_c).sqrt();
    let mut s = Solver::new(model, loads, StepParams::new(dt).unwrap()).unwrap();
    s.enable_contact(ContactSettings { model: impact.model, ..ContactSettings::new(penalty) }, &[]);
    if impact.device {
        let gpu = femdem_solver::Gpu::for_tests().expect("a test device");
        s.use_device(&gpu, femdem_solver::Residency::Auto).unwrap();
    }
    let (v, w) = (Vec3::from(impact.velocity), Vec3::from(impact.spin));
    // The cube's nodes are those above the ground; c its centre.
    let cube_nodes: Vec<Vec3> = s.model().x0.iter().copied().filter(|p| p.z > 0.0).collect();
    let c = cube_nodes.iter().sum::<Vec3>() / cube_nodes.len() as f64;
    s.set_velocity(|x| if x.z > 0.0 { v + w.cross(&(x - c)) } else { Vec3::zeros() });
    s
}

/// Runs `impact` until no contact force has acted on the cube for 200
/// steps after it touched the ground.
fn bounce(impact: &Impact) -> Cycle {
    let mut s = thrown(impact);
    s.step(Want { energy: true, ..Want::default() });
    let brought = s.energies().kinetic;
    let on_cube: Vec<bool> = s.model().x0.iter().map(|p| p.z > 0.0).collect();
    let (mut touched, mut apart, mut steps) = (false, 0, 0u64);
    while apart < 200 {
        s.step(Want::default());
        steps += 1;
        let landed = s.contact().unwrap().touched().iter().any(|&n| on_cube[n as usize]);
        touched |= landed;
        apart = if touched && !landed { apart + 1 } else { 0 };
    }
    let contact = s.contact().unwrap();
    assert_eq!(contact.spring_energy, 0.0, "frictionless");
    // What pairs still in contact hold (the two ground blocks of the crack
    // case may touch each other after the impact) is not a residual; only
    // the energy-conserving model knows it (0 with Eq. 17).
    let residual = (s.contact_normal_work().unwrap() - contact.potential) / brought;
    // One more step, with the energies: the bodies' own.
    s.step(Want { energy: true, ..Want::default() });
    let e = s.energies();
    assert_eq!((e.external_work, e.damping), (0.0, 0.0), "a free, undamped cycle");
    let held = s.contact().unwrap().potential;
    let mechanical = (e.kinetic + e.tet_elastic + e.joint_elastic + held) / brought - 1.0;
    Cycle { brought, residual, mechanical, steps }
}

/// The tilt that puts an edge (about x) or a vertex (about x, then y) down.
const EDGE: [f64; 3] = [0.3, 0.0, 0.0];
const VERTEX: [f64; 3] = [0.3, 0.25, 0.0];

fn check(name: &str, impact: Impact, measured: f64) {
    let cycle = bounce(&impact);
    eprintln!(
        "{name}: residual {:+.4e}, bodies' energy {:+.4e} of {:.4e} J in {} steps",
        cycle.residual, cycle.mechanical, cycle.brought, cycle.steps
    );
    assert!(cycle.brought > 0.0);
    assert!(
        cycle.residual.abs() <= 1.25 * measured,
        "{name}: the closed cycle left {:+.4e} of the impact energy in contact, more than the {measured:.2e} measured",
        cycle.residual
    );
}

#[test]
fn a_face_landing_gives_back_about_one_percent_more_than_it_took() {
    check("face", Impact::flat(), 1.058e-2);
}

#[test]
fn an_edge_landing_closes_its_cycle() {
    check("edge", Impact { tilt: EDGE, ..Impact::flat() }, 1.081e-3);
}

#[test]
fn a_vertex_landing_closes_its_cycle() {
    check("vertex", Impact { tilt: VERTEX, ..Impact::flat() }, 3.588e-3);
}

#[test]
fn an_oblique_spinning_landing_closes_its_cycle() {
    let impact = Impact { tilt: EDGE, velocity: [0.6, 0.3, -1.0], spin: [20.0, -30.0, 40.0], ..Impact::flat() };
    check("oblique, spinning", impact, 5.831e-4);
}

#[test]
fn sliding_across_a_crack_of_a_jointed_body_closes_its_cycle() {
    let impact = Impact { velocity: [0.8, 0.0, -1.0], ground: Ground::Cracked, ..Impact::flat() };
    check("across a crack", impact, 1.789e-4);
}

/// Three of the closed cycles (a face on the rigid plate, an oblique
/// spinning edge, sliding across the crack of a jointed deformable body),
/// and the face with the energy-conserving model and its kicks, with the
/// bulk of the step on the test device and contact on the CPU beside it
/// (issue 35): the same steps to separation, and the same residual as on
/// the CPU within 10⁻¹² of the impact energy (the bodies' energy within
/// 10⁻⁸, below): the device's bulk
/// agrees with the CPU's to round-off (10⁻¹⁶ relative per term), carried
/// through 400–750 steps into the contact work; measured on lavapipe
/// 1.5·10⁻¹⁵ (face), 2.4·10⁻¹⁶ (oblique) and 2.6·10⁻¹⁴ (crack), so the
/// bound leaves a factor of 40 over the largest.
#[test]
fn the_closed_cycles_on_the_device_leave_what_the_cpu_leaves() {
    if femdem_solver::Gpu::for_tests().is_none() {
        return;
    }
    let oblique = Impact { tilt: EDGE, velocity: [0.6, 0.3, -1.0], spin: [20.0, -30.0, 40.0], ..Impact::flat() };
    let crack = Impact { velocity: [0.8, 0.0, -1.0], ground: Ground::Cracked, ..Impact::flat() };
    let conserving = Impact { model: ContactModel::Gradient, ..Impact::flat() };
    for (name, impact) in [
        ("face", Impact::flat()),
        ("oblique, spinning", oblique),
        ("across a crack", crack),
        ("face, gradient", conserving),
    ] {
        let (cpu, dev) = (bounce(&impact), bounce(&Impact { device: true, ..impact }));
        assert!(cpu.brought > 0.0 && cpu.residual != 0.0, "{name}: an impact that leaves a residual");
        // The bodies' elastic energy is a difference of terms of size
        // (λ + 2μ) V per tet, which the device forms with its own `ln`
        // (ulps off libm's): measured 1.9e-10 apart on lavapipe (face); the
        // bound leaves 50 times that, and is still far below what the
        // gradient model's kicks change (4e-5 without them).
        let apart = (cpu.mechanical - dev.mechanical).abs();
        assert!(
            apart <= 1e-8,
            "{name}: the bodies' energy {} on the CPU, {} on the device",
            cpu.mechanical,
            dev.mechanical
        );
        let gap = (cpu.residual - dev.residual).abs();
        eprintln!(
            "{name}: residual {:+.6e} on the CPU, {:+.6e} on the device ({gap:.1e} apart); bodies' energy {apart:.1e} apart",
            cpu.residual, dev.residual
        );
        assert_eq!(cpu.steps, dev.steps, "{name}: steps to separation");
        assert!(gap <= 1e-12, "{name}: residual {} on the CPU, {} on the device", cpu.residual, dev.residual);
    }
}

/// The energy-conserving model (`ContactModel::Gradient`, forces the exact
/// gradient of `W = p ∫_{A∩B} (φ_A + φ_B) dV`, kicks made
/// energy-consistent by `contact/onset.rs`): the same five impacts at
/// safety 0.3.
///
/// * Its own account closes to round-off: the normal work less what pairs
///   still hold is within `10⁻¹²` of the impact energy (measured
///   `10⁻¹⁶ – 3·10⁻¹⁴`): every pair's debt is paid to `10⁻¹³` of the largest
///   energy term it held before it is dropped, and the account sums some
///   10³ steps of terms each rounded at `10⁻¹⁶`. Without the kicks the flat
///   landings left `4·10⁻⁵` (face) and `2.6·10⁻⁴` (crack) here, the
///   leapfrog's error at the contact's onset.
/// * The bodies' energy after the cycle (kinetic, elastic in tets and
///   joints, and what the crack case's ground pairs still hold) against
///   what the cube brought: the bulk leapfrog's own error, bounded by the
///   values measured on this build raised by a quarter, as the Eq. 17
///   cases; every one is far below issue 32's goal of `10⁻⁴`.
fn check_conserving(name: &str, impact: Impact, mechanical: f64) {
    let cycle = bounce(&Impact { model: ContactModel::Gradient, ..impact });
    eprintln!(
        "{name}, gradient: residual {:+.4e}, bodies' energy {:+.4e} of {:.4e} J in {} steps",
        cycle.residual, cycle.mechanical, cycle.brought, cycle.steps
    );
    assert!(cycle.brought > 0.0);
    assert!(cycle.residual.abs() <= 1e-12, "{name}: contact's account left {:+.4e} of the impact", cycle.residual);
    assert!(
        cycle.mechanical.abs() <= 1.25 * mechanical,
        "{name}: the bodies left with {:+.4e} of the impact energy more, beyond the {mechanical:.2e} measured",
        cycle.mechanical
    );
}

#[test]
fn gradient_model_face_landing() {
    check_conserving("face", Impact::flat(), 2.589e-8);
}

#[test]
fn gradient_model_edge_landing() {
    check_conserving("edge", Impact { tilt: EDGE, ..Impact::flat() }, 1.462e-8);
}

#[test]
fn gradient_model_vertex_landing() {
    check_conserving("vertex", Impact { tilt: VERTEX, ..Impact::flat() }, 3.831e-9);
}

#[test]
fn gradient_model_oblique_spinning_landing() {
    let impact = Impact { tilt: EDGE, velocity: [0.6, 0.3, -1.0], spin: [20.0, -30.0, 40.0], ..Impact::flat() };
    check_conserving("oblique, spinning", impact, 4.467e-9);
}

#[test]
fn gradient_model_sliding_across_a_crack() {
    let impact = Impact { velocity: [0.8, 0.0, -1.0], ground: Ground::Cracked, ..Impact::flat() };
    check_conserving("across a crack", impact, 1.116e-6);
}

/// What the gradient model's face landing leaves in the bodies is the
/// leapfrog's: cutting the step by 6 (safety 0.3 → 0.05) cuts it by more
/// than 10 (measured: −2.6e-8 → −1.1e-9). With Eq. 17 the same cut leaves
/// the face landing's 1% as it is (§10).
#[test]
fn the_gradient_models_cycle_error_falls_with_the_time_step() {
    let impact = Impact { model: ContactModel::Gradient, ..Impact::flat() };
    let coarse = bounce(&impact).mechanical;
    let fine = bounce(&Impact { safety: 0.05, ..impact }).mechanical;
    eprintln!("bodies' energy {coarse:+.3e} at safety 0.3, {fine:+.3e} at 0.05");
    assert!(fine.abs() < coarse.abs() / 10.0, "{fine} vs {coarse}");
}

/// The gradient model's kicks are part of a checkpoint: the face landing
/// snapshot a few steps after the cube touched (pairs in contact with
/// their debts, and pairs that have separated still paying theirs: both
/// asserted), restored into a second solver built the same way, continues
/// bit for bit with the first through the rest of the cycle, and ends with
/// the same snapshot.
#[test]
fn a_restored_landing_continues_bit_for_bit_with_its_kicks() {
    let impact = Impact { model: ContactModel::Gradient, ..Impact::flat() };
    let mut a = thrown(&impact);
    let mut steps = 0;
    while a.contact().unwrap().active_pairs == 0 {
        a.step(Want::default());
        steps += 1;
        assert!(steps < 1000, "the cube never landed");
    }
    for _ in 0..3 {
        a.step(Want::default());
    }
    let (held, touching) = (a.contact().unwrap().kicked_pairs(), a.contact().unwrap().active_pairs);
    assert!(held > touching && touching > 0, "{held} pairs kicked, {touching} in contact at the snapshot");
    let snap = a.snapshot();
    let mut b = thrown(&impact);
    b.restore(&snap).unwrap();
    for _ in 0..400 {
        a.step(Want::default());
        b.step(Want::default());
    }
    assert_eq!(a.state(), b.state(), "positions, velocities");
    assert_eq!(a.record(), b.record());
    assert!(a.snapshot() == b.snapshot(), "the whole state, the kicks' debts included, differs");
}

/// The five impacts with `model`.
fn five(model: ContactModel) -> [(&'static str, Impact); 5] {
    let base = Impact { model, ..Impact::flat() };
    [
        ("face", base),
        ("edge", Impact { tilt: EDGE, ..base }),
        ("vertex", Impact { tilt: VERTEX, ..base }),
        ("oblique", Impact { tilt: EDGE, velocity: [0.6, 0.3, -1.0], spin: [20.0, -30.0, 40.0], ..base }),
        ("crack", Impact { velocity: [0.8, 0.0, -1.0], ground: Ground::Cracked, ..base }),
    ]
}

/// Prints the residual of each case at each of `safeties`, then at safety
/// 0.3 with penalty E/10 and 10 E, speed × 0.3 and × 3, and 5 mm tets.
fn sweep(model: ContactModel, safeties: &[f64]) {
    println!("| case | penalty/E | V (m/s) | h (mm) | safety | residual | bodies' energy | steps |");
    println!("|---|---:|---:|---:|---:|---:|---:|---:|");
    for (name, base) in five(model) {
        let mut variants: Vec<Impact> = safeties.iter().map(|&safety| Impact { safety, ..base }).collect();
        variants.extend([0.1, 10.0].map(|penalty| Impact { penalty, ..base }));
        variants.extend([0.3, 3.0].map(|k| Impact { velocity: base.velocity.map(|c| c * k), ..base }));
        variants.push(Impact { h: 0.005, ..base });
        for i in variants {
            let c = bounce(&i);
            println!(
                "| {name} | {} | {:.2} | {} | {} | {:+.3e} | {:+.3e} | {} |",
                i.penalty,
                Vec3::from(i.velocity).norm(),
                i.h * 1e3,
                i.safety,
                c.residual,
                c.mechanical,
                c.steps
            );
        }
    }
}

/// The sweep of `docs/fidelity.md` §10: residual of each case over penalty,
/// speed, mesh and time step, with Eq. 17.
#[test]
#[ignore = "a measurement (minutes): run with --ignored --nocapture"]
fn closed_cycle_sweep() {
    sweep(ContactModel::Potential, &[0.3, 0.9, 0.1]);
}

/// The sweep of `docs/fidelity.md` §12 with the energy-conserving model
/// (`ContactModel::Gradient`), over more time steps.
#[test]
#[ignore = "a measurement (minutes): run with --ignored --nocapture"]
fn closed_cycle_sweep_gradient() {
    sweep(ContactModel::Gradient, &[0.9, 0.5, 0.3, 0.2, 0.1, 0.05]);
}
