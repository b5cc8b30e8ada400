//! Turning a case's material, platen, load and solver sections into a
//! solver model and its loads.

use femdem_core::Vec3;
use femdem_fracture::heterogeneity::Distribution;
use femdem_fracture::{Coupling, GfCalibration, JointParams};
use femdem_material::{ElasticParams, Law};
use femdem_mesh::JointedMesh;
use femdem_solver::select::{NodeSelection, UnknownName, group_faces, select_nodes};
use femdem_solver::{
    Activation, ContactModel, ContactSettings, Fixed, Loads, Model, Ramp, RegionBehaviour, SurfaceKind, SurfaceLoad,
    VelocityDrive,
};
use femdem_vtk::Compression;

use super::format::{LoadSpec, NodeSpec, OutputSpec};
use super::{CaseError, LoadedCase};

/// The fields `[output] fields` may name (written into every VTU frame
/// by the run driver).
pub const FIELDS: [&str; 6] = ["displacement", "velocity", "stress", "principal_stress", "von_mises", "region"];

/// The default joint penalty as a multiple of E (the top of Eq. 9's range).
pub const DEFAULT_PENALTY_FACTOR: f64 = 10.0;

/// Builds the region behaviours of the case.
///
/// # Errors
/// A located [`CaseError`] for an unknown region, a region with two
/// materials, a deformable region without one, bad parameters, or missing
/// joint strengths in a breakable region. What is legal but probably not
/// meant (a cohesion that caps the tensile strength through Eq. 5's
/// tension cut-off) is pushed onto `warnings`.
pub fn behaviours(
    case: &LoadedCase,
    mesh: &JointedMesh,
    warnings: &mut Vec<String>,
) -> Result<Vec<RegionBehaviour>, CaseError> {
    let m = &mesh.mesh;
    let stats = femdem_mesh::stats(m);
    let mut out: Vec<Option<RegionBehaviour>> = vec![None; m.regions.len()];
    for p in &case.case.platens {
        let r = m.region_index(&p.get_ref().region).ok_or_else(|| {
            case.error_at(p.span(), format!("platens.region: `{}` is not a region of the mesh", p.get_ref().region))
        })?;
        if m.regions[r as usize].breakable {
            return Err(case.error_at(
                p.span(),
                format!("platens.region: `{}` is breakable; a rigid platen cannot break", p.get_ref().region),
            ));
        }
        out[r as usize] = Some(RegionBehaviour::Rigid);
    }
    for (i, spec) in case.case.materials.iter().enumerate() {
        let s = spec.get_ref();
        let key = format!("materials[{i}]");
        let at = |msg: String| case.error_at(spec.span(), format!("{key}: {msg}"));
        let r = m
            .region_index(&s.region)
            .ok_or_else(|| at(format!("region `{}` is not a region of the mesh", s.region)))?;
        if out[r as usize].is_some() {
            return Err(at(format!("region `{}` already has a material or is a platen", s.region)));
        }
        let law = match s.law.as_str() {
            "neo-hookean" => Law::NeoHookean,
            "linear-elastic" => Law::LinearElastic,
            other => {
                return Err(at(format!("law `{other}` is not `neo-hookean` or `linear-elastic`")));
            }
        };
        let mean_edge = {
            // Mean edge of this region's tets.
            let mut sum = 0.0;
            let mut count = 0usize;
            for t in (0..m.num_tets()).filter(|&t| m.tet_region[t] == r) {
                sum += femdem_core::tet::edge_lengths(&m.tet_points(t)).iter().sum::<f64>();
                count += 6;
            }
            if count > 0 { sum / count as f64 } else { stats.mean_edge }
        };
        let viscosity = match (s.viscosity, s.damping_ratio) {
            (Some(_), Some(_)) => {
                return Err(at("give `viscosity` or `damping_ratio`, not both".into()));
            }
            (Some(v), None) => v,
            (None, Some(xi)) => {
                if !(xi.is_finite() && xi >= 0.0) {
                    return Err(at(format!("`damping_ratio` must be finite and ≥ 0, got {xi}")));
                }
                xi * femdem_material::critical_viscosity(mean_edge, s.young, s.density)
            }
            (None, None) => 0.0,
        };
        let material = ElasticParams { young: s.young, poisson: s.poisson, density: s.density, viscosity }
            .validate()
            .map_err(|e| at(e.to_string()))?;
        let joints = if m.regions[r as usize].breakable {
            let need = |v: Option<f64>, name: &str| {
                v.ok_or_else(|| at(format!("region `{}` is breakable: `{name}` is required", s.region)))
            };
            let calibration = match s.gf_calibration.as_deref() {
                None | Some("paper") => GfCalibration::Paper,
                Some("exact") => GfCalibration::Exact,
                Some(other) => {
                    return Err(at(format!("gf_calibration `{other}` is not `paper` or `exact`")));
                }
            };
            let coupling = match s.joint_coupling.as_deref() {
                Some("capped") => Coupling::Capped,
                None | Some("printed") => Coupling::Printed,
                Some("multiplicative") => Coupling::Multiplicative,
                Some(other) => {
                    return Err(at(format!("joint_coupling `{other}` is not `capped`, `printed` or `multiplicative`")));
                }
            };
            let gf = need(s.fracture_energy, "fracture_energy")?;
            // Checked here in the case's own keys and units (the library's
            // checks name its fields, in radians).
            let phi = need(s.friction_angle, "friction_angle")?;
            if !(phi.is_finite() && (0.0..90.0).contains(&phi)) {
                return Err(at(format!("`friction_angle` must lie in [0°, 90°), got {phi}°")));
            }
            for (key, value) in [("fracture_energy", Some(gf)), ("fracture_energy_shear", s.fracture_energy_shear)] {
                if let Some(v) = value.filter(|v| !(v.is_finite() && *v > 0.0)) {
                    return Err(at(format!("`{key}` must be finite and > 0 J/m², got {v} J/m²")));
                }
            }
            let params = JointParams {
                penalty: s.penalty.unwrap_or(DEFAULT_PENALTY_FACTOR * s.young),
                tensile_strength: need(s.tensile_strength, "tensile_strength")?,
                cohesion: need(s.cohesion, "cohesion")?,
                friction_angle: need(s.friction_angle, "friction_angle")?.to_radians(),
                gf_tension: gf,
                gf_shear: s.fracture_energy_shear.unwrap_or(gf),
                calibration,
                coupling,
            };
            let params = params.validate().map_err(|e| at(e.to_string()))?;
            if params.cohesion_limits_tension() {
                warnings.push(format!(
                    "{}: cohesion {} Pa ≤ tensile_strength × tan(friction_angle): Eq. 5's tension cut-off \
                     caps the tensile strength at c / tan φ = {:.6e} Pa",
                    at(format!("materials, region `{}`", s.region)),
                    params.cohesion,
                    params.effective_tensile_strength()
                ));
            }
            Some(params)
        } else {
            None
        };
        out[r as usize] = Some(RegionBehaviour::Deformable { law, material, joints });
    }
    out.into_iter()
        .enumerate()
        .map(|(r, b)| {
            b.ok_or_else(|| {
                let name = &m.regions[r].name;
                let message = format!("region `{name}` has no [[materials]] entry and is not a [[platens]] region");
                // At the region's declaration where the case has one.
                match case.case.mesh.regions.iter().position(|q| q.get_ref().name == *name) {
                    Some(i) => case.error_at(case.case.mesh.regions[i].span(), format!("mesh.regions[{i}]: {message}")),
                    None => CaseError { path: case.path.clone(), at: None, message },
                }
            })
        })
        .collect()
}

