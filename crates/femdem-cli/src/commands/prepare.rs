//! Shared by `check` and `run`: a case turned into a ready solver.

use anyhow::{Result, bail};
use femdem_mesh::{JointedMesh, TetMesh};
use femdem_solver::{Solver, SolverError, StableStep, StepParams, contact_omega, held_nodes, stable_time_step};

use crate::case::{self, LoadedCase};

/// Lanczos iterations allowed for the stable-step estimate.
pub const POWER_ITERATIONS: usize = 400;

/// A case with its mesh, and a solver when the case has a `[solver]`.
pub struct Prepared {
    /// The case.
    pub case: LoadedCase,
    /// The mesh before joint insertion.
    pub mesh: TetMesh,
    /// The mesh with joints.
    pub jointed: JointedMesh,
    /// The solver, its time step set, when the case can run.
    pub run: Option<Runnable>,
}

/// A solver ready to step.
pub struct Runnable {
    /// The solver.
    pub solver: Solver,
    /// The stable-step estimate.
    pub stable: StableStep,
    /// Steps to reach `end_time`.
    pub steps: u64,
    /// The end time, s.
    pub end_time: f64,
    /// Steps between run-guard checks (0: none).
    pub check_interval: u64,
    /// The load–strain columns, if asked for.
    pub load_strain: Option<case::setup::LoadStrain>,
}

/// Loads the case, builds the mesh and joints, and, if the case has a
/// `[solver]`, the model, the loads and the time step.
pub fn prepare(path: &std::path::Path) -> Result<Prepared> {
    let loaded = case::load(path)?;
    let mesh = case::mesh::build_mesh(&loaded)?;
    let jointed = femdem_mesh::insert_joints(&mesh)?;
    let Some(spec) = &loaded.case.solver else {
        return Ok(Prepared { case: loaded, mesh, jointed, run: None });
    };
    let s = spec.get_ref();
    let at = |msg: String| loaded.error_at(spec.span(), format!("solver: {msg}"));
    if !(s.end_time.is_finite() && s.end_time > 0.0) {
        bail!(at(format!("end_time must be > 0 s, got {}", s.end_time)));
    }
    if !(s.safety > 0.0 && s.safety <= 1.0) {
        bail!(at(format!("safety must lie in (0, 1], got {}", s.safety)));
    }
    if let Some(n) = s.threads {
        if n == 0 {
            bail!(at("threads must be ≥ 1".into()));
        }
        // Ignored if a pool already exists (e.g. in tests); results do not depend on it.
        let _ = rayon::ThreadPoolBuilder::new().num_threads(n).build_global();
    }
    let model = case::setup::model(&loaded, &jointed, s.mass_scaling)?;
    let loads = case::setup::loads(&loaded, &jointed, s.gravity)?;
    let load_strain = case::setup::load_strain(&loaded, &loads)?;
    let held = held_nodes(&model, &loads).map_err(|e| at(e.to_string()))?;
    let contact = case::setup::contact(&loaded, &jointed)?;
    let mut stable = stable_time_step(&model, &held, POWER_ITERATIONS);
    if let Some(settings) = &contact {
        stable = stable.with_contact(contact_omega(&model, settings.penalty));
    }
    let dt = match s.time_step {
        Some(dt) if !(dt.is_finite() && dt > 0.0) => {
            bail!(at(format!("time_step must be > 0 s, got {dt}")))
        }
        Some(dt) if dt > stable.critical => bail!(at(SolverError::UnstableStep {
            requested: dt,
            limit: stable.critical,
            suggested: s.safety * stable.critical
        }
        .to_string())),
        Some(dt) => dt,
        None => s.safety * stable.critical,
    };
    if !dt.is_finite() {
        bail!(at("no deformable free node: nothing to integrate".into()));
    }
    let params = StepParams::new(dt).map_err(|e| at(e.to_string()))?;
    let mut solver = Solver::new(model, loads, params).map_err(|e| at(e.to_string()))?;
    if let Some(settings) = contact {
        let initial: Vec<(u32, u32)> = jointed.initial_contacts.iter().map(|(a, b)| (a.tet, b.tet)).collect();
        solver.enable_contact(settings, &initial);
    }
    let steps = (s.end_time / dt).ceil() as u64;
    let end_time = s.end_time;
    let check_interval = s.check_interval;
    Ok(Prepared {
        case: loaded,
        mesh,
        jointed,
        run: Some(Runnable { solver, stable, steps, end_time, check_interval, load_strain }),
    })
}
