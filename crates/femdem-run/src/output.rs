//! What `femdem run` writes: VTU frames with a PVD series, and the CSV
//! history of energies and recorded forces.

use std::path::Path;

use anyhow::{Result, bail};
use femdem_material::{principal_stresses, von_mises};
use femdem_solver::{Solver, StepRecord};
use femdem_vtk::{Compression, Field, Frame, HistoryWriter, SeriesWriter, VtuOptions};

use femdem_case::setup::FIELDS;
use femdem_post::columns::{BROKEN, CONTACT, ENERGY, FAILURES};

use crate::checkpoint::Marks;
use crate::outdir::CASE_COMMENT;
use femdem_case::LoadedCase;
use femdem_case::probes::Probe;
use femdem_case::setup::LoadStrain;

/// Fails unless every field is one of [`FIELDS`].
fn check_fields(fields: &[String]) -> Result<()> {
    if let Some(f) = fields.iter().find(|f| !FIELDS.contains(&f.as_str())) {
        bail!("output.fields: `{f}` is not one of {}", FIELDS.join(", "));
    }
    Ok(())
}

/// The comment lines `history.csv` starts with: the case file's name
/// (`case: <name>`, what `--overwrite`'s refusal names), its title, the
/// `--set` overrides in their canonical form, and what produced the run
/// (`provenance.rs`: femdem's version and commit, the processor, the
/// vector instructions of the build, the worker threads, the GPU); line
/// breaks in the title become spaces. They are written when a run starts
/// and kept by a resumed run, whose history is then the same byte for byte
/// as an uninterrupted run's.
pub fn history_comments(case: &LoadedCase, gpu: Option<&str>) -> Vec<String> {
    let name = case.path.file_name().map_or_else(|| case.path.display().to_string(), |n| n.to_string_lossy().into());
    let mut lines = vec![format!("{CASE_COMMENT}{name}")];
    let title = case.case.title.split(['\n', '\r']).map(str::trim).filter(|l| !l.is_empty()).collect::<Vec<_>>();
    if !title.is_empty() {
        lines.push(format!("title: {}", title.join(" ")));
    }
    let sets = case.overrides.canonical();
    if !sets.is_empty() {
        lines.push(format!("set: {}", sets.join(" ")));
    }
    lines.extend(crate::provenance::lines(gpu));
    lines
}

/// What the history records besides the energies and the loads' forces.
#[derive(Clone, Debug, Default)]
pub struct Recorded {
    /// The load–strain pair of `[output.load_strain]`.
    pub load_strain: Option<LoadStrain>,
    /// The probes of `[[output.probes]]`.
    pub probes: Vec<Probe>,
}

/// The columns of `history.csv`: energies and failure counts, with contact
/// its own columns ([`CONTACT`]), each drive's force, displacement
/// and work, each surface load's force and work, the load–strain pair when
/// asked for, and each probe's twelve columns.
fn history_columns(solver: &Solver, recorded: &Recorded) -> Vec<String> {
    let mut columns: Vec<String> =
        ["time", "step"].iter().chain(&ENERGY).chain(&BROKEN).map(|s| s.to_string()).collect();
    if !solver.model().joints.is_empty() {
        columns.push("fracture_gf_area".into());
    }
    if solver.contact().is_some() {
        columns.extend(CONTACT.map(String::from));
    }
    for d in &solver.loads().drives {
        columns.extend(["fx", "fy", "fz", "ux", "uy", "uz", "work"].map(|c| format!("{}_{c}", d.name)));
    }
    for s in &solver.loads().surfaces {
        columns.extend(["fx", "fy", "fz", "work"].map(|c| format!("{}_{c}", s.name)));
    }
    if recorded.load_strain.is_some() {
        columns.extend(["load".to_string(), "strain".to_string()]);
    }
    for p in &recorded.probes {
        columns.extend(Probe::columns(&p.name));
    }
    columns
}

