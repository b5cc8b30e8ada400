//! A planar fracture network from polylines, ready for constrained
//! triangulation.
//!
//! A fracture map is a set of polylines (traces) inside a 2D outline. They
//! may cross (X-junctions), end on one another (T-junctions), end inside the
//! domain (non-persistent fractures) or run from outline to outline
//! (persistent fractures, such as the interfaces between layers). A
//! constrained triangulation needs constraint edges that meet only at
//! their ends, so [`trace_network`] splits every segment at every junction
//! on it, inserts the points where traces end on the outline into the
//! outline, drops trace segments that lie along the outline (the outline
//! already is a boundary there), and rejects what cannot be meshed: a point
//! outside the outline, a zero-length segment, a segment that leaves the
//! outline between its points, and two traces that overlap along a length.
//!
//! Points closer than a tolerance `ε = 1e-9 ×` the diagonal of the
//! outline's bounding box are the same point: a trace point within `ε` of
//! the outline is moved onto it, and a trace end within `ε` of another
//! trace is a T-junction with it. The tolerance is only there for
//! round-off: junctions are meant to be given exactly (as a generated map
//! gives them), not digitised by hand.
//!
//! This module knows no files; the case reader parses trace files into
//! polylines.

use crate::MeshError;

/// The tolerance factor: points closer than this times the outline's
/// bounding-box diagonal are the same point.
pub const TRACE_TOLERANCE: f64 = 1e-9;

/// A fracture network whose constraint edges meet only at their ends.
#[derive(Clone, Debug, PartialEq)]
pub struct TraceNetwork {
    /// The outline, with every point where a trace ends on it inserted in
    /// order along it (not closed, as [`super::Outline::Polygon`]).
    pub outline: Vec<[f64; 2]>,
    /// The trace pieces: one per segment of the input that lies inside the
    /// outline, with every junction on it as a vertex, in order. Two pieces
    /// meet only at vertices of both.
    pub pieces: Vec<Vec<[f64; 2]>>,
}

/// Who owns a segment: an outline edge, or segment `point → point + 1` of
/// trace `trace`.
#[derive(Clone, Copy, Debug)]
enum Owner {
    Outline,
    Trace { trace: usize, point: usize },
}

struct Segment {
    a: [f64; 2],
    b: [f64; 2],
    owner: Owner,
    /// Junctions on its interior: parameter along a → b and the point.
    cuts: Vec<(f64, [f64; 2])>,
}

enum Hit {
    None,
    /// Parameters `s` on the first segment and `u` on the second.
    Point {
        s: f64,
        u: f64,
    },
    /// Collinear, sharing more than a point.
    Overlap,
}

fn sub(a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
    [a[0] - b[0], a[1] - b[1]]
}

fn cross(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * b[1] - a[1] * b[0]
}

fn dot(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * b[0] + a[1] * b[1]
}

fn norm(a: [f64; 2]) -> f64 {
    dot(a, a).sqrt()
}

/// The lower and upper corners of the bounding box of `points`.
pub(crate) fn bounds(points: &[[f64; 2]]) -> ([f64; 2], [f64; 2]) {
    let lo = points.iter().fold([f64::INFINITY; 2], |m, p| [m[0].min(p[0]), m[1].min(p[1])]);
    let hi = points.iter().fold([f64::NEG_INFINITY; 2], |m, p| [m[0].max(p[0]), m[1].max(p[1])]);
    (lo, hi)
}

/// The point of segment `p q` nearest to `x`, and its distance.
pub(crate) fn nearest_on_segment(x: [f64; 2], p: [f64; 2], q: [f64; 2]) -> ([f64; 2], f64) {
    let d = sub(q, p);
    let len2 = dot(d, d);
    let s = if len2 > 0.0 { (dot(sub(x, p), d) / len2).clamp(0.0, 1.0) } else { 0.0 };
    let c = if s == 0.0 {
        p
    } else if s == 1.0 {
        q
    } else {
        [p[0] + s * d[0], p[1] + s * d[1]]
    };
    (c, norm(sub(c, x)))
}

