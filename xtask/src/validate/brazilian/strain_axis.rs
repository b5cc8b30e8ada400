//! What the strain of a Brazilian run's load–strain curve (ε_yy = Δa/d,
//! Eq. 22) consists of before the disc breaks: the disc's elasticity, the
//! joints' penalty compliance (Eq. 9) and the platen contact's penetration
//! (Eq. 17), each measured by runs that change one of them, against the
//! closed form of a disc between flat rigid platens
//! ([`femdem_post::diametral`]); and which reading of the paper's strain
//! unit (Fig. 6–7: "%" or ‰) that is consistent with.
//!
//! The decomposition at each load F:
//! - joints = ε(as bundled) − ε(no joints), both at the bundled contact
//!   penalty;
//! - the disc with rigid contact, ε∞: the no-joint runs at contact
//!   penalties p, 10 p and 100 p fitted exactly by ε = ε∞ + c p^(−α)
//!   (three points, three unknowns);
//! - contact = ε(no joints, p) − ε∞.
//!
//! The joints' share is checked by the run at p0 = 2 E (the low end of
//! Eq. 9's range): a joint's opening under a stress is σ h / p0, so their
//! share should scale as 1/p0.

use std::fmt::Write as _;
use std::path::Path;

use anyhow::Result;
use toml::Table;

use super::PAPER_PEAK;
use super::analysis::Outcome;
use super::case::{
    Base, Mesh, set_contact, set_end_strain, set_gmsh_disc, set_material, set_single_frame, set_unbreakable, slug,
};
use crate::validate::plot;
use crate::validate::runner::Femdem;
use femdem_post::diametral::{self, Elastic, Plane};

/// Platen speed of the runs, m/s: the loads are reached in a few thousand
/// steps. The `0.1 m/s` variant repeats the bundled case at the paper's
/// fastest rate to show that the strains do not depend on it.
pub const RATE: f64 = 0.5;
/// The rate of that check, m/s.
const SLOW: f64 = 0.1;
/// Where every run ends at the latest, ε_yy (Eq. 22): past the first
/// failure of the bundled case on the 4 mm and 1.2 mm discs.
const END_STRAIN: f64 = 2.5e-3;
/// The loads compared, as fractions of F_t = π d t f_t / 2, the load whose
/// Hondros centre stress σx = 2F/(πdt) is f_t.
const LOADS: [f64; 3] = [0.15, 0.3, 0.45];
/// The strain printed under the paper's Fig. 7a ("before fracture
/// initiation", V = 0.01 m/s), in the paper's printed unit.
const PAPER_FIG7A: f64 = 1.03;

type Tweak = Box<dyn Fn(&mut Table)>;
/// A run's strain, and the joints failed by then, where the load first
/// reaches F: `(run key, F)`.
type StrainAt<'a> = dyn Fn(&str, f64) -> Option<(f64, usize)> + 'a;

/// One run of the study.
struct Variant {
    key: &'static str,
    change: String,
    rate: f64,
    tweak: Tweak,
}

fn variants(base: &Base, gmsh: &'static str) -> Vec<Variant> {
    let (e, p) = (base.disc.young, base.disc.contact_penalty);
    let v = |key, change: String, rate, tweak: Tweak| Variant { key, change, rate, tweak };
    // No joints, and the contact penalty times `k`.
    let stiff = move |k: f64| -> Tweak {
        Box::new(move |t| {
            set_unbreakable(t);
            set_contact(t, "penalty", (k * p).into());
        })
    };
    vec![
        v(
            "as bundled",
            format!("joints p0 = {:.2e} Pa, contact penalty {p:.2e} Pa", base.disc.joint_penalty),
            RATE,
            Box::new(|_| {}),
        ),
        v("0.1 m/s", format!("as bundled at V = {SLOW} m/s"), SLOW, Box::new(|_| {})),
        v("no joints", "the disc unbreakable (no joints, shared nodes)".into(), RATE, Box::new(set_unbreakable)),
        v("no joints, contact ×10", format!("no joints, contact penalty {:.2e} Pa", 10.0 * p), RATE, stiff(10.0)),
        v("no joints, contact ×100", format!("no joints, contact penalty {:.2e} Pa", 100.0 * p), RATE, stiff(100.0)),
        v(
            "p0 = 2 E",
            format!("joints p0 = {:.2e} Pa (the low end of Eq. 9's 2E–10E)", 2.0 * e),
            RATE,
            Box::new(move |t| set_material(t, "penalty", (2.0 * e).into())),
        ),
        v(
            "unstructured",
            format!("as bundled on the Gmsh disc cases/paper/meshes/{gmsh}"),
            RATE,
            Box::new(move |t| set_gmsh_disc(t, gmsh)),
        ),
        v(
            "unstructured, no joints, contact ×100",
            format!("the Gmsh disc {gmsh}, no joints, contact penalty {:.2e} Pa", 100.0 * p),
            RATE,
            Box::new(move |t| {
                set_gmsh_disc(t, gmsh);
                stiff(100.0)(t);
            }),
        ),
    ]
}

