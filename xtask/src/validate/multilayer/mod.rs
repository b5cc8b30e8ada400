//! The three-dimensional multi-layer rock of the paper (Guo et al. §3.3,
//! Table 3, Fig. 14–17): a layered block holding a pre-existing fracture
//! network under an in situ stress with gravity. The checks read the run's
//! `failures.csv` against the map's fracture tips and junctions
//! (`femdem_post::tips`): where new fractures start, their modes, whether the pattern
//! stops growing, and the energy balance; the figures are the paper's
//! Fig. 17, σ1 on the mid-plane and the fracture pattern along z.

mod case;
mod figures;
mod strips;

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use anyhow::{Context, Result};

use self::case::{BASE, Base};
use super::Profile;
use super::report::{Kind, Report};
use super::runner::{Femdem, RunOutput};
use femdem_post::failures::FailureMode;
use femdem_post::failures::{Failure, Modes};
use femdem_post::frames::{self as vtu, Grid};
use femdem_post::mechanism;
use femdem_post::table::Table;
use femdem_post::tips::{self, Sites};

/// What a profile runs: the extrusion's target triangle edge (m), the end
/// time (s) and the time between frames (s).
#[derive(Debug, Clone, Copy)]
struct Plan {
    element_size: f64,
    end_time: f64,
    interval: f64,
}

/// The plan of a profile.
fn plan(profile: Profile) -> Plan {
    match profile {
        // 2,745 tets, 660 pre-existing contact faces, about 4,800 steps: a
        // few minutes on 2 cores (the bundled 75 mm mesh, 21.5k tets in
        // contact from the first step along 2,674 pre-existing faces, takes
        // about 30 min to 3 ms).
        Profile::Quick => Plan { element_size: 0.15, end_time: END_TIME, interval: 2.0e-4 },
        // The paper's mean element size, about 2.4 cm (486,425 tets in the
        // paper; here 603,099, mean edge 28 mm, about 20,400 steps):
        // hours to more than a day on 2 cores (docs/notes/2026-11-25-multilayer-paper-profile.md).
        Profile::Paper => Plan { element_size: 0.024, end_time: END_TIME, interval: 2.5e-4 },
    }
}

/// When the runs end, s: the stresses are ramped over 2 ms and then held;
/// the last fifth of the run, where no new failure may appear once the
/// pattern is stable, then starts 1.2 ms (about 5 P-wave transits of the
/// 1.5 m block, c_p ≈ 6.0 km/s) after the ramp.
const END_TIME: f64 = 4.0e-3;

/// Share of the first new failures that must lie near a tip or a junction.
const NEAR_SHARE: f64 = 0.8;
/// The earliest failures, reported beside the first [`FIRST_SHARE`]: this
/// share of all new failures.
const EARLIEST_SHARE: f64 = 0.01;
/// "Near": within this many element sizes (the 3).
const NEAR_SIZES: f64 = 3.0;
/// The first failures: this share of all new failures (the 10%).
const FIRST_SHARE: f64 = 0.1;
/// The last part of the run that must see no new failure (a fifth).
const LAST_PART: f64 = 0.2;
/// Random points drawn for the baseline share.
const BASELINE_POINTS: usize = 20_000;
/// Seed of the baseline points.
const BASELINE_SEED: u64 = 11;

/// What the run measured.
struct Outcome {
    run: RunOutput,
    failures: Vec<Failure>,
    energy_error: f64,
    steps: f64,
    /// Time of the last history row, s.
    end: f64,
    /// Kinetic energy and external work at the end, J.
    kinetic: f64,
    work: f64,
    /// The work of the pressures on the x, y and z faces at the end, J
    /// (`<group>_work` of the loads on `…xmin`, `…xmax`, …; `None` from a
    /// femdem that did not record it).
    work_by_axis: Option<[f64; 3]>,
}

