//! Where new fractures are expected to start in the multi-layer rock: the
//! tips of the pre-existing fractures and their junctions (Guo et al.
//! §3.3.2: "all new fractures propagate from existing fracture tips", "from
//! stress concentrations around the junctions of layer interfaces and
//! existing fractures").
//!
//! The map is read with the trace-file parser of `femdem` itself and split
//! at its junctions by `femdem_mesh::generate::trace_network`, the code
//! that meshes it, so the points here are those of the mesh. In the split
//! network every junction is a vertex shared by the pieces that meet there
//! (bit for bit), so a vertex's degree — the number of piece ends at it,
//! two for a vertex inside a piece — says what it is: 1 a tip (a trace
//! ending in the rock), 2 a bend of one trace, 3 a T-junction (a trace
//! ending on another), 4 an X-junction (two traces crossing). Vertices on
//! the outline (where a trace reaches the block's side) are neither.

use std::collections::BTreeMap;
use std::path::Path;

use anyhow::{Context, Result, anyhow};
use femdem_mesh::generate::TraceNetwork;

/// The parser `femdem` reads `traces_file` with (`femdem_mesh::trace_file`):
/// the validation reads the map by exactly the rules the mesh was built by.
use femdem_mesh::trace_file;

/// The points of a fracture map where new fractures are expected to start.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Sites {
    /// Trace ends inside the outline that end on no other trace, m.
    pub tips: Vec<[f64; 2]>,
    /// Points where a trace ends on another (T) or crosses it (X), m.
    pub junctions: Vec<[f64; 2]>,
}

impl Sites {
    /// Tips and junctions together.
    pub fn all(&self) -> Vec<[f64; 2]> {
        self.tips.iter().chain(&self.junctions).copied().collect()
    }
}

/// `traces` inside `outline` split at their junctions, as the mesher
/// splits them.
///
/// # Errors
/// The mesher's error for traces it would refuse (a point outside the
/// outline, overlapping traces, …).
pub fn network(outline: &[[f64; 2]], traces: &[Vec<[f64; 2]>]) -> Result<TraceNetwork> {
    femdem_mesh::generate::trace_network(outline, traces).map_err(|e| anyhow!("{e}"))
}

/// The tips and junctions of the split fracture map `network`.
pub fn sites(network: &TraceNetwork) -> Sites {
    let key = |p: [f64; 2]| (p[0].to_bits(), p[1].to_bits());
    let mut degree: BTreeMap<(u64, u64), ([f64; 2], usize)> = BTreeMap::new();
    for piece in &network.pieces {
        let last = piece.len() - 1;
        for (k, &p) in piece.iter().enumerate() {
            degree.entry(key(p)).or_insert((p, 0)).1 += if k == 0 || k == last { 1 } else { 2 };
        }
    }
    for p in &network.outline {
        degree.remove(&key(*p));
    }
    let mut s = Sites::default();
    for (p, d) in degree.into_values() {
        match d {
            1 => s.tips.push(p),
            3.. => s.junctions.push(p),
            _ => {}
        }
    }
    s
}

/// The polylines of the trace file `path`, parsed as `femdem` parses them.
///
/// # Errors
/// An unreadable file, or the parser's error with its line and column.
pub fn read_traces(path: &Path) -> Result<Vec<Vec<[f64; 2]>>> {
    let text = std::fs::read_to_string(path).with_context(|| format!("reading {}", path.display()))?;
    let polylines = trace_file::parse_traces(&text)
        .map_err(|e| anyhow!("{}:{}:{}: {}", path.display(), e.line, e.column, e.message))?;
    Ok(polylines.into_iter().map(|p| p.points).collect())
}

/// The distance from `p` to the nearest of `sites` (infinite when there
/// are none), m.
pub fn nearest(p: [f64; 2], sites: &[[f64; 2]]) -> f64 {
    sites.iter().map(|s| (p[0] - s[0]).hypot(p[1] - s[1])).fold(f64::INFINITY, f64::min)
}

