//! Inputs shared by the femdem benchmarks. See `benches/README.md` for what
//! each bench measures; run them with `cargo xtask bench`.

use femdem_mesh::Region;
use femdem_mesh::generate::{BoxSpec, ExtrusionSpec, Outline};

/// A unit box whose Freudenthal lattice has about `tets` tets (6 per cell),
/// jittered by 0.1 of the cell size, breakable.
pub fn box_with_tets(tets: usize) -> BoxSpec {
    let cells_per_axis = ((tets as f64 / 6.0).cbrt()).round().max(1.0);
    BoxSpec {
        min: [0.0; 3],
        max: [1.0; 3],
        element_size: 1.0 / cells_per_axis,
        jitter: 0.1,
        seed: 1,
        region: Region { name: "rock".into(), breakable: true },
    }
}

/// The Brazilian disc of the reference paper (40 mm × 15 mm, 10 layers).
pub fn disc_extrusion(element_size: f64) -> ExtrusionSpec {
    ExtrusionSpec {
        outline: Outline::Circle { center: [0.0, 0.0], radius: 0.02 },
        traces: vec![],
        z0: 0.0,
        thickness: 0.015,
        element_size,
        layers: Some(10),
        region: Region { name: "disc".into(), breakable: true },
    }
}

/// A solver for the paper's Brazilian disc (Table 1 rock, joints with
/// p0 = 10 E, 5% damping, no loads), or the same disc without joints when
/// `breakable` is false; `dt` at 0.9 of the critical step.
pub fn disc_solver(element_size: f64, breakable: bool) -> femdem_solver::Solver {
    use femdem_fracture::JointParams;
    use femdem_material::{ElasticParams, Law};
    use femdem_solver::{Loads, Model, RegionBehaviour, Solver, StepParams, held_nodes, stable_time_step};
    let mut spec = disc_extrusion(element_size);
    spec.region.breakable = breakable;
    let mesh = femdem_mesh::generate::generate_extrusion(&spec).expect("disc");
    let jointed = femdem_mesh::insert_joints(&mesh).expect("joints");
    let viscosity = femdem_material::critical_viscosity(element_size, 26e9, 2340.0) * 0.05;
    let material = ElasticParams { young: 26e9, poisson: 0.2, density: 2340.0, viscosity }.validate().expect("rock");
    let joints = breakable.then_some(JointParams {
        penalty: 2.6e11,
        tensile_strength: 3e6,
        cohesion: 15e6,
        friction_angle: 30f64.to_radians(),
        gf_tension: 50.0,
        gf_shear: 50.0,
        calibration: femdem_fracture::GfCalibration::Paper,
        coupling: femdem_fracture::Coupling::default(),
    });
    let model = Model::new(&jointed, &[RegionBehaviour::Deformable { law: Law::NeoHookean, material, joints }], 1.0)
        .expect("model");
    let held = held_nodes(&model, &Loads::default()).expect("constraints");
    let dt = 0.9 * stable_time_step(&model, &held, 300).critical;
    let mut s = Solver::new(model, Loads::default(), StepParams::new(dt).expect("step")).expect("solver");
    s.set_velocity(|x| femdem_core::Vec3::new(x.y, -x.x, 0.0) * 10.0);
    s
}
