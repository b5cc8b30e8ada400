//! The polyaxial cases the validation runs, made from the bundled paper
//! case `cases/paper/polyaxial.toml` (Guo et al. §3.2, Test 1) by changing
//! only the material's strength (Tests 2 and 3) and the mesh.

use anyhow::{Context, Result, bail};
use toml::{Table, Value};

use femdem_post::mohr::Stresses;

/// The bundled case every run starts from.
pub const BASE: &str = "cases/paper/polyaxial.toml";

/// One of the paper's three materials (Table 2): only c and φ differ.
#[derive(Debug, Clone, Copy)]
pub struct Test {
    /// 1, 2 or 3.
    pub number: u8,
    /// Cohesion c, Pa.
    pub cohesion: f64,
    /// Internal friction angle φ, degrees.
    pub friction_angle: f64,
}

/// Table 2's three tests.
pub const TESTS: [Test; 3] = [
    Test { number: 1, cohesion: 0.5e6, friction_angle: 33.4 },
    Test { number: 2, cohesion: 2.0e6, friction_angle: 23.8 },
    Test { number: 3, cohesion: 3.8e6, friction_angle: 12.4 },
];

/// The mesh of a run.
#[derive(Debug, Clone)]
pub enum Mesh {
    /// An unstructured Gmsh mesh in `cases/paper/meshes/`, by file name.
    Gmsh(&'static str),
    /// The built-in jittered Freudenthal lattice of this cell edge, m.
    Lattice(f64),
}

impl Mesh {
    /// A short label for tables and file names.
    pub fn label(&self) -> String {
        match self {
            Mesh::Gmsh(f) => format!("unstructured {}", f.trim_end_matches(".msh")),
            Mesh::Lattice(h) => format!("lattice {:.0} mm", 1e3 * h),
        }
    }
}

/// The base case, parsed.
#[derive(Debug, Clone)]
pub struct Base {
    table: Table,
    /// The applied stresses, read from its pressure loads.
    pub stresses: Stresses,
    /// The time over which every pressure is ramped from zero, s.
    pub ramp: f64,
}

/// The pressure (Pa) of the base case's load on `group`.
fn pressure(t: &Table, group: &str) -> Result<f64> {
    let loads = t.get("loads").and_then(Value::as_array).with_context(|| format!("{BASE}: no [[loads]]"))?;
    let load = loads
        .iter()
        .find(|l| l.get("group").and_then(Value::as_str) == Some(group))
        .with_context(|| format!("{BASE}: no load on `{group}`"))?;
    load.get("pressure")
        .and_then(Value::as_float)
        .with_context(|| format!("{BASE}: the load on `{group}` has no pressure"))
}

/// The ramp time (s) shared by every load of the base case.
fn ramp_time(t: &Table) -> Result<f64> {
    let loads = t.get("loads").and_then(Value::as_array).with_context(|| format!("{BASE}: no [[loads]]"))?;
    let ramps: Vec<f64> = loads.iter().map(|l| l.get("ramp_time").and_then(Value::as_float).unwrap_or(0.0)).collect();
    match ramps.split_first() {
        Some((&r, rest)) if rest.iter().all(|&x| x == r) => Ok(r),
        _ => bail!("{BASE}: the checks expect every load ramped over the same time (found {ramps:?} s)"),
    }
}

impl Base {
    /// Reads the base case from the workspace; its faces must carry the
    /// same pressure in pairs (the stress state is then uniform).
    pub fn load() -> Result<Base> {
        let text = std::fs::read_to_string(crate::root().join(BASE)).with_context(|| format!("reading {BASE}"))?;
        let table: Table = text.parse().with_context(|| format!("parsing {BASE}"))?;
        let mut p = [0.0; 3];
        for (k, axis) in ["x", "y", "z"].iter().enumerate() {
            let (lo, hi) =
                (pressure(&table, &format!("cube.{axis}min"))?, pressure(&table, &format!("cube.{axis}max"))?);
            if lo != hi {
                bail!("{BASE}: the pressures on cube.{axis}min and cube.{axis}max differ ({lo} and {hi} Pa)");
            }
            p[k] = lo;
        }
        let stresses = Stresses { least: p[0], most: p[1], intermediate: p[2] };
        let ramp = ramp_time(&table)?;
        if !(stresses.least < stresses.intermediate && stresses.intermediate < stresses.most) {
            bail!("{BASE}: the checks expect the least compressive stress along x, the most along y ({p:?} Pa)");
        }
        Ok(Base { table, stresses, ramp })
    }