/// The share of `points` within `radius` of one of `sites` (0 for no
/// points).
pub fn share_within(points: &[[f64; 2]], sites: &[[f64; 2]], radius: f64) -> f64 {
    if points.is_empty() {
        return 0.0;
    }
    points.iter().filter(|p| nearest(**p, sites) <= radius).count() as f64 / points.len() as f64
}

#[cfg(test)]
mod tests {
    use super::*;

    const SQUARE: [[f64; 2]; 4] = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];

    fn sorted(mut v: Vec<[f64; 2]>) -> Vec<[f64; 2]> {
        v.sort_by(|a, b| a[0].total_cmp(&b[0]).then(a[1].total_cmp(&b[1])));
        v
    }

    #[test]
    fn tips_t_and_x_junctions_are_found_and_outline_ends_and_bends_are_not() {
        let traces = vec![
            // A persistent interface, outline to outline.
            vec![[0.0, 0.5], [1.0, 0.5]],
            // Ends on the interface (a T) and inside the rock (a tip).
            vec![[0.3, 0.2], [0.3, 0.5]],
            // Crosses the interface (an X), from the outline to a tip,
            // with a bend at (0.7, 0.3).
            vec![[0.7, 0.0], [0.7, 0.3], [0.75, 0.8]],
        ];
        let s = sites(&network(&SQUARE, &traces).unwrap());
        assert_eq!(sorted(s.tips.clone()), vec![[0.3, 0.2], [0.75, 0.8]]);
        assert_eq!(s.junctions.len(), 2, "{s:?}");
        let j = sorted(s.junctions.clone());
        assert_eq!(j[0], [0.3, 0.5]);
        // The crossing of (0.7, 0.3)–(0.75, 0.8) with y = 0.5: x = 0.72.
        assert!((j[1][0] - 0.72).abs() < 1e-12 && (j[1][1] - 0.5).abs() < 1e-12, "{j:?}");
        assert_eq!(s.all().len(), 4);
    }

    #[test]
    fn a_trace_ending_on_the_outline_is_no_site() {
        let s = sites(&network(&SQUARE, &[vec![[0.0, 0.4], [1.0, 0.6]]]).unwrap());
        assert_eq!(s, Sites::default());
    }

    #[test]
    fn shares_count_the_points_within_the_radius() {
        let sites = [[0.0, 0.0], [1.0, 0.0]];
        let points = [[0.1, 0.0], [0.5, 0.0], [1.0, 0.25], [3.0, 3.0]];
        assert!((nearest([0.5, 0.0], &sites) - 0.5).abs() < 1e-15);
        assert_eq!(nearest([0.5, 0.0], &[]), f64::INFINITY);
        assert_eq!(share_within(&points, &sites, 0.3), 0.5);
        assert_eq!(share_within(&points, &sites, 0.5), 0.75);
        assert_eq!(share_within(&[], &sites, 0.5), 0.0);
    }

    #[test]
    fn the_bundled_map_has_the_sites_its_generator_put_there() {
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../cases/paper/multilayer-map.txt");
        let traces = read_traces(&path).unwrap();
        let outline = [[0.0, 0.0], [1.5, 0.0], [1.5, 1.5], [0.0, 1.5]];
        let s = sites(&network(&outline, &traces).unwrap());
        // 8 cross fractures end inside their layer: one tip each. Of the
        // 23, 3 cross an interface (an X each) and the ends on interfaces
        // make 28 Ts (counted by hand from the file).
        assert_eq!(s.tips.len(), 8, "{s:?}");
        assert_eq!(s.junctions.len(), 31, "{s:?}");
        // Every site lies strictly inside the block.
        assert!(s.all().iter().all(|p| p[0] > 0.0 && p[0] < 1.5 && p[1] > 0.0 && p[1] < 1.5));
    }
}
