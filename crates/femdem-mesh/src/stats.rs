//! Mesh statistics: counts, edge lengths, quality, volumes per region.
//!
//! Sums are taken over fixed-size chunks in a fixed order, so the numbers do
//! not depend on the thread count.

use femdem_core::tet::{aspect_ratio, edge_lengths, inradius, signed_volume};
use rayon::prelude::*;

use crate::TetMesh;

/// Statistics of one region.
#[derive(Clone, Debug, PartialEq)]
pub struct RegionStats {
    /// Region name.
    pub name: String,
    /// Number of tets.
    pub tets: usize,
    /// Total volume, m³.
    pub volume: f64,
    /// Whether the region is breakable.
    pub breakable: bool,
}

/// Statistics of a mesh.
#[derive(Clone, Debug, PartialEq)]
pub struct MeshStats {
    /// Number of tets.
    pub tets: usize,
    /// Number of nodes.
    pub nodes: usize,
    /// Shortest tet edge, m.
    pub min_edge: f64,
    /// Mean edge length over the six edges of every tet, m.
    pub mean_edge: f64,
    /// Smallest inscribed-sphere radius, m.
    pub min_inradius: f64,
    /// Worst aspect ratio `ℓ_max / (2√6 r)` (1 for a regular tet).
    pub max_aspect_ratio: f64,
    /// Smallest tet volume, m³.
    pub min_volume: f64,
    /// Total volume, m³.
    pub volume: f64,
    /// Per region, in region order.
    pub regions: Vec<RegionStats>,
}

#[derive(Clone, Copy)]
struct Partial {
    min_edge: f64,
    sum_edge: f64,
    min_inradius: f64,
    max_aspect: f64,
    min_volume: f64,
}

impl Partial {
    const EMPTY: Partial = Partial {
        min_edge: f64::INFINITY,
        sum_edge: 0.0,
        min_inradius: f64::INFINITY,
        max_aspect: 0.0,
        min_volume: f64::INFINITY,
    };

    fn merge(self, o: Partial) -> Partial {
        Partial {
            min_edge: self.min_edge.min(o.min_edge),
            sum_edge: self.sum_edge + o.sum_edge,
            min_inradius: self.min_inradius.min(o.min_inradius),
            max_aspect: self.max_aspect.max(o.max_aspect),
            min_volume: self.min_volume.min(o.min_volume),
        }
    }
}

const CHUNK: usize = 4096;

/// Computes the statistics of `mesh`.
pub fn stats(mesh: &TetMesh) -> MeshStats {
    let volumes: Vec<f64> = (0..mesh.num_tets()).into_par_iter().map(|t| signed_volume(&mesh.tet_points(t))).collect();
    let partials: Vec<Partial> = (0..mesh.num_tets())
        .collect::<Vec<_>>()
        .par_chunks(CHUNK)
        .map(|chunk| {
            chunk.iter().fold(Partial::EMPTY, |acc, &t| {
                let p = mesh.tet_points(t);
                let e = edge_lengths(&p);
                acc.merge(Partial {
                    min_edge: e.into_iter().fold(f64::INFINITY, f64::min),
                    sum_edge: e.iter().sum(),
                    min_inradius: inradius(&p),
                    max_aspect: aspect_ratio(&p),
                    min_volume: volumes[t],
                })
            })
        })
        .collect();
    let total = partials.into_iter().fold(Partial::EMPTY, Partial::merge);
    let mut regions: Vec<RegionStats> = mesh
        .regions
        .iter()
        .map(|r| RegionStats { name: r.name.clone(), tets: 0, volume: 0.0, breakable: r.breakable })
        .collect();
    for (t, &r) in mesh.tet_region.iter().enumerate() {
        regions[r as usize].tets += 1;
        regions[r as usize].volume += volumes[t];
    }
    let n = mesh.num_tets();
    MeshStats {
        tets: n,
        nodes: mesh.num_nodes(),
        min_edge: if n > 0 { total.min_edge } else { 0.0 },
        mean_edge: if n > 0 { total.sum_edge / (6 * n) as f64 } else { 0.0 },
        min_inradius: if n > 0 { total.min_inradius } else { 0.0 },
        max_aspect_ratio: total.max_aspect,
        min_volume: if n > 0 { total.min_volume } else { 0.0 },
        volume: regions.iter().map(|r| r.volume).sum(),
        regions,
    }
}
