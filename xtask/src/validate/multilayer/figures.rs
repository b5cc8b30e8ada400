//! The multi-layer figures, as the paper's Fig. 17: the maximum principal
//! stress σ1 on the mid-plane section, and the fracture pattern seen along
//! z, the pre-existing fractures and the new ones in different colours.

use std::ops::Range;
use std::path::Path;

use anyhow::Result;
use plotters::style::RGBColor;

use crate::validate::colours::mode_colour;
use crate::validate::plot;
use femdem_post::frames::Grid;

/// A triangle seen in a plane, with its colour.
type Flat = ([(f64, f64); 3], RGBColor);

/// The colour of the pre-existing fractures (the paper's purple).
const PRE_EXISTING: RGBColor = RGBColor(128, 64, 160);

/// The polygon where the plane z = `z` cuts the tet `p` (3 or 4 points, in
/// order around it; none when the tet lies on one side). A vertex on the
/// plane counts as above it, so a plane through a layer of vertices cuts
/// the tets below it along their top faces and misses those above: the
/// section is covered once.
pub fn section(p: [[f64; 3]; 4], z: f64) -> Vec<(f64, f64)> {
    let above: Vec<usize> = (0..4).filter(|&k| p[k][2] >= z).collect();
    let below: Vec<usize> = (0..4).filter(|&k| p[k][2] < z).collect();
    let cut = |a: usize, b: usize| {
        let (pa, pb) = (p[a], p[b]);
        let s = (z - pa[2]) / (pb[2] - pa[2]);
        (pa[0] + s * (pb[0] - pa[0]), pa[1] + s * (pb[1] - pa[1]))
    };
    match (below.len(), above.len()) {
        (1, 3) => above.iter().map(|&a| cut(below[0], a)).collect(),
        (3, 1) => below.iter().map(|&b| cut(b, above[0])).collect(),
        (2, 2) => {
            let ([b0, b1], [a0, a1]) = ([below[0], below[1]], [above[0], above[1]]);
            vec![cut(b0, a0), cut(b0, a1), cut(b1, a1), cut(b1, a0)]
        }
        _ => Vec::new(),
    }
}

/// σ1 (the most tensile principal stress) of `grid`'s tets on the section
/// z = `z`, at the undeformed positions, coloured from −`scale` (blue)
/// through 0 (white) to +`scale` (red).
pub fn sigma1_section(
    path: &Path,
    grid: &Grid,
    z: f64,
    scale: f64,
    bounds: (Range<f64>, Range<f64>),
    title: &str,
) -> Result<()> {
    let (_, principal) = grid.cell("principal_stress")?;
    let x0 = grid.undeformed_points()?;
    let mut tris: Vec<Flat> = Vec::new();
    for (c, cell) in grid.cells.iter().enumerate() {
        if cell.len() != 4 {
            continue;
        }
        let poly = section([0, 1, 2, 3].map(|k| x0[cell[k]]), z);
        if poly.len() < 3 {
            continue;
        }
        let colour = plot::diverging(principal[3 * c] / scale);
        for k in 1..poly.len() - 1 {
            tris.push(([poly[0], poly[k], poly[k + 1]], colour));
        }
    }
    let mpa = 1e-6 * scale;
    let legend = vec![
        (format!("σ1 ≥ +{mpa:.1} MPa (f_t)"), plot::diverging(1.0)),
        ("σ1 = 0".to_owned(), plot::diverging(0.0)),
        (format!("σ1 ≤ −{mpa:.1} MPa"), plot::diverging(-1.0)),
    ];
    plot::triangles(path, title, ("x (m)", "y (m)"), bounds, &tris, &legend, false)
}

/// A segment drawn as a thin rectangle `width` wide (the triangle map has
/// no lines of its own colour).
fn thick(a: (f64, f64), b: (f64, f64), width: f64, colour: RGBColor) -> [Flat; 2] {
    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
    let len = dx.hypot(dy).max(f64::MIN_POSITIVE);
    let (nx, ny) = (-dy / len * 0.5 * width, dx / len * 0.5 * width);
    let q = [(a.0 + nx, a.1 + ny), (b.0 + nx, b.1 + ny), (b.0 - nx, b.1 - ny), (a.0 - nx, a.1 - ny)];
    [([q[0], q[1], q[2]], colour), ([q[0], q[2], q[3]], colour)]
}

