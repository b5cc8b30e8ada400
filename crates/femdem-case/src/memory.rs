//! The memory a case will need, estimated from its parts' sizes before any
//! mesh is built, and the refusal of a run that would not fit.
//!
//! Counts per part: a box (and a platen, a box against the parts before
//! it) has exactly `6 n_x n_y n_z` tets on `(n_x+1)(n_y+1)(n_z+1)`
//! vertices; an extrusion about `3 × layers × A / (√3/4 h²)` tets (the
//! estimate its generator refuses above 2e8), on about half as many
//! vertices per layer as triangles; an MSH file is read (its size is the
//! file's) and placed by its `scale` and `translate`. A breakable region's
//! tets own their four nodes after joint insertion and carry a joint on
//! each interior face, about two per tet; an unbreakable region keeps its
//! vertices and has no joints. With
//! `joints_within`, the jointed share `s` of a part's tets is the share of
//! its volume in the zones (sampled on a grid, `crate::zones::sampled_share`;
//! exact from the centroids for an MSH part; 1 for a platen part, whose
//! place is not known before meshing): `4 s T + (1 − s) V` nodes and
//! `2 s T` joints for `T` tets on `V` vertices.
//!
//! Bytes per item are the arrays that hold them, element by element (see
//! [`PER_NODE`], [`PER_TET`], [`per_joint`]; with a viscous material,
//! [`PER_VISCOUS_NODE`] more per node); `docs/reliability.md` has
//! the ratio of a run's measured peak resident memory to this estimate.

use std::mem::size_of;
use std::path::Path;

use anyhow::{Result, bail};
use femdem_core::{Mat3, Vec3};
use femdem_mesh::TetMesh;

use crate::LoadedCase;
use crate::format::PartSpec;
use crate::zones::{centroid_share, sampled_share, zones_of};

/// Bytes per node after joint insertion: positions in the mesh, the
/// model's reference and the state (`x0`, `x`, `v`), the gathered internal
/// force and the update's force (5 `Vec3`, plus the jointed mesh's copy),
/// the lumped mass, the origin (mesh and model), the rigid flag, the two
/// gather offsets.
pub const PER_NODE: usize = 6 * size_of::<Vec3>() + size_of::<f64>() + 2 * size_of::<u32>() + 1 + 2 * size_of::<u32>();

/// Bytes per node when a material is viscous: the velocities of the step
/// before, which the viscous dissipation reads (`femdem_solver::Dissipation`).
pub const PER_VISCOUS_NODE: usize = size_of::<Vec3>();

/// Bytes per tet: its nodes in the mesh, the jointed mesh and the model
/// (3 × `[u32; 4]`, with the region ids), the reference data (`Dm⁻¹` and
/// volume), the material id, four force slots, the stress and four gather
/// slots, and the contact pass's tets around each vertex (four ids).
pub const PER_TET: usize = 3 * (size_of::<[u32; 4]>() + size_of::<u16>())
    + size_of::<femdem_material::TetReference>()
    + size_of::<u16>()
    + 4 * size_of::<Vec3>()
    + size_of::<Mat3>()
    + 4 * size_of::<u32>()
    + 4 * size_of::<u32>();

/// Bytes per joint: its six nodes (jointed mesh and model), its law (the
/// parameters and the derived lengths), its two tets, its two faces, its
/// history (the per-joint state: damage at three points, energies), six
/// force slots, the failure flag and six gather slots.
pub fn per_joint() -> usize {
    2 * size_of::<[u32; 6]>()
        + size_of::<femdem_fracture::Joint>()
        + size_of::<[u32; 2]>()
        + 2 * size_of::<femdem_mesh::FaceRef>()
        + size_of::<femdem_fracture::JointHistory>()
        + 6 * size_of::<Vec3>()
        + size_of::<Option<femdem_fracture::FailureMode>>()
        + 6 * size_of::<u32>()
}

/// What a case's mesh will hold and need.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Estimate {
    /// Tets.
    pub tets: f64,
    /// Nodes after joint insertion.
    pub nodes: f64,
    /// Joints.
    pub joints: f64,
    /// Bytes of the arrays of the mesh, the model, the state and the
    /// force pass.
    pub bytes: f64,
    /// Whether a material is viscous (its nodes need [`PER_VISCOUS_NODE`]).
    viscous: bool,
}

