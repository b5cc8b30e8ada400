//! `cargo xtask tradeoff [--quick] [--out DIR]`: the speed–accuracy trade
//! of the Brazilian disc (Guo et al. §3.1), measured. Runs the disc over
//! the knobs that trade speed for accuracy — element size, loading rate,
//! joint penalty p0/E, time-step safety, mass scaling, contact buffer, the
//! contact model — one knob at a time from a reference, plus a few combinations, and the
//! anchor (the finest mesh at the slowest rate) every error is measured
//! against. Writes `tradeoff.csv`, `report.md` and `tradeoff.png` (error
//! against wall time, Pareto front marked) to DIR (default
//! `target/tradeoff`). Runs go through `femdem run` like the validation's,
//! and a finished run with the same case text is reused.

mod figure;
mod pareto;
mod setting;

use std::fmt::Write as _;
use std::path::PathBuf;
use std::time::Instant;

use anyhow::{Context, Result};

use self::setting::{Knob, Plan, Setting};
use crate::validate::brazilian::analysis::Outcome;
use crate::validate::brazilian::case::Base;
use crate::validate::runner::{Femdem, RunOutput};

/// Error budgets on the peak load the report recommends settings for.
const BUDGETS: [f64; 3] = [0.01, 0.05, 0.20];

/// What one run cost and measured.
#[derive(Debug, Clone)]
pub struct Row {
    /// The knob it varies.
    pub knob: Knob,
    /// Its setting.
    pub setting: Setting,
    /// Whether it is the anchor.
    pub anchor: bool,
    /// Deformable tets.
    pub tets: f64,
    /// Steps taken.
    pub steps: f64,
    /// Wall time, s.
    pub wall: f64,
    /// Peak load F (Eq. 21), N.
    pub peak: f64,
    /// f_bt / f_t (Eq. 23).
    pub fbt_ratio: f64,
    /// (peak − reference peak) / reference peak.
    pub vs_reference: f64,
    /// |peak − anchor peak| / anchor peak.
    pub error: f64,
    /// Share of failures within 5 mm of the loaded diameter.
    pub on_diameter: f64,
    /// Share of tensile failures in the central fracture.
    pub central_tensile: f64,
    /// Failures by mode, `T a / S b / M c / C d`.
    pub modes: String,
    /// Largest |balance| / work.
    pub energy_error: f64,
    /// Whether the load fell past the peak (the run measured a peak).
    pub passed_peak: bool,
}

/// Deformable tets of a run, from the line of its log that counts them
/// (`femdem: N tets (M deformable), …`; other `femdem:` lines, such as
/// `--overwrite`'s, may come first).
fn deformable_tets(run: &RunOutput) -> Result<f64> {
    let log = run.dir.parent().context("run directory")?.join("run.log");
    let text = std::fs::read_to_string(&log).with_context(|| format!("reading {}", log.display()))?;
    let line = text
        .lines()
        .find(|l| l.starts_with("femdem: ") && l.contains(" deformable), "))
        .context("no `femdem: N tets (M deformable)` line in the run log")?;
    let inner = line.split('(').nth(1).and_then(|s| s.split(' ').next()).context("no deformable tet count")?;
    inner.parse().with_context(|| format!("{}: `{line}`", log.display()))
}

/// `cargo xtask tradeoff`'s arguments.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// The short plan (fewer settings, coarse meshes).
    #[arg(long)]
    quick: bool,
    /// Where the report and the runs go (default target/tradeoff).
    #[arg(long, value_name = "DIR")]
    out: Option<PathBuf>,
}

