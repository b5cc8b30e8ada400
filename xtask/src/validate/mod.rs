//! `cargo xtask validate [--profile quick|paper] [--case NAME] [--rates LIST]
//! [--ramp S] [--end-time S] [--mesh unstructured|lattice|both] [--weibull M]
//! [--disc extruded|unstructured] [--element-size M] [--out DIR]
//! [--sensitivity | --strain-axis | --crushing-onset]`:
//! runs the reference paper's examples through `femdem run`, as a user
//! would, checks the results against the paper and closed forms, and writes
//! `report.md`, `checks.csv`, the runs' data and PNG figures to DIR
//! (default `target/validation`). Exits non-zero when a gating check fails.
//!
//! `--rates 0.1,0.05` runs only those Brazilian loading rates (m/s; the
//! paper's four by default): the checks that need a missing rate are left
//! out, and those of the slowest rate run are labelled with its rate.
//!
//! A prebuilt `femdem` named by the environment variable `FEMDEM_BIN` is
//! used instead of building one (a machine without cargo).
//!
//! `--ramp S` and `--end-time S` replace the polyaxial runs' ramp time of
//! the pressures (the bundled case's by default) and their end time (the
//! profile's by default), s: how the loading rate moves the bands.
//! `--end-time S` also ends the multi-layer run at S (4 ms by default):
//! e.g. at the ramp's end, 2 ms, for the paper's 24 mm mesh, whose run to
//! 4 ms takes many hours; the stabilisation check is then not judged.
//! `--mesh unstructured` (or `lattice`) runs the polyaxial tests on that
//! mesh only (both by default): the lattice runs are the mesh-bias
//! comparison, and with a fast ramp (`--ramp 0.001`) in the paper profile
//! they fail all through the cube and cost the most. With `--mesh lattice`
//! no polyaxial check gates (they are the unstructured mesh's). `--weibull M` gives the polyaxial runs strength
//! heterogeneity: every joint's f_t and c times independent Weibull factors
//! of mean 1 and modulus M (`[heterogeneity]` of the case format).
//!
//! `--disc extruded` (or `unstructured`) meshes the Brazilian disc that way:
//! by default the quick profile extrudes its 4 mm triangles in layers and
//! the paper profile reads Gmsh's unstructured 1.2 mm tets
//! (`cases/paper/meshes/disc-1.2mm.msh`), the paper's mesh type.
//!
//! `--sensitivity` adds the Brazilian one-change-at-a-time runs (what moves
//! f_bt; seven more runs).
//!
//! `--strain-axis` runs, for the Brazilian case, only the study of what
//! its load–strain curve's strain consists of before failure (the disc's
//! elasticity against the closed form, the contact's penetration, the
//! joints' compliance; seven short runs at 0.5 m/s, one at 0.1 m/s), not the
//! rates or their checks. Both studies run the Brazilian case alone (as if
//! with `--case brazilian`).
//!
//! `--crushing-onset` (paper profile) runs, for the Brazilian case, only the
//! study of whether the first load drop (the first crushing under a platen)
//! is converged: seven runs at 0.1 m/s to their first 5% drop, one change
//! each, against the spread of two meshes of the same disc; `--variants
//! baseline,contact__10` runs only those (the run directories' names less
//! `onset_`).
//!
//! `--element-size M` (with `--case multilayer`) meshes the multi-layer
//! block with M m triangle edges instead of the profile's (0.15 quick,
//! 0.024 paper), e.g. 0.048 for h ≈ l_ch / 3; the checks stay the profile's
//! (gated in the paper profile only).
//!
//! A run that finished before with the same case text is reused, and one
//! that did not finish continues from its latest checkpoint
//! (`runner.rs`), so an interrupted validation resumes where it stopped.

pub(crate) mod brazilian;
pub(crate) mod colours;
mod multilayer;
pub(crate) mod plot;
mod polyaxial;
mod report;
pub(crate) mod runner;

use std::path::PathBuf;
use std::time::Instant;

use anyhow::{Result, bail};

use self::report::Report;
use self::runner::Femdem;

