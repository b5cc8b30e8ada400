//! Can the pre-existing fracture network alone hold the block's faces under
//! dead loads? A limit-equilibrium estimate for a rectangular block whose
//! x faces are pulled by a tension σxx > 0 (the paper's P_x = +2.5 MPa,
//! §3.3) while σyy < 0 presses its layers together.
//!
//! A piece of the block next to an x face can come away along the
//! pre-existing fractures alone (the intact rock unbroken). It is cut off by
//! a path through the fracture network from one point of the face to
//! another, possibly running along the y faces (pressure boundaries: they
//! give no friction). The face's dead load pulls it out with the force
//! `L = σxx · (y_b − y_a)` per unit thickness (N/m); the cut resists, at
//! most, with Coulomb friction on its closed segments under the far-field
//! stress:
//!
//! ```text
//! C = Σ_segments  ℓ · μ · max(0, −σn) · |t_x|,    σn = σxx n_x² + σyy n_y²
//! ```
//!
//! (ℓ the segment's length, `n` its unit normal, `t` its unit tangent, `μ`
//! the fractures' friction coefficient; a segment in tension, σn > 0,
//! opens and carries nothing). A layer interface (n = ±y) resists with
//! `μ |σyy|` per metre of its length along x; a cross fracture near the y
//! direction opens. The weakest piece is the one of least `C / L`, found
//! by Dijkstra's shortest path with the costs above between every pair of
//! points where fractures meet the face. A ratio below 1 means that no
//! static equilibrium holds that piece under a dead load: once its
//! friction is spent it slides out and keeps accelerating, whatever the
//! mesh.
//!
//! It is an estimate: the normal stress on each segment is taken as the
//! far field's (the real one redistributes as fractures open), a closed
//! inclined segment's normal traction is not counted, and only pieces
//! that translate along x are tried (no rotations). Gravity (ρ g h =
//! 0.04 MPa over the 1.5 m block, 0.3% of σyy) is left out.

use std::cmp::Reverse;
use std::collections::{BTreeMap, BinaryHeap};

use anyhow::{Result, bail};
use femdem_mesh::generate::TraceNetwork;

/// The far-field stress (Pa, tension positive) and the fractures' friction
/// coefficient.
#[derive(Debug, Clone, Copy)]
pub struct FarField {
    /// σxx: the x faces' traction (the negative of their pressure), Pa.
    pub sxx: f64,
    /// σyy, Pa.
    pub syy: f64,
    /// Coulomb friction coefficient on the fractures.
    pub friction: f64,
}

/// Which x face a piece belongs to.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Face {
    /// x = x_min.
    XMin,
    /// x = x_max.
    XMax,
}

/// The weakest piece found.
#[derive(Debug, Clone, PartialEq)]
pub struct Mechanism {
    /// The face it comes away from.
    pub face: Face,
    /// The stretch of the face it holds, `y_a < y_b`, m.
    pub from: f64,
    /// See `from`.
    pub to: f64,
    /// The dead load pulling it out, N per metre of thickness.
    pub load: f64,
    /// The friction its cut can offer, N/m.
    pub capacity: f64,
    /// The cut, from `(x_face, from)` to `(x_face, to)`, m.
    pub path: Vec<[f64; 2]>,
}

impl Mechanism {
    /// `capacity / load`: below 1, no equilibrium under the dead load.
    pub fn factor(&self) -> f64 {
        self.capacity / self.load
    }
}

/// A float ordered for the heap.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Cost(f64);
impl Eq for Cost {}
impl PartialOrd for Cost {
    fn partial_cmp(&self, other: &Self) -> Option<std::cmp::Ordering> {
        Some(self.cmp(other))
    }
}
impl Ord for Cost {
    fn cmp(&self, other: &Self) -> std::cmp::Ordering {
        self.0.total_cmp(&other.0)
    }
}

/// The network as a graph: points and, per point, `(neighbour, cost)`.
struct Graph {
    points: Vec<[f64; 2]>,
    edges: Vec<Vec<(usize, f64)>>,
}

impl Graph {
    fn new() -> Graph {
        Graph { points: Vec::new(), edges: Vec::new() }
    }

    fn id(&mut self, ids: &mut BTreeMap<(u64, u64), usize>, p: [f64; 2]) -> usize {
        *ids.entry((p[0].to_bits(), p[1].to_bits())).or_insert_with(|| {
            self.points.push(p);
            self.edges.push(Vec::new());
            self.points.len() - 1
        })
    }

    fn link(&mut self, a: usize, b: usize, cost: f64) {
        self.edges[a].push((b, cost));
        self.edges[b].push((a, cost));
    }

