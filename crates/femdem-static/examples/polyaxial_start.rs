//! The static start against the dynamic ramp on the paper's polyaxial
//! case (`cases/paper/polyaxial.toml`, Test 1), built here as the CLI
//! builds it: how many steps, and how much wall time, each needs to reach
//! the loaded state's stress.
//!
//! ```text
//! cargo run --release -p femdem-static --example polyaxial_start -- \
//!     [--mesh cases/paper/meshes/cube-50mm.msh] [--scale 1] [--end 4e-3] [--settle 0.5e-3] [--threads 1]
//! ```
//!
//! The static run goes on to `--settle`, the dynamic one (ramp 2 ms) to
//! `--end`; `--solve-only` stops after the static solve (its time and
//! memory).
//!
//! `--scale` multiplies the three pressures (1: the paper's 3.75, 15 and
//! 9.375 MPa). The reference is the static start's stress field `σ_s`
//! (volume-weighted Frobenius norm over the tets); each run reports the
//! first step after which `‖σ − σ_s‖ / ‖σ_s‖` stays below 2 % and 1 % to
//! its end, its wall time to there, and its kinetic energy.

use std::time::Instant;

use femdem_core::{Mat3, Real};
use femdem_fracture::{Coupling, GfCalibration, JointParams};
use femdem_material::{ElasticParams, Law, critical_viscosity};
use femdem_solver::select::group_faces;
use femdem_solver::{
    ContactSettings, Loads, Model, Ramp, RegionBehaviour, Solver, StepParams, SurfaceKind, SurfaceLoad, Want,
    contact_omega, held_nodes, stable_time_step,
};
use femdem_static::{StaticOptions, hold_surface_loads, static_solve};

struct Args {
    mesh: String,
    scale: Real,
    end: Real,
    settle: Real,
    threads: usize,
    solve_only: bool,
}

fn args() -> Args {
    let mut a = Args {
        mesh: "cases/paper/meshes/cube-50mm.msh".into(),
        scale: 1.0,
        end: 4e-3,
        settle: 0.5e-3,
        threads: 1,
        solve_only: false,
    };
    let mut v: Vec<String> = std::env::args().skip(1).collect();
    if let Some(i) = v.iter().position(|f| f == "--solve-only") {
        a.solve_only = true;
        v.remove(i);
    }
    for pair in v.chunks(2) {
        let value = pair.get(1).expect("a value after each flag");
        match pair[0].as_str() {
            "--mesh" => a.mesh = value.clone(),
            "--scale" => a.scale = value.parse().expect("--scale"),
            "--end" => a.end = value.parse().expect("--end"),
            "--settle" => a.settle = value.parse().expect("--settle"),
            "--threads" => a.threads = value.parse().expect("--threads"),
            other => panic!("unknown flag {other}"),
        }
    }
    a
}

/// The case's model, loads (pressures ramped over 2 ms) and contact.
fn case(mesh_path: &str, scale: Real) -> (Model, Loads, ContactSettings) {
    let bytes = std::fs::read(mesh_path).expect("the mesh file");
    let mesh = femdem_mesh::msh::read_msh(&bytes).expect("an MSH 4.1 mesh");
    let mean_edge = {
        let (mut sum, mut count) = (0.0, 0);
        for t in 0..mesh.num_tets() {
            sum += femdem_core::tet::edge_lengths(&mesh.tet_points(t)).iter().sum::<Real>();
            count += 6;
        }
        sum / count as Real
    };
    let (young, density) = (30e9, 2700.0);
    let viscosity = 0.05 * critical_viscosity(mean_edge, young, density);
    let material = ElasticParams { young, poisson: 0.27, density, viscosity }.validate().unwrap();
    let joints = JointParams {
        penalty: 10.0 * young,
        tensile_strength: 1e6,
        cohesion: 0.5e6,
        friction_angle: 33.4f64.to_radians(),
        gf_tension: 60.0,
        gf_shear: 60.0,
        calibration: GfCalibration::Paper,
        coupling: Coupling::Printed,
    }
    .validate()
    .unwrap();
    let mut mesh = mesh;
    for r in &mut mesh.regions {
        r.breakable = true;
    }
    let jointed = femdem_mesh::insert_joints(&mesh).unwrap();
    let behaviour =
        vec![RegionBehaviour::Deformable { law: Law::NeoHookean, material, joints: Some(joints) }; mesh.regions.len()];
    let model = Model::new(&jointed, &behaviour, 1.0).unwrap();
    let ramp = Ramp { ramp_time: 2e-3, stop_time: None };
    let mut loads = Loads::default();
    for (side, p) in [("x", 3.75e6), ("y", 15e6), ("z", 9.375e6)] {
        for end in ["min", "max"] {
            let name = format!("{side}{end}");
            let faces = group_faces(&jointed, &name).unwrap();
            loads.surfaces.push(SurfaceLoad { name, faces, kind: SurfaceKind::Pressure(p * scale), ramp });
        }
    }
    let contact = ContactSettings { friction: 0.6, buffer: 5e-3, ..ContactSettings::new(30e9) };
    (model, loads, contact)
}

