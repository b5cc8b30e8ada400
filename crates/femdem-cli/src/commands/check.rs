//! `femdem check CASE.toml [--json] [--set KEY.PATH=VALUE]...`: build the
//! mesh with joints and report.

use std::path::Path;

use anyhow::Result;
use femdem_mesh::{face_adjacency, faces::face_key, stats};
use serde::Serialize;

use femdem_case as case;
use femdem_case::prepare::prepare_within;

/// One region in the report.
#[derive(Serialize)]
struct RegionReport {
    name: String,
    tets: usize,
    volume: f64,
    breakable: bool,
    /// Tets that own their nodes and carry joints: all of a breakable
    /// region's, or those in its `joints_within` zones; 0 if unbreakable.
    jointed_tets: usize,
    /// Whether `joints_within` confines the region's joints.
    zoned: bool,
}

/// One boundary group in the report.
#[derive(Serialize)]
struct GroupReport {
    name: String,
    faces: usize,
}

/// What `femdem check` prints (and `--json` serialises). Lengths in m,
/// volumes in m³, memory in bytes.
#[derive(Serialize)]
struct CheckReport {
    case: String,
    /// The `--set` arguments, as given.
    overrides: Vec<String>,
    title: String,
    tets: usize,
    nodes: usize,
    vertices: usize,
    joints: usize,
    interface_joints: usize,
    interior_faces: usize,
    initial_contact_faces: usize,
    /// The mesh's bounding box, `[min, max]`, m (a file in millimetres
    /// shows here a thousand times too large).
    bounds: Option<[[f64; 3]; 2]>,
    min_volume: f64,
    volume: f64,
    min_edge: f64,
    mean_edge: f64,
    min_inradius: f64,
    max_aspect_ratio: f64,
    memory_bytes: usize,
    /// The memory estimated from the parts before meshing (what `femdem
    /// run` compares with the available memory), bytes.
    estimated_memory_bytes: Option<f64>,
    regions: Vec<RegionReport>,
    boundary_groups: Vec<GroupReport>,
    /// Present when the case has a `[solver]`.
    time_stepping: Option<TimeStepReport>,
}

/// The time step a run would take.
#[derive(Serialize)]
struct TimeStepReport {
    critical_time_step: f64,
    time_step: f64,
    element_transit_time: f64,
    omega_max: f64,
    contact_omega: f64,
    damping_ratio: f64,
    steps: u64,
    deformable_tets: usize,
    lanczos_iterations: usize,
}

/// Runs the command.
pub fn run(
    path: &Path,
    json: bool,
    threads: Option<usize>,
    sets: &[String],
    memory: Option<femdem_case::memory::Available>,
) -> Result<()> {
    let prepared = prepare_within(path, threads, sets, memory)?;
    for warning in &prepared.warnings {
        eprintln!("warning: {warning}");
    }
    let (loaded, mesh, jointed) = (&prepared.case, &prepared.mesh, &prepared.jointed);
    let s = stats(mesh);

    // Counted from the face adjacency of the unsplit mesh and the joint
    // zone, independently of joint insertion, so `joints == interior_faces`
    // (+ `interface_joints`) is a real check.
    let fracture: std::collections::HashSet<u128> =
        mesh.fracture_faces.iter().map(|f| face_key(f.nodes(&mesh.tets))).collect();
    let zone = &prepared.zone;
    let is_jointed = |t: u32| mesh.regions[mesh.tet_region[t as usize] as usize].breakable && zone[t as usize];
    let interior_faces = face_adjacency(mesh)
        .map_err(|e| anyhow::anyhow!("{}: mesh: {e}", path.display()))?
        .interior
        .iter()
        .filter(|(a, b)| is_jointed(a.tet) && is_jointed(b.tet) && !fracture.contains(&face_key(a.nodes(&mesh.tets))))
        .count();

    let report = CheckReport {
        case: path.display().to_string(),
        overrides: loaded.overrides.args(),
        title: loaded.case.title.clone(),
        tets: s.tets,
        nodes: jointed.mesh.num_nodes(),
        vertices: mesh.num_nodes(),
        joints: jointed.joints.len(),
        interface_joints: jointed.interface_joints,
        interior_faces,
        initial_contact_faces: jointed.initial_contacts.len(),
        bounds: mesh.bounding_box().map(|(lo, hi)| [lo, hi]),
        min_volume: s.min_volume,
        volume: s.volume,
        min_edge: s.min_edge,
        mean_edge: s.mean_edge,
        min_inradius: s.min_inradius,
        max_aspect_ratio: s.max_aspect_ratio,
        memory_bytes: jointed.array_bytes(),
        estimated_memory_bytes: femdem_case::memory::estimate(loaded).map(|e| e.bytes),
        regions: s
            .regions
            .iter()
            .enumerate()
            .map(|(i, r)| RegionReport {
                name: r.name.clone(),
                tets: r.tets,
                volume: r.volume,
                breakable: r.breakable,
                jointed_tets: (0..mesh.num_tets())
                    .filter(|&t| mesh.tet_region[t] as usize == i && is_jointed(t as u32))
                    .count(),
                zoned: case::zones::zones_of(&loaded.case.mesh, &r.name).is_some(),
            })
            .collect(),
        boundary_groups: mesh
            .boundary
            .iter()
            .map(|g| GroupReport { name: g.name.clone(), faces: g.faces.len() })
            .collect(),
        time_stepping: prepared.run.as_ref().map(|r| TimeStepReport {
            critical_time_step: r.stable.critical,
            time_step: r.solver.dt(),
            element_transit_time: r.stable.element_transit,
            omega_max: r.stable.omega_max,
            contact_omega: r.stable.contact_omega,
            damping_ratio: r.stable.damping_ratio,
            steps: r.steps,
            deformable_tets: r.solver.model().num_deformable_tets(),
            lanczos_iterations: r.stable.iterations,
        }),
    };
    if json {
        println!("{}", serde_json::to_string_pretty(&report)?);
    } else {
        print_text(&report);
    }
    Ok(())
}

