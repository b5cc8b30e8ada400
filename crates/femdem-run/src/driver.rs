//! The step loop of a run: prepare the case, open (or continue) the
//! output, step to the end time or the stop rule, writing frames, history
//! rows, failures and checkpoints on their schedules, and checking the
//! run guard.

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Instant;

use anyhow::{Context, Result, bail};
use femdem_case as case;
use femdem_case::prepare::{Start, prepare_within, start_static};
use femdem_solver::{Solver, Want};

use crate::checkpoint::{self, Identity, Schedule};
use crate::output::{Output, Recorded, history_comments};
use crate::peak::PeakWatch;
use crate::{Observer, PastPeak, RunOptions, Status, Summary, outdir};

/// Runs the case at `path` as `options` say, telling `observer` what
/// happens; stops early, writing a checkpoint, once `stop` is set (the
/// command line sets it on SIGINT, SIGTERM and SIGHUP).
///
/// # Errors
/// A case that does not load, prepare or fit its output directory; a
/// checkpoint that cannot be resumed; an output file that cannot be
/// written; and the run guard's verdict (after writing the state that
/// shows the trouble).
pub fn run(path: &Path, options: RunOptions, stop: &AtomicBool, observer: &mut dyn Observer) -> Result<Summary> {
    let RunOptions { out, threads, set, resume, stop_after_steps, pause_checkpoint, device, overwrite, memory } =
        options;
    let stem = path.file_stem().map_or("case".into(), |s| s.to_string_lossy().into_owned());
    let case_name = path.file_name().map_or("case".into(), |s| s.to_string_lossy().into_owned());
    // The output directory is checked before the mesh is built: a refusal
    // costs nothing, and nothing is removed unless the case prepares.
    let dir = outdir::resolve(&case::load(path, &set)?, &stem, out, &resume)?;
    outdir::refuse_dangerous(&dir, path)?;
    if resume.is_none() {
        outdir::refuse_earlier_results(&dir, &stem, &case_name, overwrite)?;
    }
    let prepared = prepare_within(path, threads, &set, memory)?;
    for warning in &prepared.warnings {
        observer.note(&format!("warning: {warning}"));
    }
    let Some(mut run) = prepared.run else {
        bail!("{}: a [solver] section is needed to run the case", path.display());
    };
    // The directory is this run's from here to the end; what another run
    // wrote while this one prepared is refused as any earlier results.
    let _lock = outdir::lock(&dir)?;
    if resume.is_none() {
        outdir::refuse_earlier_results(&dir, &stem, &case_name, overwrite)?;
    }
    let spec = run.output.clone();
    let (interval, history_interval) = (spec.interval, spec.history_interval);
    let written = (spec.fields, spec.compression);
    let checkpoints = spec.checkpoint;
    let identity = Identity::of(&prepared.case, &prepared.jointed.mesh);
    let solver = &mut run.solver;
    // The device is opened before anything is written (a missing one
    // refuses the run at once) and takes the state once it is final: after
    // a restore or a static start.
    let gpu = match device.as_deref() {
        Some(name) => case::prepare::device(name).map_err(|e| anyhow::anyhow!("--device: {e}"))?,
        None => run.device,
    };
    let from = if device.is_some() {
        format!("--device {}", device.as_deref().unwrap_or_default())
    } else {
        format!("{}: [solver] device = \"gpu\"", path.display())
    };
    let gpu = match gpu {
        case::prepare::Device::Cpu => None,
        case::prepare::Device::Gpu => {
            let g = femdem_solver::Gpu::new().map_err(|e| anyhow::anyhow!("{from}: no device for the run: {e}"))?;
            if g.is_software() {
                observer.note(&format!(
                    "warning: {from}: the best device found is {}, a software device on the CPU: its results are \
                     the GPU path's, but it runs slower than the CPU path (`--device cpu`); a GPU needs its \
                     vendor's Vulkan driver",
                    g.adapter()
                ));
            }
            Some(g)
        }
    };
    let attach = |solver: &mut Solver| -> Result<()> {
        if let Some(g) = &gpu {
            solver.use_device(g, femdem_solver::Residency::Auto).map_err(|e| anyhow::anyhow!("{from}: {e}"))?;
        }
        Ok(())
    };
    let m = &prepared.jointed.mesh;
    let pre_existing: Vec<[u32; 3]> = prepared.jointed.initial_contacts.iter().map(|(a, _)| a.nodes(&m.tets)).collect();
    let columns = Recorded { load_strain: run.load_strain, probes: run.probes.clone() };
    refuse_if_stopped(stop, "while preparing the case")?;
    let (mut output, schedule) = if resume.is_some() {
        let (file, saved) = checkpoint::latest(&dir, &mut |line| observer.note(line))?;
        saved.identity.check(&identity, &file)?;
        solver.restore(&saved.solver).with_context(|| format!("checkpoint {}", file.display()))?;
        attach(solver)?;
        let output =
            Output::resume(&dir, &stem, written, solver, pre_existing, columns, &saved.marks).with_context(|| {
                format!("continuing the output in {} from checkpoint {}", dir.display(), file.display())
            })?;
        checkpoint::remove_after(&dir, Some(saved.schedule.next_step))?;
        observer.note(&format!(
            "resuming from {} (step {}, t = {:.6e} s)",
            file.display(),
            saved.schedule.next_step,
            solver.state().time
        ));
        (output, saved.schedule)
    } else {
        if run.start == Start::Static {
            let initial: Vec<(u32, u32)> =
                prepared.jointed.initial_contacts.iter().map(|(a, b)| (a.tet, b.tet)).collect();
            let solved = start_static(solver, &initial).map_err(|e| {
                let span = prepared.case.case.solver.as_ref().map_or(0..0, |s| s.span());
                prepared.case.error_at(
                    span,
                    format!("solver: `start = \"static\"`: {e}; `start = \"dynamic\"` ramps the loads instead"),
                )
            })?;
            report_static(&solved, observer);
            refuse_if_stopped(stop, "during the static start")?;
        }
        // Attached before `--overwrite` clears anything: a refusal keeps
        // the earlier results.
        attach(solver)?;
        if overwrite && let Some(line) = outdir::clear(&dir, &stem)? {
            observer.note(&line);
        }
        let comments = history_comments(&prepared.case, solver.device_summary().as_deref());
        let output = Output::create(&dir, &stem, written, solver, pre_existing, columns, &comments)
            .with_context(|| format!("output directory {}", dir.display()))?;
        checkpoint::remove_after(&dir, None)?;
        let schedule = Schedule { next_step: 0, next_frame: 0.0, next_row: 0.0, ended_past_peak: false, peak: None };
        (output, schedule)
    };

    let elements = solver.model().num_deformable_tets() as u64;
    if !prepared.case.overrides.is_empty() {
        observer.note(&format!("with --set {}", prepared.case.overrides.args().join(" --set ")));
    }
    observer.note(&format!(
        "{} tets ({} deformable), {} joints, {} nodes; dt = {:.4e} s ({:.2} of the critical {:.4e} s), {} steps",
        solver.model().tets.len(),
        elements,
        solver.model().joints.len(),
        solver.model().num_nodes(),
        solver.dt(),
        solver.dt() / run.stable.critical,
        run.stable.critical,
        run.steps
    ));
    if let Some(device) = solver.device_summary() {
        observer.note(&format!(
            "on {device}; {} bytes a step between host and device (more on output steps)",
            solver.device_bytes_per_step()
        ));
    }
    let first = schedule.next_step;
    observer.started(first, run.steps, elements);
    let started = Instant::now();
    let dt = solver.dt();
    let Schedule { mut next_frame, mut next_row, mut ended_past_peak, .. } = schedule;
    let mut interrupted = false;
    let mut past_peak = run.load_strain.and_then(PeakWatch::new);
    if let (Some(w), Some((peak, last))) = (past_peak.as_mut(), schedule.peak) {
        (w.peak, w.last) = (peak, last);
    }
    let mut saved_at = Instant::now();
    let mut last_checkpoint: Option<PathBuf> = None;
    let mut contact_warned = false;
    for n in first..run.steps {
        let t = solver.state().time;
        let last = n + 1 == run.steps || ended_past_peak;
        let stopping = stop.load(Ordering::SeqCst) || stop_after_steps.is_some_and(|s| n >= s);
        if stopping {
            // The state to continue from: this step has not been taken, and
            // the frame and row the interruption adds below are not in it.
            let at = schedule_at(n, next_frame, next_row, ended_past_peak, &past_peak);
            last_checkpoint = Some(save(&dir, &identity, at, &mut output, solver, pause_checkpoint)?);
        }
        let frame_due = t >= next_frame - 0.5 * dt || last || stopping;
        let row_due = frame_due || t >= next_row - 0.5 * dt;
        let checked = run.check_interval > 0 && ((n + 1) % run.check_interval == 0 || last);
        // The energy check reads the energies of the step it checks; probes
        // record stress in every history row; a checked step evaluates the
        // stresses too, so that the frame and row a guard stop adds below
        // carry the stresses of their own step (they are output only).
        // The contact guard reads the energy scale of the step it checks
        // too.
        let energy_checked = checked && (run.energy_tolerance.is_some() || run.contact_check.is_some());
        let probing = row_due && !run.probes.is_empty();
        solver.step(Want { stress: frame_due || probing || checked, energy: row_due || energy_checked });
        if n == 0 {
            warn_initial_overlap(solver, observer);
        }
        let record = solver.record();
        if !record.new_failures.is_empty() {
            output.failure_rows(solver, record)?;
        }
        if row_due {
            output.history_row(solver, record)?;
            next_row += history_interval * ((t - next_row) / history_interval + 1.0).floor().max(1.0);
        }
        if frame_due {
            output.frames(solver, t)?;
            next_frame += interval * ((t - next_frame) / interval + 1.0).floor().max(1.0);
        }
        let trouble = checked
            .then(|| {
                solver
                    .check(run.stable.critical)
                    .err()
                    .or_else(|| run.energy_tolerance.and_then(|tolerance| solver.check_energy(tolerance).err()))
                    .or_else(|| contact_trouble(solver, run.contact_check, &mut contact_warned, observer))
            })
            .flatten();
        if let Some(trouble) = trouble {
            // Keep what shows the trouble: the history so far with this
            // step's row (its energies, if evaluated) and this step's frame,
            // both of t_n, as every row and frame (unless already written).
            if !row_due && solver.record().energies_current {
                output.history_row(solver, solver.record())?;
            }
            if !frame_due {
                output.frames(solver, t)?;
            }
            observer.ended();
            bail!(
                "the run guard stopped the run: {trouble}\nthe state at that point was written to {}",
                output.pvd().display()
            );
        }
        observer.stepped(n + 1, solver.state().time, &|| Status {
            failed_joints: solver.failures().len(),
            load: run.load_strain.map(|ls| {
                let r = solver.record();
                ls.evaluate(&r.drive_forces, &r.drive_displacements).0
            }),
        });
        if ended_past_peak {
            break;
        }
        // Past the peak, one more step writes the final row and frame with
        // their energies and stresses, as the last step does.
        ended_past_peak = past_peak.as_mut().is_some_and(|w| w.ended(solver));
        if stopping {
            interrupted = true;
            break;
        }
        let by_steps = checkpoints.interval_steps > 0 && (n + 1) % checkpoints.interval_steps == 0;
        let by_wall = checkpoints.interval_wall > 0.0 && saved_at.elapsed().as_secs_f64() >= checkpoints.interval_wall;
        if !last && (by_steps || by_wall) {
            let at = schedule_at(n + 1, next_frame, next_row, ended_past_peak, &past_peak);
            last_checkpoint = Some(save(&dir, &identity, at, &mut output, solver, pause_checkpoint)?);
            saved_at = Instant::now();
        }
    }
    output.flush()?;
    observer.ended();
    let wall = started.elapsed().as_secs_f64();
    let steps = solver.state().step;
    let history = output.history_path().to_path_buf();
    Ok(Summary {
        interrupted,
        steps,
        time: solver.state().time,
        past_peak: past_peak.filter(|_| ended_past_peak).map(|w| PastPeak {
            last: w.last,
            fraction: w.fraction,
            peak: w.peak,
        }),
        wall,
        throughput: steps.saturating_sub(first) as f64 * elements as f64 / wall.max(1e-9),
        vector_unit: femdem_solver::widest_name(),
        failed_joints: solver.failures().len(),
        dir,
        frames: output.pvd(),
        fractures: output.fracture_pvd(),
        failures: history.with_file_name("failures.csv"),
        history,
        checkpoint: last_checkpoint,
        overrides: prepared.case.overrides.args(),
        device: solver.device_summary(),
        device_bytes: solver.device_bytes_per_step(),
        stage_times: solver.stage_times(),
        read_backs: solver.device_transfers().unwrap_or_default(),
    })
}

