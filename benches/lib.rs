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

/// The joint law of the paper's Brazilian disc (Table 1, p0 = 10 E).
pub fn brazilian_joints() -> femdem_fracture::JointParams {
    femdem_fracture::JointParams {
        penalty: 2.6e11,
        tensile_strength: 3e6,
        cohesion: 15e6,
        friction_angle: 30f64.to_radians(),
        gf_tension: 50.0,
        gf_shear: 50.0,
        calibration: femdem_fracture::GfCalibration::Paper,
        coupling: femdem_fracture::Coupling::default(),
    }
}

/// A solver for the paper's Brazilian disc (Table 1 rock, joints with
/// p0 = 10 E, 5% damping, no loads), or the same disc without joints when
/// `breakable` is false; `dt` at 0.9 of the critical step.
pub fn disc_solver(element_size: f64, breakable: bool) -> femdem_solver::Solver {
    use femdem_solver::{Loads, held_nodes, stable_time_step};
    let mut spec = disc_extrusion(element_size);
    spec.region.breakable = breakable;
    let mesh = femdem_mesh::generate::generate_extrusion(&spec).expect("disc");
    let model = rock_model(&mesh, element_size, breakable);
    let held = held_nodes(&model, &Loads::default()).expect("constraints");
    let dt = 0.9 * stable_time_step(&model, &held, 300).critical;
    spinning(model, dt)
}

/// A solver for a jointed unit box of about `tets` tets ([`box_with_tets`])
/// of the disc's rock and joints, for the cost per element against the
/// mesh size. The step is 0.7 of the critical step of a small box of the
/// same lattice (Lanczos, 300 iterations) scaled by the cell size: the
/// jittered lattice is the same at every size, and a Lanczos estimate on
/// a million tets would cost a few hundred steps; a step's cost does not
/// depend on it, but a step past the critical one would break every joint
/// within a few steps and measure the failure path instead.
pub fn box_solver(tets: usize) -> femdem_solver::Solver {
    use femdem_solver::{Loads, held_nodes, stable_time_step};
    let small = box_with_tets(1_000);
    let small_model = rock_model(&femdem_mesh::generate::generate_box(&small).expect("box"), small.element_size, true);
    let held = held_nodes(&small_model, &Loads::default()).expect("constraints");
    let per_metre = stable_time_step(&small_model, &held, 300).critical / small.element_size;
    let spec = box_with_tets(tets);
    let mesh = femdem_mesh::generate::generate_box(&spec).expect("box");
    let model = rock_model(&mesh, spec.element_size, true);
    spinning(model, 0.7 * per_metre * spec.element_size)
}

/// The model of `mesh` with joints inserted (when `breakable`) and the
/// Brazilian disc's rock (Table 1, 5% damping at element size `h`) and
/// joint law ([`brazilian_joints`]).
fn rock_model(mesh: &femdem_mesh::TetMesh, h: f64, breakable: bool) -> femdem_solver::Model {
    use femdem_material::{ElasticParams, Law};
    use femdem_solver::{Model, RegionBehaviour};
    let jointed = femdem_mesh::insert_joints(mesh).expect("joints");
    let viscosity = femdem_material::critical_viscosity(h, 26e9, 2340.0) * 0.05;
    let material = ElasticParams { young: 26e9, poisson: 0.2, density: 2340.0, viscosity }.validate().expect("rock");
    let joints = breakable.then(brazilian_joints);
    Model::new(&jointed, &[RegionBehaviour::Deformable { law: Law::NeoHookean, material, joints }], 1.0).expect("model")
}

/// A solver of `model` without loads, stepping by `dt`, started spinning
/// about z at 10 rad/s so that every kernel has work to do.
fn spinning(model: femdem_solver::Model, dt: f64) -> femdem_solver::Solver {
    use femdem_solver::{Loads, Solver, StepParams};
    let mut s = Solver::new(model, Loads::default(), StepParams::new(dt).expect("step")).expect("solver");
    s.set_velocity(|x| femdem_core::Vec3::new(x.y, -x.x, 0.0) * 10.0);
    s
}