impl Outcome {
    fn read(run: RunOutput) -> Result<Outcome> {
        let h = Table::history(&run.dir)?;
        let last = |c: &str| -> Result<f64> { Ok(h.col(c)?.last().copied().unwrap_or(0.0)) };
        Ok(Outcome {
            failures: Failure::read_all(&run.dir)?,
            energy_error: h.energy_error()?,
            steps: last("step")?,
            end: last("time")?,
            kinetic: last("kinetic")?,
            work: last("external_work")?,
            work_by_axis: h.face_work_by_axis()?,
            run,
        })
    }

    /// The first [`FIRST_SHARE`] of the new failures (at least one, when
    /// any failed), in the order they failed.
    fn first(&self) -> &[Failure] {
        self.first_share(FIRST_SHARE)
    }

    /// The first `share` of the new failures (at least one, when any
    /// failed), in the order they failed.
    fn first_share(&self, share: f64) -> &[Failure] {
        let n = self.failures.len();
        &self.failures[..((share * n as f64).ceil() as usize).min(n)]
    }

    /// The frames of series `suffix` ("" or "_fractures"): `(time, file)`.
    fn frames(&self, suffix: &str) -> Result<Vec<(f64, PathBuf)>> {
        vtu::series(&self.run.dir.join(format!("{}{suffix}.pvd", self.run.stem)))
    }
}

/// The (x, y) of failures, m.
fn plan_view(f: &[Failure]) -> Vec<[f64; 2]> {
    f.iter().map(|f| [f.at[0], f.at[1]]).collect()
}

