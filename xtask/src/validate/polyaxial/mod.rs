//! The polyaxial compression test of the paper (Guo et al. §3.2, Table 2,
//! Fig. 9–13, Eq. 24): a 0.5 m cube under three different face pressures,
//! three materials; the shear fractures' mode shares and orientation
//! against Mohr–Coulomb, and the Mohr-circle figure.

mod case;
mod mohr;

use std::fmt::Write as _;
use std::path::Path;

use anyhow::{Context, Result};
use plotters::style::RGBColor;

use self::case::{Base, Mesh, TESTS, Test};
use super::Profile;
use femdem_post::bands::{self, Facet};
use femdem_post::failures::FailureMode;
use femdem_post::failures::{Failure, Modes};

use super::colours::{mode_colour, mode_legend};
use super::plot;
use super::report::{Kind, Report};
use super::runner::{Femdem, RunOutput};
use femdem_post::frames::{self as vtu, Grid};
use femdem_post::table::Table;

/// Picks the main or the conjugate band of [`bands::bands`].
type PickBand = fn(&(bands::Band, bands::Band)) -> bands::Band;

/// The largest error allowed on a band angle, degrees (the 8°).
const ANGLE_TOLERANCE: f64 = 8.0;

/// The unstructured mesh of a profile, and the lattice cell that gives a
/// similar tet count for the mesh-bias comparison.
fn meshes(profile: Profile) -> (Mesh, Mesh) {
    match profile {
        // 4,993 tets, mean edge 61 mm; the lattice: 10³ cells × 6 = 6,000.
        Profile::Quick => (Mesh::Gmsh("cube-50mm.msh"), Mesh::Lattice(0.05)),
        // 50,972 tets, mean edge 28 mm (the paper: 55,435, ~27 mm); the
        // lattice: 20³ × 6 = 48,000.
        Profile::Paper => (Mesh::Gmsh("cube-22mm.msh"), Mesh::Lattice(0.025)),
    }
}

/// When a profile's runs end by default, s. The bundled case's pressures
/// reach their final values at 2 ms; the Test 1 and 2 stresses exceed the
/// strength (circle reach > 1) and the cube, held by pressures, then fails
/// progressively: the runs end while the first bands form (the paper's
/// Fig. 10a-b), because fragment contact makes every later step many times
/// dearer.
fn default_end_time(profile: Profile) -> f64 {
    match profile {
        Profile::Quick => 2.5e-3,
        Profile::Paper => 3.0e-3,
    }
}

/// How the runs differ from the bundled case and the profile, as
/// `cargo xtask validate` is told on its command line: to measure how the
/// loading rate and strength heterogeneity move the bands.
#[derive(Debug, Clone, Copy, Default)]
pub struct Variant {
    /// `--ramp S`: the time over which every pressure is ramped from zero,
    /// s (the bundled case's by default).
    pub ramp: Option<f64>,
    /// `--end-time S`: when the runs end, s (the profile's by default).
    pub end: Option<f64>,
    /// `--mesh`: which meshes run.
    pub meshes: Meshes,
    /// `--weibull M`: every joint's f_t and c scaled by independent Weibull
    /// factors of mean 1 and modulus M (`[heterogeneity]`; the paper's §4
    /// suggestion for homogeneous stress fields). Homogeneous by default.
    pub weibull: Option<f64>,
}

/// Which meshes `cargo xtask validate --mesh` runs the three tests on: the
/// unstructured one (the paper's comparison) and the jittered lattice (the
/// mesh-bias comparison), or one of them to save time.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Meshes {
    /// Both meshes (the default).
    #[default]
    Both,
    /// Only the unstructured Gmsh mesh.
    Unstructured,
    /// Only the jittered lattice.
    Lattice,
}

impl Meshes {
    /// Parses the value of `--mesh`.
    pub fn parse(text: &str) -> Result<Meshes> {
        match text {
            "both" => Ok(Meshes::Both),
            "unstructured" => Ok(Meshes::Unstructured),
            "lattice" => Ok(Meshes::Lattice),
            other => anyhow::bail!("--mesh needs `unstructured`, `lattice` or `both`, not `{other}`"),
        }
    }