/// How the output begins: afresh, `history.csv` with these comment lines,
/// or where a checkpoint's marks left it.
enum Begin<'a> {
    Fresh(&'a [String]),
    Resumed(&'a Marks),
}

/// The run's writers.
pub struct Output {
    series: SeriesWriter,
    fractures: SeriesWriter,
    history: HistoryWriter,
    failures: HistoryWriter,
    fields: Vec<String>,
    /// Pre-existing fracture faces (node triples of one side).
    pre_existing: Vec<[u32; 3]>,
    recorded: Recorded,
    /// `Σ G_f A` over the failures counted so far (`fracture_gf_area`), J,
    /// and how many of the solver's failures that is.
    gf_area: f64,
    gf_counted: usize,
}

/// `G_f A` of one failed joint: its fracture energy for the way it failed
/// (`G_ft` tensile, `G_fs` shear, their mean mixed, 0 for a collapsed
/// joint, which released nothing) times its mid-plane area at failure, J.
fn gf_area(solver: &Solver, f: &femdem_solver::Failure) -> f64 {
    let p = &solver.model().joint_law[f.joint as usize].params;
    let g = match f.mode {
        femdem_fracture::FailureMode::Tensile => p.gf_tension,
        femdem_fracture::FailureMode::Shear => p.gf_shear,
        femdem_fracture::FailureMode::Mixed => 0.5 * (p.gf_tension + p.gf_shear),
        femdem_fracture::FailureMode::Collapsed => 0.0,
    };
    g * f.area
}

impl Output {
    /// Creates the writers in `dir`, `history.csv` starting with the
    /// `comments` lines ([`history_comments`]); `fields` are checked against
    /// [`FIELDS`].
    pub fn create(
        dir: &Path,
        stem: &str,
        written: (Vec<String>, Compression),
        solver: &Solver,
        pre_existing: Vec<[u32; 3]>,
        recorded: Recorded,
        comments: &[String],
    ) -> Result<Output> {
        Output::open(dir, stem, written, solver, pre_existing, recorded, Begin::Fresh(comments))
    }

    /// Continues the output an earlier run of the same case left in `dir`
    /// from a checkpoint's `marks`: the history and failure list cut back
    /// to the lengths they had, the series to the frames they listed.
    pub fn resume(
        dir: &Path,
        stem: &str,
        written: (Vec<String>, Compression),
        solver: &Solver,
        pre_existing: Vec<[u32; 3]>,
        recorded: Recorded,
        marks: &Marks,
    ) -> Result<Output> {
        Output::open(dir, stem, written, solver, pre_existing, recorded, Begin::Resumed(marks))
    }

    /// [`Output::create`] and [`Output::resume`].
    fn open(
        dir: &Path,
        stem: &str,
        (fields, compression): (Vec<String>, Compression),
        solver: &Solver,
        pre_existing: Vec<[u32; 3]>,
        recorded: Recorded,
        begin: Begin<'_>,
    ) -> Result<Output> {
        check_fields(&fields)?;
        let options = VtuOptions::default().with_compression(compression);
        let fracture_stem = format!("{stem}_fractures");
        let columns = history_columns(solver, &recorded);
        let mut seen = std::collections::HashSet::new();
        if let Some(dup) = columns.iter().find(|c| !seen.insert(c.as_str())) {
            bail!(
                "the history would have two columns named `{dup}`: rename the load, platen or probe that makes the second"
            );
        }
        let names: Vec<&str> = columns.iter().map(String::as_str).collect();
        let (history_path, failures_path) = (dir.join("history.csv"), dir.join("failures.csv"));
        let (series, fractures, history, failures) = match begin {
            Begin::Fresh(comments) => (
                SeriesWriter::new(dir, stem)?,
                SeriesWriter::new(dir, &fracture_stem)?,
                HistoryWriter::create_with_comments(
                    &history_path,
                    &comments.iter().map(String::as_str).collect::<Vec<_>>(),
                    &names,
                )?,
                HistoryWriter::create(&failures_path, &FAILURES)?,
            ),
            Begin::Resumed(m) => (
                SeriesWriter::resume(dir, stem, &m.frames)?,
                SeriesWriter::resume(dir, &fracture_stem, &m.fracture_frames)?,
                HistoryWriter::resume(&history_path, &names, m.history_len)?,
                HistoryWriter::resume(&failures_path, &FAILURES, m.failures_len)?,
            ),
        };
        let (series, fractures) = (series.with_options(options), fractures.with_options(options));
        Ok(Output { series, fractures, history, failures, fields, pre_existing, recorded, gf_area: 0.0, gf_counted: 0 })
    }

    /// How far the output has got, for a checkpoint; the history and the
    /// failure list are synced to disk first, so that their lengths are
    /// there.
    pub fn marks(&mut self) -> Result<Marks> {
        self.history.sync()?;
        self.failures.sync()?;
        Ok(Marks {
            history_len: self.history.len(),
            failures_len: self.failures.len(),
            frames: self.series.times(),
            fracture_frames: self.fractures.times(),
        })
    }

    /// Appends the joints that failed in the step of record `r` to
    /// `failures.csv`: time (s), joint index, mid-plane centroid (m), area
    /// (m²), mode code (1 tensile, 2 shear, 3 mixed, 4 collapsed; see
    /// `femdem_fracture::FailureMode`).
    pub fn failure_rows(&mut self, solver: &Solver, r: &StepRecord) -> Result<()> {
        for f in &solver.failures()[r.new_failures.clone()] {
            let c = f.centroid;
            self.failures.row(&[f.time, f64::from(f.joint), c.x, c.y, c.z, f.area, f64::from(f.mode.code())])?;
        }
        Ok(())
    }

    /// Appends the history row of a step's record; the probes read the
    /// solver's state at that step (positions as [`Output::frame`] writes
    /// them, velocities `v_{n+½}`, the step's tet stresses).
    pub fn history_row(&mut self, solver: &Solver, r: &StepRecord) -> Result<()> {
        let e = &r.energies;
        let mut row = vec![
            r.time,
            r.step as f64,
            e.kinetic,
            e.tet_elastic,
            e.joint_elastic,
            e.damping,
            e.fracture,
            e.contact,
            e.friction,
            e.external_work,
            e.balance(),
            r.failures.tensile as f64,
            r.failures.shear as f64,
            r.failures.mixed as f64,
            r.failures.collapsed as f64,
        ];
        if !solver.model().joints.is_empty() {
            // One failure at a time, in order: the same sum however the
            // rows (or a resume, which starts from 0) cut the list.
            for f in &solver.failures()[self.gf_counted..] {
                self.gf_area += gf_area(solver, f);
            }
            self.gf_counted = solver.failures().len();
            row.push(self.gf_area);
        }
        if let (Some(c), Some(energy)) = (solver.contact(), solver.contact_energy()) {
            row.extend([
                c.normal_work(energy),
                c.spring_energy,
                r.contact_pairs as f64,
                energy.released,
                energy.handed(),
                c.started_pairs() as f64,
                // At t_n, where the pass found them in contact.
                c.deepest_overlap(solver.model(), |n| solver.recorded_position(n as usize)),
            ]);
        }
        for ((f, u), w) in r.drive_forces.iter().zip(&r.drive_displacements).zip(&r.drive_work) {
            row.extend([f.x, f.y, f.z, u.x, u.y, u.z, *w]);
        }
        for (f, w) in r.surface_forces.iter().zip(&r.surface_work) {
            row.extend([f.x, f.y, f.z, *w]);
        }
        if let Some(ls) = &self.recorded.load_strain {
            let (load, strain) = ls.evaluate(&r.drive_forces, &r.drive_displacements);
            row.extend([load, strain]);
        }
        let m = &solver.model();
        for p in &self.recorded.probes {
            let u = |n: usize| solver.recorded_position(n) - m.x0[n];
            let v = |n: usize| solver.state().v[n];
            row.extend(p.values(&m.tets, u, v, &solver.workspace().stress));
        }
        self.history.row(&row)?;
        Ok(())
    }

    /// Writes the frame of time `t`: positions at the last step's record
    /// (`Solver::recorded_position`, the state the stresses of the last step
    /// belong to), velocities `v_{n+½}`, and the tet fields.
    pub fn frame(&mut self, solver: &Solver, t: f64) -> Result<()> {
        let s = &solver.state();
        let m = &solver.model();
        let points: Vec<[f64; 3]> = (0..s.x.len()).map(|i| solver.recorded_position(i).into()).collect();
        let disp: Vec<[f64; 3]> =
            points.iter().zip(&m.x0).map(|(p, x0)| [p[0] - x0.x, p[1] - x0.y, p[2] - x0.z]).collect();
        let vel: Vec<[f64; 3]> = s.v.iter().map(|v| (*v).into()).collect();
        let stress: Vec<[f64; 9]> = solver
            .workspace()
            .stress
            .iter()
            .map(|m| {
                let mut a = [0.0; 9];
                for r in 0..3 {
                    for c in 0..3 {
                        a[3 * r + c] = m[(r, c)];
                    }
                }
                a
            })
            .collect();
        let principal: Vec<[f64; 3]> = solver.workspace().stress.iter().map(principal_stresses).collect();
        let vm: Vec<f64> = solver.workspace().stress.iter().map(von_mises).collect();
        let region: Vec<f64> = m.tet_region.iter().map(|&r| f64::from(r)).collect();
        let want = |n: &str| self.fields.iter().any(|f| f == n);
        let mut point_fields = Vec::new();
        if want("displacement") {
            point_fields.push(Field::vector("displacement", &disp));
        }
        if want("velocity") {
            point_fields.push(Field::vector("velocity", &vel));
        }
        let mut cell_fields = Vec::new();
        if want("stress") {
            cell_fields.push(Field::tensor("stress", &stress));
        }
        if want("principal_stress") {
            cell_fields.push(Field::vector("principal_stress", &principal));
        }
        if want("von_mises") {
            cell_fields.push(Field::scalar("von_mises", &vm));
        }
        if want("region") {
            cell_fields.push(Field::scalar("region", &region));
        }
        let frame = Frame::new(&points, &m.tets).with_point_fields(&point_fields).with_cell_fields(&cell_fields);
        self.series.write(t, &frame)?;
        Ok(())
    }

    /// Writes the fracture surface of time `t`: every failed joint's face
    /// (side `N1 N2 N3`, at positions `x_n`) and every pre-existing fracture
    /// face, as triangles with cell data `mode` (0 pre-existing, 1 tensile,
    /// 2 shear, 3 mixed, 4 collapsed), `failure_time` (s; −1 for pre-existing) and
    /// `pre_existing` (1 or 0).
    pub fn fracture_frame(&mut self, solver: &Solver, t: f64) -> Result<()> {
        let at = |n: u32| -> [f64; 3] { solver.recorded_position(n as usize).into() };
        let mut points = Vec::new();
        let mut triangles = Vec::new();
        let (mut mode, mut time, mut pre) = (Vec::new(), Vec::new(), Vec::new());
        let mut push = |nodes: [u32; 3], m: f64, ft: f64, p: f64| {
            let base = points.len() as u32;
            points.extend(nodes.map(at));
            triangles.push([base, base + 1, base + 2]);
            mode.push(m);
            time.push(ft);
            pre.push(p);
        };
        for &f in &self.pre_existing {
            push(f, 0.0, -1.0, 1.0);
        }
        for f in solver.failures() {
            let j = solver.model().joints[f.joint as usize];
            push([j[0], j[1], j[2]], f64::from(f.mode.code()), f.time, 0.0);
        }
        let cell_fields =
            [Field::scalar("mode", &mode), Field::scalar("failure_time", &time), Field::scalar("pre_existing", &pre)];
        let frame = Frame::new(&points, &[]).with_triangles(&triangles).with_cell_fields(&cell_fields);
        self.fractures.write(t, &frame)?;
        Ok(())
    }

    /// The fracture-surface `.pvd`.
    pub fn fracture_pvd(&self) -> std::path::PathBuf {
        self.fractures.pvd_path()
    }

    /// Writes the frame and the fracture frame at time `t` (s) and flushes
    /// everything written so far.
    pub fn frames(&mut self, solver: &Solver, t: f64) -> Result<()> {
        self.frame(solver, t)?;
        self.fracture_frame(solver, t)?;
        self.flush()
    }

    /// Flushes the history and the failure list.
    pub fn flush(&mut self) -> Result<()> {
        self.history.flush()?;
        self.failures.flush()?;
        Ok(())
    }

    /// The `.pvd` file.
    pub fn pvd(&self) -> std::path::PathBuf {
        self.series.pvd_path()
    }

    /// The history file.
    pub fn history_path(&self) -> &Path {
        self.history.path()
    }
}
