//! The Brazilian-disc cases the validation runs, made from the bundled
//! paper case `cases/paper/brazilian-to-failure.toml` (Guo et al. §3.1) by
//! changing only what a profile or a sensitivity variant names.

use anyhow::{Context, Result};
use toml::{Table, Value};

/// The bundled case every run starts from.
pub const BASE: &str = "cases/paper/brazilian-to-failure.toml";

/// Largest strain ε_yy (Eq. 22) a run may reach; the runs end earlier,
/// once the load has dropped to [`STOP_BELOW_PEAK`] of its peak.
pub const MAX_STRAIN: f64 = 0.005;
/// `[output.load_strain] stop_below_peak` of every run: a tenth, so that a
/// run goes on past the crushing under the platens until the disc has
/// split (at half the peak, the quick mesh is still crushing and the
/// central fracture has not formed).
const STOP_BELOW_PEAK: f64 = 0.1;
/// Strain between frames and between history rows.
const FRAME_STRAIN: f64 = 1.0e-4;
const ROW_STRAIN: f64 = 2.0e-6;

/// The mesh of a profile.
#[derive(Debug, Clone, Copy)]
pub struct Mesh {
    /// Target triangle edge in the disc plane, m.
    pub element_size: f64,
    /// Layers of prisms through the thickness.
    pub layers: i64,
    /// Element size of the rigid platens, m.
    pub platen_size: f64,
    /// The disc as unstructured Gmsh tets instead of the extrusion: a file
    /// of `cases/paper/meshes` (`element_size` and `layers` then unused).
    pub gmsh: Option<&'static str>,
}

impl Mesh {
    /// How the mesh is described in the report.
    pub fn describe(&self) -> String {
        match self.gmsh {
            Some(file) => {
                format!("unstructured Gmsh tets, cases/paper/meshes/{file} (platens {} mm)", 1e3 * self.platen_size)
            }
            None => format!(
                "{} mm triangles, {} layers (platens {} mm)",
                1e3 * self.element_size,
                self.layers,
                1e3 * self.platen_size
            ),
        }
    }
}

/// The disc's geometry, read from the base case.
#[derive(Debug, Clone, Copy)]
pub struct Disc {
    /// Diameter d, m.
    pub diameter: f64,
    /// Thickness t, m.
    pub thickness: f64,
    /// Input tensile strength f_t, Pa.
    pub tensile_strength: f64,
    /// Young's modulus E, Pa.
    pub young: f64,
    /// Poisson's ratio ν.
    pub poisson: f64,
    /// The joints' penalty p0, Pa.
    pub joint_penalty: f64,
    /// The contact penalty, Pa.
    pub contact_penalty: f64,
}

impl Disc {
    /// Its geometry, as `femdem_post` measures a disc.
    pub fn geometry(self) -> femdem_post::brazilian::Disc {
        femdem_post::brazilian::Disc { diameter: self.diameter, thickness: self.thickness }
    }
}

/// The base case, parsed.
#[derive(Debug, Clone)]
pub struct Base {
    table: Table,
    /// Its disc.
    pub disc: Disc,
}

fn get<'a>(t: &'a Table, path: &[&str]) -> Result<&'a Value> {
    let mut v: Option<&Value> = None;
    let mut table = t;
    for (i, key) in path.iter().enumerate() {
        let next = if let Ok(k) = key.parse::<usize>() {
            v.and_then(Value::as_array).and_then(|a| a.get(k))
        } else {
            table.get(*key)
        }
        .with_context(|| format!("{BASE}: no `{}`", path[..=i].join(".")))?;
        v = Some(next);
        if let Some(t) = next.as_table() {
            table = t;
        }
    }
    v.context("empty path")
}

fn num(t: &Table, path: &[&str]) -> Result<f64> {
    let v = get(t, path)?;
    v.as_float()
        .or_else(|| v.as_integer().map(|i| i as f64))
        .with_context(|| format!("{BASE}: `{}` is not a number", path.join(".")))
}