    fn unstructured(self) -> bool {
        self != Meshes::Lattice
    }

    fn lattice(self) -> bool {
        self != Meshes::Unstructured
    }
}

/// What one run measured.
struct Outcome {
    run: RunOutput,
    test: Test,
    mesh: String,
    failures: Vec<Failure>,
    /// The shear-failed faces of the last fracture frame.
    shear: Vec<Facet>,
    /// Every failed face of the last fracture frame, for the figure.
    faces: Vec<([(f64, f64); 3], f64)>,
    energy_error: f64,
    steps: f64,
}

impl Outcome {
    fn read(run: RunOutput, test: Test, mesh: String) -> Result<Outcome> {
        let h = Table::history(&run.dir)?;
        let energy_error = h.energy_error()?;
        let failures = Failure::read_all(&run.dir)?;
        let fpvd = run.dir.join(format!("{}_fractures.pvd", run.stem));
        let last = vtu::series(&fpvd)?.pop().context("no fracture frame")?;
        let grid = Grid::read(&last.1)?;
        let (_, mode) = grid.cell("mode")?;
        let shear = bands::failed_facets(&grid, FailureMode::Shear)?;
        let faces = grid
            .cells
            .iter()
            .zip(mode)
            .map(|(cell, &m)| ([0, 1, 2].map(|k| (grid.points[cell[k]][0], grid.points[cell[k]][1])), m))
            .collect();
        Ok(Outcome {
            run,
            test,
            mesh,
            failures,
            shear,
            faces,
            energy_error,
            steps: h.col("step")?.last().copied().unwrap_or(0.0),
        })
    }

    fn modes(&self) -> Modes {
        Modes::of(self.failures.iter())
    }
}

