//! Reading back what `femdem run` wrote: the `.pvd` time series and the
//! `.vtu` frames (points, cells and cell data), with vtkio.

use std::path::{Path, PathBuf};

use anyhow::{Context, Result, bail};
use vtkio::Vtk;
use vtkio::model::{Attribute, DataSet};

/// The frames of a `.pvd` collection: `(time, file)`, in time order.
pub fn series(pvd: &Path) -> Result<Vec<(f64, PathBuf)>> {
    let text = std::fs::read_to_string(pvd).with_context(|| format!("reading {}", pvd.display()))?;
    let dir = pvd.parent().unwrap_or(Path::new("."));
    let attr = |tag: &str, key: &str| -> Option<String> {
        let at = tag.find(&format!("{key}=\""))? + key.len() + 2;
        Some(tag[at..].split('"').next()?.to_owned())
    };
    let mut frames = Vec::new();
    for tag in text.split("<DataSet").skip(1) {
        let (Some(t), Some(f)) = (attr(tag, "timestep"), attr(tag, "file")) else {
            bail!("{}: a DataSet without timestep or file", pvd.display());
        };
        frames.push((t.parse::<f64>().with_context(|| format!("{}: timestep `{t}`", pvd.display()))?, dir.join(f)));
    }
    frames.sort_by(|a, b| a.0.total_cmp(&b.0));
    Ok(frames)
}

/// One unstructured-grid frame.
#[derive(Debug, Clone)]
pub struct Grid {
    /// Point coordinates, m.
    pub points: Vec<[f64; 3]>,
    /// Each cell's point indices.
    pub cells: Vec<Vec<usize>>,
    cell_data: Vec<(String, usize, Vec<f64>)>,
    point_data: Vec<(String, usize, Vec<f64>)>,
}

impl Grid {
    /// Reads a `.vtu` file.
    pub fn read(path: &Path) -> Result<Grid> {
        let vtk = Vtk::import(path).with_context(|| format!("reading {}", path.display()))?;
        let DataSet::UnstructuredGrid { pieces, .. } = vtk.data else {
            bail!("{}: not an unstructured grid", path.display());
        };
        let piece = pieces
            .into_iter()
            .next()
            .with_context(|| format!("{}: no piece", path.display()))?
            .into_loaded_piece_data(Some(path))?;
        let xyz: Vec<f64> = piece.points.cast_into().with_context(|| format!("{}: points", path.display()))?;
        let points = xyz.chunks_exact(3).map(|p| [p[0], p[1], p[2]]).collect();
        let (connectivity, offsets) = piece.cells.cell_verts.into_xml();
        let mut cells = Vec::with_capacity(offsets.len());
        let mut start = 0usize;
        for &end in &offsets {
            let end = end as usize;
            cells.push(connectivity[start..end].iter().map(|&i| i as usize).collect());
            start = end;
        }
        let arrays = |attributes: Vec<Attribute>| -> Vec<(String, usize, Vec<f64>)> {
            attributes
                .into_iter()
                .filter_map(|a| match a {
                    Attribute::DataArray(d) => {
                        let values: Vec<f64> = d.data.cast_into().unwrap_or_default();
                        Some((d.name, d.elem.num_comp() as usize, values))
                    }
                    Attribute::Field { .. } => None,
                })
                .collect()
        };
        let cell_data = arrays(piece.data.cell);
        let point_data = arrays(piece.data.point);
        Ok(Grid { points, cells, cell_data, point_data })
    }

    /// The point array `name`: its number of components and its values.
    pub fn point(&self, name: &str) -> Result<(usize, &[f64])> {
        array(&self.point_data, "point", name)
    }

    /// The cell array `name`: its number of components and its values.
    pub fn cell(&self, name: &str) -> Result<(usize, &[f64])> {
        array(&self.cell_data, "cell", name)
    }

    /// The centroid of cell `c`.
    pub fn centroid(&self, c: usize) -> [f64; 3] {
        let cell = &self.cells[c];
        let mut s = [0.0; 3];
        for &i in cell {
            for (a, p) in s.iter_mut().zip(self.points[i]) {
                *a += p;
            }
        }
        s.map(|v| v / cell.len() as f64)
    }

    /// The volume of tetrahedral cell `c` at the frame's positions, m³.
    pub fn tet_volume(&self, c: usize) -> f64 {
        tet_volume([0, 1, 2, 3].map(|k| self.points[self.cells[c][k]]))
    }

    /// The undeformed positions of the points (their positions less the
    /// frame's `displacement`), m.
    pub fn undeformed_points(&self) -> Result<Vec<[f64; 3]>> {
        let (_, u) = self.point("displacement")?;
        Ok(self.points.iter().enumerate().map(|(i, p)| [0, 1, 2].map(|k| p[k] - u[3 * i + k])).collect())
    }

    /// A grid of `points` and `cells` without arrays (to build frames in
    /// tests; add arrays with [`Grid::add_point`]).
    pub fn new(points: Vec<[f64; 3]>, cells: Vec<Vec<usize>>) -> Grid {
        Grid { points, cells, cell_data: Vec::new(), point_data: Vec::new() }
    }

    /// Adds the point array `name` of `components` values per point.
    pub fn add_point(&mut self, name: &str, components: usize, values: Vec<f64>) {
        assert_eq!(
            values.len(),
            components * self.points.len(),
            "point array `{name}`: one value per component and point"
        );
        self.point_data.push((name.to_owned(), components, values));
    }
}

/// The volume of the tetrahedron `p`, m³.
pub fn tet_volume(p: [[f64; 3]; 4]) -> f64 {
    let d = |k: usize| [0, 1, 2].map(|c| p[k][c] - p[0][c]);
    let (u, v, w) = (d(1), d(2), d(3));
    let det =
        u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) + u[2] * (v[0] * w[1] - v[1] * w[0]);
    det.abs() / 6.0
}

/// The array `name` of `arrays` (`kind` names them in the error): its
/// number of components and its values.
fn array<'a>(arrays: &'a [(String, usize, Vec<f64>)], kind: &str, name: &str) -> Result<(usize, &'a [f64])> {
    arrays
        .iter()
        .find(|(n, _, _)| n == name)
        .map(|(_, c, v)| (*c, v.as_slice()))
        .with_context(|| format!("no {kind} array `{name}`"))
}