/// The strain where the load first reaches `f` (linear between history
/// rows), and how many joints had failed by then.
fn strain_at(o: &Outcome, f: f64) -> Option<(f64, usize)> {
    let i = o.curve.iter().position(|c| c.1 >= f).filter(|&i| i > 0)?;
    let (a, b) = (o.curve[i - 1], o.curve[i]);
    let strain = a.0 + (b.0 - a.0) * (f - a.1) / (b.1 - a.1);
    Some((strain, o.failures.iter().filter(|x| x.time <= o.time[i]).count()))
}

/// The strain of the first joint failure, if one failed by the run's end.
fn strain_at_failure(o: &Outcome) -> Option<f64> {
    o.strain_at_time(o.first_failure()?.time)
}

/// The rigid-contact limit ε∞ and the exponent α of
/// `ε = ε∞ + c p^(−α)` through the strains at penalties p, 10 p, 100 p:
/// `q = 10^(−α) = (ε₁₀ − ε₁₀₀) / (ε₁ − ε₁₀)`; none unless 0 < q < 1.
fn rigid_limit(e1: f64, e10: f64, e100: f64) -> Option<(f64, f64)> {
    let q = (e10 - e100) / (e1 - e10);
    (q > 0.0 && q < 1.0).then(|| (e1 - (e1 - e10) / (1.0 - q), -q.log10()))
}

fn permille(e: Option<(f64, usize)>) -> String {
    match e {
        Some((e, 0)) => format!("{:.3}", 1e3 * e),
        Some((e, n)) => format!("{:.3} ({n} failed)", 1e3 * e),
        None => "—".into(),
    }
}