/// Runs the case in `profile` (on `element_size` m elements and to
/// `end_time` s where given, else the profile's), adding its checks and
/// sections to `report`.
pub fn validate(
    femdem: &Femdem,
    profile: Profile,
    (element_size, end_time): (Option<f64>, Option<f64>),
    out: &Path,
    report: &mut Report,
) -> Result<()> {
    let base = Base::load()?;
    let block = base.block.clone();
    let mut p = plan(profile);
    if let Some(h) = element_size {
        p.element_size = h;
    }
    if let Some(t) = end_time {
        p.end_time = t;
    }
    let title = format!(
        "Multi-layer rock (Guo et al. §3.3), {:.0} mm elements, {} profile (cargo xtask validate)",
        1e3 * p.element_size,
        profile.name()
    );
    let case = base.case(&title, p.element_size, p.end_time, p.interval)?;
    let run = femdem.run(&out.join("multilayer").join("run"), "multilayer", &case)?;
    let o = Outcome::read(run)?;
    let traces = tips::read_traces(&block.map)?;
    let network = tips::network(&block.outline, &traces)?;
    let sites: Sites = tips::sites(&network);
    let all_sites = sites.all();
    let mechanism = mechanism::weakest(&block.outline, &network, block.far)?;
    let lo = block.outline.iter().fold([f64::INFINITY; 2], |m, q| [m[0].min(q[0]), m[1].min(q[1])]);
    let hi = block.outline.iter().fold([f64::NEG_INFINITY; 2], |m, q| [m[0].max(q[0]), m[1].max(q[1])]);
    let baseline = crate::map::uniform_points(BASELINE_POINTS, lo, hi, BASELINE_SEED);

    let c = "multilayer";
    let gate_paper = if profile == Profile::Paper { Kind::Gate } else { Kind::Info };
    let h = p.element_size;
    let radius = NEAR_SIZES * h;
    let first = o.first();
    let first_xy = plan_view(first);
    let all_xy = plan_view(&o.failures);
    let near = tips::share_within(&first_xy, &all_sites, radius);
    let near_random = tips::share_within(&baseline, &all_sites, radius);
    let modes = Modes::of(o.failures.iter());
    let first_modes = Modes::of(first.iter());
    let last_from = o.end * (1.0 - LAST_PART);
    let late = o.failures.iter().filter(|f| f.time > last_from).count();
    let last_failure = o.failures.last().map_or(f64::NAN, |f| f.time);

    report.check(
        c,
        "energy balance (|balance| / work)",
        "0".into(),
        format!("{:.2}%", 100.0 * o.energy_error),
        "< 2%",
        o.energy_error < 0.02,
        Kind::Gate,
    );
    report.check(
        c,
        "new fractures form from the pre-existing ones (intact rock is below its strength)",
        "new fractures (Fig. 17)".into(),
        format!("{} joints failed ({})", modes.total(), modes.text()),
        "≥ 1",
        modes.total() >= 1,
        Kind::Gate,
    );
    report.check(
        c,
        &format!("first {:.0}% of new failures near a pre-existing tip or junction", 100.0 * FIRST_SHARE),
        "\"all new fractures propagate from existing fracture tips\" (§3.3.2)".into(),
        format!(
            "{:.0}% of {} within {:.0} mm ({NEAR_SIZES} element sizes); uniformly random points: {:.0}%",
            100.0 * near,
            first.len(),
            1e3 * radius,
            100.0 * near_random
        ),
        &format!("≥ {:.0}%", 100.0 * NEAR_SHARE),
        !first.is_empty() && near >= NEAR_SHARE,
        gate_paper,
    );
    report.check(
        c,
        "mostly tensile with some shear (all new failures)",
        "mostly tensile, a few shear (§3.3.2)".into(),
        format!(
            "{:.0}% tensile, {:.0}% shear, {:.0}% mixed ({}); the first {:.0}%: {:.0}% tensile, {:.0}% shear",
            100.0 * modes.share(FailureMode::Tensile),
            100.0 * modes.share(FailureMode::Shear),
            100.0 * modes.share(FailureMode::Mixed),
            modes.text(),
            100.0 * FIRST_SHARE,
            100.0 * first_modes.share(FailureMode::Tensile),
            100.0 * first_modes.share(FailureMode::Shear)
        ),
        "> 50% tensile, ≥ 1 shear",
        modes.share(FailureMode::Tensile) > 0.5 && modes.counts[1] >= 1,
        gate_paper,
    );
    // The paper's "afterwards" is once the stresses are held: a last fifth
    // that starts within the ramp (a run ended early with `--end-time`)
    // says nothing about it, so it is reported and not judged.
    let held = last_from >= block.ramp;
    report.check(
        c,
        &format!(
            "the pattern stabilises: no new failure over the last fifth ({:.2}–{:.2} ms)",
            1e3 * last_from,
            1e3 * o.end
        ),
        "\"no more new fractures are developed afterwards\" (§3.3.2)".into(),
        format!(
            "{late} new failures; the last at {:.3} ms; kinetic energy at the end {:.0}% of the external work{}",
            1e3 * last_failure,
            100.0 * o.kinetic / o.work.max(f64::MIN_POSITIVE),
            if held {
                String::new()
            } else {
                format!("; not judged: the last fifth starts within the {:.1} ms ramp", 1e3 * block.ramp)
            }
        ),
        if held { "0" } else { "0 (not judged)" },
        late == 0 && !o.failures.is_empty(),
        if held { gate_paper } else { Kind::Info },
    );

    report.check(
        c,
        "can the pre-existing fractures alone hold the x faces' dead load? (weakest piece, limit equilibrium)",
        "a stable final pattern (§3.3.2)".into(),
        mechanism.as_ref().map_or_else(
            || "no piece can come away along the fractures alone".into(),
            |m| {
                format!(
                    "friction {:.2} of the pull: the piece at {} from y = {:.3} to {:.3} m, {:.0} kN/m of friction against {:.0} kN/m",
                    m.factor(),
                    if m.face == mechanism::Face::XMin { "x_min" } else { "x_max" },
                    m.from,
                    m.to,
                    1e-3 * m.capacity,
                    1e-3 * m.load
                )
            },
        ),
        "≥ 1 (reported)",
        mechanism.as_ref().is_none_or(|m| m.factor() >= 1.0),
        Kind::Info,
    );

    // The section: the run, the distance shares, the figures.
    let mut md = format!(
        "## Multi-layer rock ({} profile)\n\n{BASE} (the seeded stand-in map `{}`: {} tips, {} junctions) on {:.0} mm elements; \
         the stresses ramped over {:.1} ms and held to {:.1} ms. {} steps, {:.0} s{}. \
         At the end the kinetic energy is {:.1}% of the external work.\n\n",
        profile.name(),
        block.map.file_name().map_or_else(String::new, |f| f.to_string_lossy().into_owned()),
        sites.tips.len(),
        sites.junctions.len(),
        1e3 * h,
        1e3 * block.ramp,
        1e3 * o.end,
        o.steps,
        o.run.wall,
        o.run.provenance(),
        100.0 * o.kinetic / o.work.max(f64::MIN_POSITIVE)
    );
    let _ = writeln!(
        md,
        "New failures: {} ({}); the first {:.0}%: {} ({}), from {:.3} to {:.3} ms.\n",
        modes.total(),
        modes.text(),
        100.0 * FIRST_SHARE,
        first.len(),
        first_modes.text(),
        1e3 * first.first().map_or(f64::NAN, |f| f.time),
        1e3 * first.last().map_or(f64::NAN, |f| f.time)
    );
    // On a fine mesh the first tenth spans much of the ramp: the first
    // hundredth shows where the fracturing starts.
    let earliest = o.first_share(EARLIEST_SHARE);
    let earliest_xy = plan_view(earliest);
    let _ = writeln!(
        md,
        "Share of failures (seen along z) within a distance of a pre-existing tip or junction, against uniformly random points \
         (the share of the section that lies that close); the first {:.0}% are {} failures to {:.3} ms ({}):\n\n\
         | distance | first {:.0}% of failures | first {:.0}% | all failures | random points |\n|---|---|---|---|---|",
        100.0 * EARLIEST_SHARE,
        earliest.len(),
        1e3 * earliest.last().map_or(f64::NAN, |f| f.time),
        Modes::of(earliest.iter()).text(),
        100.0 * EARLIEST_SHARE,
        100.0 * FIRST_SHARE
    );
    for k in [1.0, 2.0, NEAR_SIZES] {
        let r = k * h;
        let _ = writeln!(
            md,
            "| {:.0} mm ({k} element size{}) | {:.0}% | {:.0}% | {:.0}% | {:.0}% |",
            1e3 * r,
            if k == 1.0 { "" } else { "s" },
            100.0 * tips::share_within(&earliest_xy, &all_sites, r),
            100.0 * tips::share_within(&first_xy, &all_sites, r),
            100.0 * tips::share_within(&all_xy, &all_sites, r),
            100.0 * tips::share_within(&baseline, &all_sites, r)
        );
    }
    md.push('\n');
    if let Some(w) = o.work_by_axis {
        let share = |x: f64| 100.0 * x / o.work.max(f64::MIN_POSITIVE);
        let _ = writeln!(
            md,
            "Work of the pressures at the end: on the x faces {:.3} kJ ({:.0}% of the external work), on the y faces \
             {:.3} kJ ({:.0}%), on the z faces {:.3} kJ ({:.0}%); gravity's is the rest (how to read it: pieces \
             sliding along new shear fractures under the y pressures raise the y faces' share; the block opening \
             along x raises the x faces').\n",
            1e-3 * w[0],
            share(w[0]),
            1e-3 * w[1],
            share(w[1]),
            1e-3 * w[2],
            share(w[2])
        );
    }
    let _ = writeln!(md, "\n{}.", super::runner::fragments_line(&o.run.fragments()?));
    let _ = writeln!(md, "\nNew failures per fifth of the run:\n");
    let fifths: Vec<String> = (0..5)
        .map(|k| {
            let (a, b) = (o.end * k as f64 / 5.0, o.end * (k + 1) as f64 / 5.0);
            let n = o.failures.iter().filter(|f| (k == 0 || f.time > a) && f.time <= b).count();
            format!("{:.1}–{:.1} ms: {n}", 1e3 * a, 1e3 * b)
        })
        .collect();
    let _ = writeln!(md, "{}\n", fifths.join("; "));

    // Where the kinetic energy lies: the strips along the x faces or the
    // interior, once the stresses are held and at the end.
    let frames = o.frames("")?;
    // The frame at the end of the ramp (the first within half an interval
    // of it: frames are stamped at the step nearest their time, up to half
    // a step early), and the last frame.
    let after_ramp = |f: &[(f64, PathBuf)]| -> Result<(f64, PathBuf)> {
        f.iter().find(|(t, _)| *t >= block.ramp - 0.5 * p.interval).or(f.last()).cloned().context("no frame")
    };
    let last = |f: &[(f64, PathBuf)]| -> Result<(f64, PathBuf)> { f.last().cloned().context("no frame") };
    // The two frames, read once for the strips and the σ1 figures.
    let read = |(t, file): (f64, PathBuf)| -> Result<(f64, Grid)> { Ok((t, Grid::read(&file)?)) };
    let held = [read(after_ramp(&frames)?)?, read(last(&frames)?)?];
    let _ = writeln!(
        md,
        "Kinetic energy in the {:.0} mm strips along the two x faces (from the frames' nodal velocities, lumped mass):\n\n\
         | frame | t (ms) | kinetic energy (kJ) | in the strips | strips' mass | strips' mean outward v_x (m/s) | fastest outward node (m/s) | interior rms speed (m/s) |\n|---|---|---|---|---|---|---|---|",
        1e3 * strips::WIDTH
    );
    let mut measured = Vec::new();
    for (name, (t, grid)) in ["end of the ramp", "end"].into_iter().zip(&held) {
        let s = strips::measure(grid, lo[0], hi[0], block.mass_density)?;
        let _ = writeln!(
            md,
            "| {name} | {:.2} | {:.3} | {:.0}% | {:.0}% | {:.2} | {:.2} | {:.3} |",
            1e3 * t,
            1e-3 * s.kinetic,
            100.0 * s.kinetic_share,
            100.0 * s.mass_share,
            s.mean_outward,
            s.max_outward,
            s.interior_rms
        );
        measured.push(s);
    }
    md.push('\n');
    if let [held, s] = measured[..] {
        report.check(
            c,
            &format!(
                "the x-face strips ({:.0} mm wide) do not speed up once the stresses are held",
                1e3 * strips::WIDTH
            ),
            "no run-away: a stable final pattern (§3.3.2)".into(),
            format!(
                "mean outward v_x {:.2} m/s at the end of the ramp, {:.2} m/s at the end (fastest node {:.2} m/s); \
                 {:.0}% of the kinetic energy ({:.0}% of the mass); interior rms {:.3} m/s",
                held.mean_outward,
                s.mean_outward,
                s.max_outward,
                100.0 * s.kinetic_share,
                100.0 * s.mass_share,
                s.interior_rms
            ),
            "end ≤ end of the ramp",
            s.mean_outward <= held.mean_outward,
            Kind::Info,
        );
    }

    let figs = out.join("figures");
    std::fs::create_dir_all(&figs)?;
    let pad = 0.03 * (hi[0] - lo[0]).max(hi[1] - lo[1]);
    let bounds = (lo[0] - pad..hi[0] + pad, lo[1] - pad..hi[1] + pad);
    let z_mid = block.z0 + 0.5 * block.thickness;
    let fracture_frames = o.frames("_fractures")?;
    let shots = [("ramp", after_ramp(&fracture_frames)?), ("end", last(&fracture_frames)?)];
    for ((name, (tf, fracture)), (t, frame)) in shots.into_iter().zip(&held) {
        let s1 = format!("multilayer_sigma1_{name}.png");
        figures::sigma1_section(
            &figs.join(&s1),
            frame,
            z_mid,
            block.tensile_strength,
            bounds.clone(),
            &format!("Maximum principal stress σ1 on z = {z_mid} m (undeformed), t = {:.2} ms", 1e3 * t),
        )?;
        let fp = format!("multilayer_fractures_{name}.png");
        figures::fracture_pattern(
            &figs.join(&fp),
            &Grid::read(&fracture)?,
            bounds.clone(),
            &format!("Fractures along z, t = {:.2} ms", 1e3 * tf),
        )?;
        let _ = writeln!(
            md,
            "![σ1, t = {:.2} ms](figures/{s1}) ![fractures, t = {:.2} ms](figures/{fp})\n",
            1e3 * t,
            1e3 * tf
        );
    }
    report.sections.push(md);
    Ok(())
}