/// The quick polyaxial cube of the contact profile: `cases/paper/polyaxial.toml`
/// (Test 1: limestone, c = 0.5 MPa, φ = 33.4°, G_f = 60 J/m², pressures of
/// 3.75, 15 and 9.375 MPa on the x, y and z faces ramped over 2 ms, contact
/// with penalty E, μ = 0.6 and a 5 mm buffer) on the 50 mm Gmsh cube
/// (`cases/paper/meshes/cube-50mm.msh`, 4,993 tets), built with the library
/// crates as `femdem run` builds it (mean-edge damping ratio 0.05, joint
/// penalty 10 E, 400 Lanczos iterations, 0.9 of the critical step with the
/// contact bound): 3,638 steps to 2.5 ms, joints failing from about step
/// 2,900 on.
pub fn polyaxial_cube() -> femdem_solver::Solver {
    use femdem_fracture::{Coupling, GfCalibration, JointParams};
    use femdem_material::{ElasticParams, Law};
    use femdem_solver::{
        ContactSettings, Loads, Model, Ramp, RegionBehaviour, Solver, StepParams, SurfaceKind, SurfaceLoad,
        contact_omega, held_nodes, stable_time_step,
    };
    // Where it was built, else from the working directory (a binary
    // carried to another machine runs in a copy of the repository).
    let built = concat!(env!("CARGO_MANIFEST_DIR"), "/../cases/paper/meshes/cube-50mm.msh");
    let bytes = std::fs::read(built)
        .or_else(|_| std::fs::read("cases/paper/meshes/cube-50mm.msh"))
        .expect("cases/paper/meshes/cube-50mm.msh, where the benches were built or in the working directory");
    let mut mesh = femdem_mesh::msh::read_msh(&bytes).expect("cube mesh");
    for r in &mut mesh.regions {
        r.breakable = true;
    }
    let jointed = femdem_mesh::insert_joints(&mesh).expect("joints");
    let m = &jointed.mesh;
    let (young, density) = (30.0e9, 2700.0);
    let mean_edge =
        (0..m.num_tets()).map(|t| femdem_core::tet::edge_lengths(&m.tet_points(t)).iter().sum::<f64>()).sum::<f64>()
            / (6 * m.num_tets()) as f64;
    let viscosity = 0.05 * femdem_material::critical_viscosity(mean_edge, young, density);
    let material = ElasticParams { young, poisson: 0.27, density, viscosity }.validate().expect("limestone");
    let joints = JointParams {
        penalty: 10.0 * young,
        tensile_strength: 1.0e6,
        cohesion: 0.5e6,
        friction_angle: 33.4f64.to_radians(),
        gf_tension: 60.0,
        gf_shear: 60.0,
        calibration: GfCalibration::Paper,
        coupling: Coupling::Printed,
    }
    .validate()
    .expect("joints");
    let model = Model::new(
        &jointed,
        &[RegionBehaviour::Deformable { law: Law::NeoHookean, material, joints: Some(joints) }],
        1.0,
    )
    .expect("model");
    let mut loads = Loads::default();
    for (face, pressure) in
        [("xmin", 3.75e6), ("xmax", 3.75e6), ("ymin", 15e6), ("ymax", 15e6), ("zmin", 9.375e6), ("zmax", 9.375e6)]
    {
        let group = m.boundary.iter().find(|g| g.name.ends_with(face)).expect("face group").name.clone();
        loads.surfaces.push(SurfaceLoad {
            faces: femdem_solver::select::group_faces(&jointed, &group).expect("group"),
            name: group,
            kind: SurfaceKind::Pressure(pressure),
            ramp: Ramp { ramp_time: 2.0e-3, stop_time: None },
        });
    }
    let held = held_nodes(&model, &loads).expect("constraints");
    let mut settings = ContactSettings::new(30.0e9);
    settings.friction = 0.6;
    settings.buffer = 5.0e-3;
    let stable = stable_time_step(&model, &held, 400).with_contact(contact_omega(&model, settings.penalty));
    let dt = 0.9 * stable.critical;
    let mut s = Solver::new(model, loads, StepParams::new(dt).expect("step")).expect("solver");
    s.enable_contact(settings, &[]);
    s
}

/// [`polyaxial_cube`] advanced to step `step`: restored from the snapshot
/// `target/contact_profile/cube50_<step>.snap` when one is there (and
/// restores), else run there (about 20 s to step 3,400 on one core) and
/// saved, so that a profiler sees only the steps after it.
pub fn polyaxial_cube_at(step: u64) -> femdem_solver::Solver {
    use femdem_solver::Want;
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../target/contact_profile");
    let file = dir.join(format!("cube50_{step}.snap"));
    let mut s = polyaxial_cube();
    if let Ok(bytes) = std::fs::read(&file) {
        if s.restore(&bytes).is_ok() && s.state().step == step {
            return s;
        }
        s = polyaxial_cube();
    }
    while s.state().step < step {
        s.step(Want::default());
    }
    // Kept for the next run where it can be written (a carried binary's
    // build path may not exist where it runs).
    if std::fs::create_dir_all(&dir).and_then(|()| std::fs::write(&file, s.snapshot())).is_err() {
        eprintln!("polyaxial_cube_at: could not keep the snapshot at {}", file.display());
    }
    s
}
