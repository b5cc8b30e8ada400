//! `[[platens]]` as velocity drives and `[[loads]]` (fixed, velocity,
//! pressure, traction), with their node selectors and time windows.

use femdem_core::Vec3;
use femdem_mesh::JointedMesh;
use femdem_solver::select::{NodeSelection, UnknownName, group_faces, select_nodes};
use femdem_solver::{Fixed, Loads, Ramp, SolverError, SurfaceKind, SurfaceLoad, VelocityDrive};

use crate::format::{LoadSpec, NodeSpec};
use crate::{CaseError, LoadedCase};

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

/// The refusal of a surface load (`what`) on boundary group `group`,
/// which holds no triangle (an MSH physical surface of quadrangles, whose
/// faces are no tet's): it would act on nothing.
fn no_faces(group: &str, what: &str) -> String {
    format!(
        "`group` `{group}` has no faces, so the {what} would act on nothing (an MSH physical surface meshed \
         with quadrangles, or lying on no tet's face, gives an empty group: `femdem check` lists each group's \
         faces)"
    )
}

/// The error of a velocity component constrained twice where the first
/// constraint is an unnamed fixed load (the solver knows it only as "a
/// fixed constraint"): placed at that load and naming it, `loads[i]`.
/// `None` for any other error (the caller places it as before).
pub fn constrained_twice(case: &LoadedCase, loads: &Loads, e: &SolverError) -> Option<CaseError> {
    let SolverError::PrescribedTwice { node, at, component, first, by } = e else { return None };
    let c = ["x", "y", "z"].iter().position(|n| n == component)?;
    if first != "a fixed constraint" {
        return None;
    }
    // The solver's fixed loads are the case's fixed loads without a name
    // or a start time, in the case's order (`loads`).
    let k = loads.fixed.iter().position(|f| f.components[c] && f.nodes.contains(node))?;
    let unnamed = |l: &LoadSpec| matches!(l, LoadSpec::Fixed { name: None, start_time: None, .. });
    let (i, spec) = case.case.loads.iter().enumerate().filter(|(_, l)| unnamed(l.get_ref())).nth(k)?;
    let named = SolverError::PrescribedTwice {
        node: *node,
        at: *at,
        component,
        first: format!("the fixed load loads[{i}]"),
        by: by.clone(),
    };
    Some(case.error_at(spec.span(), format!("loads[{i}]: {named}")))
}

/// Pushes onto `warnings` every pressure or traction of `case` whose
/// faces' nodes (`loads.surfaces`, in the order of `[[loads]]`) are all
/// `held` in the three directions from the start (by a platen, a fixed
/// support or a velocity load): such a load moves nothing and only adds
/// to those supports' recorded reactions.
pub fn surface_loads_on_held_nodes(case: &LoadedCase, loads: &Loads, held: &[bool], warnings: &mut Vec<String>) {
    let specs = case.case.loads.iter().enumerate().filter_map(|(i, l)| match l.get_ref() {
        LoadSpec::Pressure { .. } => Some((i, l, "pressure")),
        LoadSpec::Traction { .. } => Some((i, l, "traction")),
        _ => None,
    });
    for ((i, l, what), surface) in specs.zip(&loads.surfaces) {
        if surface.faces.iter().flatten().all(|&n| held.get(n as usize).copied().unwrap_or(false)) {
            let message = format!(
                "loads[{i}]: every node of the {} faces of `{}` is held in all three directions from the start (by \
                 a platen, a fixed support or a velocity load): the {what} moves nothing and only adds to those \
                 supports' recorded reactions",
                surface.faces.len(),
                surface.name
            );
            warnings.push(case.error_at(l.span(), message).to_string());
        }
    }
}

/// Pushes onto `warnings` every pressure or traction of `case` whose group
/// holds faces inside `mesh` (each a face of two tets of the input mesh: a
/// surface embedded in a volume, a pre-existing fracture, or where two
/// volumes of one MSH part meet). The load acts on the one side the face was given to, as a
/// net force on the body rather than a load on its boundary.
pub fn surface_loads_on_interior_faces(
    case: &LoadedCase,
    loads: &Loads,
    mesh: &JointedMesh,
    warnings: &mut Vec<String>,
) {
    // A face by the input mesh's vertices, which joint insertion split.
    let key = |f: &[u32; 3]| {
        let mut k = f.map(|n| mesh.origin[n as usize]);
        k.sort_unstable();
        k
    };
    let mut tets_of: std::collections::HashMap<[u32; 3], u8> =
        loads.surfaces.iter().flat_map(|s| s.faces.iter().map(|f| (key(f), 0))).collect();
    if tets_of.is_empty() {
        return;
    }
    let tets = &mesh.mesh.tets;
    for t in 0..tets.len() {
        for local in 0..4 {
            let face = femdem_mesh::FaceRef { tet: t as u32, local }.nodes(tets);
            if let Some(n) = tets_of.get_mut(&key(&face)) {
                *n = n.saturating_add(1);
            }
        }
    }
    let specs = case.case.loads.iter().enumerate().filter_map(|(i, l)| match l.get_ref() {
        LoadSpec::Pressure { .. } => Some((i, l, "pressure")),
        LoadSpec::Traction { .. } => Some((i, l, "traction")),
        _ => None,
    });
    for ((i, l, what), surface) in specs.zip(&loads.surfaces) {
        let inside = surface.faces.iter().filter(|f| tets_of[&key(f)] > 1).count();
        if inside > 0 {
            let message = format!(
                "loads[{i}]: {inside} of the {} faces of `{}` lie inside the mesh (each a face of two tets: a \
                 surface embedded in a volume, a pre-existing fracture, or where two volumes of one MSH file meet): the {what} acts \
                 on one side of each only (the tet the face belongs to; in an MSH file, the one whose outward \
                 order agrees with the triangle's), a net force on the body rather than a load on its boundary; \
                 load only outer surfaces, unless one side is meant",
                surface.faces.len(),
                surface.name
            );
            warnings.push(case.error_at(l.span(), message).to_string());
        }
    }
}