/// Ends the run before it writes anything when `stop` was set during
/// `what` (a signal while the case meshes or the static start solves):
/// nothing of an earlier run has been removed, and there is no state to
/// keep.
fn refuse_if_stopped(stop: &AtomicBool, what: &str) -> Result<()> {
    if stop.load(Ordering::SeqCst) {
        bail!("stopped {what}, before the first step: nothing was written");
    }
    Ok(())
}

/// Warns when tets already overlap at the first step (a platen or part
/// placed into another): how they start is `[contact] activation`'s, and
/// the user should know that the scene starts with an overlap.
fn warn_initial_overlap(solver: &Solver, observer: &mut dyn Observer) {
    let Some(c) = solver.contact() else { return };
    // Deeper than round-off of the element: faces that only touch (across
    // a pre-existing fracture) are not an overlap.
    let (pairs, depth) = c.started_overlaps(solver.model(), |n| solver.recorded_position(n as usize), 1e-9);
    if pairs > 0 {
        observer.note(&format!(
            "warning: {pairs} tet pairs overlap at t = 0 (the deepest by {depth:.3} of an element's shortest \
             altitude); they start as [contact] activation = \"{}\" says",
            case::setup::activation_name(c.settings.activation)
        ));
    }
}

/// The guard's check of contact's own account
/// (`Solver::check_contact_energy`) under `[contact] energy_check`: the
/// trouble that stops the run, or `None` after warning once (`warned`).
fn contact_trouble(
    solver: &Solver,
    check: Option<(case::setup::ContactCheck, f64)>,
    warned: &mut bool,
    observer: &mut dyn Observer,
) -> Option<femdem_solver::Trouble> {
    let (check, tolerance) = check?;
    let trouble = solver.check_contact_energy(tolerance).err()?;
    match check {
        case::setup::ContactCheck::Stop => Some(trouble),
        case::setup::ContactCheck::Warn => {
            if !*warned {
                *warned = true;
                observer.note(&format!("warning ([contact] energy_check = \"warn\"; reported once): {trouble}"));
            }
            None
        }
    }
}

