//! Is the crushing onset converged? On a fine disc the first load drop of
//! a Brazilian run is the first crushing event under a platen, before the
//! split; this study moves one thing at a time — the platens' tets, the
//! contact penalty, the platen friction, the disc's mesh near the platens —
//! and compares the load at the first drop with the difference between two
//! meshes of the same size and type (the same disc turned 0.3 rad about its
//! axis before meshing). One such difference is a scale, not a
//! distribution: a change that does nothing exceeds it half the time, so
//! the table gives each change's shift as a multiple of it, and only a
//! shift of several times it says the onset moved. Each run ends at its
//! first 5% drop (`[output.load_strain] stop_below_peak = 0.95`).

use std::fmt::Write as _;
use std::path::Path;

use anyhow::{Result, bail};
use toml::{Table, Value};

use super::analysis::{DROP, Outcome};
use super::case::{Base, MAX_STRAIN, Mesh, set_contact, set_platen_friction, set_single_frame, slug};
use crate::validate::runner::Femdem;

/// Platen speed of the runs, m/s (the paper's fastest rate).
pub const RATE: f64 = 0.1;

/// The Gmsh discs of the study, in `cases/paper/meshes` (made by its
/// `regenerate.py`): the baseline, the same disc turned before meshing,
/// and the baseline refined to 0.6 mm within 3 mm of the loaded points.
const BASELINE: &str = "disc-1.2mm.msh";
const TURNED: &str = "disc-1.2mm-turned.msh";
const REFINED: &str = "disc-1.2mm-platens-0.6mm.msh";

type Tweak = Box<dyn Fn(&mut Table)>;

/// The variants, the dearest last (a smaller step: contact ×10, the
/// refined disc), so that an interrupted study has the cheap ones.
fn variants(base: &Base, mesh: Mesh) -> Vec<(&'static str, String, Mesh, Tweak)> {
    let p = base.disc.contact_penalty;
    let on = |file: &'static str| Mesh { gmsh: Some(file), ..mesh };
    vec![
        ("baseline", format!("{BASELINE}, as bundled"), on(BASELINE), Box::new(|_: &mut Table| {})),
        ("turned mesh", format!("{TURNED}: the disc turned 0.3 rad before meshing"), on(TURNED), Box::new(|_| {})),
        (
            "platens' tets halved",
            format!("platen tets of {} mm instead of {} mm", 0.5e3 * mesh.platen_size, 1e3 * mesh.platen_size),
            Mesh { platen_size: 0.5 * mesh.platen_size, ..on(BASELINE) },
            Box::new(|_| {}),
        ),
        (
            "platen friction 0.6",
            "disc–platen friction 0.6 instead of 0.1".into(),
            on(BASELINE),
            Box::new(|t| set_platen_friction(t, 0.6)),
        ),
        (
            "platen friction 0",
            "disc–platen friction 0 instead of 0.1".into(),
            on(BASELINE),
            Box::new(|t| set_platen_friction(t, 0.0)),
        ),
        (
            "contact ×10",
            format!("contact penalty {:.2e} Pa instead of {p:.2e}", 10.0 * p),
            on(BASELINE),
            Box::new(move |t| set_contact(t, "penalty", (10.0 * p).into())),
        ),
        (
            "disc refined at the platens",
            format!("{REFINED}: 0.6 mm tets within 3 mm of the loaded points"),
            on(REFINED),
            Box::new(|_| {}),
        ),
    ]
}

/// Ends the run at its first drop of [`DROP`] after a failure, with a
/// single frame at the end.
fn stop_at_first_drop(t: &mut Table) {
    set_single_frame(t);
    let ls = t.get_mut("output").and_then(|o| o.get_mut("load_strain")).and_then(Value::as_table_mut);
    if let Some(ls) = ls {
        ls.insert("stop_below_peak".into(), (1.0 - DROP).into());
    }
}