impl Estimate {
    /// Adds a part of `tets` tets on `vertices` vertices, the share
    /// `jointed` (0 to 1) of them jointed.
    fn add(&mut self, tets: f64, vertices: f64, jointed: f64) {
        self.tets += tets;
        self.nodes += 4.0 * jointed * tets + (1.0 - jointed) * vertices;
        self.joints += 2.0 * jointed * tets;
        let per_node = PER_NODE + if self.viscous { PER_VISCOUS_NODE } else { 0 };
        self.bytes = self.nodes * per_node as f64 + self.tets * PER_TET as f64 + self.joints * per_joint() as f64;
    }
}

/// The estimate of `case`'s mesh, from its parts, before building it; `None`
/// when a part cannot be sized (a bad parameter or an unreadable MSH file:
/// building the mesh reports it).
pub fn estimate(case: &LoadedCase) -> Option<Estimate> {
    let section = &case.case.mesh;
    let breakable = |region: &str| section.regions.iter().any(|r| r.get_ref().name == region && r.get_ref().breakable);
    // The jointed share of a part of `region` in the box `[lo, hi]`, where
    // `inside` says which points belong to the part.
    let jointed = |region: &str, lo: [f64; 3], hi: [f64; 3], inside: &dyn Fn([f64; 3]) -> bool| {
        if !breakable(region) {
            return 0.0;
        }
        zones_of(section, region).map_or(1.0, |zones| sampled_share(&zones, lo, hi, inside))
    };
    let mut out = Estimate { viscous: viscous(case), ..Estimate::default() };
    // The bounding box of the parts so far, for platens.
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    let grow = |a: [f64; 3], b: [f64; 3], lo: &mut [f64; 3], hi: &mut [f64; 3]| {
        for k in 0..3 {
            lo[k] = lo[k].min(a[k]);
            hi[k] = hi[k].max(b[k]);
        }
    };
    for part in &section.parts {
        match part.get_ref() {
            PartSpec::Box { region, min, max, element_size, .. } => {
                let (tets, vertices) = box_counts(*min, *max, *element_size)?;
                out.add(tets, vertices, jointed(region, *min, *max, &|_| true));
                grow(*min, *max, &mut lo, &mut hi);
            }
            PartSpec::Extrusion { region, circle, polygon, z0, thickness, element_size, layers, .. } => {
                let h = *element_size;
                let (area, b_lo, b_hi) = match (circle, polygon) {
                    (Some(c), None) => (
                        std::f64::consts::PI * c.radius * c.radius,
                        [c.center[0] - c.radius, c.center[1] - c.radius],
                        [c.center[0] + c.radius, c.center[1] + c.radius],
                    ),
                    (None, Some(p)) if !p.is_empty() => {
                        let area = femdem_mesh::generate::polygon_area(p);
                        let lo = p.iter().fold([f64::INFINITY; 2], |l, q| [l[0].min(q[0]), l[1].min(q[1])]);
                        let hi = p.iter().fold([f64::NEG_INFINITY; 2], |l, q| [l[0].max(q[0]), l[1].max(q[1])]);
                        (area, lo, hi)
                    }
                    _ => return None,
                };
                let layers = layers.map_or_else(|| (thickness / h).round().max(1.0), |n| n as f64);
                // The generator's own estimate (equilateral triangles of
                // edge h).
                let triangles = area / (3f64.sqrt() / 4.0 * h * h);
                let tets = 3.0 * layers * triangles;
                let vertices = 0.5 * triangles * (layers + 1.0);
                if !(tets.is_finite() && tets >= 0.0) {
                    return None;
                }
                let (p_lo, p_hi) = ([b_lo[0], b_lo[1], *z0], [b_hi[0], b_hi[1], z0 + thickness]);
                let in_outline = |p: [f64; 3]| match (circle, polygon) {
                    (Some(c), _) => (p[0] - c.center[0]).powi(2) + (p[1] - c.center[1]).powi(2) <= c.radius * c.radius,
                    (_, Some(poly)) => in_polygon(poly, [p[0], p[1]]),
                    _ => false,
                };
                out.add(tets, vertices, jointed(region, p_lo, p_hi, &in_outline));
                grow(p_lo, p_hi, &mut lo, &mut hi);
            }
            PartSpec::Platen { region, side, thickness, extent, element_size, .. } => {
                if lo[0] > hi[0] {
                    return None;
                }
                let side = crate::mesh::parse_side(side)?;
                let axis = side.axis();
                let others = [(axis + 1) % 3, (axis + 2) % 3];
                let others = if others[0] < others[1] { others } else { [others[1], others[0]] };
                let mut size = [*thickness; 3];
                for (k, &a) in others.iter().enumerate() {
                    size[a] = extent.map_or(hi[a] - lo[a], |e| e[k]);
                }
                let (tets, vertices) = box_counts([0.0; 3], size, *element_size)?;
                out.add(tets, vertices, if breakable(region) { 1.0 } else { 0.0 });
            }
            PartSpec::Msh { path, scale, translate, .. } => {
                let bytes = std::fs::read(case.dir().join(path)).ok()?;
                let mut mesh = femdem_mesh::msh::read_msh(&bytes).ok()?;
                // In the case's coordinates, as the mesh will be: its
                // bounds size a later platen, its centroids meet the zones.
                crate::mesh::place(&mut mesh, *scale, *translate).ok()?;
                let (b_lo, b_hi) = mesh.bounding_box()?;
                for (r, region) in mesh.regions.iter().enumerate() {
                    let of_region: Vec<usize> =
                        (0..mesh.num_tets()).filter(|&t| mesh.tet_region[t] as usize == r).collect();
                    let tets = of_region.len() as f64;
                    let share = tets / mesh.num_tets().max(1) as f64;
                    let jointed = match (breakable(&region.name), zones_of(section, &region.name)) {
                        (false, _) => 0.0,
                        (true, None) => 1.0,
                        (true, Some(zones)) => centroid_share(&zones, &mesh, &of_region),
                    };
                    out.add(tets, share * mesh.num_nodes() as f64, jointed);
                }
                grow(b_lo, b_hi, &mut lo, &mut hi);
            }
        }
    }
    Some(out)
}

