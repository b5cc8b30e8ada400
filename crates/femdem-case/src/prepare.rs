//! Shared by `check` and `run`: a case turned into a ready solver.

use anyhow::{Result, bail};
use femdem_mesh::{JointedMesh, TetMesh};
use femdem_solver::{Solver, SolverError, StableStep, StepParams, contact_omega, held_nodes, stable_time_step};

use crate::LoadedCase;
use crate::format::LoadSpec;

/// The most steps a run may take (1e9 steps of even a 1000-tet model is
/// days of computing: more is a unit mistake, not a plan).
pub const MAX_STEPS: f64 = 1e9;

/// The most worker threads a run may ask for. Rayon starts every thread
/// it is asked for: `--threads 100000000000000` hung before any output
/// (found fuzzing the case loader); a thousand is far above any machine's
/// cores.
pub const MAX_THREADS: usize = 1024;

/// Lanczos iterations allowed for the stable-step estimate.
pub const POWER_ITERATIONS: usize = 400;

/// A case with its mesh, and a solver when the case has a `[solver]`.
pub struct Prepared {
    /// The case.
    pub case: LoadedCase,
    /// The mesh before joint insertion.
    pub mesh: TetMesh,
    /// The joint zone: false for the tets that `joints_within` leaves
    /// without joints (`crate::zones::joint_zone`).
    pub zone: Vec<bool>,
    /// The mesh with joints.
    pub jointed: JointedMesh,
    /// The solver, its time step set, when the case can run.
    pub run: Option<Runnable>,
    /// What is legal in the case but probably not meant, one sentence
    /// each, for the caller to show.
    pub warnings: Vec<String>,
}

/// How a run starts (`[solver] start`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Start {
    /// At rest in the reference state; loads follow their ramps.
    Dynamic,
    /// Surface loads held from t = 0; a static solve
    /// (`femdem_static::static_solve`) puts the body into equilibrium
    /// before the first step ([`start_static`]).
    Static,
}

/// `[solver] energy_tolerance`: a fraction in [0, 1]; 0 turns the energy
/// check off (`None`).
pub fn energy_tolerance(tolerance: f64) -> Result<Option<f64>, String> {
    if !(0.0..=1.0).contains(&tolerance) {
        return Err(format!(
            "`energy_tolerance` must lie in [0, 1] (a fraction of the run's energy scale; 0 turns the energy check \
             off), got {tolerance}"
        ));
    }
    Ok((tolerance > 0.0).then_some(tolerance))
}

/// `[solver] start`: `dynamic` or `static`.
pub fn start(name: &str) -> Result<Start, String> {
    match name {
        "dynamic" => Ok(Start::Dynamic),
        "static" => Ok(Start::Static),
        _ => Err(format!("`start`: `{name}` is not one of dynamic, static")),
    }
}

/// Where the step runs (`[solver] device`; on a GPU, the bulk of it).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Device {
    /// On the CPU's threads.
    Cpu,
    /// On a Vulkan device with 64-bit floats (`femdem_solver::Solver::use_device`).
    Gpu,
}

/// `[solver] device` (or `--device`): `cpu` or `gpu`.
pub fn device(name: &str) -> Result<Device, String> {
    match name {
        "cpu" => Ok(Device::Cpu),
        "gpu" => Ok(Device::Gpu),
        _ => Err(format!("`device`: `{name}` is not one of cpu, gpu")),
    }
}

/// A solver ready to step.
pub struct Runnable {
    /// The solver.
    pub solver: Solver,
    /// The stable-step estimate.
    pub stable: StableStep,
    /// Steps to reach `end_time`.
    pub steps: u64,
    /// Steps between run-guard checks (0: none).
    pub check_interval: u64,
    /// The energy check's tolerance, a fraction of the run's energy scale
    /// (`None`: off).
    pub energy_tolerance: Option<f64>,
    /// What the guard does when contact has given back more than it took,
    /// and the tolerance, a fraction of the run's energy scale (`None`
    /// without contact, or with no check).
    pub contact_check: Option<(crate::setup::ContactCheck, f64)>,
    /// `[output]`, resolved and checked.
    pub output: crate::setup::OutputSettings,
    /// The load–strain columns, if asked for.
    pub load_strain: Option<crate::setup::LoadStrain>,
    /// The probes of `[[output.probes]]`, placed.
    pub probes: Vec<crate::probes::Probe>,
    /// How the run starts.
    pub start: Start,
    /// Where the step runs, as the case asks.
    pub device: Device,
}