/// Runs the case in `profile`, adding its checks and sections to `report`.
pub fn validate(femdem: &Femdem, profile: Profile, variant: Variant, out: &Path, report: &mut Report) -> Result<()> {
    let base = Base::load()?;
    let s = base.stresses;
    let ramp = variant.ramp.unwrap_or(base.ramp);
    let end_time = variant.end.unwrap_or_else(|| default_end_time(profile));
    let which = variant.meshes;
    let (unstructured, lattice) = meshes(profile);
    let dir = out.join("polyaxial");
    let mut runs = Vec::new();
    let plan: Vec<(Test, &Mesh)> = TESTS
        .iter()
        .filter(|_| which.unstructured())
        .map(|t| (*t, &unstructured))
        .chain(TESTS.iter().filter(|_| which.lattice()).map(|t| (*t, &lattice)))
        .collect();
    for (test, mesh) in plan {
        let title = format!(
            "Polyaxial compression, Test {} (c = {} MPa, φ = {}°), {}, {} profile (cargo xtask validate)",
            test.number,
            1e-6 * test.cohesion,
            test.friction_angle,
            mesh.label(),
            profile.name()
        );
        let case = base.case(&title, test, mesh, ramp, end_time, variant.weibull)?;
        let slug = match mesh {
            Mesh::Gmsh(_) => format!("test{}", test.number),
            Mesh::Lattice(_) => format!("test{}_lattice", test.number),
        };
        let run = femdem.run(&dir.join(slug), "polyaxial", &case)?;
        runs.push(Outcome::read(run, test, mesh.label())?);
    }
    let c = "polyaxial";
    let gate_paper = if profile == Profile::Paper { Kind::Gate } else { Kind::Info };
    let width = match profile {
        Profile::Quick => 0.1,
        Profile::Paper => 0.05,
    };
    let mut md = format!(
        "## Polyaxial compression ({} profile)\n\nApplied: σ1 = −{} MPa along x, σ2 = −{} MPa along z, σ3 = −{} MPa along y, ramped over {} ms and held; runs end at {} ms.{} \
         Bands: Hough transform of the shear-failed faces' centroids seen along z, slabs {} mm wide; facets: median angle to x of the \
         shear-failed faces' traces on x–y, weighted by area and by how nearly a face contains z. Mohr–Coulomb (Eq. 24): 45° + φ/2 from the σ1 axis.\n\n\
         | test | mesh | c (MPa) | φ (°) | circle reach R/R_fail | failures T/S/M/C | shear share | main band to x (°, share) | conjugate to x (°, share) | facets (°) | 45° + φ/2 | energy error | steps | wall (s) |\n\
         |---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n",
        profile.name(),
        1e-6 * s.least,
        1e-6 * s.intermediate,
        1e-6 * s.most,
        1e3 * ramp,
        1e3 * end_time,
        variant.weibull.map_or(String::new(), |m| format!(
            " Strength heterogeneity: every joint's f_t and c times independent Weibull factors of mean 1, modulus {m}."
        )),
        1e3 * width
    );
    for o in &runs {
        let t = o.test;
        let modes = o.modes();
        let found = bands::bands(&o.shear, width);
        let band = |b: Option<bands::Band>| {
            b.map_or("—".into(), |b| format!("{:.0} ({:.0}%)", b.angle_to_x(), 100.0 * b.share))
        };
        let facets = bands::facet_angle(&o.shear).map_or("—".into(), |a| format!("{a:.1}"));
        let _ = writeln!(
            md,
            "| {} | {} | {} | {} | {:.3} | {} | {:.0}% | {} | {} | {facets} | {:.1} | {:.2}% | {} | {:.0}{} |",
            t.number,
            o.mesh,
            1e-6 * t.cohesion,
            t.friction_angle,
            femdem_post::mohr::reach(s, t.cohesion, t.friction_angle),
            modes.text(),
            100.0 * modes.share(FailureMode::Shear),
            band(found.map(|b| b.0)),
            band(found.map(|b| b.1)),
            femdem_post::mohr::band_angle(t.friction_angle),
            100.0 * o.energy_error,
            o.steps,
            o.run.wall,
            o.run.provenance()
        );
    }
    for o in runs.iter().filter(|o| o.mesh == unstructured.label()) {
        let t = o.test;
        let name = format!("Test {}", t.number);
        report.check(
            c,
            &format!("energy balance, {name} (|balance| / work)"),
            "0".into(),
            format!("{:.2}%", 100.0 * o.energy_error),
            "< 2%",
            o.energy_error < 0.02,
            Kind::Gate,
        );
        let reach = femdem_post::mohr::reach(s, t.cohesion, t.friction_angle);
        let modes = o.modes();
        if reach >= 1.0 {
            report.check(
                c,
                &format!("shear fractures, {name} (circle reach {reach:.3})"),
                "shear-dominated failure (Fig. 10-11)".into(),
                format!(
                    "{} failures, {:.0}% shear ({})",
                    modes.total(),
                    100.0 * modes.share(FailureMode::Shear),
                    modes.text()
                ),
                "> 50% shear",
                modes.share(FailureMode::Shear) > 0.5,
                gate_paper,
            );
            let expected = femdem_post::mohr::band_angle(t.friction_angle);
            let within = |a: f64| (a - expected).abs() <= ANGLE_TOLERANCE;
            let found = bands::bands(&o.shear, width);
            let sets: [(&str, String, PickBand, Kind); 2] = [
                ("main", format!("{expected:.1}° (45° + φ/2, Eq. 24)"), |b| b.0, Kind::Gate),
                ("conjugate", format!("{expected:.1}°, mirrored (Fig. 10-11)"), |b| b.1, gate_paper),
            ];
            if let Some((main, _)) = found {
                let m = bands::mirrored(&o.shear, main, width);
                report.check(
                    c,
                    &format!("mirrored family beside the main band, {name} (its faces set aside)"),
                    format!("{expected:.1}°, mirrored (Fig. 10-11)"),
                    m.map_or("no shear failure outside the main band".into(), |b| {
                        format!(
                            "{:.0}° ({:.0}% of the shear area; scattered failures score about 20-28%)",
                            b.angle_to_x(),
                            100.0 * b.share
                        )
                    }),
                    "±8°",
                    m.is_some_and(|b| within(b.angle_to_x())),
                    Kind::Info,
                );
            }
            for (set, reference, pick, kind) in sets {
                let band = found.as_ref().map(pick);
                report.check(
                    c,
                    &format!("{set} shear band angle to σ1 (x), {name}"),
                    reference,
                    band.map_or("no shear failure".into(), |b| {
                        format!("{:.0}° ({:.0}% of the shear area)", b.angle_to_x(), 100.0 * b.share)
                    }),
                    "±8°",
                    band.is_some_and(|b| within(b.angle_to_x())),
                    kind,
                );
            }
        } else {
            report.check(
                c,
                &format!("{name}: the applied circle stays below the envelope (reach {reach:.3})"),
                "the paper shows shear bands (Fig. 12)".into(),
                format!("{} failures ({})", modes.total(), modes.text()),
                "reported",
                true,
                Kind::Info,
            );
        }
    }
    let angle = |o: &Outcome| bands::facet_angle(&o.shear);
    let unstr: Vec<&Outcome> = runs.iter().filter(|o| o.mesh == unstructured.label()).collect();
    if let [u1, u2, ..] = unstr[..]
        && let (Some(a1), Some(a2)) = (angle(u1), angle(u2))
    {
        report.check(
            c,
            "facet angle falls with φ (Test 1 > Test 2)",
            format!(
                "{:.1}° > {:.1}°",
                femdem_post::mohr::band_angle(TESTS[0].friction_angle),
                femdem_post::mohr::band_angle(TESTS[1].friction_angle)
            ),
            format!("{a1:.1}° vs {a2:.1}°"),
            "strict",
            a1 > a2,
            gate_paper,
        );
    }
    for t in TESTS {
        let on = |label: String| runs.iter().find(|o| o.mesh == label && o.test.number == t.number);
        let (Some(l), Some(u)) = (on(lattice.label()), on(unstructured.label())) else {
            continue;
        };
        let describe = |o: &Outcome| {
            let main = bands::bands(&o.shear, width).map_or("—".into(), |b| format!("{:.0}°", b.0.angle_to_x()));
            match angle(o) {
                Some(a) => format!("band {main}, facets {a:.1}° ({})", o.modes().text()),
                None => format!("no shear failure ({})", o.modes().text()),
            }
        };
        report.check(
            c,
            &format!("mesh bias, Test {}: lattice against unstructured", t.number),
            format!("{:.1}° on both (no preferred direction)", femdem_post::mohr::band_angle(t.friction_angle)),
            format!("lattice: {}; unstructured: {}", describe(l), describe(u)),
            "reported",
            true,
            Kind::Info,
        );
    }
    // Figures: Mohr circles, and each run's failed faces seen along z.
    let figs = out.join("figures");
    std::fs::create_dir_all(&figs)?;
    let materials: Vec<(String, f64, f64)> = TESTS
        .iter()
        .map(|t| {
            (
                format!("Test {} (c = {} MPa, φ = {}°)", t.number, 1e-6 * t.cohesion, t.friction_angle),
                t.cohesion,
                t.friction_angle,
            )
        })
        .collect();
    mohr::figure(&figs.join("polyaxial_mohr.png"), s, &materials)?;
    md.push_str("\n![Mohr circles](figures/polyaxial_mohr.png)\n");
    for o in &runs {
        let name = format!(
            "polyaxial_fractures_{}.png",
            o.run.dir.parent().and_then(|d| d.file_name()).map_or("run".into(), |d| d.to_string_lossy().into_owned())
        );
        let tris: Vec<([(f64, f64); 3], RGBColor)> = o.faces.iter().map(|(p, m)| (*p, mode_colour(*m))).collect();
        plot::triangles(
            &figs.join(&name),
            &format!("Test {}, {}: failed faces along z (σ1 along x)", o.test.number, o.mesh),
            ("x (m)", "y (m)"),
            (-0.02..0.52, -0.02..0.52),
            &tris,
            &mode_legend(),
            true,
        )?;
        let _ = writeln!(md, "\n![Test {} {}](figures/{name})", o.test.number, o.mesh);
    }
    report.sections.push(md);
    Ok(())
}