/// The load at a run's first drop and its time: where the history's rows
/// fall by [`DROP`], or, for a run that stopped at its drop between two
/// rows (the stop rule watches every step, the rows every 2·10⁻⁶ of
/// strain), its largest recorded load; none for a run that reached its end
/// strain without one.
fn first_drop(o: &Outcome) -> Option<(f64, f64)> {
    let stopped = o.curve.last().is_some_and(|c| c.0 < 0.99 * MAX_STRAIN);
    o.first_drop.or_else(|| stopped.then_some((o.peak, o.peak_time)))
}

/// The variants named in `only` (by their run directories' slugs, e.g.
/// `contact__10`), or all of them; an unknown name is an error listing the
/// names.
fn chosen(
    all: Vec<(&'static str, String, Mesh, Tweak)>,
    only: Option<&[String]>,
) -> Result<Vec<(&'static str, String, Mesh, Tweak)>> {
    let Some(only) = only else { return Ok(all) };
    let names: Vec<String> = all.iter().map(|v| slug(v.0)).collect();
    if let Some(bad) = only.iter().find(|o| !names.contains(o)) {
        bail!("--variants: no crushing-onset variant `{bad}`; the variants: {}", names.join(", "));
    }
    Ok(all.into_iter().zip(names).filter(|(_, n)| only.contains(n)).map(|(v, _)| v).collect())
}

/// Runs the study on the 1.2 mm Gmsh discs (only the variants `only`
/// names, where given) and returns its Markdown section.
pub fn run(femdem: &Femdem, base: &Base, mesh: Mesh, only: Option<&[String]>, dir: &Path) -> Result<String> {
    let disc = base.disc;
    let mut rows = Vec::new();
    for (name, change, m, tweak) in chosen(variants(base, mesh), only)? {
        let title = format!("Brazilian disc, V_y = {RATE} m/s, crushing onset: {name} (cargo xtask validate)");
        let case = base.case(&title, m, RATE, &|t: &mut Table| {
            tweak(t);
            stop_at_first_drop(t);
        })?;
        let run = femdem.run(&dir.join(format!("onset_{}", slug(name))), "brazilian", &case)?;
        rows.push((name, change, Outcome::read(run, disc)?));
    }
    let first = |o: &Outcome| first_drop(o).map(|(f, t)| (f, t, o.failures.iter().filter(|x| x.time <= t).count()));
    let drop = |name: &str| rows.iter().find(|r| r.0 == name).and_then(|r| first(&r.2)).map(|d| d.0);
    let (base_drop, spread) = match (drop("baseline"), drop("turned mesh")) {
        (Some(a), Some(b)) => (Some(a), Some((a - b).abs())),
        (a, _) => (a, None),
    };
    let mut md = format!(
        "\n### Is the crushing onset converged? (V = {RATE} m/s, each run to its first {:.0}% drop)\n\n\
         The baseline and the turned mesh are two meshes of the same size and type; each change's shift is \
         given as a multiple of their difference (one difference is a scale, not a distribution: only a \
         shift of several times it says the onset moved).\n\n\
         | variant | change | first failure at F (N) | first drop F (N) | f_bt there (MPa) | against the baseline | shift / the meshes' difference | strain (‰) | failures before it (T/S/M/C) | steps | wall (s) |\n\
         |---|---|---|---|---|---|---|---|---|---|---|\n",
        100.0 * DROP
    );
    for (name, change, o) in &rows {
        let first_failure = o.first_failure().map_or("none".into(), |x| format!("{:.0}", o.load_at(x.time)));
        // Where the rows show no 5% fall, the drop is the stop's.
        let marked = if o.first_drop.is_none() { " (stopped)" } else { "" };
        let Some((f, t, _)) = first(o) else {
            let _ = writeln!(
                md,
                "| {name} | {change} | {first_failure} | no drop by the end | — | — | — | — | {} | {} | {:.0} |",
                o.modes().text(),
                o.steps,
                o.run.wall
            );
            continue;
        };
        let strain = o.strain_at_time(t).unwrap_or(f64::NAN);
        let before = femdem_post::failures::Modes::of(o.failures.iter().filter(|x| x.time <= t));
        let delta = base_drop.map_or("—".into(), |b| format!("{:+.1}%", 100.0 * (f / b - 1.0)));
        let beyond = match (base_drop, spread) {
            (Some(b), Some(s)) if *name != "baseline" && *name != "turned mesh" && s > 0.0 => {
                format!("{:.1}", (f - b).abs() / s)
            }
            _ => "—".into(),
        };
        let _ = writeln!(
            md,
            "| {name} | {change} | {first_failure} | {f:.0}{marked} | {:.3} | {delta} | {beyond} | {:.3} | {} | {} | {:.0}{} |",
            1e-6 * disc.geometry().f_bt(f),
            1e3 * strain,
            before.text(),
            o.steps,
            o.run.wall,
            o.run.provenance()
        );
    }
    if let (Some(b), Some(s)) = (base_drop, spread) {
        let _ = writeln!(md, "\nThe meshes' difference: {s:.0} N ({:.1}% of the baseline's {b:.0} N).", 100.0 * s / b);
    }
    Ok(md)
}

#[cfg(test)]
mod tests {
    use super::{REFINED, chosen, stop_at_first_drop, variants};
    use crate::validate::brazilian::case::{Base, Mesh};
    use toml::Table;

    fn parsed(text: &str) -> Table {
        text.parse().unwrap()
    }

    /// Every variant's disc file exists, each changes what it says, and
    /// every run stops at its first 5% drop.
    #[test]
    fn the_variants_change_one_thing_and_stop_at_the_first_drop() {
        let base = Base::load().unwrap();
        let mesh = Mesh { element_size: 1.2e-3, layers: 10, platen_size: 2.0e-3, gmsh: None };
        for (name, _, m, tweak) in variants(&base, mesh) {
            let t = parsed(
                &base
                    .case(name, m, super::RATE, &|t: &mut Table| {
                        tweak(t);
                        stop_at_first_drop(t);
                    })
                    .unwrap(),
            );
            let path = t["mesh"]["parts"][0]["path"].as_str().unwrap();
            assert!(std::path::Path::new(path).is_file(), "{name}: {path}");
            assert_eq!(t["output"]["load_strain"]["stop_below_peak"].as_float(), Some(0.95), "{name}");
            let platen = t["mesh"]["parts"][1]["element_size"].as_float().unwrap();
            assert_eq!(platen, if name == "platens' tets halved" { 1.0e-3 } else { 2.0e-3 }, "{name}");
            assert_eq!(path.ends_with(REFINED), name == "disc refined at the platens", "{name}");
            let friction = t["contact"]["pairs"][0]["friction"].as_float().unwrap();
            let expected = match name {
                "platen friction 0.6" => 0.6,
                "platen friction 0" => 0.0,
                _ => 0.1,
            };
            assert_eq!(friction, expected, "{name}");
        }
    }

    #[test]
    fn variants_are_chosen_by_their_run_directories_names() {
        let base = Base::load().unwrap();
        let mesh = Mesh { element_size: 1.2e-3, layers: 10, platen_size: 2.0e-3, gmsh: None };
        let all = || variants(&base, mesh);
        assert_eq!(chosen(all(), None).unwrap().len(), all().len());
        let only = ["contact__10".to_owned(), "disc_refined_at_the_platens".to_owned()];
        let names: Vec<&str> = chosen(all(), Some(&only)).unwrap().iter().map(|v| v.0).collect();
        assert_eq!(names, ["contact ×10", "disc refined at the platens"]);
        let e = chosen(all(), Some(&["contact".to_owned()])).err().unwrap().to_string();
        assert!(e.contains("`contact`") && e.contains("contact__10") && e.contains("baseline"), "{e}");
    }
}