/// Sets the global thread pool to `threads` (the command line's
/// `--threads`), else to the case's `[solver] threads`; neither: rayon's
/// default (one per core). Must run before any parallel work of the
/// process, reading a mesh included: rayon's pool is built once, by its
/// first use, and a later request is refused (`prepare` calls it first;
/// so does the CLI's memory check, which reads MSH files before
/// `prepare`).
///
/// # Errors
/// A count of 0 or above [`MAX_THREADS`], located in the case file when it
/// comes from there.
pub fn set_threads(loaded: &LoadedCase, threads: Option<usize>) -> Result<()> {
    let from_case = loaded.case.solver.as_ref().and_then(|s| s.get_ref().threads.map(|n| (n, s.span())));
    match (threads, from_case) {
        (Some(0), _) => bail!("--threads must be ≥ 1"),
        (None, Some((0, span))) => bail!(loaded.error_at(span, "solver: threads must be ≥ 1")),
        (Some(n), _) if n > MAX_THREADS => bail!("--threads {n} is more than the {MAX_THREADS} femdem allows"),
        (None, Some((n, span))) if n > MAX_THREADS => {
            bail!(loaded.error_at(span, format!("solver: threads = {n} is more than the {MAX_THREADS} femdem allows")))
        }
        (Some(n), _) | (None, Some((n, _))) => {
            // Refused only if a pool already exists: set by an earlier call
            // (the memory check, or tests calling `run` twice in one process).
            let _ = rayon::ThreadPoolBuilder::new().num_threads(n).build_global();
        }
        (None, None) => {}
    }
    Ok(())
}

/// Frames above which an output `interval` shorter than the time step is
/// named: a frame every step for a few thousand steps is a choice; for more,
/// usually a slip of unit.
pub const FRAMES_NOTED: f64 = 10_000.0;

/// Loads the case with the command line's `--set` arguments `sets`
/// applied, builds the mesh and joints, and, if the case has a `[solver]`,
/// the model, the loads and the time step. `threads` (the command line's
/// `--threads`) overrides `[solver] threads`; either is set before any
/// parallel work, meshing included.
pub fn prepare(path: &std::path::Path, threads: Option<usize>, sets: &[String]) -> Result<Prepared> {
    prepare_within(path, threads, sets, None)
}

