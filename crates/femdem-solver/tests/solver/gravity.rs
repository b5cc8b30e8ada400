//! Self-weight under mass scaling (fidelity: gravity acts on the physical
//! mass).
//!
//! A 20 mm rock cube rests on a support: its bottom face is a velocity drive
//! held at zero, whose reaction is recorded. In static equilibrium the
//! support carries the cube's weight, `W = ρ V g`, whatever the mass-scaling
//! factor `s`: scaling multiplies the inertia (so the dynamics slow by
//! `√s` and the stable step grows by `√s`) but must not multiply the load.
//! Before the fix gravity acted on the scaled mass and the support carried
//! `s W`.
//!
//! The cube starts unloaded, so it oscillates about the equilibrium while
//! the viscosity damps it. The viscosity is Munjiza's critical value for the
//! scaled density (`2 h √(E ρ s)`), so every scaling sees the same damping
//! ratio, and each run covers the same number of periods (same step count,
//! step `∝ √s`). The reaction averaged over the last fifth of the run is
//! then the weight to within the residual oscillation, which the damping
//! has brought below 1% (measured: see the printed figures); the old
//! behaviour is off by a factor 100 at `s = 100`.

use femdem_core::Vec3;
use femdem_material::{Law, critical_viscosity};
use femdem_mesh::insert_joints;
use femdem_solver::select::{NodeSelection, select_nodes};
use femdem_solver::{Loads, Model, Ramp, RegionBehaviour, VelocityDrive, Want};

use crate::common::{at_step, box_mesh, rock, stable};

/// The mean support reaction over the last fifth of 4000 steps, and the
/// physical weight, for mass scaling `s`.
fn support_reaction(s: f64) -> (f64, f64) {
    let h = 0.005;
    let mesh = box_mesh([0.0; 3], [0.02, 0.02, 0.02], h, 0.0, false);
    let jointed = insert_joints(&mesh).unwrap();
    let visc = critical_viscosity(h, 26e9, 2340.0 * s);
    let behaviour = [RegionBehaviour::Deformable { law: Law::NeoHookean, material: rock(visc), joints: None }];
    let model = Model::new(&jointed, &behaviour, s).unwrap();
    let base = select_nodes(&jointed, &NodeSelection { group: Some("zmin".into()), ..Default::default() }).unwrap();
    let g = 9.81 * 1000.0; // strong, so that the load is far above round-off
    let loads = Loads {
        gravity: Vec3::new(0.0, 0.0, -g),
        drives: vec![VelocityDrive {
            name: "support".into(),
            nodes: base,
            velocity: Vec3::zeros(),
            components: [true; 3],
            ramp: Ramp::STEP,
            start_time: None,
        }],
        ..Loads::default()
    };
    let weight = 2340.0 * 0.02f64.powi(3) * g;
    let dt = 0.9 * stable(&model, &loads, 300).critical;
    let mut solver = at_step(model, loads, dt);
    let (steps, window) = (4000, 800);
    let mut sum = 0.0;
    for n in 0..steps {
        let r = solver.step(Want::default()).drive_forces[0].z;
        if n >= steps - window {
            sum += r;
        }
    }
    (sum / window as f64, weight)
}

#[test]
fn self_weight_does_not_grow_with_mass_scaling() {
    for s in [1.0, 100.0] {
        let (reaction, weight) = support_reaction(s);
        eprintln!("mass scaling {s}: support reaction {reaction:.5e} N, weight {weight:.5e} N");
        assert!((reaction / weight - 1.0).abs() < 0.01, "s = {s}: reaction {reaction} N vs weight {weight} N");
    }
}