/// The fracture faces of `fractures` (a fracture frame: `mode` 0 for
/// pre-existing faces, 1–4 for failed joints) seen along z. A face standing
/// along z (all of the map's, most new ones) is seen edge-on and drawn as
/// a line; a face across z (between layers of the extrusion) as its
/// filled triangle, under the lines.
pub fn fracture_pattern(path: &Path, fractures: &Grid, bounds: (Range<f64>, Range<f64>), title: &str) -> Result<()> {
    let (_, mode) = fractures.cell("mode")?;
    let width = 0.004 * (bounds.0.end - bounds.0.start);
    let (mut flat, mut pre, mut new) = (Vec::new(), Vec::new(), Vec::new());
    for (cell, &m) in fractures.cells.iter().zip(mode) {
        let p = [0, 1, 2].map(|k| (fractures.points[cell[k]][0], fractures.points[cell[k]][1]));
        let area = 0.5 * ((p[1].0 - p[0].0) * (p[2].1 - p[0].1) - (p[2].0 - p[0].0) * (p[1].1 - p[0].1)).abs();
        let edges = [(p[0], p[1]), (p[1], p[2]), (p[2], p[0])];
        let (a, b) = edges
            .into_iter()
            .max_by(|x, y| {
                let l = |e: &((f64, f64), (f64, f64))| (e.1.0 - e.0.0).hypot(e.1.1 - e.0.1);
                l(x).total_cmp(&l(y))
            })
            .expect("three edges");
        let longest = (b.0 - a.0).hypot(b.1 - a.1);
        let colour = if m == 0.0 { PRE_EXISTING } else { mode_colour(m) };
        if area > 0.05 * longest * longest {
            flat.push((p, colour));
        } else {
            let target = if m == 0.0 { &mut pre } else { &mut new };
            target.extend(thick(a, b, width, colour));
        }
    }
    let tris: Vec<Flat> = flat.into_iter().chain(pre).chain(new).collect();
    let mut legend = vec![("pre-existing".to_owned(), PRE_EXISTING)];
    legend.extend(
        ["new, tensile", "new, shear", "new, mixed", "new, collapsed"]
            .iter()
            .zip(1..)
            .map(|(n, c)| ((*n).to_owned(), mode_colour(f64::from(c)))),
    );
    plot::triangles(path, title, ("x (m)", "y (m)"), bounds, &tris, &legend, false)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn area(poly: &[(f64, f64)]) -> f64 {
        let n = poly.len();
        0.5 * (0..n).map(|i| poly[i].0 * poly[(i + 1) % n].1 - poly[(i + 1) % n].0 * poly[i].1).sum::<f64>().abs()
    }

    #[test]
    fn a_plane_cuts_a_tet_in_a_triangle_or_a_convex_quadrilateral() {
        let tet = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
        // One vertex above: a triangle (1 − z)²/2 in area.
        let t = section(tet, 0.5);
        assert_eq!(t.len(), 3);
        assert!((area(&t) - 0.125).abs() < 1e-15);
        // Two above, two below: a quadrilateral whose points go round it
        // (its shoelace area is that of the square cut of the tet).
        let tet2 = [[0.0, 0.0, 0.0], [1.0, 1.0, 0.0], [1.0, 0.0, 1.0], [0.0, 1.0, 1.0]];
        let q = section(tet2, 0.5);
        assert_eq!(q.len(), 4);
        assert!((area(&q) - 0.5).abs() < 1e-15, "{q:?}");
        // A plane through the base face: the tet lies above it, no cut; a
        // plane through the apex cuts the tet at its apex only: a point,
        // counted as three equal points.
        assert!(section(tet, 0.0).is_empty());
        assert!(section(tet, 2.0).is_empty());
        assert!(area(&section(tet, 1.0)) < 1e-15);
    }

    #[test]
    fn a_plane_through_a_layer_of_vertices_is_covered_once() {
        // Two tets stacked through the plane z = 1: only the lower one's top face is drawn.
        let lower = [[0.0, 0.0, 0.0], [1.0, 0.0, 1.0], [0.0, 1.0, 1.0], [0.0, 0.0, 1.0]];
        let upper = [[1.0, 0.0, 1.0], [0.0, 1.0, 1.0], [0.0, 0.0, 1.0], [0.0, 0.0, 2.0]];
        assert!((area(&section(lower, 1.0)) - 0.5).abs() < 1e-15);
        assert!(section(upper, 1.0).is_empty());
    }

    #[test]
    fn a_thick_segment_is_a_rectangle_of_its_length_and_width() {
        let r = thick((0.0, 0.0), (3.0, 4.0), 0.1, RGBColor(0, 0, 0));
        let total: f64 = r.iter().map(|(p, _)| area(p)).sum();
        assert!((total - 0.5).abs() < 1e-12, "{total}");
    }
}
