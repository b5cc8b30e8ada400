//! Extrusion of a 2D domain along z.
//!
//! The outline (a polygon, or a circle discretised into a polygon whose edge
//! is close to the element size and whose vertex count is a multiple of four,
//! so that the disc has vertices on both axes) and any internal polylines
//! are inserted as constraint edges of a constrained Delaunay triangulation
//! (the `spade` crate), which is refined until no triangle exceeds the area
//! of an equilateral triangle of the target size and no angle is below 25°.
//! The triangles are extruded in `layers` equal layers and each prism is
//! split into three tets by the consistent diagonal rule of
//! [`super::prism`]. Internal polylines are pre-existing fracture traces:
//! the vertical faces on them become [`TetMesh::fracture_faces`].

use std::collections::HashSet;

use spade::{AngleLimit, ConstrainedDelaunayTriangulation, Point2, RefinementParameters, Triangulation};

use super::{MAX_CELLS, positive, prism::split_prism};
use crate::{BoundaryGroup, FaceRef, MeshError, Region, TetMesh};

/// Refinement splits any triangle larger than this multiple of the
/// equilateral triangle of edge `h`. Delaunay refinement leaves triangles
/// well below the limit (about 0.65 of it on average), so the factor 1.5
/// makes the mean in-plane edge close to `h` (measured by the test
/// `extruded_mean_edge_is_close_to_the_element_size`).
pub const AREA_FACTOR: f64 = 1.5;

/// The outer boundary of an extruded domain.
#[derive(Clone, Debug, PartialEq)]
pub enum Outline {
    /// A simple polygon, vertices in order (either orientation), not closed
    /// (the last vertex connects back to the first).
    Polygon(Vec<[f64; 2]>),
    /// A circle, discretised into a regular polygon inscribed in it.
    Circle {
        /// Centre.
        center: [f64; 2],
        /// Radius, m.
        radius: f64,
    },
}

/// Parameters of [`generate_extrusion`]. Lengths in metres.
#[derive(Clone, Debug, PartialEq)]
pub struct ExtrusionSpec {
    /// The 2D outline in the xy-plane.
    pub outline: Outline,
    /// Internal polylines (pre-existing fracture traces), each at least two
    /// points, inside the outline, not crossing each other.
    pub traces: Vec<Vec<[f64; 2]>>,
    /// Bottom of the extrusion (z).
    pub z0: f64,
    /// Extrusion height.
    pub thickness: f64,
    /// Target edge length of the triangles.
    pub element_size: f64,
    /// Number of layers; `None` chooses `round(thickness / element_size)`.
    pub layers: Option<usize>,
    /// Region given to every tet.
    pub region: Region,
}

/// Number of segments of the polygon inscribed in a circle: the edge is at
/// most `h`, and the count is a multiple of 4 and at least 8.
pub fn circle_segments(radius: f64, h: f64) -> usize {
    let n = (std::f64::consts::TAU * radius / h).ceil() as usize;
    n.div_ceil(4).max(2) * 4
}

fn outline_points(outline: &Outline, h: f64) -> Result<Vec<[f64; 2]>, MeshError> {
    match outline {
        Outline::Polygon(p) => {
            if p.len() < 3 {
                return Err(MeshError::InvalidParameter {
                    name: "outline",
                    reason: format!("a polygon needs at least 3 vertices, got {}", p.len()),
                });
            }
            Ok(p.clone())
        }
        Outline::Circle { center, radius } => {
            let r = positive("radius", *radius)?;
            let n = circle_segments(r, h);
            Ok((0..n)
                .map(|i| {
                    let a = std::f64::consts::TAU * i as f64 / n as f64;
                    [center[0] + r * a.cos(), center[1] + r * a.sin()]
                })
                .collect())
        }
    }
}