/// The node selection of a case's node selector. An empty selector (no
/// `group`, `region` or `box`) would select every node of the mesh: it is
/// refused by the callers (see [`selector`]).
fn selection(spec: &NodeSpec) -> NodeSelection {
    NodeSelection {
        group: spec.group.clone(),
        region: spec.region.clone(),
        within: spec.within.map(|b| (b.min, b.max)),
    }
}

/// [`selection`], refusing a selector with no criterion under `key`.
fn selector(spec: &NodeSpec, key: &str) -> Result<NodeSelection, String> {
    if spec.group.is_none() && spec.region.is_none() && spec.within.is_none() {
        return Err(format!(
            "`{key}` has no `group`, `region` or `box`: it would select every node of the mesh; name what it selects"
        ));
    }
    Ok(selection(spec))
}

fn components(s: &str) -> Option<[bool; 3]> {
    let mut c = [false; 3];
    for ch in s.chars() {
        match ch {
            'x' => c[0] = true,
            'y' => c[1] = true,
            'z' => c[2] = true,
            _ => return None,
        }
    }
    c.iter().any(|&b| b).then_some(c)
}

fn unknown(u: UnknownName) -> String {
    format!("no {} `{}` in the mesh (have: {})", u.kind, u.name, u.available.join(", "))
}