/// Whether a material of `case` is viscous (its nodes then carry
/// [`PER_VISCOUS_NODE`] more).
fn viscous(case: &LoadedCase) -> bool {
    case.case.materials.iter().any(|m| {
        let m = m.get_ref();
        m.viscosity.is_some_and(|v| v > 0.0) || m.damping_ratio.is_some_and(|r| r > 0.0)
    })
}

/// The estimate of `case`'s mesh once built, `mesh` with its joint zone
/// `zone` (false for the tets that `joints_within` leaves without joints),
/// before its joints are inserted: exact in tets, the jointed share from
/// the breakable regions and the zone, nodes and joints counted as
/// [`estimate`] counts them. It differs from [`estimate`]'s where an
/// extrusion refines around crowded features ([`crate::refinement`]).
pub fn of_built(case: &LoadedCase, mesh: &TetMesh, zone: &[bool]) -> Estimate {
    let tets = mesh.num_tets();
    let jointed = (0..tets)
        .filter(|&t| mesh.regions[mesh.tet_region[t] as usize].breakable && zone.get(t).copied().unwrap_or(true))
        .count();
    let mut out = Estimate { viscous: viscous(case), ..Estimate::default() };
    out.add(tets as f64, mesh.num_nodes() as f64, if tets == 0 { 0.0 } else { jointed as f64 / tets as f64 });
    out
}

/// The refusal message when the mesh built, whose estimate is `built`,
/// would need more than the `available` memory: the check that
/// [`refuse_if_too_big`] made from the parts' sizes, made again on the
/// tets that were actually made, before joint insertion multiplies the
/// nodes by four. `warnings` (what meshing noted) are appended: they say
/// where a mesh grew beyond its sizes.
pub fn refusal_built(built: &Estimate, available: Available, warnings: &[String]) -> Option<String> {
    const GIB: f64 = 1024.0 * 1024.0 * 1024.0;
    let source = if available.from_flag { "--memory-available" } else { "MemAvailable" };
    (built.bytes > available.bytes).then(|| {
        let noted: String = warnings.iter().map(|w| format!("\n  warning: {w}")).collect();
        format!(
            "the mesh built has {:.3e} tets and, with its joints, would need about {:.1} GiB ({:.3e} nodes, \
             {:.3e} joints), more than the {:.1} GiB of memory available ({source}); use a larger element_size, \
             or --force to try anyway{noted}",
            built.tets,
            built.bytes / GIB,
            built.nodes,
            built.joints,
            available.bytes / GIB
        )
    })
}

