//! An extrusion meshed far finer than its `element_size` asks: where the
//! outline's points or its traces lie much closer together than
//! `element_size` (two traces nearly on top of each other, a trace ending
//! a hair short of another or of the outline), the constrained Delaunay
//! refinement has to fill the gap with triangles of the gap's size. The
//! tet count and the stable time step (proportional to the shortest edge)
//! then follow the gap, not `element_size`: a run can cost thousands of
//! times what the case suggests, without being wrong. Worth a warning
//! that says where.

use femdem_mesh::TetMesh;

/// A part's tet count above this multiple of what its `element_size`
/// gives is called out. The bundled extrusions, traces included, mesh to
/// 1.04–1.11 times the estimate (`traces.toml`, the multi-layer case at
/// 75 and 24 mm, the Brazilian discs); a gap between features ten times
/// smaller than `element_size` makes some 5–20 times it.
pub const FACTOR: f64 = 2.0;

/// The warning for extrusion part `key`, meshed as `body` at element size
/// `h` in `layers` layers of total `thickness`, when it holds more than
/// [`FACTOR`] times the tets `h` gives: the count, the ratio, and the
/// shortest edge in the plane with where it lies (its midpoint), which
/// is where the features crowd. `None` for a mesh of the size asked.
pub fn warning(key: &str, body: &TetMesh, h: f64, layers: usize, thickness: f64) -> Option<String> {
    let volume: f64 = (0..body.num_tets()).map(|t| femdem_core::tet::signed_volume(&body.tet_points(t)).abs()).sum();
    let expected = femdem_mesh::generate::estimated_tets(volume / thickness, h, layers);
    let tets = body.num_tets() as f64;
    if !(expected > 0.0 && tets > FACTOR * expected) {
        return None;
    }
    // In the plane: a thin layer's vertical edges say nothing of the gap.
    let (length, mid) = shortest_edge(body, |a, b| a.z == b.z)?;
    Some(format!(
        "{key}: {} tets, {:.0} times the {:.0} that element_size = {h} m gives over this outline: the mesh \
         refines down to edges of {length:.3e} m (the shortest at x = {:.6}, y = {:.6} m), where points of the \
         outline or traces lie closer together than element_size; both the tet count and the time step (which \
         scales with the shortest edge) follow that gap. Move the traces there apart or join them, if the gap \
         is not meant",
        body.num_tets(),
        tets / expected,
        expected,
        mid[0],
        mid[1],
    ))
}

/// The length and midpoint of the shortest edge of `body`'s tets among
/// those whose ends `keep` accepts.
pub(crate) fn shortest_edge(
    body: &TetMesh,
    keep: impl Fn(&femdem_core::Vec3, &femdem_core::Vec3) -> bool,
) -> Option<(f64, [f64; 3])> {
    const EDGES: [(usize, usize); 6] = [(0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3)];
    let mut best: Option<(f64, [f64; 3])> = None;
    for t in 0..body.num_tets() {
        let p = body.tet_points(t);
        for (a, b) in EDGES {
            if !keep(&p[a], &p[b]) {
                continue;
            }
            let length = (p[b] - p[a]).norm();
            if best.is_none_or(|(l, _)| length < l) {
                let m = 0.5 * (p[a] + p[b]);
                best = Some((length, [m.x, m.y, m.z]));
            }
        }
    }
    best
}