/// Even–odd point-in-polygon test.
pub(crate) fn inside(x: [f64; 2], polygon: &[[f64; 2]]) -> bool {
    let mut inside = false;
    let mut j = polygon.len() - 1;
    for i in 0..polygon.len() {
        let (a, b) = (polygon[i], polygon[j]);
        if (a[1] > x[1]) != (b[1] > x[1]) && x[0] < (b[0] - a[0]) * (x[1] - a[1]) / (b[1] - a[1]) + a[0] {
            inside = !inside;
        }
        j = i;
    }
    inside
}

/// The point of the outline nearest to `x`, and its distance.
fn nearest_on_outline(x: [f64; 2], outline: &[[f64; 2]]) -> ([f64; 2], f64) {
    (0..outline.len())
        .map(|i| nearest_on_segment(x, outline[i], outline[(i + 1) % outline.len()]))
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .expect("an outline has points")
}

/// How segments `a1 b1` and `a2 b2` meet, with tolerance `eps` (a length).
fn intersect(a1: [f64; 2], b1: [f64; 2], a2: [f64; 2], b2: [f64; 2], eps: f64) -> Hit {
    let (d1, d2) = (sub(b1, a1), sub(b2, a2));
    let (l1, l2) = (norm(d1), norm(d2));
    let w = sub(a2, a1);
    let den = cross(d1, d2);
    // |den| = l1 l2 |sin θ|: parallel when the far end of the shorter
    // segment leaves the other's line by less than eps.
    if den.abs() <= eps * l1.max(l2) {
        if (cross(d1, w) / l1).abs() > eps {
            return Hit::None;
        }
        let t0 = dot(w, d1) / (l1 * l1);
        let t1 = dot(sub(b2, a1), d1) / (l1 * l1);
        let overlap = (t0.max(t1).min(1.0) - t0.min(t1).max(0.0)) * l1;
        // Collinear segments that only share an end need no junction.
        return if overlap > eps { Hit::Overlap } else { Hit::None };
    }
    let s = cross(w, d2) / den;
    let u = cross(w, d1) / den;
    let (es, eu) = (eps / l1, eps / l2);
    if s < -es || s > 1.0 + es || u < -eu || u > 1.0 + eu {
        return Hit::None;
    }
    Hit::Point { s, u }
}

fn trace_error(trace: usize, point: usize, reason: String) -> MeshError {
    MeshError::Trace { trace, point, reason }
}