/// Runs the study on `mesh` (and on the Gmsh disc `gmsh` of the same size)
/// and returns its Markdown section; the figure goes to `figures`.
pub fn run(femdem: &Femdem, base: &Base, mesh: Mesh, gmsh: &'static str, dir: &Path, figures: &Path) -> Result<String> {
    let disc = base.disc;
    let elastic = Elastic { young: disc.young, poisson: disc.poisson };
    let geometry = disc.geometry();
    let f_t = std::f64::consts::PI * disc.diameter * disc.thickness * disc.tensile_strength / 2.0;
    let loads: Vec<f64> = LOADS.iter().map(|s| (s * f_t).round()).collect();
    let mut runs: Vec<(Variant, Outcome)> = Vec::new();
    for variant in variants(base, gmsh) {
        let title = format!("Brazilian disc, strain axis: {} (cargo xtask validate --strain-axis)", variant.key);
        let rate = variant.rate;
        let tweak = |t: &mut Table| {
            (variant.tweak)(t);
            set_end_strain(t, END_STRAIN, rate, disc.diameter);
            set_single_frame(t);
        };
        let case = base.case(&title, mesh, rate, &tweak)?;
        let run = femdem.run(&dir.join(format!("strain_{}", slug(variant.key))), "brazilian", &case)?;
        let outcome = Outcome::read(run, disc)?;
        runs.push((variant, outcome));
    }
    let at = |key: &str, f: f64| runs.iter().find(|(v, _)| v.key == key).and_then(|(_, o)| strain_at(o, f));
    let closed = |plane, f| diametral::strain(geometry, elastic, plane, f);

    let mut md = format!(
        "\n### What the strain consists of (ε_yy of Eq. 22 before failure, V = {RATE} m/s)\n\n\
         Strains (‰) where the load first reaches F; \"(n failed)\" where joints had already failed. \
         The closed form is `femdem_post::diametral` (a disc between flat rigid platens, Johnson §5.6), \
         plane stress and plane strain bounding the {} mm thick disc.\n\n| variant | change |",
        1e3 * disc.thickness
    );
    for f in &loads {
        let _ = write!(md, " ε at {f:.0} N |");
    }
    md.push_str(" ε at the paper's peak load | ε at the first failure | steps | wall (s) |\n|---|---|");
    md.push_str(&"---|".repeat(loads.len() + 4));
    md.push('\n');
    for (plane, name) in [(Plane::Stress, "plane stress"), (Plane::Strain, "plane strain")] {
        let _ = write!(md, "| closed form, {name} | elastic disc, rigid platens |");
        for &f in loads.iter().chain([&PAPER_PEAK]) {
            let _ = write!(md, " {:.3} |", 1e3 * closed(plane, f));
        }
        md.push_str(" — | — | — |\n");
    }
    for (v, o) in &runs {
        let _ = write!(md, "| {} | {} |", v.key, v.change);
        for &f in loads.iter().chain([&PAPER_PEAK]) {
            let _ = write!(md, " {} |", permille(strain_at(o, f)));
        }
        let first = strain_at_failure(o).map_or("none".into(), |e| format!("{:.3}", 1e3 * e));
        let _ = writeln!(md, " {first} | {} | {:.0}{} |", o.steps, o.run.wall, o.run.provenance());
    }

    md.push_str(
        "\nThe decomposition at each load (‰): the disc with rigid contact (the no-joint runs' three contact \
         penalties fitted by ε∞ + c p^(−α)), the contact's penetration at the bundled penalty, the joints' \
         compliance at the bundled p0; their sum is the bundled case's strain by construction. The last columns \
         check the joints' share against the p0 = 2 E run (1/p0 scaling) and the rate.\n\n\
         | F (N) | closed form (strain – stress) | disc, rigid contact ε∞ (α) | + contact | + joints | = as bundled | p0 = 2 E: predicted / measured | 0.1 m/s against 0.5 m/s |\n\
         |---|---|---|---|---|---|---|---|\n",
    );
    let scale = disc.joint_penalty / (2.0 * disc.young) - 1.0;
    for &f in &loads {
        let cell = |x: Option<f64>| x.map_or("—".into(), |x| format!("{:.3}", 1e3 * x));
        let plain = |key: &str| at(key, f).filter(|x| x.1 == 0).map(|x| x.0);
        let (bundled, nj) = (plain("as bundled"), plain("no joints"));
        let fit = match (nj, plain("no joints, contact ×10"), plain("no joints, contact ×100")) {
            (Some(a), Some(b), Some(c)) => rigid_limit(a, b, c),
            _ => None,
        };
        let joints = bundled.zip(nj).map(|(b, n)| b - n);
        let predicted = bundled.zip(joints).map(|(b, j)| b + scale * j);
        let slow = plain("0.1 m/s").zip(bundled).map(|(s, b)| format!("{:+.1}%", 100.0 * (s / b - 1.0)));
        let _ = writeln!(
            md,
            "| {f:.0} | {:.3} – {:.3} | {} | {} | {} | {} | {} / {} | {} |",
            1e3 * closed(Plane::Strain, f),
            1e3 * closed(Plane::Stress, f),
            fit.map_or("—".into(), |(e, a)| format!("{:.3} ({a:.2})", 1e3 * e)),
            cell(nj.zip(fit).map(|(n, (e, _))| n - e)),
            cell(joints),
            cell(bundled),
            cell(predicted),
            cell(plain("p0 = 2 E")),
            slow.unwrap_or("—".into()),
        );
    }

    md.push_str(&paper_unit(&at, (closed(Plane::Strain, PAPER_PEAK), closed(Plane::Stress, PAPER_PEAK))));
    md.push('\n');

    // Eight series, the palette's size: the 0.1 m/s run lies on the bundled
    // one and plane strain within 1 − ν² of plane stress (both in the tables).
    let mut series: Vec<(String, Vec<(f64, f64)>)> = runs
        .iter()
        .filter(|(v, _)| v.rate == RATE)
        .map(|(v, o)| {
            let upto = o.curve.iter().take_while(|c| c.0 <= END_STRAIN);
            (v.key.to_owned(), upto.map(|(e, f)| (1e3 * e, 1e-3 * f)).collect())
        })
        .collect();
    let top = runs.iter().map(|(_, o)| o.peak).fold(0.0, f64::max);
    let curve = (0..=60).map(|i| top * i as f64 / 60.0).map(|f| (1e3 * closed(Plane::Stress, f), 1e-3 * f));
    series.push(("closed form, plane stress".to_owned(), curve.filter(|p| p.0 <= 1e3 * END_STRAIN).collect()));
    plot::lines(
        &figures.join("brazilian_strain_axis.png"),
        "Brazilian disc: what the strain consists of",
        "strain ε_yy (‰)",
        "load F (kN)",
        &series,
    )?;
    md.push_str("\n![strain axis](figures/brazilian_strain_axis.png)\n");
    Ok(md)
}