/// Builds the loads of the case: platens as velocity drives of their
/// region's nodes plus the specimen nodes they drive, then `[[loads]]`.
///
/// # Errors
/// A located [`CaseError`] for unknown groups or regions, empty node sets
/// and bad component strings.
pub fn loads(case: &LoadedCase, mesh: &JointedMesh, gravity: [f64; 3]) -> Result<Loads, CaseError> {
    let mut loads = Loads { gravity: Vec3::from(gravity), ..Default::default() };
    if !gravity.iter().all(|g| g.is_finite()) {
        let at = case.case.solver.as_ref().map(|s| s.span());
        let message = format!("solver: gravity must be finite, got {gravity:?} m/s²");
        return Err(match at {
            Some(span) => case.error_at(span, message),
            None => CaseError { path: case.path.clone(), at: None, message },
        });
    }
    for (i, p) in case.case.platens.iter().enumerate() {
        let s = p.get_ref();
        let at = |msg: String| case.error_at(p.span(), format!("platens[{i}]: {msg}"));
        let mut nodes = select_nodes(mesh, &NodeSelection { region: Some(s.region.clone()), ..Default::default() })
            .map_err(|u| at(unknown(u)))?;
        if let Some(d) = &s.drives {
            let driven = select_nodes(mesh, &selector(d, "drives").map_err(at)?).map_err(|u| at(unknown(u)))?;
            if driven.is_empty() {
                return Err(at("`drives` selects no node".into()));
            }
            nodes.extend(driven);
            nodes.sort_unstable();
            nodes.dedup();
        }
        finite("velocity", &s.velocity, "m/s").map_err(at)?;
        loads.drives.push(VelocityDrive {
            name: s.region.clone(),
            nodes,
            velocity: Vec3::from(s.velocity),
            components: [true; 3],
            ramp: ramp(s.ramp_time, None).map_err(at)?,
            start_time: None,
        });
    }
    for (i, l) in case.case.loads.iter().enumerate() {
        let at = |msg: String| case.error_at(l.span(), format!("loads[{i}]: {msg}"));
        match l.get_ref() {
            LoadSpec::Fixed { name, nodes, components: c, start_time } => {
                let nodes = select_nodes(mesh, &selector(nodes, "nodes").map_err(at)?).map_err(|u| at(unknown(u)))?;
                if nodes.is_empty() {
                    return Err(at("`nodes` selects no node".into()));
                }
                let components = components(c).ok_or_else(|| at(format!("components `{c}` is not letters of xyz")))?;
                let start_time = start(*start_time).map_err(at)?;
                match (name, start_time) {
                    (None, None) => loads.fixed.push(Fixed { nodes, components }),
                    // A named support records its reaction, and one that
                    // starts later switches on: a drive holding the
                    // components at zero velocity moves its nodes as the
                    // constraint does (v = 0 on them; no work done once held,
                    // the work of stopping them in the step it starts).
                    _ => loads.drives.push(VelocityDrive {
                        name: name.clone().unwrap_or_else(|| format!("fixed{i}")),
                        nodes,
                        velocity: Vec3::zeros(),
                        components,
                        ramp: Ramp { ramp_time: 0.0, stop_time: None },
                        start_time,
                    }),
                }
            }
            LoadSpec::Velocity { name, nodes, velocity, components: c, ramp_time, stop_time, start_time } => {
                let nodes = select_nodes(mesh, &selector(nodes, "nodes").map_err(at)?).map_err(|u| at(unknown(u)))?;
                if nodes.is_empty() {
                    return Err(at("`nodes` selects no node".into()));
                }
                let c = c.as_deref().unwrap_or("xyz");
                let components = components(c).ok_or_else(|| at(format!("components `{c}` is not letters of xyz")))?;
                finite("velocity", velocity, "m/s").map_err(at)?;
                // A value in a component the drive leaves free would be
                // ignored without a word.
                if let Some(k) = (0..3).find(|&k| !components[k] && velocity[k] != 0.0) {
                    let axis = ["x", "y", "z"][k];
                    return Err(at(format!(
                        "`velocity` has {axis} = {} m/s, but `components = \"{c}\"` leaves {axis} free, so that \
                         value would be ignored; set it to 0, or add {axis} to `components`",
                        velocity[k]
                    )));
                }
                loads.drives.push(VelocityDrive {
                    name: name.clone().unwrap_or_else(|| format!("velocity{i}")),
                    nodes,
                    velocity: Vec3::from(*velocity),
                    components,
                    ramp: ramp(*ramp_time, *stop_time).map_err(at)?,
                    start_time: start(*start_time).map_err(at)?,
                });
            }
            LoadSpec::Pressure { group, pressure, ramp_time, stop_time } => {
                let faces = group_faces(mesh, group).map_err(|u| at(unknown(u)))?;
                finite("pressure", &[*pressure], "Pa").map_err(at)?;
                loads.surfaces.push(SurfaceLoad {
                    name: group.clone(),
                    faces,
                    kind: SurfaceKind::Pressure(*pressure),
                    ramp: ramp(*ramp_time, *stop_time).map_err(at)?,
                });
            }
            LoadSpec::Traction { group, traction, ramp_time, stop_time } => {
                let faces = group_faces(mesh, group).map_err(|u| at(unknown(u)))?;
                finite("traction", traction, "Pa").map_err(at)?;
                loads.surfaces.push(SurfaceLoad {
                    name: group.clone(),
                    faces,
                    kind: SurfaceKind::Traction(Vec3::from(*traction)),
                    ramp: ramp(*ramp_time, *stop_time).map_err(at)?,
                });
            }
        }
        // Each drive and surface load names columns of the history.
        let names = loads.drives.iter().map(|d| &d.name).chain(loads.surfaces.iter().map(|s| &s.name));
        let mut seen = std::collections::HashSet::new();
        if let Some(dup) = names.into_iter().find(|n| !seen.insert(n.as_str())) {
            return Err(at(format!(
                "a load or platen named `{dup}` already exists (names label the history's columns; give `name` a new value)"
            )));
        }
        // `<name>_work` of a load named `external` would repeat the energy
        // column `external_work`.
        if seen.contains("external") {
            return Err(at(
                "a load or platen named `external`: its `external_work` column would repeat the external work's \
                 (names label the history's columns; give `name` another value)"
                    .to_string(),
            ));
        }
    }
    Ok(loads)
}

