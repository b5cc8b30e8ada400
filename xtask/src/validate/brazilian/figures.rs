//! The Brazilian figures: load–strain curves of all rates (the paper's
//! Fig. 6), the failed faces along z and in 3D coloured by mode (Fig. 7–8),
//! and σx on the mid-plane before fracture (Fig. 7a).

use std::path::Path;

use anyhow::Result;
use plotters::style::RGBColor;

use super::analysis::Outcome;

/// A triangle seen in a plane, with its colour.
type Flat = ([(f64, f64); 3], RGBColor);
use super::case::Disc;
use crate::validate::colours::{mode_colour, mode_legend};
use crate::validate::plot;
use femdem_post::frames::Grid;

/// Fig. 6: F (kN) against ε_yy (‰) for every rate.
pub fn load_strain(path: &Path, runs: &[(f64, &Outcome)]) -> Result<()> {
    let series: Vec<(String, Vec<(f64, f64)>)> = runs
        .iter()
        .map(|(v, o)| (format!("V = {v} m/s"), o.curve.iter().map(|(e, f)| (1e3 * e, 1e-3 * f)).collect()))
        .collect();
    plot::lines(path, "Brazilian disc: load against strain (Eq. 21-22)", "strain ε_yy (‰)", "load F (kN)", &series)
}

/// Fig. 7–8: the failed faces of `fractures` (the last fracture frame)
/// seen along z (`view_z`) and in an oblique 3D view (`view_3d`).
pub fn fracture_pattern(view_z: &Path, view_3d: &Path, fractures: &Grid, disc: Disc, title: &str) -> Result<()> {
    let (_, mode) = fractures.cell("mode")?;
    let r = 0.5e3 * disc.diameter;
    let mm = |p: [f64; 3]| p.map(|v| 1e3 * v);
    let along_z: Vec<Flat> = fractures
        .cells
        .iter()
        .zip(mode)
        .map(|(c, &m)| {
            let p = [0, 1, 2].map(|k| mm(fractures.points[c[k]]));
            (p.map(|q| (q[0], q[1])), mode_colour(m))
        })
        .collect();
    let b = 1.1 * r;
    plot::triangles(
        view_z,
        &format!("{title}: failed faces along z"),
        ("x (mm)", "y (mm)"),
        (-b..b, -b..b),
        &along_z,
        &mode_legend(),
        true,
    )?;
    // Oblique view: turn 35° about y, then tilt 25° about x; draw far to near.
    let (a, e) = (35f64.to_radians(), 25f64.to_radians());
    let z0 = 0.5e3 * disc.thickness;
    let project = |p: [f64; 3]| {
        let (x, y, z) = (p[0], p[1], p[2] - z0);
        let (x1, z1) = (x * a.cos() + z * a.sin(), -x * a.sin() + z * a.cos());
        let (y2, z2) = (y * e.cos() - z1 * e.sin(), y * e.sin() + z1 * e.cos());
        (x1, y2, z2)
    };
    let mut oblique: Vec<(f64, Flat)> = fractures
        .cells
        .iter()
        .zip(mode)
        .map(|(c, &m)| {
            let p = [0, 1, 2].map(|k| project(mm(fractures.points[c[k]])));
            let depth = (p[0].2 + p[1].2 + p[2].2) / 3.0;
            (depth, (p.map(|q| (q.0, q.1)), mode_colour(m)))
        })
        .collect();
    oblique.sort_by(|x, y| x.0.total_cmp(&y.0));
    let tris: Vec<Flat> = oblique.into_iter().map(|(_, f)| f).collect();
    plot::triangles(
        view_3d,
        &format!("{title}: failed faces, oblique view"),
        ("", ""),
        (-b..b, -b..b),
        &tris,
        &mode_legend(),
        true,
    )
}

/// Fig. 7a: σx of the disc's tets whose centroids lie within half a layer
/// of the mid-plane, each drawn as its outline seen along z, in units of
/// Hondros' centre value `s0` = 2F/(πDt).
pub fn mid_plane_sigma_x(path: &Path, grid: &Grid, disc: Disc, layer: f64, s0: f64, title: &str) -> Result<()> {
    let (_, stress) = grid.cell("stress")?;
    let (_, region) = grid.cell("region")?;
    let z_mid = 0.5 * disc.thickness;
    let mut tris = Vec::new();
    for (c, cell) in grid.cells.iter().enumerate() {
        if region[c] != 0.0 || (grid.centroid(c)[2] - z_mid).abs() > 0.5 * layer {
            continue;
        }
        let colour = plot::diverging(stress[9 * c] / (3.0 * s0));
        let p: Vec<(f64, f64)> = cell.iter().map(|&i| (1e3 * grid.points[i][0], 1e3 * grid.points[i][1])).collect();
        // A tet seen along z covers the hull of its 4 points: draw the
        // triangles of every 3 of them (overlaps share the colour).
        for skip in 0..4 {
            let t: Vec<(f64, f64)> = (0..4).filter(|&k| k != skip).map(|k| p[k]).collect();
            tris.push(([t[0], t[1], t[2]], colour));
        }
    }
    let b = 0.55e3 * disc.diameter;
    let legend = vec![
        ("σx = +3·2F/(πDt)".to_owned(), plot::diverging(1.0)),
        ("σx = 0".to_owned(), plot::diverging(0.0)),
        ("σx = -3·2F/(πDt)".to_owned(), plot::diverging(-1.0)),
    ];
    plot::triangles(path, title, ("x (mm)", "y (mm)"), (-b..b, -b..b), &tris, &legend, false)
}
