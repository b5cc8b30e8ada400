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

use std::collections::{HashMap, HashSet};

use spade::handles::FixedVertexHandle;
use spade::{AngleLimit, ConstrainedDelaunayTriangulation, Point2, RefinementParameters, Triangulation};

use super::traces::{bounds, inside, nearest_on_segment, trace_network};
use super::{MAX_CELLS, TraceNetwork, positive, prism::split_prism};
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
    /// points, inside the outline or on it. They may cross and end on each
    /// other or on the outline: [`super::trace_network`] splits them at
    /// their junctions.
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

fn point(p: [f64; 2]) -> Result<Point2<f64>, MeshError> {
    if p[0].is_finite() && p[1].is_finite() {
        Ok(Point2::new(p[0], p[1]))
    } else {
        Err(MeshError::InvalidParameter { name: "outline", reason: format!("non-finite point {p:?}") })
    }
}

impl ExtrusionSpec {
    /// The layers: `layers`, else `round(thickness / element_size)`, at
    /// least 1.
    pub fn layer_count(&self) -> usize {
        self.layers.unwrap_or_else(|| ((self.thickness / self.element_size).round() as usize).max(1))
    }
}

/// The area enclosed by the polygon `p` (shoelace formula; its absolute
/// value, either orientation), m².
pub fn polygon_area(p: &[[f64; 2]]) -> f64 {
    0.5 * (0..p.len())
        .map(|i| {
            let (a, b) = (p[i], p[(i + 1) % p.len()]);
            a[0] * b[1] - b[0] * a[1]
        })
        .sum::<f64>()
        .abs()
}

/// The generator's estimate of an extrusion's tets: the outline's `area`
/// over an equilateral triangle of edge `h`, three tets per prism in each
/// of `layers` layers.
pub fn estimated_tets(area: f64, h: f64, layers: usize) -> f64 {
    3.0 * layers as f64 * area / (3f64.sqrt() / 4.0 * h * h)
}

/// The narrowest gap between features, as a fraction of the larger of the
/// element size and the layer height, that is meshed: edges below about
/// 7.7·10⁻⁵ of the layer height make degenerate tets
/// ([`super::clearance`]), and gaps near it cost minutes of refinement.
/// Measured on a 1 × 0.6 m outline at 0.05 m with a trace along an edge:
/// at 2·10⁻⁴ of h it meshes (443 times the tets h gives, in 6.5 s), at
/// 2·10⁻⁵ the tets are degenerate (16 s), at 2·10⁻⁶ (3 min, 5.6 GB) too.
pub const MIN_CLEARANCE: f64 = 1e-4;