/// Checks that every component of `key` is finite.
fn finite(key: &str, values: &[f64], unit: &str) -> Result<(), String> {
    if values.iter().all(|v| v.is_finite()) {
        Ok(())
    } else {
        Err(format!("`{key}` must be finite, got {values:?} {unit}"))
    }
}

/// A load's ramp, checked: `ramp_time` finite and ≥ 0 s, `stop_time` finite
/// and > 0 s.
fn ramp(ramp_time: f64, stop_time: Option<f64>) -> Result<Ramp, String> {
    if !(ramp_time.is_finite() && ramp_time >= 0.0) {
        return Err(format!("`ramp_time` must be finite and ≥ 0 s, got {ramp_time} s"));
    }
    if let Some(t) = stop_time {
        if !(t.is_finite() && t > 0.0) {
            return Err(format!("`stop_time` must be finite and > 0 s, got {t} s"));
        }
    }
    Ok(Ramp { ramp_time, stop_time })
}

/// A constraint's `start_time`, checked: finite and ≥ 0 s.
fn start(start_time: Option<f64>) -> Result<Option<f64>, String> {
    match start_time {
        Some(t) if !(t.is_finite() && t >= 0.0) => Err(format!("`start_time` must be finite and ≥ 0 s, got {t} s")),
        t => Ok(t),
    }
}