/// Runs the task.
pub fn run(args: Args) -> Result<()> {
    let quick = args.quick;
    let out = args.out.unwrap_or_else(|| crate::root().join("target").join("tradeoff"));
    std::fs::create_dir_all(&out)?;
    let load_before = load_average();
    let start = Instant::now();
    let femdem = Femdem::build()?;
    let base = Base::load()?;
    let plan = Plan::new(quick);
    let mut outcomes = Vec::new();
    for (knob, s) in &plan.runs {
        let dir = out.join("runs").join(s.key().replace(' ', "_"));
        let run = femdem.run(&dir, "brazilian", &s.case(&base)?)?;
        let tets = deformable_tets(&run)?;
        outcomes.push((*knob, *s, tets, Outcome::read(run, base.disc)?));
    }
    let peak_of = |s: Setting| outcomes.iter().find(|o| o.1 == s).map(|o| o.3.peak).context("missing run");
    let (p_ref, p_anchor) = (peak_of(plan.reference)?, peak_of(plan.anchor)?);
    let rows: Vec<Row> = outcomes
        .into_iter()
        .map(|(knob, setting, tets, o)| Row {
            knob,
            setting,
            anchor: setting == plan.anchor,
            tets,
            steps: o.steps,
            wall: o.run.wall,
            peak: o.peak,
            fbt_ratio: o.f_bt / base.disc.tensile_strength,
            vs_reference: o.peak / p_ref - 1.0,
            error: (o.peak / p_anchor - 1.0).abs(),
            on_diameter: o.on_diameter(),
            central_tensile: o.central(base.disc.geometry()).share(femdem_post::failures::FailureMode::Tensile),
            modes: o.modes().text(),
            energy_error: o.energy_error,
            passed_peak: o.passed_peak,
        })
        .collect();
    let front = pareto::front(&points(&rows));
    std::fs::write(out.join("tradeoff.csv"), csv(&rows))?;
    let profile = if quick { "quick" } else { "full" };
    figure::draw(
        &out.join("tradeoff.png"),
        &format!("Brazilian disc: peak-load error against wall time ({profile})"),
        &rows,
        &front,
    )?;
    let wall = start.elapsed().as_secs_f64();
    let load = format!("{} at the start, {} at the end", load_before, load_average());
    std::fs::write(out.join("report.md"), report(&rows, &front, &plan, profile, wall, &load))?;
    println!("report: {}", out.join("report.md").display());
    println!("{} runs, {wall:.0} s", rows.len());
    Ok(())
}

/// The 1-minute load average (`/proc/loadavg`), or `unknown`.
fn load_average() -> String {
    std::fs::read_to_string("/proc/loadavg")
        .ok()
        .and_then(|s| s.split_whitespace().next().map(str::to_owned))
        .unwrap_or_else(|| "unknown".into())
}

/// `(wall time, error)` of every run for the front and the budgets; a run
/// that never passed its peak has an unknown error (its peak is a lower
/// bound) and counts as infinitely wrong.
fn points(rows: &[Row]) -> Vec<(f64, f64)> {
    rows.iter().map(|r| (r.wall, if r.passed_peak { r.error } else { f64::INFINITY })).collect()
}

/// The rows as CSV, one per run.
fn csv(rows: &[Row]) -> String {
    let mut s = String::from(
        "knob,setting,h_m,velocity_m_s,penalty_over_E,safety,mass_scaling,buffer_m,contact_model,tets,steps,tet_steps,wall_s,\
         peak_N,fbt_over_ft,vs_reference,error_vs_anchor,on_diameter,central_tensile,modes,energy_error,passed_peak\n",
    );
    for r in rows {
        let g = &r.setting;
        let _ = writeln!(
            s,
            "{},{}{},{},{},{},{},{},{},{},{},{},{},{:.3},{},{},{},{},{},{},{},{},{}",
            r.knob.name(),
            g.key(),
            if r.anchor { " (anchor)" } else { "" },
            g.h,
            g.velocity,
            g.penalty,
            g.safety,
            g.mass_scaling,
            g.buffer,
            if g.gradient { "gradient" } else { "potential" },
            r.tets,
            r.steps,
            r.tets * r.steps,
            r.wall,
            r.peak,
            r.fbt_ratio,
            r.vs_reference,
            r.error,
            r.on_diameter,
            r.central_tensile,
            r.modes,
            r.energy_error,
            r.passed_peak
        );
    }
    s
}

