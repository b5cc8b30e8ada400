//! Where the kinetic energy of the multi-layer block lies: in the strips
//! along its two x faces, which the applied tension (a dead load) pulls
//! out once the cross fractures near the faces have grown through the
//! layers, or in the interior. Read from a frame's nodal velocities with
//! femdem's lumped mass: every tet owns its four nodes, each carrying a
//! quarter of the tet's mass ρV (V from the undeformed positions).

use anyhow::{Result, bail};
use femdem_post::frames::{Grid, tet_volume};

/// The width of each strip, m, measured inward from the undeformed x face:
/// fixed in metres (the 150 mm quick mesh's element size) so that runs on
/// different meshes are compared over the same rock.
pub const WIDTH: f64 = 0.15;

/// The kinetic energy and outward velocity of the two strips in one frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Strips {
    /// The strips' share of the block's mass.
    pub mass_share: f64,
    /// The kinetic energy of the whole block, J.
    pub kinetic: f64,
    /// The strips' share of it.
    pub kinetic_share: f64,
    /// The strips' mass-weighted mean outward velocity (+v_x at x_max,
    /// −v_x at x_min), m/s.
    pub mean_outward: f64,
    /// The largest outward nodal velocity in the strips, m/s.
    pub max_outward: f64,
    /// The interior's mass-weighted root-mean-square speed, m/s.
    pub interior_rms: f64,
}

/// The strips of `grid` (a frame with `displacement` and `velocity` point
/// arrays) for a block between `x_min` and `x_max` whose nodal mass per
/// unit volume is `mass_density` (kg/m³: ρ times `[solver] mass_scaling`).
pub fn measure(grid: &Grid, x_min: f64, x_max: f64, mass_density: f64) -> Result<Strips> {
    let x0 = grid.undeformed_points()?;
    let (_, v) = grid.point("velocity")?;
    let (mut mass, mut strip_mass, mut kinetic, mut strip_kinetic) = (0.0, 0.0, 0.0, 0.0);
    let (mut outward_momentum, mut max_outward, mut interior_mv2) = (0.0, f64::NEG_INFINITY, 0.0);
    for cell in grid.cells.iter().filter(|c| c.len() == 4) {
        let p = [0, 1, 2, 3].map(|k| x0[cell[k]]);
        let m = 0.25 * mass_density * tet_volume(p);
        let cx = 0.25 * p.iter().map(|q| q[0]).sum::<f64>();
        // Outward along x: +1 in the x_max strip, −1 in the x_min strip.
        let side = if cx > x_max - WIDTH {
            1.0
        } else if cx < x_min + WIDTH {
            -1.0
        } else {
            0.0
        };
        for &i in cell {
            let vi = [v[3 * i], v[3 * i + 1], v[3 * i + 2]];
            let v2 = vi.iter().map(|c| c * c).sum::<f64>();
            mass += m;
            kinetic += 0.5 * m * v2;
            if side == 0.0 {
                interior_mv2 += m * v2;
            } else {
                strip_mass += m;
                strip_kinetic += 0.5 * m * v2;
                outward_momentum += m * side * vi[0];
                max_outward = max_outward.max(side * vi[0]);
            }
        }
    }
    if strip_mass <= 0.0 || strip_mass >= mass {
        bail!("no tet lies in (or every tet lies in) the {WIDTH} m strips along the x faces");
    }
    Ok(Strips {
        mass_share: strip_mass / mass,
        kinetic,
        kinetic_share: if kinetic > 0.0 { strip_kinetic / kinetic } else { 0.0 },
        mean_outward: outward_momentum / strip_mass,
        max_outward,
        interior_rms: (interior_mv2 / (mass - strip_mass)).sqrt(),
    })
}

#[cfg(test)]
mod tests {
    use super::{WIDTH, measure};
    use femdem_post::frames::Grid;

    /// A tet of edge `a` with its right-angle corner at `o`.
    fn tet(o: [f64; 3], a: f64) -> Vec<[f64; 3]> {
        vec![o, [o[0] + a, o[1], o[2]], [o[0], o[1] + a, o[2]], [o[0], o[1], o[2] + a]]
    }

    /// Three equal tets (each with its own nodes): one in the x_min strip,
    /// one in the interior, one in the x_max strip, with given velocities.
    fn block(velocities: [[f64; 3]; 3]) -> Grid {
        let a = 0.05;
        let mut points = tet([0.0, 0.0, 0.0], a);
        points.extend(tet([0.5, 0.0, 0.0], a));
        points.extend(tet([1.0 - a, 0.0, 0.0], a));
        let cells = (0..3).map(|t| (4 * t..4 * t + 4).collect()).collect();
        let mut g = Grid::new(points, cells);
        // Deformed by a uniform shift: the strips are found at the
        // undeformed positions.
        let shift = [0.3, 0.0, 0.0];
        for p in &mut g.points {
            p[0] += shift[0];
        }
        g.add_point("displacement", 3, (0..12).flat_map(|_| shift).collect());
        g.add_point("velocity", 3, (0..12).flat_map(|i| velocities[i / 4]).collect());
        g
    }

    #[test]
    fn the_strips_kinetic_energy_and_outward_speed_are_those_of_their_tets() {
        let rho = 2000.0;
        let s = measure(&block([[-3.0, 0.0, 0.0], [0.0, 0.0, 0.0], [1.0, 2.0, 0.0]]), 0.0, 1.0, rho).unwrap();
        let m = rho * 0.05f64.powi(3) / 6.0;
        assert!((s.mass_share - 2.0 / 3.0).abs() < 1e-12);
        assert!((s.kinetic - 0.5 * m * (9.0 + 5.0)).abs() < 1e-12 * s.kinetic);
        assert_eq!(s.kinetic_share, 1.0);
        // Outward: +3 at x_min (moving −x), +1 at x_max.
        assert!((s.mean_outward - 2.0).abs() < 1e-12);
        assert_eq!(s.max_outward, 3.0);
        assert_eq!(s.interior_rms, 0.0);
    }

    #[test]
    fn a_rigid_drift_along_x_is_not_an_outward_motion() {
        let v = [5.0, 0.0, 0.0];
        let s = measure(&block([v, v, v]), 0.0, 1.0, 1000.0).unwrap();
        assert!(s.mean_outward.abs() < 1e-12);
        assert!((s.kinetic_share - 2.0 / 3.0).abs() < 1e-12);
        assert!((s.interior_rms - 5.0).abs() < 1e-12);
    }

    #[test]
    fn a_block_all_strip_or_without_strips_is_refused() {
        let g = block([[0.0; 3]; 3]);
        // Every tet within WIDTH of x_max.
        assert!(measure(&g, 0.0, 2.0 * WIDTH - 0.2, 1000.0).is_err());
        // No tet within WIDTH of either face.
        assert!(measure(&g, -1.0, 3.0, 1000.0).is_err());
    }
}