/// Builds the model with the case's mass scaling.
///
/// # Errors
/// As [`behaviours`], plus model set-up errors; its warnings are pushed
/// onto `warnings`.
pub fn model(
    case: &LoadedCase,
    mesh: &JointedMesh,
    mass_scaling: f64,
    warnings: &mut Vec<String>,
) -> Result<Model, CaseError> {
    let b = behaviours(case, mesh, warnings)?;
    let mut model = Model::new(mesh, &b, mass_scaling).map_err(|e| CaseError {
        path: case.path.clone(),
        at: None,
        message: e.to_string(),
    })?;
    if let Some(h) = &case.case.heterogeneity {
        let spec = h.get_ref();
        let at = |msg: String| case.error_at(h.span(), format!("heterogeneity: {msg}"));
        let dist = match spec.distribution.as_str() {
            "weibull" => Distribution::Weibull {
                modulus: spec.modulus.ok_or_else(|| at("`modulus` is required for a Weibull distribution".into()))?,
            },
            "normal" => Distribution::Normal {
                cov: spec.cov.ok_or_else(|| at("`cov` is required for a normal distribution".into()))?,
            },
            other => {
                return Err(at(format!("distribution `{other}` is not `weibull` or `normal`")));
            }
        };
        model.randomise_strengths(dist, spec.seed.unwrap_or(case.case.mesh.seed)).map_err(|e| at(e.to_string()))?;
    }
    Ok(model)
}

/// The case file's names of `[contact] activation`'s options.
const ACTIVATIONS: [(&str, Activation); 5] = [
    ("couple", Activation::Couple),
    ("offset", Activation::Offset),
    ("paper", Activation::Paper),
    ("ramp", Activation::Ramp),
    ("settle", Activation::Settle),
];

/// The case file's name of `activation`.
pub fn activation_name(activation: Activation) -> &'static str {
    ACTIVATIONS.iter().find(|(_, a)| *a == activation).map_or("?", |(n, _)| n)
}

/// The case file's names of `[contact] model`'s options.
const CONTACT_MODELS: [(&str, ContactModel); 2] =
    [("potential", ContactModel::Potential), ("gradient", ContactModel::Gradient)];

/// The contact model named `name` (`[contact] model`); `None` for an
/// unknown name.
fn contact_model(name: &str) -> Option<ContactModel> {
    CONTACT_MODELS.iter().find(|(n, _)| *n == name).map(|&(_, m)| m)
}

