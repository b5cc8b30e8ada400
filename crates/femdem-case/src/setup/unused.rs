//! What a case declares that the run would not use, or not in full: a
//! region no part meshes, pre-existing fractures with nothing to keep their
//! faces apart, a `[heterogeneity]` with no joint to act on, a load whose
//! ramp outlasts the run. Each is legal and each has been a slip; they
//! come back as warnings.

use femdem_mesh::JointedMesh;

use crate::LoadedCase;
use crate::format::PartSpec;

/// Pushes a warning for every `[[mesh.regions]]` entry that holds no tet
/// of `mesh` (no part meshes it: a misspelt `region` of a part, say): its
/// material and loads act on nothing. (A platen's region without tets is
/// refused with the platen.)
pub fn regions_without_tets(case: &LoadedCase, mesh: &JointedMesh, warnings: &mut Vec<String>) {
    let m = &mesh.mesh;
    let mut count = vec![0usize; m.regions.len()];
    for &r in &m.tet_region {
        count[r as usize] += 1;
    }
    let platen = |name: &str| case.case.platens.iter().any(|p| p.get_ref().region == name);
    for (i, r) in case.case.mesh.regions.iter().enumerate() {
        let name = &r.get_ref().name;
        let tets = m.region_index(name).map_or(0, |k| count[k as usize]);
        if tets == 0 && !platen(name) {
            let message = format!(
                "mesh.regions[{i}] (`{name}`): no part meshes this region (it holds no tet), so its material and \
                 whatever selects it act on nothing; check the `region` of each [[mesh.parts]]"
            );
            warnings.push(case.error_at(r.span(), message).to_string());
        }
    }
}

/// Pushes a warning when `mesh` has faces on pre-existing fractures
/// (traces) but the case has no `[contact]`: nothing keeps the two sides
/// of a trace apart, so they pass through each other under compression.
pub fn fractures_without_contact(case: &LoadedCase, mesh: &JointedMesh, warnings: &mut Vec<String>) {
    if mesh.initial_contacts.is_empty() || case.case.contact.is_some() {
        return;
    }
    let traced = case.case.mesh.parts.iter().enumerate().find(|(_, p)| match p.get_ref() {
        PartSpec::Extrusion { traces, traces_file, .. } => !traces.is_empty() || traces_file.is_some(),
        _ => false,
    });
    let message = format!(
        "{} tet pairs face each other across pre-existing fractures (traces), but the case has no [contact]: \
         nothing keeps the two sides apart, so they carry no compression and pass through each other; add a \
         [contact] section",
        mesh.initial_contacts.len()
    );
    warnings.push(match traced {
        Some((i, p)) => case.error_at(p.span(), format!("mesh.parts[{i}]: {message}")).to_string(),
        None => crate::CaseError { path: case.path.clone(), at: None, message }.to_string(),
    });
}

/// Pushes a warning when `[heterogeneity]` is given but no region is
/// breakable: it scales the joints' strengths, and there are no joints.
pub fn heterogeneity_without_joints(case: &LoadedCase, mesh: &JointedMesh, warnings: &mut Vec<String>) {
    if let Some(h) = &case.case.heterogeneity
        && mesh.joints.is_empty()
    {
        let message = "heterogeneity: the mesh has no joints (no region is breakable, or its zones hold no tet), \
                       and heterogeneity scales the joints' strengths: it changes nothing";
        warnings.push(case.error_at(h.span(), message.to_string()).to_string());
    }
}

/// Pushes a warning for every platen and load whose `ramp_time` is longer
/// than the run (`end_time`, s) and that no `stop_time` cuts first: it
/// reaches only `end_time / ramp_time` of its value. With `surfaces_held`
/// (a static start, which applies pressures and tractions in full) only
/// velocities ramp.
pub fn ramps_longer_than_the_run(case: &LoadedCase, end_time: f64, surfaces_held: bool, warnings: &mut Vec<String>) {
    let mut warn = |span: std::ops::Range<usize>, what: String, ramp_time: f64| {
        let message = format!(
            "{what}: `ramp_time` {ramp_time:e} s is longer than the run (`end_time` {end_time:e} s): it reaches only \
             {:.3} of its value",
            end_time / ramp_time
        );
        warnings.push(case.error_at(span, message).to_string());
    };
    for (i, p) in case.case.platens.iter().enumerate() {
        if p.get_ref().ramp_time > end_time {
            warn(p.span(), format!("platens[{i}]"), p.get_ref().ramp_time);
        }
    }
    for (i, l) in case.case.loads.iter().enumerate() {
        let Some((ramp_time, stop_time)) = super::loads::ramp_of(l.get_ref(), surfaces_held) else { continue };
        // A stop before the end of the ramp is the other warning's.
        if ramp_time > end_time && stop_time.is_none_or(|t| t >= ramp_time) {
            warn(l.span(), format!("loads[{i}]"), ramp_time);
        }
    }
}