/// `report.md`: the table by knob, the Pareto front, the budgets.
fn report(rows: &[Row], front: &[usize], plan: &Plan, profile: &str, wall: f64, load: &str) -> String {
    let mut md = format!(
        "# Speed–accuracy trade of the Brazilian disc ({profile} profile)\n\n\
         Made by `cargo xtask tradeoff{}`; {} runs, {wall:.0} s in all on {} cores \
         (1-minute load average {load}; reused runs keep the wall time of the run that made them).\n\n\
         Reference: `{}`. Anchor (finest mesh, slowest rate): `{}`. \
         h: in-plane element size (mm), V: platen speed (m/s), p: p0/E, s: time-step safety, \
         m: mass scaling, b: contact buffer (mm), `gradient`: the energy-conserving contact \
         (`[contact] model`; Eq. 17's otherwise). *vs ref*: peak load against the reference's; \
         *error*: |peak − anchor's| / anchor's, the accuracy measure of the figure. \
         *diam.*: share of failures within 5 mm of the loaded diameter; *centre T*: tensile share \
         of the central fracture; *energy*: largest |balance| / work.\n\n",
        if profile == "quick" { " --quick" } else { "" },
        rows.len(),
        std::thread::available_parallelism().map_or(1, |n| n.get()),
        plan.reference.key(),
        plan.anchor.key(),
    );
    md.push_str(
        "| knob | setting | tets | steps | tet-steps | wall (s) | tet-steps/s | peak (N) | f_bt/f_t | vs ref | error | diam. | centre T | modes T/S/M/C | energy |\n\
         |---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n",
    );
    for r in rows {
        let _ = writeln!(
            md,
            "| {} | `{}`{} | {:.0} | {:.0} | {:.2e} | {:.1} | {:.2e} | {:.0}{} | {:.3} | {:+.1}% | {:.2}% | {:.0}% | {:.0}% | {} | {:.2}% |",
            r.knob.name(),
            r.setting.key(),
            if r.anchor { " (anchor)" } else { "" },
            r.tets,
            r.steps,
            r.tets * r.steps,
            r.wall,
            r.tets * r.steps / r.wall,
            r.peak,
            if r.passed_peak { "" } else { " (no peak)" },
            r.fbt_ratio,
            100.0 * r.vs_reference,
            100.0 * r.error,
            100.0 * r.on_diameter,
            100.0 * r.central_tensile,
            r.modes,
            100.0 * r.energy_error
        );
    }
    md.push_str("\n![error against wall time](tradeoff.png)\n\n## Pareto front\n\n");
    md.push_str("Runs no other run beats on both wall time and error, cheapest first (runs with no peak, marked above, left out):\n\n");
    for &i in front {
        let r = &rows[i];
        let _ = writeln!(md, "- `{}`: {:.1} s, error {:.2}%", r.setting.key(), r.wall, 100.0 * r.error);
    }
    md.push_str("\n## Cheapest run within an error budget on the peak load\n\n| budget | run | wall (s) | error | speed-up over the anchor |\n|---|---|---|---|---|\n");
    let points = points(rows);
    let anchor_wall = rows.iter().find(|r| r.anchor).map_or(f64::NAN, |r| r.wall);
    for b in BUDGETS {
        match pareto::cheapest_within(&points, b) {
            Some(i) => {
                let r = &rows[i];
                let _ = writeln!(
                    md,
                    "| {:.0}% | `{}` | {:.1} | {:.2}% | {:.1}× |",
                    100.0 * b,
                    r.setting.key(),
                    r.wall,
                    100.0 * r.error,
                    anchor_wall / r.wall
                );
            }
            None => {
                let _ = writeln!(md, "| {:.0}% | none | — | — | — |", 100.0 * b);
            }
        }
    }
    md.push_str("\n## Each knob alone\n\nThe largest change of the peak load from the reference's, and the wall time against the reference's:\n\n| knob | settings | largest |vs ref| | wall / reference's |\n|---|---|---|---|\n");
    let ref_wall = rows.iter().find(|r| r.knob == Knob::Reference).map_or(f64::NAN, |r| r.wall);
    let mut knobs: Vec<Knob> = rows.iter().map(|r| r.knob).filter(|k| *k != Knob::Reference).collect();
    knobs.sort();
    knobs.dedup();
    for k in knobs {
        let of: Vec<&Row> = rows.iter().filter(|r| r.knob == k).collect();
        let worst = of.iter().map(|r| r.vs_reference.abs()).fold(0.0, f64::max);
        let ratios: Vec<String> = of.iter().map(|r| format!("{:.2}", r.wall / ref_wall)).collect();
        let settings: Vec<String> = of.iter().map(|r| format!("`{}`", r.setting.key())).collect();
        let _ =
            writeln!(md, "| {} | {} | {:.2}% | {} |", k.name(), settings.join(", "), 100.0 * worst, ratios.join(", "));
    }
    md
}