/// Builds the contact settings of the case's `[contact]`, if any.
///
/// # Errors
/// A located [`CaseError`] for a penalty that is not positive, a friction
/// coefficient that is negative or not finite, a negative buffer, a
/// `negligible` outside `[0, 1e-3)`, an unknown `activation` or `model`,
/// or an unknown region in `[[contact.pairs]]`.
pub fn contact(case: &LoadedCase, mesh: &JointedMesh) -> Result<Option<ContactSettings>, CaseError> {
    let Some(c) = &case.case.contact else { return Ok(None) };
    let spec = c.get_ref();
    let at = |msg: String| case.error_at(c.span(), format!("contact.{msg}"));
    if !(spec.penalty.is_finite() && spec.penalty > 0.0) {
        return Err(at(format!("penalty must be > 0 Pa, got {}", spec.penalty)));
    }
    if !(spec.friction.is_finite() && spec.friction >= 0.0) {
        return Err(at(format!("friction must be ≥ 0, got {}", spec.friction)));
    }
    if !(spec.buffer.is_finite() && spec.buffer >= 0.0) {
        return Err(at(format!("buffer must be ≥ 0 m, got {}", spec.buffer)));
    }
    if !(spec.negligible.is_finite() && (0.0..1e-3).contains(&spec.negligible)) {
        return Err(at(format!("negligible must be in [0, 1e-3), got {}", spec.negligible)));
    }
    let activation = match spec.activation.as_deref() {
        None => Activation::default(),
        Some(name) => ACTIVATIONS.iter().find(|(n, _)| *n == name).map(|&(_, a)| a).ok_or_else(|| {
            let names: Vec<String> = ACTIVATIONS.iter().map(|(n, _)| format!("`{n}`")).collect();
            let (last, rest) = names.split_last().expect("activations");
            at(format!("activation `{name}` is not {} or {last}", rest.join(", ")))
        })?,
    };
    let model = match spec.model.as_deref() {
        None => ContactModel::default(),
        Some(name) => {
            contact_model(name).ok_or_else(|| at(format!("model `{name}` is not `potential` or `gradient`")))?
        }
    };
    let mut settings = ContactSettings {
        activation,
        penalty: spec.penalty,
        surfaces: spec.surfaces,
        friction: spec.friction,
        pair_friction: Vec::new(),
        buffer: spec.buffer,
        ramp_steps: spec.ramp_steps,
        incremental: true,
        certify: true,
        negligible: spec.negligible,
        model,
    };
    for (i, p) in spec.pairs.iter().enumerate() {
        let pair = p.get_ref();
        let at = |msg: String| case.error_at(p.span(), format!("contact.pairs[{i}]: {msg}"));
        let mut ids = [0u16; 2];
        for (k, name) in pair.regions.iter().enumerate() {
            ids[k] = mesh.mesh.region_index(name).ok_or_else(|| at(format!("`{name}` is not a region of the mesh")))?;
        }
        if !(pair.friction.is_finite() && pair.friction >= 0.0) {
            return Err(at(format!("friction must be ≥ 0, got {}", pair.friction)));
        }
        // The same pair twice (in either order) would leave which μ holds
        // to the solver's lookup order.
        let same = |q: &[u16; 2]| *q == ids || *q == [ids[1], ids[0]];
        if let Some(j) = settings.pair_friction.iter().position(|(q, _)| same(q)) {
            return Err(at(format!(
                "the regions `{}` and `{}` already have a friction, in contact.pairs[{j}]; give each pair once",
                pair.regions[0], pair.regions[1]
            )));
        }
        settings.pair_friction.push((ids, pair.friction));
    }
    Ok(Some(settings))
}

/// What the run guard does when contact has given back more energy than
/// it absorbed (`[contact] energy_check`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ContactCheck {
    /// Stop the run (the default).
    Stop,
    /// Warn once and go on.
    Warn,
}

/// The case's `[contact] energy_check` and `energy_tolerance` (`None`
/// without `[contact]` or with `energy_check = "off"`).
///
/// # Errors
/// A located [`CaseError`] for a check other than `stop`, `warn` or `off`,
/// or a tolerance outside (0, 1].
pub fn contact_check(case: &LoadedCase) -> Result<Option<(ContactCheck, f64)>, CaseError> {
    let Some(c) = &case.case.contact else { return Ok(None) };
    let spec = c.get_ref();
    let tolerance = spec.energy_tolerance.unwrap_or(femdem_solver::CONTACT_ENERGY_TOLERANCE);
    if !(tolerance > 0.0 && tolerance <= 1.0) {
        let message = format!(
            "contact.energy_tolerance must lie in (0, 1] (a fraction of the run's energy scale), got {tolerance}"
        );
        return Err(case.error_at(c.span(), message));
    }
    let check = match spec.energy_check.as_deref() {
        None | Some("stop") => ContactCheck::Stop,
        Some("warn") => ContactCheck::Warn,
        Some("off") => return Ok(None),
        Some(other) => {
            return Err(
                case.error_at(c.span(), format!("contact.energy_check `{other}` is not `stop`, `warn` or `off`"))
            );
        }
    };
    Ok(Some((check, tolerance)))
}