/// The run loop's schedule at the start of step `n`.
fn schedule_at(n: u64, next_frame: f64, next_row: f64, ended: bool, watch: &Option<PeakWatch>) -> Schedule {
    Schedule {
        next_step: n,
        next_frame,
        next_row,
        ended_past_peak: ended,
        peak: watch.as_ref().map(|w| (w.peak, w.last)),
    }
}

/// Writes a checkpoint of `solver` and `output` at `schedule` into `dir`
/// (pausing before the rename if its step is `pause`, for tests); returns
/// its file.
fn save(
    dir: &Path,
    identity: &Identity,
    schedule: Schedule,
    output: &mut Output,
    solver: &mut Solver,
    pause: Option<u64>,
) -> Result<PathBuf> {
    // The joint histories of a device run are brought back first.
    solver.sync_device();
    checkpoint::write(dir, identity, &schedule, &output.marks()?, &|w| solver.write_snapshot(w), pause)
}

/// One line on the static start: its size, its checks and its cost.
fn report_static(s: &femdem_static::StaticSolution, observer: &mut dyn Observer) {
    let t = s.seconds;
    observer.note(&format!(
        "static start: {} unknowns, {} bodies ({} free, load {:.1e} unbalanced); residual {:.1e}, explicit model {:.1e} \
         after {} corrections; factor {:.1} MiB; {:.2} s (assembly {:.2}, factorisation {:.2}, solve {:.2}, correction {:.2})",
        s.dofs,
        s.bodies,
        s.free_bodies,
        s.unbalanced,
        s.residual,
        s.model_residual.unwrap_or(0.0),
        s.corrections,
        s.memory_bytes() as f64 / (1024.0 * 1024.0),
        t.assembly + t.factorisation + t.solve + t.correction,
        t.assembly,
        t.factorisation,
        t.solve,
        t.correction
    ));
    if s.joints.past_peak > 0 {
        observer.note(&format!(
            "warning: the static start leaves {} joints past their peak ({} failed): the loaded state is not elastic \
             everywhere, and the first step damages them at once",
            s.joints.past_peak, s.joints.failed
        ));
    }
}
