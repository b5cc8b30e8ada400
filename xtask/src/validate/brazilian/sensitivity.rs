//! What moves the Brazilian strength: one change at a time from the
//! baseline at the fastest rate, each a full run, f_bt compared with the
//! baseline's. The causes the issue lists: the joint penalty p0, the
//! Eq. 11 coupling, the platens' friction, the contact penalty, damping,
//! the element size, and an unstructured (Gmsh) disc instead of extruded
//! prisms.

use std::fmt::Write as _;
use std::path::Path;

use anyhow::Result;
use toml::Table;

use super::analysis::Outcome;
use super::case::{Base, Mesh, set_contact, set_gmsh_disc, set_material, set_platen_friction};
use crate::validate::runner::Femdem;

/// The rate the variants run at, m/s (the baseline's is the same run as
/// the rate study's fastest).
pub const RATE: f64 = 0.1;

type Tweak = Box<dyn Fn(&mut Table)>;

/// The variants: name, what changes, the mesh, the change.
fn variants(base: &Base, mesh: Mesh) -> Vec<(&'static str, String, Mesh, Tweak)> {
    let e = base.disc.young;
    let finer = Mesh { element_size: 0.75 * mesh.element_size, layers: mesh.layers + 1, gmsh: None, ..mesh };
    vec![
        (
            "p0 = E",
            format!("joint penalty p0 = {e:.2e} Pa instead of 10 E"),
            mesh,
            Box::new(move |t: &mut Table| set_material(t, "penalty", e.into())),
        ),
        (
            "coupling multiplicative",
            "Eq. 11 coupling `multiplicative` instead of `printed`".into(),
            mesh,
            Box::new(|t: &mut Table| set_material(t, "joint_coupling", "multiplicative".into())),
        ),
        (
            "coupling capped",
            "Eq. 11 coupling `capped` instead of `printed`".into(),
            mesh,
            Box::new(|t: &mut Table| set_material(t, "joint_coupling", "capped".into())),
        ),
        (
            "platen friction 0",
            "disc–platen friction 0 instead of 0.1".into(),
            mesh,
            Box::new(|t: &mut Table| set_platen_friction(t, 0.0)),
        ),
        (
            "contact penalty 10 E",
            format!("contact penalty {:.2e} Pa instead of E", 10.0 * e),
            mesh,
            Box::new(move |t: &mut Table| set_contact(t, "penalty", (10.0 * e).into())),
        ),
        (
            "no damping",
            "damping_ratio 0 instead of 0.05".into(),
            mesh,
            Box::new(|t: &mut Table| set_material(t, "damping_ratio", 0.0.into())),
        ),
        (
            "finer mesh",
            format!("{} mm triangles, {} layers", 1e3 * finer.element_size, finer.layers),
            finer,
            Box::new(|_: &mut Table| {}),
        ),
        (
            "unstructured 4 mm",
            "Gmsh tets of 4 mm target size (cases/paper/meshes/disc-4mm.msh) instead of extruded prisms".into(),
            mesh,
            Box::new(|t: &mut Table| set_gmsh_disc(t, "disc-4mm.msh")),
        ),
        (
            "unstructured 2 mm",
            "Gmsh tets of 2 mm target size (disc-2mm.msh), platens 2 mm".into(),
            Mesh { platen_size: 2.0e-3, ..mesh },
            Box::new(|t: &mut Table| set_gmsh_disc(t, "disc-2mm.msh")),
        ),
    ]
}

/// Runs the variants and returns their Markdown section.
pub fn run(femdem: &Femdem, base: &Base, mesh: Mesh, dir: &Path, baseline: &Outcome) -> Result<String> {
    let mut md = format!(
        "\n### What moves f_bt (V = {RATE} m/s, one change at a time)\n\n| variant | change | peak F (N) | f_bt (MPa) | Δ f_bt | central T/S/M/C | first failure | wall (s) |\n|---|---|---|---|---|---|---|---|\n"
    );
    let row = |md: &mut String, name: &str, change: &str, o: &Outcome| {
        let first =
            o.first_failure().map_or("none".into(), |f| format!("mode {:?} at y = {:.1} mm", f.mode, 1e3 * f.at[1]));
        let _ = writeln!(
            md,
            "| {name} | {change} | {:.0} | {:.3} | {:+.1}% | {} | {first} | {:.0} |",
            o.peak,
            1e-6 * o.f_bt,
            100.0 * (o.f_bt / baseline.f_bt - 1.0),
            o.central(base.disc.geometry()).text(),
            o.run.wall
        );
    };
    row(&mut md, "baseline", "the case as bundled, on this profile's mesh", baseline);
    for (name, change, m, tweak) in variants(base, mesh) {
        let title = format!("Brazilian disc, V_y = {RATE} m/s, sensitivity: {name} (cargo xtask validate)");
        let case = base.case(&title, m, RATE, &*tweak)?;
        let slug = super::case::slug(name);
        let run = femdem.run(&dir.join(format!("sensitivity_{slug}")), "brazilian", &case)?;
        row(&mut md, name, &change, &Outcome::read(run, base.disc)?);
    }
    Ok(md)
}