/// The load–strain columns of `[output.load_strain]`, resolved against the
/// drives of `loads`.
#[derive(Clone, Copy, Debug)]
pub struct LoadStrain {
    /// Index of the upper platen's drive.
    pub upper: usize,
    /// Index of the lower platen's drive.
    pub lower: usize,
    /// Specimen length `d`, m.
    pub length: f64,
    /// Unit loading axis.
    pub axis: Vec3,
    /// `stop_below_peak`: the fraction of the peak load below which a run
    /// with failed joints ends.
    pub stop_below_peak: Option<f64>,
}

impl LoadStrain {
    /// `(F, ε)` of Eq. 21–22 from the drives' reaction forces `forces` (the
    /// force each drive applies to its platen) and mean displacements `u`:
    /// the specimen pushes the upper platen along `+axis`, so
    /// `F_upper = −f_upper·axis` and `F_lower = f_lower·axis`, and
    /// `Δa = (u_lower − u_upper)·axis` is the shortening.
    pub fn evaluate(&self, forces: &[Vec3], u: &[Vec3]) -> (f64, f64) {
        let f_upper = -forces[self.upper].dot(&self.axis);
        let f_lower = forces[self.lower].dot(&self.axis);
        let shortening = (u[self.lower] - u[self.upper]).dot(&self.axis);
        (0.5 * (f_upper + f_lower), shortening / self.length)
    }
}

/// Resolves `[output.load_strain]`, if any.
///
/// # Errors
/// A located [`CaseError`] when a name is not a platen of the case, the two
/// are the same, the length is not positive or the axis is zero.
pub fn load_strain(case: &LoadedCase, loads: &Loads) -> Result<Option<LoadStrain>, CaseError> {
    let Some(spec) = case.case.output.as_ref().and_then(|o| o.get_ref().load_strain.as_ref()) else {
        return Ok(None);
    };
    let s = spec.get_ref();
    let at = |msg: String| case.error_at(spec.span(), format!("output.load_strain.{msg}"));
    let find = |key: &str, name: &str| {
        loads
            .drives
            .iter()
            .position(|d| d.name == name)
            .ok_or_else(|| at(format!("{key}: `{name}` is not a platen of the case")))
    };
    let (upper, lower) = (find("upper", &s.upper)?, find("lower", &s.lower)?);
    if upper == lower {
        return Err(at("lower: must differ from upper".into()));
    }
    if !(s.length.is_finite() && s.length > 0.0) {
        return Err(at(format!("length must be > 0 m, got {}", s.length)));
    }
    let axis = Vec3::from(s.axis);
    if !(axis.norm().is_finite() && axis.norm() > 0.0) {
        return Err(at("axis must be a non-zero vector".into()));
    }
    if let Some(f) = s.stop_below_peak
        && !(f > 0.0 && f < 1.0)
    {
        return Err(at(format!("stop_below_peak must be a fraction in (0, 1), got {f}")));
    }
    Ok(Some(LoadStrain { upper, lower, length: s.length, axis: axis.normalize(), stop_below_peak: s.stop_below_peak }))
}

/// What `[output]` resolves to for a run of `end_time` seconds.
#[derive(Debug, Clone)]
pub struct OutputSettings {
    /// Simulated time between VTU frames, s.
    pub interval: f64,
    /// Simulated time between history rows, s.
    pub history_interval: f64,
    /// Fields written.
    pub fields: Vec<String>,
    /// Compression of the VTU frames.
    pub compression: Compression,
    /// When checkpoints are written.
    pub checkpoint: CheckpointSettings,
}