/// [`prepare`], refusing a case whose mesh, once built, would need more
/// than `memory` with its joints (`None`: no check, as `--force` asks).
/// The command line checks the parts' sizes against the same figure
/// before meshing ([`crate::memory::refuse_if_too_big`]); this check is
/// for the meshes that grow beyond their sizes ([`crate::refinement`]).
pub fn prepare_within(
    path: &std::path::Path,
    threads: Option<usize>,
    sets: &[String],
    memory: Option<crate::memory::Available>,
) -> Result<Prepared> {
    let loaded = crate::load(path, sets)?;
    set_threads(&loaded, threads)?;
    let mut warnings = Vec::new();
    let (mesh, zone, jointed) = jointed_within(&loaded, memory, &mut warnings)?;
    let Some(spec) = &loaded.case.solver else {
        return Ok(Prepared { case: loaded, mesh, zone, jointed, run: None, warnings });
    };
    let s = spec.get_ref();
    let at = |msg: String| loaded.error_at(spec.span(), format!("solver: {msg}"));
    if !(s.end_time.is_finite() && s.end_time > 0.0) {
        bail!(at(format!("end_time must be > 0 s, got {}", s.end_time)));
    }
    if !(s.safety > 0.0 && s.safety <= 1.0) {
        bail!(at(format!("safety must lie in (0, 1], got {}", s.safety)));
    }
    let energy_tolerance = energy_tolerance(s.energy_tolerance).map_err(at)?;
    let start = start(s.start.as_deref().unwrap_or("dynamic")).map_err(at)?;
    let device = device(s.device.as_deref().unwrap_or("cpu")).map_err(at)?;
    if start == Start::Static && !jointed.initial_contacts.is_empty() {
        bail!(at(format!(
            "`start = \"static\"`: {} tet pairs start in contact across pre-existing fracture faces (traces), and the \
             static start does not linearise contact; use `start = \"dynamic\"`",
            jointed.initial_contacts.len()
        )));
    }
    if !(s.mass_scaling.is_finite() && s.mass_scaling >= 1.0) {
        bail!(at(format!("mass_scaling must be finite and ≥ 1, got {}", s.mass_scaling)));
    }
    let model = crate::setup::model(&loaded, &jointed, s.mass_scaling, &mut warnings)?;
    let mut loads = crate::setup::loads(&loaded, &jointed, s.gravity)?;
    if start == Start::Static {
        femdem_static::hold_surface_loads(&mut loads);
    }
    let load_strain = crate::setup::load_strain(&loaded, &loads, &model.x0, &mut warnings)?;
    let held = held_nodes(&model, &loads)
        .map_err(|e| crate::setup::constrained_twice(&loaded, &loads, &e).unwrap_or_else(|| at(e.to_string())))?;
    crate::setup::surface_loads_on_held_nodes(&loaded, &loads, &held, &mut warnings);
    crate::setup::surface_loads_on_interior_faces(&loaded, &loads, &jointed, &mut warnings);
    crate::setup::loads_that_stop_while_ramping(&loaded, start == Start::Static, &mut warnings);
    crate::setup::ramps_longer_than_the_run(&loaded, s.end_time, start == Start::Static, &mut warnings);
    crate::setup::regions_without_tets(&loaded, &jointed, &mut warnings);
    crate::setup::fractures_without_contact(&loaded, &jointed, &mut warnings);
    crate::setup::heterogeneity_without_joints(&loaded, &jointed, &mut warnings);
    let contact = crate::setup::contact_noting(&loaded, &jointed, &mut warnings)?;
    if contact.as_ref().is_none_or(|c| !c.surfaces) {
        crate::setup::platens_that_touch_nothing(&loaded, &jointed, &mut warnings);
    }
    let contact_check = crate::setup::contact_check(&loaded)?;
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
    if !(0..model.num_nodes()).any(|i| !held[i] && model.mass[i] > 0.0) {
        bail!(at("no deformable free node: nothing to integrate".into()));
    }
    if !(dt.is_finite() && dt > 0.0) {
        // The estimate itself overflowed or underflowed: material values
        // far outside any solid's (a unit slip, e.g. MPa given as Pa×10⁶
        // twice, or g/cm³ as kg/m³), whose warnings say which value.
        let warned: String = warnings.iter().map(|w| format!("\n  warning: {w}")).collect();
        bail!(at(format!(
            "the stable time step could not be estimated (got {:e} s): check the materials' young (Pa) and \
             density (kg/m³), whose wave speeds set it{warned}",
            stable.critical
        )));
    }
    let params = StepParams::new(dt).map_err(|e| at(e.to_string()))?;
    let mut solver = Solver::new(model, loads, params).map_err(|e| at(e.to_string()))?;
    if let Some(settings) = contact {
        let initial: Vec<(u32, u32)> = jointed.initial_contacts.iter().map(|(a, b)| (a.tet, b.tet)).collect();
        solver.enable_contact(settings, &initial);
    }
    let steps = (s.end_time / dt).ceil();
    if steps > MAX_STEPS {
        // A step that small may come from the materials (a modulus given
        // in the wrong unit): their warnings say which value.
        let warned: String = warnings.iter().map(|w| format!("\n  warning: {w}")).collect();
        bail!(at(format!(
            "end_time {:e} s at time_step {dt:e} s is {steps:e} steps, more than the {MAX_STEPS:e} a run may take; \
             check time_step and end_time (they are in seconds), and the materials' young and density, whose \
             wave speeds set the stable step{warned}",
            s.end_time
        )));
    }
    let steps = steps as u64;
    if s.end_time < dt {
        // A run takes ceil(end_time / dt) steps and records the state t_n
        // of each (the last before end_time): here only t = 0.
        warnings.push(
            at(format!(
                "end_time {:e} s is shorter than one time step ({dt:.4e} s): the run takes one step and records \
                 only the state at t = 0",
                s.end_time
            ))
            .to_string(),
        );
    }
    // A constraint acts from the step with t_n + Δt/2 ≥ start_time; the
    // last step starts at t = (steps − 1) Δt, so one that starts after
    // (steps − ½) Δt never acts.
    let last_act = (steps as f64 - 0.5) * dt;
    for (i, l) in loaded.case.loads.iter().enumerate() {
        let (LoadSpec::Fixed { start_time: Some(t), name, .. } | LoadSpec::Velocity { start_time: Some(t), name, .. }) =
            l.get_ref()
        else {
            continue;
        };
        if *t > last_act {
            let named = name.as_ref().map_or(String::new(), |n| format!(" (`{n}`)"));
            let message = format!(
                "loads[{i}]{named}: `start_time` {t:e} s comes after the run's last step (from {:e} s, \
                 `end_time` {:e} s): this constraint never acts",
                last_act - 0.5 * dt,
                s.end_time
            );
            warnings.push(loaded.error_at(l.span(), message).to_string());
        }
    }
    let end_time = s.end_time;
    let check_interval = s.check_interval;
    let output = crate::setup::output(&loaded, end_time, &crate::setup::FIELDS)?;
    // Frames more often than steps are written once a step: name how many,
    // where that is many (each frame is a VTU file of the whole mesh).
    let frames = (end_time / output.interval.max(dt)).ceil();
    if output.interval < dt && frames > FRAMES_NOTED {
        let at = loaded.case.output.as_ref().map_or(0..0, |o| o.span());
        let message = format!(
            "output: `interval` {:e} s is shorter than the time step ({dt:.4e} s), so a frame is written at every \
             step: {frames:.0} frames of {} tets each; a longer `interval` writes fewer",
            output.interval,
            jointed.mesh.num_tets()
        );
        warnings.push(loaded.error_at(at, message).to_string());
    }
    let probes = crate::probes::probes(&loaded, solver.model(), solver.loads())?;
    Ok(Prepared {
        case: loaded,
        mesh,
        zone,
        jointed,
        run: Some(Runnable {
            solver,
            stable,
            steps,
            check_interval,
            energy_tolerance,
            contact_check,
            output,
            load_strain,
            probes,
            start,
            device,
        }),
        warnings,
    })
}