    /// Shortest costs from `from` to every point, with each point's
    /// predecessor.
    fn dijkstra(&self, from: usize) -> (Vec<f64>, Vec<usize>) {
        let n = self.points.len();
        let mut dist = vec![f64::INFINITY; n];
        let mut prev = vec![usize::MAX; n];
        let mut heap = BinaryHeap::new();
        dist[from] = 0.0;
        heap.push(Reverse((Cost(0.0), from)));
        while let Some(Reverse((Cost(d), u))) = heap.pop() {
            if d > dist[u] {
                continue;
            }
            for &(v, c) in &self.edges[u] {
                if d + c < dist[v] {
                    dist[v] = d + c;
                    prev[v] = u;
                    heap.push(Reverse((Cost(d + c), v)));
                }
            }
        }
        (dist, prev)
    }
}

/// The friction a segment `a → b` can offer against sliding along x, per
/// unit thickness (the module's `ℓ μ max(0, −σn) |t_x|`).
fn resistance(a: [f64; 2], b: [f64; 2], far: FarField) -> f64 {
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let len = dx.hypot(dy);
    if len == 0.0 {
        return 0.0;
    }
    let (tx, ty) = (dx / len, dy / len);
    // n = (−t_y, t_x): n_x² = t_y², n_y² = t_x².
    let sn = far.sxx * ty * ty + far.syy * tx * tx;
    len * far.friction * (-sn).max(0.0) * tx.abs()
}

/// The weakest piece of the axis-aligned rectangular block `outline` that
/// the split fracture network `network` lets come away from an x face
/// under `far`; `None` when σxx does not pull (σxx ≤ 0) or no piece can be
/// cut off along the fractures.
///
/// # Errors
/// When `outline` is not an axis-aligned rectangle.
pub fn weakest(outline: &[[f64; 2]], network: &TraceNetwork, far: FarField) -> Result<Option<Mechanism>> {
    let lo = outline.iter().fold([f64::INFINITY; 2], |m, q| [m[0].min(q[0]), m[1].min(q[1])]);
    let hi = outline.iter().fold([f64::NEG_INFINITY; 2], |m, q| [m[0].max(q[0]), m[1].max(q[1])]);
    if outline.len() != 4
        || outline.iter().any(|p| (p[0] != lo[0] && p[0] != hi[0]) || (p[1] != lo[1] && p[1] != hi[1]))
    {
        bail!("the limit-equilibrium estimate needs an axis-aligned rectangular outline");
    }
    if far.sxx <= 0.0 {
        return Ok(None);
    }
    let mut best: Option<Mechanism> = None;
    for face in [Face::XMin, Face::XMax] {
        let x_face = if face == Face::XMin { lo[0] } else { hi[0] };
        let x_other = if face == Face::XMin { hi[0] } else { lo[0] };
        let mut graph = Graph::new();
        let mut ids = BTreeMap::new();
        for piece in &network.pieces {
            for w in piece.windows(2) {
                let (a, b) = (graph.id(&mut ids, w[0]), graph.id(&mut ids, w[1]));
                graph.link(a, b, resistance(w[0], w[1], far));
            }
        }
        // The outline: the y faces give no friction; the face itself is
        // where the piece is pulled, and a piece holding the other x face
        // too is pulled both ways: neither is a way round.
        let ring = &network.outline;
        for k in 0..ring.len() {
            let (p, q) = (ring[k], ring[(k + 1) % ring.len()]);
            let vertical = p[0] == q[0];
            if vertical && (p[0] == x_face || p[0] == x_other) {
                graph.id(&mut ids, p);
                graph.id(&mut ids, q);
                continue;
            }
            let (a, b) = (graph.id(&mut ids, p), graph.id(&mut ids, q));
            graph.link(a, b, 0.0);
        }
        let mut on_face: Vec<usize> = (0..graph.points.len()).filter(|&i| graph.points[i][0] == x_face).collect();
        on_face.sort_by(|&a, &b| graph.points[a][1].total_cmp(&graph.points[b][1]));
        for (k, &a) in on_face.iter().enumerate() {
            let (dist, prev) = graph.dijkstra(a);
            for &b in &on_face[k + 1..] {
                if !dist[b].is_finite() {
                    continue;
                }
                let (ya, yb) = (graph.points[a][1], graph.points[b][1]);
                let load = far.sxx * (yb - ya);
                let candidate = dist[b] / load;
                if best.as_ref().is_none_or(|m| candidate < m.factor()) {
                    let mut path = vec![graph.points[b]];
                    let mut v = b;
                    while v != a {
                        v = prev[v];
                        path.push(graph.points[v]);
                    }
                    path.reverse();
                    best = Some(Mechanism { face, from: ya, to: yb, load, capacity: dist[b], path });
                }
            }
        }
    }
    Ok(best)
}

#[cfg(test)]
mod tests {
    use super::*;

    const SQUARE: [[f64; 2]; 4] = [[0.0, 0.0], [1.5, 0.0], [1.5, 1.5], [0.0, 1.5]];
    /// The paper's stresses (P_x = +2.5 MPa, P_y = −15 MPa) and μ = 0.6:
    /// an interface resists with μ |σyy| = 9 MPa per metre.
    const PAPER: FarField = FarField { sxx: 2.5e6, syy: -15.0e6, friction: 0.6 };

