//! The Brazilian disc test of the paper (Guo et al. §3.1, Fig. 6–8, Eq.
//! 21–23): four loading rates, the paper's checks, the figures, the
//! sensitivity runs that measure what moves the tensile strength, and the
//! study of what the load–strain curve's strain consists of.

pub(crate) mod analysis;
pub(crate) mod case;
mod crushing_onset;
mod figures;
mod sensitivity;
mod strain_axis;

use std::fmt::Write as _;
use std::path::Path;

use anyhow::{Context, Result};

use self::analysis::{BAND, Outcome};
use self::case::{Base, Mesh};
use super::Profile;
use super::report::{Kind, Report};
use super::runner::Femdem;
use femdem_post::failures::FailureMode;
use femdem_post::frames::{self as vtu, Grid};
use femdem_post::hondros;

/// The paper's loading rates V_y, m/s, fastest first.
pub const RATES: [f64; 4] = [0.1, 0.05, 0.02, 0.01];

/// The rates of `--rates`: a comma-separated list of positive platen
/// speeds, m/s, returned fastest first without repeats.
pub fn parse_rates(list: &str) -> Result<Vec<f64>> {
    let mut rates = Vec::new();
    for item in list.split(',') {
        let v: f64 = item.trim().parse().with_context(|| format!("--rates: `{item}` is not a number (m/s)"))?;
        if !(v.is_finite() && v > 0.0) {
            anyhow::bail!("--rates: `{item}` is not a positive platen speed (m/s)");
        }
        rates.push(v);
    }
    rates.sort_by(|a, b| b.total_cmp(a));
    rates.dedup();
    Ok(rates)
}
/// The paper's peak load at 0.01 m/s (Fig. 6), N, and its f_bt, Pa.
const PAPER_PEAK: f64 = 1844.76;
const PAPER_FBT: f64 = 1.96e6;

/// How the disc is meshed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum DiscMesh {
    /// The bundled case's circle triangulated and extruded in layers.
    Extruded,
    /// Gmsh's unstructured tets (`cases/paper/meshes/disc-*.msh`), the
    /// paper's mesh type.
    Unstructured,
}

impl DiscMesh {
    /// A profile's own: extruded in the quick profile, unstructured (the
    /// paper's type) in the paper profile.
    pub fn of(profile: Profile) -> DiscMesh {
        match profile {
            Profile::Quick => DiscMesh::Extruded,
            Profile::Paper => DiscMesh::Unstructured,
        }
    }
}

/// The mesh a profile runs, of the disc mesh `disc`.
fn mesh(profile: Profile, disc: DiscMesh) -> Mesh {
    let gmsh = (disc == DiscMesh::Unstructured).then(|| gmsh_disc(profile));
    match profile {
        // Ten 4 mm triangles across the diameter: minutes per rate.
        Profile::Quick => Mesh { element_size: 4.0e-3, layers: 4, platen_size: 4.0e-3, gmsh },
        // The paper's ~1.2 mm (§3.1; the paper's disc has 51,690 tets).
        Profile::Paper => Mesh { element_size: 1.2e-3, layers: 10, platen_size: 2.0e-3, gmsh },
    }
}

/// The Gmsh disc of a profile's size (`cases/paper/meshes`).
fn gmsh_disc(profile: Profile) -> &'static str {
    match profile {
        Profile::Quick => "disc-4mm.msh",
        Profile::Paper => "disc-1.2mm.msh",
    }
}

/// What the Brazilian case runs.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Study {
    /// The rates and the paper's checks.
    Rates,
    /// The rates, then the one-change-at-a-time runs at the fastest.
    Sensitivity,
    /// Only the study of the strain axis (no rates, no checks).
    StrainAxis,
    /// Only the study of the crushing onset's convergence (paper profile).
    CrushingOnset,
}