fn print_text(r: &CheckReport) {
    println!("case      {}", r.case);
    for o in &r.overrides {
        println!("  --set   {o}");
    }
    if !r.title.is_empty() {
        println!("title     {}", r.title);
    }
    println!("tets      {}", r.tets);
    println!("nodes     {} (from {} vertices; jointed tets own their nodes)", r.nodes, r.vertices);
    println!(
        "joints    {} ({} on interfaces: breakable/unbreakable, or a joints_within zone's edge)",
        r.joints, r.interface_joints
    );
    println!("interior faces (jointed|jointed, not pre-fractured)       {}", r.interior_faces);
    println!("initial contact faces (pre-existing fractures)            {}", r.initial_contact_faces);
    if let Some([lo, hi]) = r.bounds {
        let xyz = |p: [f64; 3]| format!("({:.6e}, {:.6e}, {:.6e})", p[0], p[1], p[2]);
        println!("bounds    {} to {} m", xyz(lo), xyz(hi));
    }
    println!("volume    {:.6e} m³   min tet volume {:.3e} m³", r.volume, r.min_volume);
    println!("edges     min {:.4e} m   mean {:.4e} m", r.min_edge, r.mean_edge);
    println!(
        "quality   min inradius {:.4e} m   worst aspect ratio {:.3} (1 = regular)",
        r.min_inradius, r.max_aspect_ratio
    );
    println!("memory    {:.1} MiB in mesh and joint arrays", r.memory_bytes as f64 / (1024.0 * 1024.0));
    if let Some(bytes) = r.estimated_memory_bytes {
        println!(
            "          {:.1} MiB estimated for the run before meshing (mesh, model, state, force pass)",
            bytes / (1024.0 * 1024.0)
        );
    }
    println!("regions");
    for g in &r.regions {
        let kind = match (g.breakable, g.zoned) {
            (false, _) => "unbreakable".to_string(),
            (true, false) => "breakable".to_string(),
            (true, true) => format!("breakable, joints in {} tets (joints_within)", g.jointed_tets),
        };
        println!("  {:<20} {:>9} tets  {:.6e} m³  {kind}", g.name, g.tets, g.volume);
    }
    if let Some(t) = &r.time_stepping {
        println!(
            "time step {:.4e} s (critical {:.4e} s from ω_max = {:.4e} rad/s, contact ω_c = {:.4e} rad/s, \
             top-mode damping β_max/(2 ω_max) = {:.3}; element transit {:.4e} s)",
            t.time_step, t.critical_time_step, t.omega_max, t.contact_omega, t.damping_ratio, t.element_transit_time
        );
        println!("steps     {} ({:.3e} tet-steps)", t.steps, t.steps as f64 * t.deformable_tets as f64);
    }
    println!("boundary groups");
    for g in &r.boundary_groups {
        println!("  {:<28} {:>8} faces", g.name, g.faces);
    }
}