/// How much a validation runs.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum Profile {
    /// Coarse meshes, minutes on two cores; paper comparisons reported but
    /// not gated (the meshes are not the paper's).
    Quick,
    /// The paper's mesh sizes and rates: hours on two cores; the paper's
    /// numbers are gated too.
    Paper,
}

impl Profile {
    /// Its name on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Profile::Quick => "quick",
            Profile::Paper => "paper",
        }
    }
}

/// The cases, in the paper's order, and whether they are built yet.
const CASES: [(&str, bool); 3] = [("brazilian", true), ("polyaxial", true), ("multilayer", true)];

/// A positive, finite time in seconds given to option `flag`.
fn seconds(flag: &str, text: &str) -> Result<f64> {
    positive(flag, text, "a positive time in seconds")
}

/// A positive, finite number given to option `flag`; `what` names it in
/// the error.
fn positive(flag: &str, text: &str, what: &str) -> Result<f64> {
    match text.trim().parse::<f64>() {
        Ok(t) if t.is_finite() && t > 0.0 => Ok(t),
        _ => bail!("{flag} needs {what}, not `{text}`"),
    }
}

/// `--element-size` sets the multi-layer mesh alone: refused unless the
/// run is that case's alone (`only`), so that no other case seems to follow it.
fn element_size_applies(only: Option<&str>, element_size: Option<f64>) -> Result<()> {
    match (element_size, only) {
        (Some(_), Some("multilayer")) | (None, _) => Ok(()),
        (Some(_), other) => bail!(
            "--element-size sets the multi-layer case's mesh: add `--case multilayer` (the run asked for {})",
            other.map_or("every case".to_owned(), |o| format!("`{o}`"))
        ),
    }
}

/// The platen speeds of `--rates`, m/s (a newtype: clap would read a
/// `Vec` as repeated options).
#[derive(Debug, Clone)]
pub struct Rates(Vec<f64>);

/// `cargo xtask validate`'s arguments.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// How much runs: coarse meshes (minutes) or the paper's (hours).
    #[arg(long, value_enum, default_value_t = Profile::Quick)]
    profile: Profile,
    /// Only this case.
    #[arg(long, value_name = "NAME", value_parser = ["brazilian", "polyaxial", "multilayer"])]
    case: Option<String>,
    /// The Brazilian platen speeds, m/s, comma-separated (default: the
    /// paper's four).
    #[arg(long, value_name = "LIST", value_parser = |s: &str| brazilian::parse_rates(s).map(Rates))]
    rates: Option<Rates>,
    /// Polyaxial: the time over which every pressure is ramped, s.
    #[arg(long, value_name = "S", value_parser = |s: &str| seconds("--ramp", s))]
    ramp: Option<f64>,
    /// Polyaxial and multi-layer: when the runs end, s.
    #[arg(long = "end-time", value_name = "S", value_parser = |s: &str| seconds("--end-time", s))]
    end_time: Option<f64>,
    /// Polyaxial: which meshes run (unstructured, lattice or both).
    #[arg(long, value_name = "MESH", value_parser = |s: &str| polyaxial::Meshes::parse(s))]
    mesh: Option<polyaxial::Meshes>,
    /// Polyaxial: joints' f_t and c scaled by Weibull factors of this
    /// modulus.
    #[arg(long, value_name = "M", value_parser = |s: &str| positive("--weibull", s, "a positive Weibull modulus"))]
    weibull: Option<f64>,
    /// Multi-layer: the extrusion's target triangle edge, m (default: the
    /// profile's, 0.15 quick, 0.024 paper), e.g. 0.048 for h ≈ l_ch / 3.
    #[arg(long = "element-size", value_name = "M", value_parser = |s: &str| positive("--element-size", s, "a positive length in metres"))]
    element_size: Option<f64>,
    /// Where the report and the runs go (default target/validation).
    #[arg(long, value_name = "DIR")]
    out: Option<PathBuf>,
    /// Brazilian: the disc's mesh (default: extruded in the quick profile,
    /// unstructured, the paper's type, in the paper profile).
    #[arg(long, value_enum, value_name = "MESH")]
    disc: Option<brazilian::DiscMesh>,
    /// Brazilian: also the sensitivity runs.
    #[arg(long)]
    sensitivity: bool,
    /// Brazilian: only the strain-axis study (what the strain consists of
    /// before failure), instead of the rates.
    #[arg(long = "strain-axis", conflicts_with_all = ["sensitivity", "rates", "disc"])]
    strain_axis: bool,
    /// Brazilian, paper profile: only the crushing-onset study (is the
    /// first load drop converged?), instead of the rates.
    #[arg(long = "crushing-onset", conflicts_with_all = ["sensitivity", "rates", "strain_axis", "disc"])]
    crushing_onset: bool,
    /// With --crushing-onset: only these variants, by their run
    /// directories' names less `onset_` (comma-separated, e.g.
    /// `baseline,contact__10`).
    #[arg(long, value_name = "LIST", requires = "crushing_onset", value_delimiter = ',')]
    variants: Option<Vec<String>>,
}

