//! Builders shared by the static-start tests.
#![allow(dead_code)]

use femdem_core::{Real, Vec3};
use femdem_fracture::{Coupling, GfCalibration, JointParams};
use femdem_material::{ElasticParams, Law, Material};
use femdem_mesh::generate::{BoxSpec, generate_box};
use femdem_mesh::{JointedMesh, Region, insert_joints};
use femdem_solver::select::{NodeSelection, group_faces, select_nodes};
use femdem_solver::{
    Fixed, Loads, Model, Ramp, RegionBehaviour, Solver, StepParams, SurfaceKind, SurfaceLoad, held_nodes,
    stable_time_step,
};

/// Limestone of the polyaxial case (Table 2): E = 30 GPa, ν = 0.27,
/// ρ = 2700 kg/m³, with viscosity `eta`.
pub fn limestone(eta: Real) -> Material {
    ElasticParams { young: 30e9, poisson: 0.27, density: 2700.0, viscosity: eta }.validate().unwrap()
}

/// The polyaxial case's joints (Table 2, Test 1), penalty 10 E (Eq. 9).
pub fn joints() -> JointParams {
    JointParams {
        penalty: 3e11,
        tensile_strength: 1e6,
        cohesion: 0.5e6,
        friction_angle: 33.4f64.to_radians(),
        gf_tension: 60.0,
        gf_shear: 60.0,
        calibration: GfCalibration::Paper,
        coupling: Coupling::default(),
    }
    .validate()
    .unwrap()
}

/// A jointed (breakable) box of cell size `h`, jitter 0.1.
pub fn jointed_box(max: [Real; 3], h: Real) -> JointedMesh {
    let region = Region { name: "rock".into(), breakable: true };
    let spec = BoxSpec { min: [0.0; 3], max, element_size: h, jitter: 0.1, seed: 7, region };
    insert_joints(&generate_box(&spec).unwrap()).unwrap()
}

/// The model of a jointed box with the neo-Hookean law (Eq. 1).
pub fn model(mesh: &JointedMesh, material: Material) -> Model {
    let behaviour = [RegionBehaviour::Deformable { law: Law::NeoHookean, material, joints: Some(joints()) }];
    Model::new(mesh, &behaviour, 1.0).unwrap()
}

/// A surface load on boundary group `group`.
pub fn surface(mesh: &JointedMesh, group: &str, kind: SurfaceKind, ramp: Ramp) -> SurfaceLoad {
    SurfaceLoad { name: group.into(), faces: group_faces(mesh, group).unwrap(), kind, ramp }
}

/// Pressures `p[axis]` on both faces normal to each axis.
pub fn pressures(mesh: &JointedMesh, p: [Real; 3], ramp: Ramp) -> Vec<SurfaceLoad> {
    let sides = [["xmin", "xmax"], ["ymin", "ymax"], ["zmin", "zmax"]];
    sides.iter().zip(p).flat_map(|(pair, p)| pair.map(|g| surface(mesh, g, SurfaceKind::Pressure(p), ramp))).collect()
}

/// All three components fixed on boundary group `group`.
pub fn fixed(mesh: &JointedMesh, group: &str) -> Fixed {
    let selection = NodeSelection { group: Some(group.into()), ..Default::default() };
    Fixed { nodes: select_nodes(mesh, &selection).unwrap(), components: [true; 3] }
}

/// A solver at `safety` times the estimated critical step.
pub fn solver(model: Model, loads: Loads, safety: Real) -> Solver {
    let held = held_nodes(&model, &loads).unwrap();
    let dt = safety * stable_time_step(&model, &held, 400).critical;
    Solver::new(model, loads, StepParams::new(dt).unwrap()).unwrap()
}

/// Displacement of every node, `x − x0`.
pub fn displacement(s: &Solver) -> Vec<Vec3> {
    s.state().x.iter().zip(&s.model().x0).map(|(x, x0)| x - x0).collect()
}

/// `√(Σ |a − b|²) / √(Σ |b|²)`.
pub fn relative_difference(a: &[Vec3], b: &[Vec3]) -> Real {
    let num: Real = a.iter().zip(b).map(|(p, q)| (p - q).norm_squared()).sum();
    let den: Real = b.iter().map(|q| q.norm_squared()).sum();
    (num / den).sqrt()
}

/// `η` for a damping ratio `zeta` at element size `h`: `ζ · 2 h √(E ρ)`
/// (as `[materials] damping_ratio` of a case).
pub fn viscosity(zeta: Real, h: Real) -> Real {
    let m = limestone(0.0);
    zeta * femdem_material::critical_viscosity(h, m.young(), m.density())
}