/// The bounding box of an outline (of the circle itself, not of its
/// inscribed polygon); NaN bounds, which no point satisfies, for a
/// non-finite outline.
fn outline_bounds(outline: &Outline) -> ([f64; 2], [f64; 2]) {
    match outline {
        Outline::Circle { center, radius } => {
            ([center[0] - radius, center[1] - radius], [center[0] + radius, center[1] + radius])
        }
        Outline::Polygon(p) => p.iter().fold(([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]), |(lo, hi), q| {
            ([lo[0].min(q[0]), lo[1].min(q[1])], [hi[0].max(q[0]), hi[1].max(q[1])])
        }),
    }
}

fn point(p: [f64; 2]) -> Result<Point2<f64>, MeshError> {
    if p[0].is_finite() && p[1].is_finite() {
        Ok(Point2::new(p[0], p[1]))
    } else {
        Err(MeshError::InvalidParameter { name: "outline", reason: format!("non-finite point {p:?}") })
    }
}

/// A planar triangulation: points, triangles (counter-clockwise), the
/// outline's edges and the trace edges as vertex pairs `(min, max)`.
struct Planar {
    points: Vec<[f64; 2]>,
    triangles: Vec<[u32; 3]>,
    outline_edges: HashSet<(u32, u32)>,
    trace_edges: HashSet<(u32, u32)>,
}

fn triangulate(spec: &ExtrusionSpec, h: f64) -> Result<Planar, MeshError> {
    let outline = outline_points(&spec.outline, h)?;
    let mut cdt = ConstrainedDelaunayTriangulation::<Point2<f64>>::new();
    let ins = |cdt: &mut ConstrainedDelaunayTriangulation<Point2<f64>>, p| {
        cdt.insert(point(p)?).map_err(|e| MeshError::Triangulation(format!("{e:?}")))
    };
    let handles = outline.iter().map(|&p| ins(&mut cdt, p)).collect::<Result<Vec<_>, _>>()?;
    for i in 0..handles.len() {
        let (a, b) = (handles[i], handles[(i + 1) % handles.len()]);
        if a == b || !cdt.can_add_constraint(a, b) {
            return Err(MeshError::Triangulation(format!(
                "outline edge {i} ({:?} → {:?}) repeats a point or crosses another edge",
                outline[i],
                outline[(i + 1) % outline.len()]
            )));
        }
        cdt.add_constraint(a, b);
    }
    // Trace segments in point form, to recognise their sub-edges after refinement.
    let mut segments = Vec::new();
    for (t, trace) in spec.traces.iter().enumerate() {
        if trace.len() < 2 {
            return Err(MeshError::InvalidParameter {
                name: "traces",
                reason: format!("trace {t} needs at least 2 points, got {}", trace.len()),
            });
        }
        let hs = trace.iter().map(|&p| ins(&mut cdt, p)).collect::<Result<Vec<_>, _>>()?;
        for w in 0..hs.len() - 1 {
            if hs[w] == hs[w + 1] || !cdt.can_add_constraint(hs[w], hs[w + 1]) {
                return Err(MeshError::Triangulation(format!(
                    "segment {w} of trace {t} repeats a point or crosses another constraint"
                )));
            }
            cdt.add_constraint(hs[w], hs[w + 1]);
            segments.push((trace[w], trace[w + 1]));
        }
    }

    let max_area = AREA_FACTOR * 3f64.sqrt() / 4.0 * h * h;
    // The whole convex hull is refined and the triangles outside the outline
    // dropped afterwards: spade's `exclude_outer_faces` tells inside from
    // outside by the parity of constraint edges crossed, which open traces
    // would flip.
    let params = RefinementParameters::<f64>::new()
        .with_max_allowed_area(max_area)
        .with_angle_limit(AngleLimit::from_deg(25.0))
        .with_max_additional_vertices(MAX_CELLS as usize / 3);
    let result = cdt.refine(params);
    if !result.refinement_complete {
        return Err(MeshError::Triangulation("refinement ran out of vertices".into()));
    }

    let all_points: Vec<[f64; 2]> = cdt.vertices().map(|v| [v.position().x, v.position().y]).collect();
    let mut new_id = vec![u32::MAX; all_points.len()];
    let mut points = Vec::with_capacity(all_points.len());
    let mut triangles = Vec::new();
    for f in cdt.inner_faces() {
        let v = f.vertices().map(|v| v.fix().index());
        let c = [0, 1].map(|k| (all_points[v[0]][k] + all_points[v[1]][k] + all_points[v[2]][k]) / 3.0);
        if !inside(c, &outline) {
            continue;
        }
        triangles.push(v.map(|i| {
            if new_id[i] == u32::MAX {
                new_id[i] = points.len() as u32;
                points.push(all_points[i]);
            }
            new_id[i]
        }));
    }
    let mut outline_edges = HashSet::new();
    let mut trace_edges = HashSet::new();
    for e in cdt.undirected_edges() {
        if !cdt.is_constraint_edge(e.fix()) {
            continue;
        }
        let [a, b] = e.vertices().map(|v| new_id[v.fix().index()]);
        if a == u32::MAX || b == u32::MAX {
            continue;
        }
        let key = (a.min(b), a.max(b));
        let mid = [
            (points[a as usize][0] + points[b as usize][0]) / 2.0,
            (points[a as usize][1] + points[b as usize][1]) / 2.0,
        ];
        let on_trace = segments.iter().any(|&(p, q)| distance_to_segment(mid, p, q) <= 1e-9 * h);
        if on_trace {
            trace_edges.insert(key);
        } else {
            outline_edges.insert(key);
        }
    }
    Ok(Planar { points, triangles, outline_edges, trace_edges })
}