/// Splits `traces` at their junctions with each other and with `outline`
/// (see the module documentation for the rules).
///
/// # Errors
/// [`MeshError::Trace`], naming the trace and the point, for a trace of
/// fewer than two points, a non-finite point, a point outside the
/// outline, a zero-length segment, a segment that leaves the outline
/// between its points, or two traces (or a trace and the outline) that
/// overlap along a length; [`MeshError::InvalidParameter`] for an outline
/// of fewer than three points.
pub fn trace_network(outline: &[[f64; 2]], traces: &[Vec<[f64; 2]>]) -> Result<TraceNetwork, MeshError> {
    if outline.len() < 3 {
        return Err(MeshError::InvalidParameter {
            name: "outline",
            reason: format!("a polygon needs at least 3 vertices, got {}", outline.len()),
        });
    }
    let (lo, hi) = bounds(outline);
    let eps = TRACE_TOLERANCE * norm(sub(hi, lo));

    let mut segments: Vec<Segment> = (0..outline.len())
        .map(|i| Segment {
            a: outline[i],
            b: outline[(i + 1) % outline.len()],
            owner: Owner::Outline,
            cuts: Vec::new(),
        })
        .collect();
    for (t, trace) in traces.iter().enumerate() {
        if trace.len() < 2 {
            return Err(trace_error(t, 0, format!("a trace needs at least 2 points, got {}", trace.len())));
        }
        let mut points = Vec::with_capacity(trace.len());
        let mut on_outline = Vec::with_capacity(trace.len());
        for (k, &p) in trace.iter().enumerate() {
            if !(p[0].is_finite() && p[1].is_finite()) {
                return Err(trace_error(t, k, format!("non-finite point {p:?}")));
            }
            let (q, d) = nearest_on_outline(p, outline);
            if d <= eps {
                points.push(q);
                on_outline.push(true);
            } else if inside(p, outline) {
                points.push(p);
                on_outline.push(false);
            } else {
                return Err(trace_error(
                    t,
                    k,
                    format!("({}, {}) m is outside the outline ({d:.3e} m from it)", p[0], p[1]),
                ));
            }
        }
        for k in 0..points.len() - 1 {
            let (a, b) = (points[k], points[k + 1]);
            if norm(sub(b, a)) <= eps {
                return Err(trace_error(t, k + 1, format!("zero-length segment: it repeats point {k}")));
            }
            let mid = [(a[0] + b[0]) / 2.0, (a[1] + b[1]) / 2.0];
            if on_outline[k] && on_outline[k + 1] && nearest_on_outline(mid, outline).1 <= eps {
                // Along the outline: the outline is a boundary there already.
                continue;
            }
            segments.push(Segment { a, b, owner: Owner::Trace { trace: t, point: k }, cuts: Vec::new() });
        }
    }

    // Every pair that can meet (bounding boxes overlapping within eps).
    for i in 0..segments.len() {
        let (a1, b1) = (segments[i].a, segments[i].b);
        for j in i + 1..segments.len() {
            let (a2, b2) = (segments[j].a, segments[j].b);
            if a1[0].min(b1[0]) > a2[0].max(b2[0]) + eps
                || a2[0].min(b2[0]) > a1[0].max(b1[0]) + eps
                || a1[1].min(b1[1]) > a2[1].max(b2[1]) + eps
                || a2[1].min(b2[1]) > a1[1].max(b1[1]) + eps
            {
                continue;
            }
            let (oi, oj) = (segments[i].owner, segments[j].owner);
            // Outline edges are checked by the triangulation; j > i, so j is a trace
            // whenever i is.
            let Owner::Trace { trace: tj, point: pj } = oj else { continue };
            match intersect(a1, b1, a2, b2, eps) {
                Hit::None => {}
                Hit::Overlap => {
                    let what = match oi {
                        Owner::Outline => "the outline".to_string(),
                        Owner::Trace { trace, point } => format!("segment {point} of trace {trace}"),
                    };
                    return Err(trace_error(tj, pj, format!("segment {pj} overlaps {what} along a length")));
                }
                Hit::Point { s, u } => {
                    let (li, lj) = (norm(sub(b1, a1)), norm(sub(b2, a2)));
                    let end_i = s * li <= eps || (1.0 - s) * li <= eps;
                    let end_j = u * lj <= eps || (1.0 - u) * lj <= eps;
                    // The junction point: an end where there is one, so that
                    // both segments get exactly the same coordinates.
                    let p = if end_j {
                        if u * lj <= eps { a2 } else { b2 }
                    } else if end_i {
                        if s * li <= eps { a1 } else { b1 }
                    } else {
                        [a1[0] + s * (b1[0] - a1[0]), a1[1] + s * (b1[1] - a1[1])]
                    };
                    if let Owner::Outline = oi
                        && !end_j
                    {
                        return Err(trace_error(
                            tj,
                            pj,
                            format!("segment {pj} leaves the outline between its points (at ({}, {}) m)", p[0], p[1]),
                        ));
                    }
                    if !end_i {
                        segments[i].cuts.push((s, p));
                    }
                    if !end_j {
                        segments[j].cuts.push((u, p));
                    }
                }
            }
        }
    }

    let chain = |seg: &Segment, last: bool| -> Vec<[f64; 2]> {
        let mut cuts = seg.cuts.clone();
        cuts.sort_by(|x, y| x.0.total_cmp(&y.0));
        let mut out = vec![seg.a];
        for (_, p) in cuts {
            if norm(sub(p, *out.last().expect("not empty"))) > eps {
                out.push(p);
            }
        }
        if last {
            if norm(sub(seg.b, *out.last().expect("not empty"))) <= eps {
                out.pop();
            }
            out.push(seg.b);
        }
        out
    };
    let mut network = TraceNetwork { outline: Vec::new(), pieces: Vec::new() };
    for seg in &segments {
        match seg.owner {
            Owner::Outline => network.outline.extend(chain(seg, false)),
            Owner::Trace { .. } => network.pieces.push(chain(seg, true)),
        }
    }
    Ok(network)
}