impl Base {
    /// Reads the base case from the workspace.
    pub fn load() -> Result<Base> {
        let text = std::fs::read_to_string(crate::root().join(BASE)).with_context(|| format!("reading {BASE}"))?;
        let table: Table = text.parse().with_context(|| format!("parsing {BASE}"))?;
        let disc = Disc {
            diameter: 2.0 * num(&table, &["mesh", "parts", "0", "circle", "radius"])?,
            thickness: num(&table, &["mesh", "parts", "0", "thickness"])?,
            tensile_strength: num(&table, &["materials", "0", "tensile_strength"])?,
            young: num(&table, &["materials", "0", "young"])?,
            poisson: num(&table, &["materials", "0", "poisson"])?,
            joint_penalty: num(&table, &["materials", "0", "penalty"])?,
            contact_penalty: num(&table, &["contact", "penalty"])?,
        };
        Ok(Base { table, disc })
    }

    /// The case at platen speed `velocity` (m/s) on `mesh`, after `tweak`
    /// (a sensitivity variant's change), as TOML text.
    pub fn case(&self, title: &str, mesh: Mesh, velocity: f64, tweak: &dyn Fn(&mut Table)) -> Result<String> {
        let mut t = self.table.clone();
        t.insert("title".into(), title.into());
        let parts = t["mesh"]["parts"].as_array().context("mesh.parts")?.len();
        for p in 0..parts {
            let part = t.get_mut("mesh").and_then(|m| m.get_mut("parts")).and_then(|a| a.get_mut(p)).context("part")?;
            let part = part.as_table_mut().context("part")?;
            if part.get("kind").and_then(Value::as_str) == Some("extrusion") {
                part.insert("element_size".into(), mesh.element_size.into());
                part.insert("layers".into(), mesh.layers.into());
            } else {
                part.insert("element_size".into(), mesh.platen_size.into());
            }
        }
        if let Some(file) = mesh.gmsh {
            set_gmsh_disc(&mut t, file);
        }
        let platens = t.get_mut("platens").and_then(Value::as_array_mut).context("platens")?;
        for p in platens.iter_mut() {
            let p = p.as_table_mut().context("platen")?;
            let sign = p["velocity"][1].as_float().context("platen velocity")?.signum();
            p.insert("velocity".into(), Value::Array(vec![0.0.into(), (sign * velocity).into(), 0.0.into()]));
        }
        // Strain rate of Eq. 22: both platens approach at `velocity`.
        let per_strain = self.disc.diameter / (2.0 * velocity);
        let ramp = t["platens"][0].get("ramp_time").and_then(Value::as_float).unwrap_or(0.0);
        let solver = t.get_mut("solver").and_then(Value::as_table_mut).context("solver")?;
        solver.insert("end_time".into(), (ramp + MAX_STRAIN * per_strain).into());
        let output = t.get_mut("output").and_then(Value::as_table_mut).context("output")?;
        output.insert("interval".into(), (FRAME_STRAIN * per_strain).into());
        output.insert("history_interval".into(), (ROW_STRAIN * per_strain).into());
        output.insert("fields".into(), Value::Array(vec!["displacement".into(), "stress".into(), "region".into()]));
        let ls = output.get_mut("load_strain").and_then(Value::as_table_mut).context("output.load_strain")?;
        ls.insert("stop_below_peak".into(), STOP_BELOW_PEAK.into());
        tweak(&mut t);
        Ok(format!(
            "# Generated by `cargo xtask validate` from {BASE}; run it with\n# `femdem run` to reproduce this validation run.\n{}",
            toml::to_string(&t)?
        ))
    }
}

/// Sets `materials[0].key` to `value`.
pub fn set_material(t: &mut Table, key: &str, value: Value) {
    if let Some(m) = t.get_mut("materials").and_then(|m| m.get_mut(0)).and_then(Value::as_table_mut) {
        m.insert(key.into(), value);
    }
}

/// Replaces the disc's extrusion (`mesh.parts[0]`) by the Gmsh mesh
/// `cases/paper/meshes/<file>` (one physical volume `disc`).
pub fn set_gmsh_disc(t: &mut Table, file: &str) {
    if let Some(part) =
        t.get_mut("mesh").and_then(|m| m.get_mut("parts")).and_then(|p| p.get_mut(0)).and_then(Value::as_table_mut)
    {
        part.clear();
        part.insert("kind".into(), "msh".into());
        part.insert("name".into(), "disc".into());
        let path = crate::root().join("cases/paper/meshes").join(file);
        part.insert("path".into(), path.to_string_lossy().into_owned().into());
    }
}

