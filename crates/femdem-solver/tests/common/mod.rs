//! Builders shared by the solver's verification tests.
#![allow(dead_code)]

use femdem_core::Vec3;
use femdem_fracture::JointParams;
use femdem_material::{ElasticParams, Law, Material};
use femdem_mesh::generate::{BoxSpec, generate_box};
use femdem_mesh::{JointedMesh, Region, TetMesh, insert_joints};
use femdem_solver::{Loads, Model, RegionBehaviour, Solver, stable_time_step};

/// The paper's rock (Table 1): ρ = 2340 kg/m³, E = 26 GPa, ν = 0.2.
pub fn rock(viscosity: f64) -> Material {
    ElasticParams {
        young: 26e9,
        poisson: 0.2,
        density: 2340.0,
        viscosity,
    }
    .validate()
    .unwrap()
}

/// The paper's joint strengths with penalty `p0`.
pub fn joints(penalty: f64) -> JointParams {
    JointParams {
        penalty,
        tensile_strength: 3e6,
        cohesion: 15e6,
        friction_angle: 30f64.to_radians(),
    }
}

/// A jittered box mesh, breakable or not.
pub fn box_mesh(min: [f64; 3], max: [f64; 3], h: f64, jitter: f64, breakable: bool) -> TetMesh {
    generate_box(&BoxSpec {
        min,
        max,
        element_size: h,
        jitter,
        seed: 11,
        region: Region {
            name: "rock".into(),
            breakable,
        },
    })
    .unwrap()
}

/// The model of a one-region mesh with `law`, `material` and, if the region
/// is breakable, joints of penalty `p0`.
pub fn model(mesh: &TetMesh, law: Law, material: Material, p0: f64) -> (JointedMesh, Model) {
    let jointed = insert_joints(mesh).unwrap();
    let joints = mesh.regions[0].breakable.then(|| joints(p0));
    let model = Model::new(
        &jointed,
        &[RegionBehaviour::Deformable {
            law,
            material,
            joints,
        }],
        1.0,
    )
    .unwrap();
    (jointed, model)
}

/// A solver stepping at `safety` times the estimated critical step.
pub fn solver(model: Model, loads: Loads, safety: f64) -> Solver {
    let mut s = Solver::new(model, loads, 1.0).unwrap();
    let stable = stable_time_step(&s.model, &s.held_nodes(), 400);
    s.dt = safety * stable.critical;
    s
}

/// Sets every node's position to `x0 + u(x0)`.
pub fn displace(s: &mut Solver, u: impl Fn(&Vec3) -> Vec3) {
    for (x, x0) in s.state.x.iter_mut().zip(&s.model.x0) {
        *x = x0 + u(x0);
    }
}