/// Even–odd point-in-polygon test.
fn inside(x: [f64; 2], polygon: &[[f64; 2]]) -> bool {
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

fn distance_to_segment(x: [f64; 2], p: [f64; 2], q: [f64; 2]) -> f64 {
    let d = [q[0] - p[0], q[1] - p[1]];
    let len2 = d[0] * d[0] + d[1] * d[1];
    let s = if len2 > 0.0 { (((x[0] - p[0]) * d[0] + (x[1] - p[1]) * d[1]) / len2).clamp(0.0, 1.0) } else { 0.0 };
    let c = [p[0] + s * d[0] - x[0], p[1] + s * d[1] - x[1]];
    (c[0] * c[0] + c[1] * c[1]).sqrt()
}

/// Meshes the extrusion. Boundary groups: `bottom` (z = z0), `top`
/// (z = z0 + thickness) and `side` (the extruded outline).
///
/// # Errors
/// [`MeshError::InvalidParameter`] or [`MeshError::Triangulation`] for a bad
/// outline, trace, size or thickness.
pub fn generate_extrusion(spec: &ExtrusionSpec) -> Result<TetMesh, MeshError> {
    let h = positive("element_size", spec.element_size)?;
    let thickness = positive("thickness", spec.thickness)?;
    let layers = match spec.layers {
        Some(0) => {
            return Err(MeshError::InvalidParameter { name: "layers", reason: "must be at least 1".into() });
        }
        Some(n) => n,
        None => ((thickness / h).round() as usize).max(1),
    };
    // Estimate before triangulating (a tiny element size would exhaust
    // memory in the 2D mesher first): the outline's area over the area of
    // an equilateral triangle of edge h, three tets per prism per layer.
    let area = match &spec.outline {
        Outline::Circle { radius, .. } => std::f64::consts::PI * radius * radius,
        Outline::Polygon(p) => {
            0.5 * (0..p.len())
                .map(|i| {
                    let (a, b) = (p[i], p[(i + 1) % p.len()]);
                    a[0] * b[1] - b[0] * a[1]
                })
                .sum::<f64>()
                .abs()
        }
    };
    // The 2D mesher refines the convex hull of the outline and the traces:
    // a trace point outside the outline would widen it far past the area
    // estimated here (a centre moved to 1e19 m left a trace at the origin
    // and refined for ever). Traces lie inside the outline: refuse any
    // point outside its bounding box.
    let (lo, hi) = outline_bounds(&spec.outline);
    for (t, trace) in spec.traces.iter().enumerate() {
        for (k, p) in trace.iter().enumerate() {
            if !(p[0] >= lo[0] && p[0] <= hi[0] && p[1] >= lo[1] && p[1] <= hi[1]) {
                return Err(MeshError::InvalidParameter {
                    name: "traces",
                    reason: format!(
                        "point {k} of trace {t}, {p:?}, lies outside the outline (its bounding box is {lo:?} to {hi:?})"
                    ),
                });
            }
        }
    }
    let estimate = area / (3f64.sqrt() / 4.0 * h * h) * layers as f64 * 3.0;
    if estimate > MAX_CELLS {
        return Err(MeshError::InvalidParameter {
            name: "element_size",
            reason: format!(
                "{h} m over an outline of {area:.4e} m² and {layers} layers would make about {estimate:.3e} tets; \
                 refuse above {MAX_CELLS:e}"
            ),
        });
    }
    let planar = triangulate(spec, h)?;
    if (planar.triangles.len() * layers * 3) as f64 > MAX_CELLS {
        return Err(MeshError::InvalidParameter {
            name: "element_size",
            reason: format!("would make {} tets; refuse above {MAX_CELLS:e}", planar.triangles.len() * layers * 3),
        });
    }
    let np = planar.points.len() as u32;
    let mut coords = Vec::with_capacity(planar.points.len() * (layers + 1));
    for l in 0..=layers {
        let z = spec.z0 + thickness * l as f64 / layers as f64;
        coords.extend(planar.points.iter().map(|p| [p[0], p[1], z]));
    }
    let mut tets = Vec::with_capacity(planar.triangles.len() * layers * 3);
    for l in 0..layers as u32 {
        for tri in &planar.triangles {
            let bottom = tri.map(|v| v + l * np);
            let top = tri.map(|v| v + (l + 1) * np);
            tets.extend(split_prism(bottom, top, &coords));
        }
    }
    let mut mesh = TetMesh {
        tet_region: vec![0; tets.len()],
        coords,
        tets,
        regions: vec![spec.region.clone()],
        ..Default::default()
    };
    classify_faces(&mut mesh, &planar, np, layers as u32);
    Ok(mesh)
}

/// Fills the boundary groups and the fracture faces from the planar edges.
fn classify_faces(mesh: &mut TetMesh, planar: &Planar, np: u32, layers: u32) {
    let mut groups: Vec<BoundaryGroup> =
        ["bottom", "top", "side"].iter().map(|n| BoundaryGroup { name: (*n).to_string(), faces: Vec::new() }).collect();
    let mut seen_trace_faces = HashSet::new();
    for t in 0..mesh.tets.len() {
        for local in 0..4u8 {
            let f = FaceRef { tet: t as u32, local };
            let nodes = f.nodes(&mesh.tets);
            let layer = nodes.map(|n| n / np);
            if layer.iter().all(|&l| l == 0) {
                groups[0].faces.push(f);
                continue;
            }
            if layer.iter().all(|&l| l == layers) {
                groups[1].faces.push(f);
                continue;
            }
            // A vertical face projects onto exactly two planar vertices.
            let mut p = nodes.map(|n| n % np);
            p.sort_unstable();
            let pair = if p[0] == p[1] {
                (p[0], p[2])
            } else if p[1] == p[2] {
                (p[0], p[1])
            } else {
                continue;
            };
            if p[0] == p[2] {
                continue;
            }
            if planar.outline_edges.contains(&pair) {
                groups[2].faces.push(f);
            } else if planar.trace_edges.contains(&pair) {
                let mut key = nodes;
                key.sort_unstable();
                // One side of each trace face is enough.
                if seen_trace_faces.insert(key) {
                    mesh.fracture_faces.push(f);
                }
            }
        }
    }
    mesh.boundary = groups;
}