/// Makes the disc's region (`mesh.regions[0]`) unbreakable: no joints,
/// the tets share their nodes (plain continuous FEM).
pub fn set_unbreakable(t: &mut Table) {
    let region = t.get_mut("mesh").and_then(|m| m.get_mut("regions")).and_then(|r| r.get_mut(0));
    if let Some(r) = region.and_then(Value::as_table_mut) {
        r.insert("breakable".into(), false.into());
    }
}

/// Ends the run at strain `strain` (Eq. 22) of platens approaching at
/// `velocity` (m/s) each, after their ramp.
pub fn set_end_strain(t: &mut Table, strain: f64, velocity: f64, diameter: f64) {
    let ramp = t["platens"][0].get("ramp_time").and_then(Value::as_float).unwrap_or(0.0);
    let end = ramp + strain * diameter / (2.0 * velocity);
    if let Some(s) = t.get_mut("solver").and_then(Value::as_table_mut) {
        s.insert("end_time".into(), end.into());
    }
}

/// One frame, at the end time, for a study that reads the history only.
pub fn set_single_frame(t: &mut Table) {
    let end = t["solver"]["end_time"].as_float().unwrap_or(0.0);
    if let Some(o) = t.get_mut("output").and_then(Value::as_table_mut) {
        o.insert("interval".into(), end.into());
    }
}

/// A run's directory name from a variant's name: ASCII letters and digits
/// kept, anything else `_`.
pub fn slug(name: &str) -> String {
    name.chars().map(|c| if c.is_ascii_alphanumeric() { c } else { '_' }).collect()
}

/// Sets `[contact] key` to `value`.
pub fn set_contact(t: &mut Table, key: &str, value: Value) {
    if let Some(c) = t.get_mut("contact").and_then(Value::as_table_mut) {
        c.insert(key.into(), value);
    }
}

/// Sets the friction of every `[[contact.pairs]]` entry (disc–platen).
pub fn set_platen_friction(t: &mut Table, mu: f64) {
    if let Some(pairs) = t.get_mut("contact").and_then(|c| c.get_mut("pairs")).and_then(Value::as_array_mut) {
        for p in pairs.iter_mut().filter_map(Value::as_table_mut) {
            p.insert("friction".into(), mu.into());
        }
    }
}

#[cfg(test)]
mod tests {
    use super::{Base, Mesh, set_end_strain, set_unbreakable};
    use toml::{Table, Value};

    fn disc_part(text: &str) -> Table {
        let t: Table = text.parse().unwrap();
        t["mesh"]["parts"][0].as_table().unwrap().clone()
    }

    /// A profile's mesh reaches the case: the extrusion's size and layers,
    /// or the Gmsh file in place of the extrusion; the strain-axis changes
    /// end the run at a strain and make the disc unbreakable.
    #[test]
    fn the_disc_mesh_and_the_study_changes_reach_the_case() {
        let base = Base::load().unwrap();
        let extruded = Mesh { element_size: 4.0e-3, layers: 4, platen_size: 4.0e-3, gmsh: None };
        let part = disc_part(&base.case("t", extruded, 0.1, &|_| {}).unwrap());
        assert_eq!(part["kind"].as_str(), Some("extrusion"));
        assert_eq!(part["element_size"].as_float(), Some(4.0e-3));
        assert_eq!(part["layers"].as_integer(), Some(4));
        let gmsh = Mesh { gmsh: Some("disc-1.2mm.msh"), ..extruded };
        let part = disc_part(&base.case("t", gmsh, 0.1, &|_| {}).unwrap());
        assert_eq!(part["kind"].as_str(), Some("msh"));
        let path = part["path"].as_str().unwrap();
        assert!(path.ends_with("cases/paper/meshes/disc-1.2mm.msh") && std::path::Path::new(path).is_file(), "{path}");

        let tweak = |t: &mut Table| {
            set_unbreakable(t);
            set_end_strain(t, 2.5e-3, 0.5, base.disc.diameter);
        };
        let text = base.case("t", extruded, 0.5, &tweak).unwrap();
        let t: Table = text.parse().unwrap();
        assert_eq!(t["mesh"]["regions"][0]["breakable"], Value::Boolean(false));
        let ramp = t["platens"][0]["ramp_time"].as_float().unwrap();
        let end = t["solver"]["end_time"].as_float().unwrap();
        assert!((end - ramp - 2.5e-3 * base.disc.diameter / (2.0 * 0.5)).abs() < 1e-15, "{end}");
    }
}