/// Whether `p` lies inside the polygon `poly` (even–odd rule).
fn in_polygon(poly: &[[f64; 2]], p: [f64; 2]) -> bool {
    let mut inside = false;
    for i in 0..poly.len() {
        let (a, b) = (poly[i], poly[(i + 1) % poly.len()]);
        if (a[1] > p[1]) != (b[1] > p[1]) && p[0] < a[0] + (p[1] - a[1]) / (b[1] - a[1]) * (b[0] - a[0]) {
            inside = !inside;
        }
    }
    inside
}

/// Tets and vertices of a box meshed at `h`, as `generate_box` makes them.
fn box_counts(min: [f64; 3], max: [f64; 3], h: f64) -> Option<(f64, f64)> {
    let mut cells = 1.0;
    let mut vertices = 1.0;
    for k in 0..3 {
        let n = ((max[k] - min[k]) / h).round().max(1.0);
        if !n.is_finite() {
            return None;
        }
        cells *= n;
        vertices *= n + 1.0;
    }
    Some((6.0 * cells, vertices))
}

/// `MemAvailable` of `/proc/meminfo`, bytes (Linux; `None` elsewhere or if
/// unreadable).
pub fn available_memory() -> Option<f64> {
    let text = std::fs::read_to_string("/proc/meminfo").ok()?;
    let line = text.lines().find(|l| l.starts_with("MemAvailable:"))?;
    let kib: f64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib * 1024.0)
}

/// The memory a case may use, bytes, and where the figure comes from.
#[derive(Clone, Copy, Debug)]
pub struct Available {
    /// Bytes.
    pub bytes: f64,
    /// `MemAvailable` of `/proc/meminfo`, or `--memory-available`.
    pub from_flag: bool,
}

impl Available {
    /// `--memory-available` if given, else `MemAvailable`; `None` when
    /// neither is known.
    pub fn of(flag: Option<f64>) -> Option<Available> {
        match flag {
            Some(bytes) => Some(Available { bytes, from_flag: true }),
            None => available_memory().map(|bytes| Available { bytes, from_flag: false }),
        }
    }
}

/// The refusal message when `estimate` exceeds the `available` memory;
/// `command` is `run` or `check`.
pub fn refusal(path: &Path, estimate: &Estimate, available: Available, command: &str) -> Option<String> {
    const GIB: f64 = 1024.0 * 1024.0 * 1024.0;
    let source = if available.from_flag { "--memory-available" } else { "MemAvailable" };
    (estimate.bytes > available.bytes).then(|| {
        format!(
            "{}: the mesh would need about {:.1} GiB ({:.3e} tets, {:.3e} nodes, {:.3e} joints), more than the \
             {:.1} GiB of memory available ({source}); use a larger element_size, or {command} with --force to \
             try anyway",
            path.display(),
            estimate.bytes / GIB,
            estimate.tets,
            estimate.nodes,
            estimate.joints,
            available.bytes / GIB
        )
    })
}