/// The `ramp_time` and `stop_time` of a load that ramps: a velocity, or
/// a pressure or traction unless `surfaces_held` (a static start applies
/// those in full from t = 0). `None` for a fixed load.
pub(super) fn ramp_of(load: &LoadSpec, surfaces_held: bool) -> Option<(f64, Option<f64>)> {
    match load {
        LoadSpec::Velocity { ramp_time, stop_time, .. } => Some((*ramp_time, *stop_time)),
        LoadSpec::Pressure { ramp_time, stop_time, .. } | LoadSpec::Traction { ramp_time, stop_time, .. }
            if !surfaces_held =>
        {
            Some((*ramp_time, *stop_time))
        }
        _ => None,
    }
}

/// Pushes onto `warnings` every load of `case` whose `stop_time` comes
/// before its `ramp_time` ends: it stops at the fraction
/// `stop_time / ramp_time` of its value, never reaching it.
/// With `surfaces_held` (a static start, which applies pressures and
/// tractions in full from t = 0) only velocity loads ramp.
pub fn loads_that_stop_while_ramping(case: &LoadedCase, surfaces_held: bool, warnings: &mut Vec<String>) {
    for (i, l) in case.case.loads.iter().enumerate() {
        let Some((ramp_time, stop_time)) = ramp_of(l.get_ref(), surfaces_held) else { continue };
        if let Some(t) = stop_time.filter(|t| *t < ramp_time) {
            let message = format!(
                "loads[{i}]: `stop_time` {t:e} s comes before `ramp_time` {ramp_time:e} s ends: the load stops at \
                 {:.3} of its value, never reaching it",
                t / ramp_time
            );
            warnings.push(case.error_at(l.span(), message).to_string());
        }
    }
}

/// Pushes onto `warnings` every platen without `drives` in a case without
/// `[contact]` that is joined to no other region of `mesh` (no node shared
/// with another region's tet, no joint to one, as an MSH part meshing
/// platen and specimen together has): it can neither touch the specimen
/// nor move any of its nodes, so it passes through it and its recorded
/// force stays zero.
pub fn platens_that_touch_nothing(case: &LoadedCase, mesh: &JointedMesh, warnings: &mut Vec<String>) {
    let m = &mesh.mesh;
    let joined = |region: &str| {
        let Some(r) = m.region_index(region) else { return false };
        let mut on = vec![false; m.num_nodes()];
        for (t, tet) in m.tets.iter().enumerate() {
            if m.tet_region[t] == r {
                tet.iter().for_each(|&n| on[n as usize] = true);
            }
        }
        let shared =
            m.tets.iter().enumerate().any(|(t, tet)| m.tet_region[t] != r && tet.iter().any(|&n| on[n as usize]));
        let of = |f: &femdem_mesh::FaceRef| m.tet_region[f.tet as usize] == r;
        shared || mesh.joint_faces.iter().any(|(a, b)| of(a) != of(b))
    };
    for (i, p) in case.case.platens.iter().enumerate() {
        if p.get_ref().drives.is_none() && !joined(&p.get_ref().region) {
            let message = format!(
                "platens[{i}] (`{}`): without [contact] (or with its `surfaces = false`) and without `drives`, the \
                 platen touches nothing: it moves through the specimen and its force stays zero; add a [contact] \
                 section with outer surfaces in contact, or glue specimen nodes to it with `drives`",
                p.get_ref().region
            );
            warnings.push(case.error_at(p.span(), message).to_string());
        }
    }
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
        if nodes.is_empty() {
            return Err(at(format!(
                "region `{}` holds no tet (no part meshes it), so the platen would press nothing and record no \
                 force; check the `region` of each [[mesh.parts]]",
                s.region
            )));
        }
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
    // The nodes the platens drive in x, y and z (their own and those of
    // their `drives`), to refuse a load that would claim them again at
    // its own table (the solver's check would name only the node).
    let platens = loads.drives.clone();
    let on_platen = |nodes: &[u32]| -> Option<String> {
        platens.iter().find_map(|d| {
            let n = nodes.iter().filter(|n| d.nodes.binary_search(n).is_ok()).count();
            (n > 0).then(|| {
                format!(
                    "`nodes` selects {n} node(s) that platen `{}` already drives in x, y and z (its region's, or \
                     those of its `drives`): a platen moves only as its `velocity` says; set that velocity (0 \
                     holds it), or select nodes off the platen",
                    d.name
                )
            })
        })
    };
    for (i, l) in case.case.loads.iter().enumerate() {
        let at = |msg: String| case.error_at(l.span(), format!("loads[{i}]: {msg}"));
        match l.get_ref() {
            LoadSpec::Fixed { name, nodes, components: c, start_time } => {
                let nodes = select_nodes(mesh, &selector(nodes, "nodes").map_err(at)?).map_err(|u| at(unknown(u)))?;
                if nodes.is_empty() {
                    return Err(at("`nodes` selects no node".into()));
                }
                if let Some(message) = on_platen(&nodes) {
                    return Err(at(message));
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
                if let Some(message) = on_platen(&nodes) {
                    return Err(at(message));
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
                if faces.is_empty() {
                    return Err(at(no_faces(group, "pressure")));
                }
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
                if faces.is_empty() {
                    return Err(at(no_faces(group, "traction")));
                }
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
    if let Some(t) = stop_time
        && !(t.is_finite() && t > 0.0)
    {
        return Err(format!("`stop_time` must be finite and > 0 s, got {t} s"));
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