/// The paragraph on the paper's strain unit. Fig. 7a is "before fracture
/// initiation", at a load below the paper's peak, so its strain is at most
/// what the paper's disc shows at that peak. `at(key, F)` is a run's strain
/// at load F; `(strain, stress)` the closed form's strains at the peak.
fn paper_unit(at: &StrainAt, (strain, stress): (f64, f64)) -> String {
    let fig = 1e-3 * PAPER_FIG7A;
    let mut md = format!(
        "\nThe paper's unit. Fig. 7a (\"before fracture initiation\", V = 0.01 m/s) prints ε_yy = {PAPER_FIG7A}, \
         the later panels up to 4.15, with the unit %. Fig. 7a's load is below the paper's peak, {PAPER_PEAK} N, \
         where the closed form gives {:.3}–{:.3} ‰. Read as %, Fig. 7a's strain is {:.1} ‰ with nothing broken, \
         at least {:.1}× the elastic disc's; read as ‰, {:.2}–{:.2}× it.",
        1e3 * strain,
        1e3 * stress,
        1e4 * fig,
        10.0 * fig / stress,
        fig / stress,
        fig / strain
    );
    let keys = ["as bundled", "p0 = 2 E", "unstructured", "no joints"];
    let runs: Vec<(&str, f64, usize)> =
        keys.iter().filter_map(|k| at(k, PAPER_PEAK).map(|(e, n)| (*k, e, n))).collect();
    let range = runs.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |r, x| (r.0.min(x.1), r.1.max(x.1)));
    if runs.is_empty() {
        md.push_str(" No run reached that load.");
        return md;
    }
    let list: Vec<String> = runs
        .iter()
        .map(|(k, e, n)| {
            let failed = if *n > 0 { format!(", {n} joints failed") } else { String::new() };
            format!("`{k}` {:.3} ‰{failed}", 1e3 * e)
        })
        .collect();
    md.push_str(&format!(" femdem's runs at that load: {}.", list.join("; ")));
    // A strain below the peak load may be anything up to the strain there.
    let verdict = if fig <= range.1 {
        "the ‰ reading is no more than the runs' strains at the paper's peak load, as a strain below that load must be"
    } else {
        "even the ‰ reading lies above every run's strain at the paper's peak load"
    };
    md.push_str(&format!(" So {verdict}, and the % reading is {:.1}× the most compliant run's.", 10.0 * fig / range.1));
    // How soft would contact have to be for the % reading: the contact
    // share at penalty p (no joints, fitted ε∞ + c p^(−α)) would have to
    // supply what the disc and the softest joints (p0 = 2 E) leave.
    let nj = |k: &str| at(k, PAPER_PEAK).filter(|x| x.1 == 0).map(|x| x.0);
    let fit = match (nj("no joints"), nj("no joints, contact ×10"), nj("no joints, contact ×100")) {
        (Some(a), Some(b), Some(c)) => rigid_limit(a, b, c).map(|f| (a, f)),
        _ => None,
    };
    if let (Some((e1, (inf, alpha))), Some(soft)) = (fit, at("p0 = 2 E", PAPER_PEAK)) {
        let contact = e1 - inf;
        let joints = soft.0 - e1;
        let needed = 10.0 * fig - inf - joints;
        if needed > contact && contact > 0.0 {
            let factor = (needed / contact).powf(1.0 / alpha);
            md.push_str(&format!(
                " With the disc's {:.3} ‰ and the p0 = 2 E joints' {:.3} ‰, contact would have to give {:.2} ‰ where \
                 it gives {:.3} ‰ at the bundled penalty: with its fitted exponent α = {alpha:.2}, a contact penalty \
                 about {factor:.0}× lower (the paper does not give its contact penalty).",
                1e3 * inf,
                1e3 * joints,
                1e3 * needed,
                1e3 * contact
            ));
        }
    }
    md
}

#[cfg(test)]
mod tests {
    use super::rigid_limit;

    /// Three strains of ε∞ + c p^(−α) at p, 10 p, 100 p give back ε∞ and α;
    /// strains that do not fall geometrically give none.
    #[test]
    fn the_rigid_limit_inverts_a_power_law() {
        for (inf, c, alpha) in [(0.3e-3, 0.2e-3, 0.5), (1.0, 2.0, 1.0), (0.0, 1.0, 2.0 / 3.0)] {
            let e = |x: f64| inf + c * x.powf(-alpha);
            let (got, a) = rigid_limit(e(1.0), e(10.0), e(100.0)).unwrap();
            assert!((got - inf).abs() < 1e-12 * c.max(inf), "{got} vs {inf}");
            assert!((a - alpha).abs() < 1e-12, "{a} vs {alpha}");
        }
        assert!(rigid_limit(1.0, 0.5, 0.5).is_none());
        assert!(rigid_limit(1.0, 0.9, 0.7).is_none());
    }
}