#[cfg(test)]
mod tests {
    use super::*;

    const SQUARE: [[f64; 2]; 4] = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];

    #[test]
    fn an_x_junction_splits_both_traces_at_the_crossing() {
        let n = trace_network(&SQUARE, &[vec![[0.2, 0.2], [0.8, 0.8]], vec![[0.2, 0.8], [0.8, 0.2]]]).unwrap();
        assert_eq!(n.pieces.len(), 2);
        for piece in &n.pieces {
            assert_eq!(piece.len(), 3);
            assert!(norm(sub(piece[1], [0.5, 0.5])) < 1e-15, "{piece:?}");
        }
        assert_eq!(n.outline, SQUARE.to_vec());
    }

    #[test]
    fn a_t_junction_splits_the_trace_it_ends_on_and_the_outline() {
        // A persistent trace across the square, a trace ending on it.
        let n = trace_network(&SQUARE, &[vec![[0.0, 0.5], [1.0, 0.5]], vec![[0.3, 0.1], [0.3, 0.5]]]).unwrap();
        assert_eq!(n.pieces[0], vec![[0.0, 0.5], [0.3, 0.5], [1.0, 0.5]]);
        assert_eq!(n.pieces[1], vec![[0.3, 0.1], [0.3, 0.5]]);
        assert_eq!(n.outline, vec![[0.0, 0.0], [1.0, 0.0], [1.0, 0.5], [1.0, 1.0], [0.0, 1.0], [0.0, 0.5]]);
    }

    #[test]
    fn a_segment_along_the_outline_is_dropped() {
        let n = trace_network(&SQUARE, &[vec![[0.0, 0.0], [0.5, 0.0], [0.5, 0.5]]]).unwrap();
        assert_eq!(n.pieces, vec![vec![[0.5, 0.0], [0.5, 0.5]]]);
        assert_eq!(n.outline.len(), 5);
    }

    #[test]
    fn bad_traces_are_named_with_their_point() {
        let e = |traces: &[Vec<[f64; 2]>]| trace_network(&SQUARE, traces).unwrap_err().to_string();
        assert_eq!(
            e(&[vec![[0.1, 0.1], [0.2, 0.2]], vec![[0.5, 0.5], [1.5, 0.5]]]),
            "trace 1, point 1: (1.5, 0.5) m is outside the outline (5.000e-1 m from it)"
        );
        assert!(e(&[vec![[0.5, 0.5]]]).starts_with("trace 0, point 0: a trace needs at least 2 points"));
        assert!(e(&[vec![[0.1, 0.1], [0.2, 0.2], [0.2, 0.2]]]).starts_with("trace 0, point 2: zero-length"));
        assert!(
            e(&[vec![[0.1, 0.1], [0.6, 0.1]], vec![[0.4, 0.1], [0.9, 0.1]]]).contains("overlaps segment 0 of trace 0")
        );
        let l_shape = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.5, 1.0], [0.5, 0.5], [0.0, 0.5]];
        let e = trace_network(&l_shape, &[vec![[0.1, 0.1], [0.9, 0.2]], vec![[0.25, 0.4], [0.75, 0.9]]])
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("trace 1, point 0: segment 0 leaves the outline"), "{e}");
    }
}