/// Runs the task.
pub fn run(args: Args) -> Result<()> {
    let Args {
        profile,
        case: only,
        rates,
        ramp,
        end_time,
        mesh,
        weibull,
        element_size,
        out,
        disc,
        sensitivity,
        strain_axis,
        crushing_onset,
        variants,
    } = args;
    let study = match (sensitivity, strain_axis, crushing_onset) {
        (_, _, true) => brazilian::Study::CrushingOnset,
        (_, true, _) => brazilian::Study::StrainAxis,
        (true, ..) => brazilian::Study::Sensitivity,
        _ => brazilian::Study::Rates,
    };
    let disc = disc.unwrap_or(brazilian::DiscMesh::of(profile));
    // The Brazilian studies run that case alone.
    let study_flag = match study {
        brazilian::Study::StrainAxis => Some("--strain-axis"),
        brazilian::Study::CrushingOnset => Some("--crushing-onset"),
        _ => None,
    };
    let only = match (study_flag, only) {
        (Some(flag), Some(name)) if name != "brazilian" => {
            bail!("{flag} is a study of the Brazilian case, not `{name}`")
        }
        (Some(_), _) => Some("brazilian".to_owned()),
        (None, only) => only,
    };
    element_size_applies(only.as_deref(), element_size)?;
    let rates = rates.map(|r| r.0);
    let mut variant = polyaxial::Variant { ramp, end: end_time, weibull, ..polyaxial::Variant::default() };
    if let Some(m) = mesh {
        variant.meshes = m;
    }
    let out = out.unwrap_or_else(|| crate::root().join("target").join("validation"));
    if let Some(name) = &only
        && !CASES.iter().any(|(c, _)| c == name)
    {
        bail!("unknown case `{name}`; cases: brazilian, polyaxial, multilayer");
    }
    std::fs::create_dir_all(&out)?;
    let start = Instant::now();
    let femdem = Femdem::build()?;
    let mut report = Report::default();
    for (name, built) in CASES {
        if only.as_ref().is_some_and(|o| o != name) {
            continue;
        }
        if !built {
            report.sections.push(format!("## {name}\n\nNot reproduced yet: no runs, no checks.\n"));
            continue;
        }
        match name {
            "brazilian" => {
                let rates = rates.as_deref().unwrap_or(&brazilian::RATES);
                brazilian::validate(&femdem, (profile, disc), rates, (study, variants.as_deref()), &out, &mut report)?
            }
            "polyaxial" => polyaxial::validate(&femdem, profile, variant, &out, &mut report)?,
            "multilayer" => multilayer::validate(&femdem, profile, (element_size, end_time), &out, &mut report)?,
            _ => unreachable!("every built case is dispatched"),
        }
    }
    let wall = start.elapsed().as_secs_f64();
    report.sections.push(format!(
        "Total wall time {wall:.0} s on {} cores (`cargo xtask validate --profile {}{}`).",
        std::thread::available_parallelism().map_or(1, |n| n.get()),
        profile.name(),
        study_flag.map_or(String::new(), |f| format!(" {f}"))
    ));
    report.write(&out, &format!("femdem validation against Guo et al. ({} profile)", profile.name()))?;
    let failed: Vec<String> = report.failures().map(|c| format!("{}: {} = {}", c.case, c.metric, c.value)).collect();
    println!("report: {}", out.join("report.md").display());
    if !failed.is_empty() {
        bail!("{} check(s) failed:\n  {}", failed.len(), failed.join("\n  "));
    }
    println!(
        "all {} gating checks passed ({wall:.0} s)",
        report.checks.iter().filter(|c| c.kind == report::Kind::Gate).count()
    );
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::polyaxial::Meshes;
    use super::{Args, brazilian, element_size_applies, positive, seconds};
    use clap::{Args as _, FromArgMatches as _};

    fn parse(args: &[&str]) -> Result<Args, clap::Error> {
        let cmd = Args::augment_args(clap::Command::new("validate"));
        let matches = cmd.try_get_matches_from(std::iter::once("validate").chain(args.iter().copied()))?;
        Args::from_arg_matches(&matches)
    }

    #[test]
    fn the_strain_axis_study_runs_alone_and_the_disc_mesh_is_named() {
        let a = parse(&["--strain-axis"]).unwrap();
        assert!(a.strain_axis && a.disc.is_none());
        let a = parse(&["--disc", "unstructured"]).unwrap();
        assert_eq!(a.disc, Some(brazilian::DiscMesh::Unstructured));
        assert_eq!(parse(&[]).unwrap().disc, None);
        for clash in [
            &["--strain-axis", "--rates", "0.1"][..],
            &["--strain-axis", "--sensitivity"],
            &["--crushing-onset", "--strain-axis"],
            &["--strain-axis", "--disc", "extruded"],
        ] {
            let e = parse(clash).unwrap_err().to_string();
            assert!(e.contains("--strain-axis") && e.contains("cannot be used with"), "{e}");
        }
        let e = parse(&["--disc", "lattice"]).unwrap_err().to_string();
        assert!(e.contains("lattice") && e.contains("extruded"), "{e}");
        assert_eq!(brazilian::DiscMesh::of(super::Profile::Quick), brazilian::DiscMesh::Extruded);
        assert_eq!(brazilian::DiscMesh::of(super::Profile::Paper), brazilian::DiscMesh::Unstructured);
    }

    #[test]
    fn the_polyaxial_meshes_are_named_on_the_command_line() {
        assert_eq!(Meshes::parse("unstructured").unwrap(), Meshes::Unstructured);
        assert_eq!(Meshes::parse("lattice").unwrap(), Meshes::Lattice);
        assert_eq!(Meshes::parse("both").unwrap(), Meshes::Both);
        let e = Meshes::parse("gmsh").unwrap_err().to_string();
        assert!(e.contains("--mesh") && e.contains("gmsh"), "{e}");
    }

    #[test]
    fn times_on_the_command_line_must_be_positive_and_finite() {
        assert_eq!(seconds("--ramp", "1e-3").unwrap(), 1e-3);
        for bad in ["0", "-1e-3", "inf", "NaN", "1 ms", ""] {
            let e = seconds("--ramp", bad).unwrap_err().to_string();
            assert!(e.contains("--ramp") && e.contains(bad), "{e}");
        }
        assert_eq!(positive("--weibull", "20", "a modulus").unwrap(), 20.0);
        let e = positive("--weibull", "-8", "a positive Weibull modulus").unwrap_err().to_string();
        assert!(e.contains("--weibull needs a positive Weibull modulus, not `-8`"), "{e}");
    }

    #[test]
    fn the_element_size_is_the_multilayer_cases_alone() {
        let a = parse(&["--case", "multilayer", "--element-size", "0.048"]).unwrap();
        assert_eq!(a.element_size, Some(0.048));
        assert!(element_size_applies(Some("multilayer"), a.element_size).is_ok());
        assert!(element_size_applies(None, None).is_ok());
        for only in [None, Some("brazilian")] {
            let e = element_size_applies(only, Some(0.048)).unwrap_err().to_string();
            assert!(e.contains("--case multilayer"), "{e}");
        }
        let a = parse(&["--profile", "paper", "--case", "multilayer", "--end-time", "0.002"]).unwrap();
        assert_eq!((a.end_time, a.case.as_deref()), (Some(0.002), Some("multilayer")));
        for bad in ["--element-size=-0.05", "--element-size=0", "--element-size=48mm"] {
            let e = parse(&[bad]).unwrap_err().to_string();
            assert!(e.contains("--element-size needs a positive length in metres"), "{bad}: {e}");
        }
    }
}