/// Before `femdem run` or `femdem check` (`command`) builds anything:
/// refuses a case (with its `--set` arguments `sets`) whose estimate
/// exceeds the available memory (`memory_available` bytes if given, for
/// tests; else `MemAvailable`), unless `force`. A case that does not load or cannot be sized is left to the
/// run, which reports why. Sets the run's thread count (`threads`, the
/// command line's `--threads`, else the case's) before it reads an MSH
/// part ([`crate::prepare::set_threads`]).
pub fn refuse_if_too_big(
    path: &Path,
    sets: &[String],
    threads: Option<usize>,
    force: bool,
    memory_available: Option<f64>,
    command: &str,
) -> Result<()> {
    if force {
        return Ok(());
    }
    if let Some(bytes) = memory_available
        && !(bytes.is_finite() && bytes > 0.0)
    {
        bail!("--memory-available must be a number of bytes > 0, got {bytes}");
    }
    let (Ok(loaded), Some(available)) = (crate::load(path, sets), Available::of(memory_available)) else {
        return Ok(());
    };
    // Reading an MSH part below uses rayon's pool, which its first use
    // builds for good: set the run's thread count first. A bad count is
    // left to `prepare`, which refuses it.
    let _ = crate::prepare::set_threads(&loaded, threads);
    if let Some(message) = estimate(&loaded).and_then(|e| refusal(path, &e, available, command)) {
        bail!(message);
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The counts estimated from the parts against those of the mesh built:
    /// boxes and platens exactly in tets and nodes; joints within 5% (two
    /// per tet counts the boundary faces as interior: 1.7% high on the
    /// 192,000-tet box of `docs/reliability.md`, more on a small mesh with
    /// more of its faces on the boundary); an extrusion's tets within 10% and joints within 15% (measured 3% and 10% on the small Brazilian disc)
    /// (refinement makes triangles smaller than the equilateral one of edge
    /// h, up to `AREA_FACTOR` times larger, and the circle is inscribed).
    /// The band case (`joints_within`) within the same bounds: its jointed
    /// share is sampled from the band's area, the mesh's from its tets'
    /// centroids.
    #[test]
    fn the_estimate_counts_what_the_mesh_holds() {
        let root = Path::new(env!("CARGO_MANIFEST_DIR"));
        for (file, tet_tol, joint_tol) in [
            ("../femdem-cli/tests/cases/small_brazilian.toml", 0.1, 0.15),
            ("../femdem-cli/tests/cases/bad/crushed_cube.toml", 0.0, 0.0),
            ("../../cases/brazilian-split-band.toml", 0.1, 0.15),
        ] {
            let path = root.join(file);
            let loaded = crate::load(&path, &[]).unwrap();
            let e = estimate(&loaded).expect("the case can be sized");
            let mesh = crate::mesh::build_mesh(&loaded).unwrap();
            let zone = crate::zones::joint_zone(&loaded, &mesh).unwrap();
            let jointed = femdem_mesh::insert_joints_within(&mesh, &zone).unwrap();
            let (tets, joints) = (mesh.num_tets() as f64, jointed.joints.len() as f64);
            let rel = |a: f64, b: f64| if b == 0.0 { a } else { (a - b).abs() / b };
            eprintln!("{file}: tets {} vs {tets}, joints {} vs {joints}", e.tets, e.joints);
            assert!(rel(e.tets, tets) <= tet_tol, "{file}: tets {} vs {tets}", e.tets);
            assert!(rel(e.joints, joints) <= joint_tol, "{file}: joints {} vs {joints}", e.joints);
            assert!(e.bytes > jointed.array_bytes() as f64, "the run holds more than the jointed mesh");
            // Counted on the mesh built: exact in tets, the joints as close
            // as the parts' estimate (two a jointed tet).
            let built = of_built(&loaded, &mesh, &zone);
            assert_eq!(built.tets, tets, "{file}");
            assert!(rel(built.joints, joints) <= joint_tol.max(0.05), "{file}: joints {} vs {joints}", built.joints);
            assert!(built.bytes > jointed.array_bytes() as f64, "{file}");
        }
    }

    #[test]
    fn a_run_that_does_not_fit_is_refused_with_its_figures() {
        let e = Estimate { tets: 1e8, nodes: 4e8, joints: 2e8, bytes: 3e11, viscous: false };
        let at = |bytes: f64| Available { bytes, from_flag: false };
        let message = refusal(Path::new("big.toml"), &e, at(16e9), "run").expect("refused");
        assert!(message.starts_with("big.toml: the mesh would need about 279.4 GiB"), "{message}");
        assert!(message.contains("1.000e8 tets") && message.contains("run with --force"), "{message}");
        assert!(message.contains("(MemAvailable)"), "{message}");
        assert_eq!(refusal(Path::new("big.toml"), &e, at(4e11), "run"), None);
        let given = Available { bytes: 16e9, from_flag: true };
        let message = refusal(Path::new("big.toml"), &e, given, "check").expect("refused");
        assert!(message.contains("(--memory-available)") && message.contains("check with --force"), "{message}");
    }
}
