//! The multi-layer cases the validation runs, made from the bundled paper
//! case `cases/paper/multilayer.toml` (Guo et al. §3.3) by changing only the
//! element size, the end time and the output: the map, the material, the
//! stresses and their ramp are the bundled case's.

use std::path::PathBuf;

use anyhow::{Context, Result, bail};
use toml::{Table, Value};

use femdem_post::mechanism::FarField;

/// The bundled case every run starts from.
pub const BASE: &str = "cases/paper/multilayer.toml";

/// The block, read from the base case.
#[derive(Debug, Clone)]
pub struct Block {
    /// The extrusion's outline (x, y), m.
    pub outline: Vec<[f64; 2]>,
    /// Its bottom z and thickness along z, m.
    pub z0: f64,
    /// Thickness along z, m.
    pub thickness: f64,
    /// The trace file, resolved against the base case's folder.
    pub map: PathBuf,
    /// Input tensile strength f_t, Pa.
    pub tensile_strength: f64,
    /// The nodal mass per unit volume, kg/m³: the rock's density times
    /// `[solver] mass_scaling` (1 where not set), as femdem lumps it (the
    /// kinetic energy of the x-face strips).
    pub mass_density: f64,
    /// The longest ramp of the loads, s: the stresses are held after it.
    pub ramp: f64,
    /// The stresses the held pressures set far from the fractures, and the
    /// fractures' friction (`[contact] friction`).
    pub far: FarField,
}

/// The base case, parsed.
#[derive(Debug, Clone)]
pub struct Base {
    table: Table,
    /// Its block.
    pub block: Block,
}

fn num(v: Option<&Value>, what: &str) -> Result<f64> {
    v.and_then(|v| v.as_float().or_else(|| v.as_integer().map(|i| i as f64)))
        .with_context(|| format!("{BASE}: `{what}` is missing or not a number"))
}

fn part(t: &mut Table) -> Result<&mut Table> {
    t.get_mut("mesh")
        .and_then(|m| m.get_mut("parts"))
        .and_then(|p| p.get_mut(0))
        .and_then(Value::as_table_mut)
        .with_context(|| format!("{BASE}: no mesh.parts[0]"))
}

impl Base {
    /// Reads the base case from the workspace: one extrusion with a
    /// `traces_file`, one material.
    pub fn load() -> Result<Base> {
        let path = crate::root().join(BASE);
        let text = std::fs::read_to_string(&path).with_context(|| format!("reading {BASE}"))?;
        let mut table: Table = text.parse().with_context(|| format!("parsing {BASE}"))?;
        let p = part(&mut table)?.clone();
        if p.get("kind").and_then(Value::as_str) != Some("extrusion") {
            bail!("{BASE}: mesh.parts[0] is not an extrusion");
        }
        let outline = p
            .get("polygon")
            .and_then(Value::as_array)
            .context("mesh.parts[0].polygon")?
            .iter()
            .map(|xy| Ok([num(xy.get(0), "polygon x")?, num(xy.get(1), "polygon y")?]))
            .collect::<Result<Vec<_>>>()?;
        let file = p.get("traces_file").and_then(Value::as_str).context("mesh.parts[0].traces_file")?;
        let map = path.parent().context("the case's folder")?.join(file);
        let material = table.get("materials").and_then(|m| m.get(0)).context("materials[0]")?;
        let ramp = table
            .get("loads")
            .and_then(Value::as_array)
            .context("[[loads]]")?
            .iter()
            .map(|l| num(l.get("ramp_time"), "loads.ramp_time"))
            .collect::<Result<Vec<_>>>()?
            .into_iter()
            .fold(0.0, f64::max);
        let loads = table.get("loads").and_then(Value::as_array).context("[[loads]]")?;
        // σ = −p on the faces normal to an axis: the pressure on `*.xmin`
        // (or `*.ymin`).
        let stress = |side: &str| -> Result<f64> {
            let load = loads
                .iter()
                .find(|l| {
                    l.get("kind").and_then(Value::as_str) == Some("pressure")
                        && l.get("group").and_then(Value::as_str).is_some_and(|g| g.ends_with(side))
                })
                .with_context(|| format!("{BASE}: no pressure on a group `*{side}`"))?;
            Ok(-num(load.get("pressure"), "loads.pressure")?)
        };
        let mass_scaling = match table.get("solver").and_then(|s| s.get("mass_scaling")) {
            None => 1.0,
            v => num(v, "solver.mass_scaling")?,
        };
        if table.get("materials").and_then(Value::as_array).is_some_and(|m| m.len() != 1) {
            bail!("{BASE}: the multi-layer checks read one material, the rock's");
        }
        let friction = num(table.get("contact").and_then(|c| c.get("friction")), "contact.friction")?;
        let far = FarField { sxx: stress(".xmin")?, syy: stress(".ymin")?, friction };
        let block = Block {
            outline,
            z0: num(p.get("z0"), "mesh.parts[0].z0")?,
            thickness: num(p.get("thickness"), "mesh.parts[0].thickness")?,
            map,
            tensile_strength: num(material.get("tensile_strength"), "materials[0].tensile_strength")?,
            mass_density: num(material.get("density"), "materials[0].density")? * mass_scaling,
            ramp,
            far,
        };
        Ok(Base { table, block })
    }

    /// The case on `element_size` (m) ending at `end_time` (s), with a frame
    /// every `interval` (s), as TOML text. The frames carry the displacement
    /// (to draw the section at the undeformed mid-plane), the velocity (of
    /// the strips along the x faces), the principal stresses (the paper's
    /// Fig. 17 shows σ1) and the region.
    pub fn case(&self, title: &str, element_size: f64, end_time: f64, interval: f64) -> Result<String> {
        let mut t = self.table.clone();
        t.insert("title".into(), title.into());
        let p = part(&mut t)?;
        p.insert("element_size".into(), element_size.into());
        // The generated case lives elsewhere: name the map by its full path.
        p.insert("traces_file".into(), self.block.map.to_string_lossy().into_owned().into());
        t.get_mut("solver")
            .and_then(Value::as_table_mut)
            .context("[solver]")?
            .insert("end_time".into(), end_time.into());
        let output = t.get_mut("output").and_then(Value::as_table_mut).context("[output]")?;
        output.insert("interval".into(), interval.into());
        output.insert(
            "fields".into(),
            Value::Array(vec!["displacement".into(), "velocity".into(), "principal_stress".into(), "region".into()]),
        );
        Ok(format!(
            "# Generated by `cargo xtask validate` from {BASE}; run it with\n# `femdem run` to reproduce this validation run.\n{}",
            toml::to_string(&t)?
        ))
    }
}