/// Runs the case in `profile` on the disc mesh `disc` as `study` says
/// (the crushing-onset study only the variants named in `onset_only`,
/// where given), adding its checks and sections to `report`.
pub fn validate(
    femdem: &Femdem,
    (profile, disc_mesh): (Profile, DiscMesh),
    rates: &[f64],
    (study, onset_only): (Study, Option<&[String]>),
    out: &Path,
    report: &mut Report,
) -> Result<()> {
    if study == Study::Sensitivity && rates.first() != Some(&RATES[0]) {
        anyhow::bail!("--sensitivity compares with the {} m/s run: keep that rate in --rates", RATES[0]);
    }
    let base = Base::load()?;
    let disc = base.disc;
    let mesh = mesh(profile, disc_mesh);
    let dir = out.join("brazilian");
    if study == Study::CrushingOnset {
        if profile != Profile::Paper {
            anyhow::bail!("--crushing-onset runs the 1.2 mm discs: give --profile paper");
        }
        let mut md = format!("## Brazilian disc: the crushing onset ({} profile)\n", profile.name());
        md.push_str(&crushing_onset::run(femdem, &base, mesh, onset_only, &dir)?);
        report.sections.push(md);
        return Ok(());
    }
    if study == Study::StrainAxis {
        let figs = out.join("figures");
        std::fs::create_dir_all(&figs)?;
        let mut md = format!(
            "## Brazilian disc: the strain axis ({} profile)
",
            profile.name()
        );
        // Its main set on the extrusion, its last rows on the Gmsh disc.
        let extruded = Mesh { gmsh: None, ..mesh };
        md.push_str(&strain_axis::run(femdem, &base, extruded, gmsh_disc(profile), &dir, &figs)?);
        report.sections.push(md);
        return Ok(());
    }
    let mut runs = Vec::new();
    for &v in rates {
        let title = format!("Brazilian disc, V_y = {v} m/s, {} profile (cargo xtask validate)", profile.name());
        let case = base.case(&title, mesh, v, &|_| {})?;
        let run = femdem.run(&dir.join(format!("v{v}")), "brazilian", &case)?;
        runs.push((v, Outcome::read(run, disc)?));
    }
    let gate_paper = if profile == Profile::Paper { Kind::Gate } else { Kind::Info };
    let c = "brazilian";
    let mut md = format!("## Brazilian disc ({} profile)\n\n", profile.name());
    let _ = writeln!(
        md,
        "Mesh: {}. Runs end once the load has fallen to a tenth of its peak (the disc has split).\n",
        mesh.describe()
    );
    md.push_str("| V_y (m/s) | peak F (N) | f_bt (MPa) | f_bt / f_t | ε at peak (‰) | first 5% drop F (N) | failures T/S/M/C | steps | wall (s) |\n|---|---|---|---|---|---|---|---|---|\n");
    for (v, o) in &runs {
        let eps = o.curve.iter().find(|p| p.1 == o.peak).map_or(0.0, |p| p.0);
        let _ = writeln!(
            md,
            "| {v} | {:.1} | {:.3} | {:.2} | {:.3} | {} | {} | {} | {:.0}{} |",
            o.peak,
            1e-6 * o.f_bt,
            o.f_bt / disc.tensile_strength,
            1e3 * eps,
            o.first_drop.map_or("—".into(), |(f, _)| format!("{f:.0}")),
            o.modes().text(),
            o.steps,
            o.run.wall,
            o.run.provenance()
        );
        report.check(
            c,
            &format!("peak passed at V = {v} m/s"),
            "load falls below 90% of the peak".into(),
            if o.passed_peak { "yes" } else { "no" }.into(),
            "—",
            o.passed_peak,
            Kind::Gate,
        );
        report.check(
            c,
            &format!("energy balance at V = {v} m/s (|balance| / work)"),
            "0".into(),
            format!("{:.2}%", 100.0 * o.energy_error),
            "< 2%",
            o.energy_error < 0.02,
            Kind::Gate,
        );
    }
    // The rate effect above the quasi-static rates (the paper's 0.1 > 0.05
    // > 0.02 m/s), over the runs there are.
    let fast: Vec<&(f64, Outcome)> = runs.iter().filter(|(v, _)| *v >= 0.02).collect();
    if fast.len() >= 2 {
        let falls = fast.windows(2).all(|w| w[0].1.peak > w[1].1.peak);
        let names: Vec<String> = fast.iter().map(|(v, _)| v.to_string()).collect();
        let peaks: Vec<String> = fast.iter().map(|(_, o)| format!("{:.0}", o.peak)).collect();
        report.check(
            c,
            &format!("peak F falls with the rate ({} m/s)", names.join(" > ")),
            "falls (Fig. 6)".into(),
            format!("{} N", peaks.join(" / ")),
            "strict",
            falls,
            Kind::Gate,
        );
    }
    let at = |v: f64| runs.iter().find(|(r, _)| *r == v).map(|(_, o)| o);
    if let (Some(a), Some(b)) = (at(0.02), at(0.01)) {
        let quasi = (a.peak - b.peak).abs() / b.peak;
        report.check(
            c,
            "peaks at 0.02 and 0.01 m/s agree (quasi-static)",
            "almost equal (Fig. 6)".into(),
            format!("{:.0} vs {:.0} N ({:.1}%)", a.peak, b.peak, 100.0 * quasi),
            "≤ 5%",
            quasi <= 0.05,
            Kind::Gate,
        );
    }
    // The slowest run stands for the paper's 0.01 m/s; its comparison with
    // the paper gates only at that rate.
    let (v_slow, slow) = runs.last().map(|(v, o)| (*v, o)).context("no Brazilian rate to run")?;
    let gate_slow = if v_slow == 0.01 { gate_paper } else { Kind::Info };
    let fbt_err = (slow.f_bt - PAPER_FBT).abs() / PAPER_FBT;
    report.check(
        c,
        &format!("f_bt at {v_slow} m/s (Eq. 23; the paper's is at 0.01 m/s)"),
        format!("{:.2} MPa (F = {PAPER_PEAK} N)", 1e-6 * PAPER_FBT),
        format!("{:.2} MPa (F = {:.0} N)", 1e-6 * slow.f_bt, slow.peak),
        "≤ 15%",
        fbt_err <= 0.15,
        gate_slow,
    );
    // The first load drop: on fine meshes the first crushing event under a
    // platen drops the load well before the peak (the split).
    if let Some((f1, t1)) = slow.first_drop {
        let crushed = slow.failures.iter().filter(|f| f.time <= t1).count();
        let fbt1 = 2.0 * f1 / (std::f64::consts::PI * disc.diameter * disc.thickness);
        report.check(
            c,
            &format!("load before the first {:.0}% drop, {v_slow} m/s (Eq. 23)", 100.0 * analysis::DROP),
            format!("{:.2} MPa (F = {PAPER_PEAK} N)", 1e-6 * PAPER_FBT),
            format!(
                "{:.2} MPa (F = {f1:.0} N, {:.0}% of the peak; {crushed} failures before it)",
                1e-6 * fbt1,
                100.0 * f1 / slow.peak
            ),
            "reported",
            true,
            Kind::Info,
        );
    }
    // The fracture pattern at the paper's figure rates, or at the slowest run.
    let mut pattern: Vec<&(f64, Outcome)> = runs.iter().filter(|(v, _)| *v == 0.01 || *v == 0.05).collect();
    if pattern.is_empty() {
        pattern.extend(runs.last());
    }
    for (v, o) in pattern.iter().map(|r| (&r.0, &r.1)) {
        let share = o.on_diameter();
        report.check(
            c,
            &format!("failures within {} mm of the loaded diameter, V = {v} m/s", 1e3 * BAND),
            "splitting along it (Fig. 8)".into(),
            format!("{:.0}% of {}", 100.0 * share, o.failures.len()),
            "≥ 80%",
            share >= 0.8,
            Kind::Gate,
        );
        let central = o.central(disc.geometry());
        report.check(
            c,
            &format!("central fracture mode, V = {v} m/s (|y| < d/4)"),
            "tensile (Fig. 7-8)".into(),
            format!("{:.0}% tensile ({})", 100.0 * central.share(FailureMode::Tensile), central.text()),
            "> 50% tensile",
            central.share(FailureMode::Tensile) > 0.5,
            if *v == 0.01 || *v == 0.05 { gate_paper } else { Kind::Info },
        );
    }
    let (top, bottom) = (slow.at_contact(disc.geometry(), 1.0), slow.at_contact(disc.geometry(), -1.0));
    let crushed = top.counts[1] > 0 && bottom.counts[1] > 0;
    report.check(
        c,
        &format!("shear failures within {} mm of both contacts, {v_slow} m/s", 1e3 * BAND),
        "crushing at both ends (Fig. 7b, 8)".into(),
        format!("top {}, bottom {}", top.text(), bottom.text()),
        "≥ 1 shear at each",
        crushed,
        gate_slow,
    );
    if let Some(f) = slow.first_failure() {
        let at_contact = f.at[1].abs() > 0.5 * disc.diameter - BAND;
        report.check(
            c,
            &format!("first failure at {v_slow} m/s"),
            "shear, at a platen (Fig. 7b)".into(),
            format!("mode {:?} at y = {:.1} mm, F = {:.0} N", f.mode, 1e3 * f.at[1], slow.load_at(f.time)),
            "same place and mode",
            at_contact && f.mode == FailureMode::Shear,
            Kind::Info,
        );
    }
    // Hondros' centre stresses in the last frame before the first failure.
    let pvd = slow.run.dir.join(format!("{}.pvd", slow.run.stem));
    let first = slow.first_failure().map_or(slow.peak_time, |f| f.time);
    let frames = vtu::series(&pvd)?;
    let (t_frame, file) =
        frames.iter().rfind(|(t, _)| *t < first && *t > 0.0).context("no frame before the first failure")?;
    let grid = Grid::read(file)?;
    let load = slow.load_at(*t_frame);
    let centre = hondros::centre(&grid, disc.geometry(), load)?;
    let (ex, ey) = (centre.sx / centre.sx_exact - 1.0, centre.sy / centre.sy_exact - 1.0);
    let zone = format!(
        "{} tets within {} R of the centre, t = {:.3e} s, F = {:.0} N",
        centre.tets,
        hondros::ZONE,
        t_frame,
        load
    );
    report.check(
        c,
        &format!("σx at the centre before failure ({zone})"),
        format!("{:.3} MPa (2P/πDt)", 1e-6 * centre.sx_exact),
        format!("{:.3} MPa ({:+.1}%)", 1e-6 * centre.sx, 100.0 * ex),
        "≤ 5%",
        ex.abs() <= 0.05,
        Kind::Gate,
    );
    report.check(
        c,
        "σy at the centre before failure (same tets)",
        format!("{:.3} MPa (−6P/πDt)", 1e-6 * centre.sy_exact),
        format!("{:.3} MPa ({:+.1}%)", 1e-6 * centre.sy, 100.0 * ey),
        "≤ 5%",
        ey.abs() <= 0.05,
        Kind::Gate,
    );
    // Figures.
    let figs = out.join("figures");
    std::fs::create_dir_all(&figs)?;
    let curves: Vec<(f64, &Outcome)> = runs.iter().map(|(v, o)| (*v, o)).collect();
    figures::load_strain(&figs.join("brazilian_load_strain.png"), &curves)?;
    let s0 = 2.0 * load / (std::f64::consts::PI * disc.diameter * disc.thickness);
    // The slice drawn: one layer of the extrusion, or an element's size.
    let layer = if mesh.gmsh.is_some() { mesh.element_size } else { disc.thickness / mesh.layers as f64 };
    figures::mid_plane_sigma_x(
        &figs.join("brazilian_sigma_x.png"),
        &grid,
        disc,
        layer,
        s0,
        &format!("σx on the mid-plane, V = {v_slow} m/s, F = {load:.0} N"),
    )?;
    md.push_str("\n![load–strain](figures/brazilian_load_strain.png)\n\n![σx](figures/brazilian_sigma_x.png)\n");
    for (v, o) in pattern.iter().map(|r| (&r.0, &r.1)) {
        let fpvd = o.run.dir.join(format!("{}_fractures.pvd", o.run.stem));
        let last = vtu::series(&fpvd)?.pop().context("no fracture frame")?;
        let fr = Grid::read(&last.1)?;
        let (z, d3) = (format!("brazilian_fractures_z_v{v}.png"), format!("brazilian_fractures_3d_v{v}.png"));
        figures::fracture_pattern(&figs.join(&z), &figs.join(&d3), &fr, disc, &format!("V = {v} m/s"))?;
        let _ = writeln!(md, "\n![fractures along z, V = {v}](figures/{z}) ![fractures 3D, V = {v}](figures/{d3})");
        let _ = writeln!(md, "\nV = {v} m/s: {}.", super::runner::fragments_line(&o.run.fragments()?));
    }
    if study == Study::Sensitivity {
        md.push_str(&sensitivity::run(femdem, &base, mesh, &dir, &runs[0].1)?);
    }
    report.sections.push(md);
    Ok(())
}