/// The case's mesh, its joint zone (false for the tets that
/// `joints_within` leaves without joints) and the mesh with its joints:
/// what a run of the case is built on, and what its `failures.csv` joint
/// indices index (for `femdem_post::fragments`).
///
/// # Errors
/// A located [`crate::CaseError`] for a bad zone or mesh, or when joint
/// insertion fails.
pub fn jointed(loaded: &LoadedCase) -> Result<(TetMesh, Vec<bool>, JointedMesh), crate::CaseError> {
    jointed_within(loaded, None, &mut Vec::new())
}

/// [`jointed`], pushing what meshing notes onto `warnings`, and refusing
/// the mesh before its joints are inserted when it would need more than
/// `memory` ([`crate::memory::refusal_built`]; `None`: no check).
///
/// # Errors
/// As [`jointed`], and the refusal.
pub fn jointed_within(
    loaded: &LoadedCase,
    memory: Option<crate::memory::Available>,
    warnings: &mut Vec<String>,
) -> Result<(TetMesh, Vec<bool>, JointedMesh), crate::CaseError> {
    crate::zones::check(loaded)?;
    let mesh = crate::mesh::build_mesh_noting(loaded, warnings)?;
    warnings.extend(crate::placement::warning(&mesh).map(|w| format!("{}: {w}", loaded.path.display())));
    let zone = crate::zones::joint_zone(loaded, &mesh)?;
    if let Some(available) = memory {
        let built = crate::memory::of_built(loaded, &mesh, &zone);
        if let Some(message) = crate::memory::refusal_built(&built, available, warnings) {
            return Err(crate::CaseError { path: loaded.path.clone(), at: None, message });
        }
    }
    let jointed = femdem_mesh::insert_joints_within(&mesh, &zone).map_err(|e| crate::CaseError {
        path: loaded.path.clone(),
        at: None,
        message: format!("mesh: inserting the joints failed: {e}"),
    })?;
    Ok((mesh, zone, jointed))
}

/// The static start: solves for the equilibrium of `solver`'s model under
/// its loads of t = 0 and moves it there at rest
/// (`Solver::start_displaced`). `initial` are the tet pairs in contact
/// from the start (refused by the solve). Returns the solve's report.
pub fn start_static(
    solver: &mut Solver,
    initial: &[(u32, u32)],
) -> Result<femdem_static::StaticSolution, femdem_static::StaticError> {
    let options = femdem_static::StaticOptions::default();
    let solution = femdem_static::static_solve(solver.model(), solver.loads(), initial, &options)?;
    solver.start_displaced(&solution.displacement)?;
    Ok(solution)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `[solver] energy_tolerance`: a fraction in [0, 1], 0 turning the
    /// energy check off; anything else refused.
    #[test]
    fn energy_tolerance_is_a_fraction_and_zero_turns_it_off() {
        assert_eq!(energy_tolerance(0.0), Ok(None));
        assert_eq!(energy_tolerance(0.01), Ok(Some(0.01)));
        assert_eq!(energy_tolerance(1.0), Ok(Some(1.0)));
        for bad in [-1e-3, 1.5, f64::NAN, f64::INFINITY] {
            let err = energy_tolerance(bad).unwrap_err();
            assert!(err.contains("`energy_tolerance` must lie in [0, 1]"), "{bad}: {err}");
        }
    }
}