/// `[output.checkpoint]`, resolved.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CheckpointSettings {
    /// Steps between checkpoints (0: none by step count).
    pub interval_steps: u64,
    /// Wall-clock time between checkpoints, s (0: none by wall time).
    pub interval_wall: f64,
}

/// The default wall-clock interval between checkpoints, s: half an hour
/// bounds the work a crash loses on a long run, and a run shorter than
/// that writes none (but the one a signal asks for).
pub const CHECKPOINT_WALL_DEFAULT: f64 = 1800.0;

/// Resolves and checks `[output]`: intervals finite and > 0 s (defaults
/// `end_time / 20` and a tenth of the frame interval), fields among
/// `fields_known`, the compression one of [`compression`]'s.
///
/// # Errors
/// A located [`CaseError`] naming the key.
pub fn output(case: &LoadedCase, end_time: f64, fields_known: &[&str]) -> Result<OutputSettings, CaseError> {
    let default = OutputSpec::default();
    let (spec, span) = match &case.case.output {
        Some(o) => (o.get_ref(), Some(o.span())),
        None => (&default, None),
    };
    let at = |msg: String| match span.clone() {
        Some(span) => case.error_at(span, format!("output: {msg}")),
        None => CaseError { path: case.path.clone(), at: None, message: format!("output: {msg}") },
    };
    let interval = spec.interval.unwrap_or(end_time / 20.0);
    if !(interval.is_finite() && interval > 0.0) {
        return Err(at(format!("`interval` must be finite and > 0 s, got {interval} s")));
    }
    let history_interval = spec.history_interval.unwrap_or(interval / 10.0);
    if !(history_interval.is_finite() && history_interval > 0.0) {
        return Err(at(format!("`history_interval` must be finite and > 0 s, got {history_interval} s")));
    }
    let fields = spec.fields.clone().unwrap_or_else(|| fields_known.iter().map(|s| s.to_string()).collect());
    if let Some(f) = fields.iter().find(|f| !fields_known.contains(&f.as_str())) {
        return Err(at(format!("`fields`: `{f}` is not one of {}", fields_known.join(", "))));
    }
    let compression = compression(spec.compression.as_deref().unwrap_or("lz4")).map_err(at)?;
    let default_checkpoint = crate::format::CheckpointSpec::default();
    let (cp, cp_span) = match &spec.checkpoint {
        Some(c) => (c.get_ref(), Some(c.span())),
        None => (&default_checkpoint, None),
    };
    let interval_wall = cp.interval_wall.unwrap_or(CHECKPOINT_WALL_DEFAULT);
    if !(interval_wall.is_finite() && interval_wall >= 0.0) {
        let message = format!("output.checkpoint: `interval_wall` must be finite and ≥ 0 s, got {interval_wall} s");
        return Err(match cp_span {
            Some(span) => case.error_at(span, message),
            None => CaseError { path: case.path.clone(), at: None, message },
        });
    }
    let checkpoint = CheckpointSettings { interval_steps: cp.interval_steps.unwrap_or(0), interval_wall };
    Ok(OutputSettings { interval, history_interval, fields, compression, checkpoint })
}

/// `[output] compression`: `lz4` (read by VTK 8.1 and later, ParaView 5.5
/// and later; not by meshio), `zlib` (level 6) or `zlib:N` (N = 0–9; read
/// by every VTK version and by meshio, slower to write), `none` (read by
/// every reader, largest files).
///
/// # Errors
/// The message for any other value.
pub fn compression(name: &str) -> Result<Compression, String> {
    let bad = || format!("`compression`: `{name}` is not one of lz4, zlib, zlib:N (N = 0 to 9), none");
    match name {
        "lz4" => Ok(Compression::Lz4),
        "none" => Ok(Compression::None),
        "zlib" => Ok(Compression::Zlib { level: 6 }),
        _ => match name.strip_prefix("zlib:").map(str::parse::<u32>) {
            Some(Ok(level)) if level <= 9 => Ok(Compression::Zlib { level }),
            _ => Err(bad()),
        },
    }
}