    fn network(traces: &[Vec<[f64; 2]>]) -> TraceNetwork {
        femdem_mesh::generate::trace_network(&SQUARE, traces).unwrap()
    }

    fn close(a: f64, b: f64) -> bool {
        (a - b).abs() <= 1e-9 * b.abs().max(1.0)
    }

    #[test]
    fn a_fracture_through_the_block_frees_the_strip_outside_it() {
        let m = weakest(&SQUARE, &network(&[vec![[0.3, 0.0], [0.3, 1.5]]]), PAPER).unwrap().unwrap();
        assert_eq!((m.face, m.from, m.to), (Face::XMin, 0.0, 1.5));
        assert_eq!(m.capacity, 0.0);
        assert!(close(m.load, 2.5e6 * 1.5));
    }

    #[test]
    fn staggered_cross_fractures_hold_by_the_friction_on_the_stagger() {
        // Interface at y = 0.75; cross fractures at x = 0.2 below it and
        // x = 0.5 above it; the x_max side is uncut.
        let traces = [vec![[0.0, 0.75], [1.5, 0.75]], vec![[0.2, 0.0], [0.2, 0.75]], vec![[0.5, 0.75], [0.5, 1.5]]];
        let m = weakest(&SQUARE, &network(&traces), PAPER).unwrap().unwrap();
        // Bottom strip: 9 MPa × 0.2 m against 2.5 MPa × 0.75 m (0.96); top
        // strip: 9 × 0.5 against 2.5 × 0.75 (2.4); both together, sliding
        // on the 0.3 m stagger only: 9 × 0.3 against 2.5 × 1.5 (0.72).
        assert_eq!((m.face, m.from, m.to), (Face::XMin, 0.0, 1.5));
        assert!(close(m.capacity, 9.0e6 * 0.3), "{m:?}");
        assert!(close(m.factor(), 0.72), "{}", m.factor());
        assert_eq!(m.path.first(), Some(&[0.0, 0.0]));
        assert_eq!(m.path.last(), Some(&[0.0, 1.5]));
        assert!(m.path.contains(&[0.2, 0.75]) && m.path.contains(&[0.5, 0.75]), "{:?}", m.path);
    }

    #[test]
    fn the_weaker_face_is_found_and_a_single_layer_strip_can_be_the_weakest() {
        // Interfaces at y = 0.5 and 1.0; near x_max a cross fracture in the
        // middle layer only, 0.1 m from the face: that strip holds by
        // friction on both interfaces, 2 × 9 × 0.1 against 2.5 × 0.5 (1.44);
        // near x_min nothing is cut.
        let traces = [vec![[0.0, 0.5], [1.5, 0.5]], vec![[0.0, 1.0], [1.5, 1.0]], vec![[1.4, 0.5], [1.4, 1.0]]];
        let m = weakest(&SQUARE, &network(&traces), PAPER).unwrap().unwrap();
        assert_eq!((m.face, m.from, m.to), (Face::XMax, 0.5, 1.0));
        assert!(close(m.factor(), 1.44), "{}", m.factor());
    }

    #[test]
    fn an_inclined_fracture_in_compression_resists_and_one_in_tension_does_not() {
        // σn on a plane at angle θ to y: σxx cos²θ + σyy sin²θ; with the
        // paper's stresses it turns compressive past θ = atan √(1/6) ≈ 22°.
        let steep = network(&[vec![[0.3, 0.0], [0.4, 1.5]]]);
        let m = weakest(&SQUARE, &steep, PAPER).unwrap().unwrap();
        assert_eq!(m.capacity, 0.0, "{m:?}");
        let flat = network(&[vec![[0.3, 0.0], [1.2, 1.5]]]);
        let m = weakest(&SQUARE, &flat, PAPER).unwrap().unwrap();
        let (dx, dy) = (0.9_f64, 1.5_f64);
        let len = dx.hypot(dy);
        let sn = 2.5e6 * (dy / len).powi(2) - 15.0e6 * (dx / len).powi(2);
        assert!(sn < 0.0);
        assert!(close(m.capacity, len * 0.6 * -sn * dx / len), "{m:?}");
    }

    #[test]
    fn no_tension_or_no_cut_means_no_mechanism() {
        let traces = [vec![[0.0, 0.75], [1.5, 0.75]]];
        assert_eq!(weakest(&SQUARE, &network(&traces), PAPER).unwrap(), None);
        let through = network(&[vec![[0.3, 0.0], [0.3, 1.5]]]);
        let compressed = FarField { sxx: -2.5e6, ..PAPER };
        assert_eq!(weakest(&SQUARE, &through, compressed).unwrap(), None);
        let triangle = [[0.0, 0.0], [1.5, 0.0], [0.0, 1.5]];
        assert!(weakest(&triangle, &network(&[]), PAPER).is_err());
    }
}