    /// The case for `test` on `mesh`, its pressures ramped over `ramp` (s)
    /// and the run ending at `end_time` (s), as TOML text.
    pub fn case(
        &self,
        title: &str,
        test: Test,
        mesh: &Mesh,
        ramp: f64,
        end_time: f64,
        weibull: Option<f64>,
    ) -> Result<String> {
        let mut t = self.table.clone();
        if let Some(modulus) = weibull {
            let mut h = toml::Table::new();
            h.insert("distribution".into(), "weibull".into());
            h.insert("modulus".into(), modulus.into());
            t.insert("heterogeneity".into(), Value::Table(h));
        }
        for load in t.get_mut("loads").and_then(Value::as_array_mut).context("[[loads]]")? {
            load.as_table_mut().context("[[loads]]")?.insert("ramp_time".into(), ramp.into());
        }
        t.insert("title".into(), title.into());
        t.get_mut("solver")
            .and_then(Value::as_table_mut)
            .context("[solver]")?
            .insert("end_time".into(), end_time.into());
        let m =
            t.get_mut("materials").and_then(|m| m.get_mut(0)).and_then(Value::as_table_mut).context("materials[0]")?;
        m.insert("cohesion".into(), test.cohesion.into());
        m.insert("friction_angle".into(), test.friction_angle.into());
        let part = t
            .get_mut("mesh")
            .and_then(|m| m.get_mut("parts"))
            .and_then(|p| p.get_mut(0))
            .and_then(Value::as_table_mut)
            .context("mesh.parts[0]")?;
        match mesh {
            Mesh::Gmsh(file) => {
                let path = crate::root().join("cases/paper/meshes").join(file);
                part.insert("path".into(), path.to_string_lossy().into_owned().into());
            }
            Mesh::Lattice(h) => {
                part.clear();
                part.insert("kind".into(), "box".into());
                part.insert("name".into(), "cube".into());
                part.insert("region".into(), "cube".into());
                part.insert("min".into(), Value::Array(vec![0.0.into(); 3]));
                part.insert("max".into(), Value::Array(vec![0.5.into(); 3]));
                part.insert("element_size".into(), (*h).into());
                part.insert("jitter".into(), 0.12.into());
            }
        }
        Ok(format!(
            "# Generated by `cargo xtask validate` from {BASE}; run it with\n# `femdem run` to reproduce this validation run.\n{}",
            toml::to_string(&t)?
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_ramp_and_end_time_replace_the_bundled_ones_on_every_load() {
        let base = Base::load().unwrap();
        assert_eq!(base.ramp, 2.0e-3, "the bundled case's ramp");
        let text = base.case("t", TESTS[2], &Mesh::Lattice(0.1), 1.0e-3, 1.5e-3, None).unwrap();
        let t: Table = text.parse().unwrap();
        let loads = t["loads"].as_array().unwrap();
        assert_eq!(loads.len(), 6);
        assert!(loads.iter().all(|l| l["ramp_time"].as_float() == Some(1.0e-3)));
        assert_eq!(t["solver"]["end_time"].as_float(), Some(1.5e-3));
        assert_eq!(t["materials"][0]["cohesion"].as_float(), Some(3.8e6));
        assert!(t.get("heterogeneity").is_none(), "homogeneous unless asked");
    }

    #[test]
    fn a_weibull_modulus_adds_the_heterogeneity_table() {
        let base = Base::load().unwrap();
        let text = base.case("t", TESTS[0], &Mesh::Lattice(0.1), 2.0e-3, 2.5e-3, Some(20.0)).unwrap();
        let t: Table = text.parse().unwrap();
        assert_eq!(t["heterogeneity"]["distribution"].as_str(), Some("weibull"));
        assert_eq!(t["heterogeneity"]["modulus"].as_float(), Some(20.0));
    }
}