/// Refuses a network whose features come closer than [`MIN_CLEARANCE`]
/// times `max(h, dz)` without meeting, naming where. That length is at
/// most the outline's bounding-box diagonal `D` (an element size above
/// the outline makes elements of the outline's size).
fn clear_enough(network: &TraceNetwork, h: f64, dz: f64) -> Result<(), MeshError> {
    let (lo, hi) = bounds(&network.outline);
    let diagonal = ((hi[0] - lo[0]).powi(2) + (hi[1] - lo[1]).powi(2)).sqrt();
    let same = super::TRACE_TOLERANCE * diagonal;
    let below = MIN_CLEARANCE * h.max(dz).min(diagonal);
    match super::closest_approach(network, same, below, h.min(diagonal)) {
        None => Ok(()),
        Some(m) => Err(MeshError::Clearance(format!(
            "a point of {} at ({:.9}, {:.9}) m lies {:.3e} m from a segment of {} that does not end there \
             (nearest at ({:.9}, {:.9}) m), closer than {MIN_CLEARANCE:e} of the element size or layer height \
             ({below:.3e} m): the mesh would need elements of that width there, and tets that thin against \
             their layer height are degenerate (below 7.7e-5 of it). Where the two are meant to meet, put the \
             point exactly on the other (within {same:.1e} m, the tolerance of a junction); otherwise move \
             them apart, or drop a segment that short",
            m.point_of.name(),
            m.point[0],
            m.point[1],
            m.distance,
            m.segment_of.name(),
            m.nearest[0],
            m.nearest[1],
        ))),
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

/// Triangulates the outline and traces at edge `h` for an extrusion of
/// `layers` layers. The refinement may add at most the vertices whose
/// triangles (about two a vertex) make [`MAX_CELLS`] tets in those layers:
/// beyond that the mesh would be refused anyway, and outline points or
/// traces crowding far closer than `h` would otherwise refine on to
/// tens of millions of vertices (gigabytes, minutes) before the count is
/// seen. Running out is refused with the place of the shortest edge,
/// where the crowding is. Before that, features that come within
/// [`MIN_CLEARANCE`] of the element size or layer height of each other
/// (without meeting) are refused with the place
/// ([`super::closest_approach`]).
fn triangulate(spec: &ExtrusionSpec, h: f64, layers: usize) -> Result<Planar, MeshError> {
    let network = trace_network(&outline_points(&spec.outline, h)?, &spec.traces)?;
    clear_enough(&network, h, spec.thickness / layers as f64)?;
    let outline = network.outline;
    let mut cdt = ConstrainedDelaunayTriangulation::<Point2<f64>>::new();
    // Junctions are shared by several pieces with bit-identical coordinates:
    // insert each point once.
    let mut inserted: HashMap<[u64; 2], FixedVertexHandle> = HashMap::new();
    let mut ins = |cdt: &mut ConstrainedDelaunayTriangulation<Point2<f64>>, p: [f64; 2]| {
        if let Some(&v) = inserted.get(&p.map(f64::to_bits)) {
            return Ok(v);
        }
        let v = cdt.insert(point(p)?).map_err(|e| MeshError::Triangulation(format!("{e:?}")))?;
        inserted.insert(p.map(f64::to_bits), v);
        Ok::<_, MeshError>(v)
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
    // Trace segments in point form, to recognise their sub-edges after
    // refinement. The network's pieces meet only at their vertices.
    let mut segments = Vec::new();
    for piece in &network.pieces {
        let hs = piece.iter().map(|&p| ins(&mut cdt, p)).collect::<Result<Vec<_>, _>>()?;
        for w in 0..hs.len() - 1 {
            if hs[w] == hs[w + 1] || !cdt.can_add_constraint(hs[w], hs[w + 1]) {
                return Err(MeshError::Triangulation(format!(
                    "trace segment {:?} → {:?} repeats a point or crosses another constraint",
                    piece[w],
                    piece[w + 1]
                )));
            }
            cdt.add_constraint(hs[w], hs[w + 1]);
            segments.push((piece[w], piece[w + 1]));
        }
    }

    let max_area = AREA_FACTOR * 3f64.sqrt() / 4.0 * h * h;
    // The whole convex hull is refined and the triangles outside the outline
    // dropped afterwards: spade's `exclude_outer_faces` tells inside from
    // outside by the parity of constraint edges crossed, which open traces
    // would flip.
    // The vertex budget: about two triangles a vertex, three tets a
    // triangle and layer, scaled by the outline's bounding box over its
    // area (≥ the hull's share refined outside a non-convex outline).
    let area = polygon_area(&outline);
    let (lo, hi) = bounds(&outline);
    let hull_share = ((hi[0] - lo[0]) * (hi[1] - lo[1]) / area).max(1.0);
    // Twice that, for the vertices a narrow notch draws into the hull
    // and those on the outline; the exact count below decides a mesh that
    // completes.
    let budget = (2.0 * MAX_CELLS / (6.0 * layers as f64) * hull_share).min(MAX_CELLS / 3.0);
    let params = RefinementParameters::<f64>::new()
        .with_max_allowed_area(max_area)
        .with_angle_limit(AngleLimit::from_deg(25.0))
        .with_max_additional_vertices(budget as usize);
    let result = cdt.refine(params);
    if !result.refinement_complete {
        let shortest = cdt
            .undirected_edges()
            .map(|e| {
                let [a, b] = e.vertices().map(|v| v.position());
                (((b.x - a.x).powi(2) + (b.y - a.y).powi(2)).sqrt(), [(a.x + b.x) / 2.0, (a.y + b.y) / 2.0])
            })
            .min_by(|p, q| p.0.total_cmp(&q.0));
        let why = match shortest {
            // Crowding, where the edges fall far below h.
            Some((l, m)) if l < h / 5.0 => format!(
                ": the refinement has to fill gaps far narrower than element_size = {h} m (edges down to {l:.3e} \
                 m, the shortest at x = {:.6}, y = {:.6} m), where points of the outline or traces lie that close \
                 together; move them apart or join them",
                m[0], m[1]
            ),
            _ => format!(" at element_size = {h} m in {layers} layers; use a larger element_size"),
        };
        return Err(MeshError::Triangulation(format!("the mesh would exceed {MAX_CELLS:e} tets{why}")));
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
        let on_trace = segments.iter().any(|&(p, q)| nearest_on_segment(mid, p, q).1 <= 1e-9 * h);
        if on_trace {
            trace_edges.insert(key);
        } else {
            outline_edges.insert(key);
        }
    }
    Ok(Planar { points, triangles, outline_edges, trace_edges })
}

/// Meshes the extrusion. Boundary groups: `bottom` (z = z0), `top`
/// (z = z0 + thickness) and `side` (the extruded outline); when the outline
/// is a polygon whose every edge lies on a side of its bounding box (an
/// axis-aligned rectangle, possibly with extra vertices on its sides), also
/// `xmin`, `xmax`, `ymin` and `ymax`, which split `side` face for face.
///
/// # Errors
/// [`MeshError::InvalidParameter`] or [`MeshError::Triangulation`] for a bad
/// outline, trace, size or thickness.
pub fn generate_extrusion(spec: &ExtrusionSpec) -> Result<TetMesh, MeshError> {
    let h = positive("element_size", spec.element_size)?;
    let thickness = positive("thickness", spec.thickness)?;
    if !spec.z0.is_finite() {
        return Err(MeshError::InvalidParameter { name: "z0", reason: format!("must be finite, got {}", spec.z0) });
    }
    if spec.layers == Some(0) {
        return Err(MeshError::InvalidParameter { name: "layers", reason: "must be at least 1".into() });
    }
    let layers = spec.layer_count();
    // Estimate before triangulating (a tiny element size would exhaust
    // memory in the 2D mesher first): the outline's area over the area of
    // an equilateral triangle of edge h, three tets per prism per layer.
    let area = match &spec.outline {
        Outline::Circle { radius, .. } => std::f64::consts::PI * radius * radius,
        Outline::Polygon(p) => polygon_area(p),
    };
    if let Outline::Polygon(p) = &spec.outline
        && let Some(q) = p.iter().find(|q| !(q[0].is_finite() && q[1].is_finite()))
    {
        return Err(MeshError::InvalidParameter {
            name: "outline",
            reason: format!("has a point that is not finite: {q:?}"),
        });
    }
    if area.is_nan() || area <= 0.0 {
        return Err(MeshError::InvalidParameter {
            name: "outline",
            reason: format!(
                "encloses no area ({area:e} m²): its vertices lie on one line, or it crosses itself so that its \
                 parts' signed areas cancel"
            ),
        });
    }
    let estimate = estimated_tets(area, h, layers);
    if estimate > MAX_CELLS {
        return Err(MeshError::InvalidParameter {
            name: "element_size",
            reason: format!(
                "{h} m over an outline of {area:.4e} m² and {layers} layers would make about {estimate:.3e} tets; \
                 refuse above {MAX_CELLS:e}"
            ),
        });
    }
    let planar = triangulate(spec, h, layers)?;
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
    classify_faces(&mut mesh, &planar, np, layers as u32, axis_aligned_rectangle(&spec.outline));
    Ok(mesh)
}

/// `[xmin, xmax, ymin, ymax]` of a polygon outline whose every edge lies on
/// a side of its bounding box; `None` otherwise.
fn axis_aligned_rectangle(outline: &Outline) -> Option<[f64; 4]> {
    let Outline::Polygon(p) = outline else { return None };
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for q in p {
        for k in 0..2 {
            lo[k] = lo[k].min(q[k]);
            hi[k] = hi[k].max(q[k]);
        }
    }
    let on_side = |a: [f64; 2], b: [f64; 2]| (0..2).any(|k| a[k] == b[k] && (a[k] == lo[k] || a[k] == hi[k]));
    (0..p.len()).all(|i| on_side(p[i], p[(i + 1) % p.len()])).then_some([lo[0], hi[0], lo[1], hi[1]])
}

/// Fills the boundary groups and the fracture faces from the planar edges;
/// `rect` (`[xmin, xmax, ymin, ymax]`) adds a group per side of a
/// rectangular outline.
fn classify_faces(mesh: &mut TetMesh, planar: &Planar, np: u32, layers: u32, rect: Option<[f64; 4]>) {
    let names: &[&str] = if rect.is_some() {
        &["bottom", "top", "side", "xmin", "xmax", "ymin", "ymax"]
    } else {
        &["bottom", "top", "side"]
    };
    let mut groups: Vec<BoundaryGroup> =
        names.iter().map(|n| BoundaryGroup { name: (*n).to_string(), faces: Vec::new() }).collect();
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
                if let Some(r) = rect {
                    let [a, b] = [pair.0, pair.1].map(|v| planar.points[v as usize]);
                    // Sides in the order of `names` after `side`: x = xmin, xmax, y = ymin, ymax.
                    let tol = 1e-9 * ((r[1] - r[0]).powi(2) + (r[3] - r[2]).powi(2)).sqrt();
                    let group = (0..4).find(|&g| {
                        let (k, v) = (g / 2, r[g]);
                        (a[k] - v).abs() <= tol && (b[k] - v).abs() <= tol
                    });
                    if let Some(g) = group {
                        groups[3 + g].faces.push(f);
                    }
                }
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