/// `Σ V |σ|²` and `Σ V |σ − reference|²` over the tets.
fn stress_error(model: &Model, stress: &[Mat3], reference: &[Mat3]) -> Real {
    let (mut num, mut den) = (0.0, 0.0);
    for ((s, r), t) in stress.iter().zip(reference).zip(&model.tet_ref) {
        num += t.volume * (s - r).norm_squared();
        den += t.volume * r.norm_squared();
    }
    (num / den).sqrt()
}

fn solver(model: Model, loads: Loads, contact: &ContactSettings) -> Solver {
    let held = held_nodes(&model, &loads).unwrap();
    let stable = stable_time_step(&model, &held, 400).with_contact(contact_omega(&model, contact.penalty));
    let mut s = Solver::new(model, loads, StepParams::new(0.9 * stable.critical).unwrap()).unwrap();
    s.enable_contact(contact.clone(), &[]);
    s
}

/// Steps until the end, every `every` steps the stress error against
/// `reference`; returns (step, seconds) of the last time the error was
/// above each threshold, the final error and the failures.
fn watch(s: &mut Solver, reference: &[Mat3], end: Real, every: u64, label: &str) {
    let clock = Instant::now();
    let thresholds = [0.02, 0.01];
    let mut last_above = [(0u64, 0.0); 2];
    let mut error = 0.0;
    let mut peak_kinetic: Real = 0.0;
    while s.state().time < end {
        let n = s.state().step;
        let check = n.is_multiple_of(every);
        let kinetic = s.step(Want { stress: check, energy: check }).energies.kinetic;
        if check {
            peak_kinetic = peak_kinetic.max(kinetic);
            error = stress_error(s.model(), &s.workspace().stress, reference);
            for (k, th) in thresholds.iter().enumerate() {
                if error > *th {
                    last_above[k] = (n + every, clock.elapsed().as_secs_f64());
                }
            }
            if n.is_multiple_of(every * 50) {
                eprintln!(
                    "{label}: step {n} t = {:.4e} s error {error:.4e} kinetic {kinetic:.3e} J failures {}",
                    s.state().time,
                    s.failures().len()
                );
            }
        }
    }
    println!(
        "{label}: {} steps to t = {:.3e} s in {:.2} s; stress within 2 % from step {} ({:.2} s), within 1 % from step {} ({:.2} s); final error {error:.3e}; largest kinetic energy {peak_kinetic:.3e} J; {} joints failed",
        s.state().step,
        s.state().time,
        clock.elapsed().as_secs_f64(),
        last_above[0].0,
        last_above[0].1,
        last_above[1].0,
        last_above[1].1,
        s.failures().len()
    );
}

fn main() {
    let a = args();
    rayon::ThreadPoolBuilder::new().num_threads(a.threads).build_global().unwrap();
    let (model, loads, contact) = case(&a.mesh, a.scale);
    println!("{} tets, {} joints, {} nodes", model.tets.len(), model.joints.len(), model.num_nodes());

    let mut held = loads.clone();
    hold_surface_loads(&mut held);
    let clock = Instant::now();
    let solution = static_solve(&model, &held, &[], &StaticOptions::default());
    let static_seconds = clock.elapsed().as_secs_f64();
    let solution = match solution {
        Ok(s) => s,
        Err(e) => {
            println!("static solve failed after {static_seconds:.2} s: {e}");
            return;
        }
    };
    let t = solution.seconds;
    println!(
        "static solve: {:.2} s ({} unknowns, factor {} entries = {:.1} MiB; assembly {:.2} s, factorisation {:.2} s, solve {:.2} s, correction {:.2} s in {} steps); residual {:.1e}, model {:.1e}; joints past peak {}, failed {}",
        static_seconds,
        solution.dofs,
        solution.factor_entries,
        solution.memory_bytes() as f64 / (1024.0 * 1024.0),
        t.assembly,
        t.factorisation,
        t.solve,
        t.correction,
        solution.corrections,
        solution.residual,
        solution.model_residual.unwrap_or(0.0),
        solution.joints.past_peak,
        solution.joints.failed
    );
    eprintln!("correction history {:?}", solution.correction_history);
    if a.solve_only {
        return;
    }

    let mut statik = solver(model.clone(), held, &contact);
    statik.start_displaced(&solution.displacement).unwrap();
    statik.step(Want { stress: true, energy: true });
    let reference = statik.workspace().stress.clone();
    let every = 10;
    watch(&mut statik, &reference, a.settle, every, "static");
    let mut dynamic = solver(model, loads, &contact);
    watch(&mut dynamic, &reference, a.end, every, "dynamic");
}
