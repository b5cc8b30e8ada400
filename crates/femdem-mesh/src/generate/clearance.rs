//! The closest approach of an extrusion's features before it is meshed.
//!
//! A trace that ends a hair short of another or of the outline, two traces
//! that run side by side, or a notch of the outline narrower than a hair
//! leave a gap between constraint edges that the 2D refinement must fill
//! with triangles of the gap's width. Far below `element_size` that costs
//! minutes and gigabytes (a trace 10⁻⁷ m from a 0.6 m outline edge at
//! 0.05 m: three minutes, 5.6 GB, in 2026-11) and ends in tets the mesh
//! check refuses as degenerate: a triangle of edge `a` extruded through a
//! layer of height `dz` makes tets of volume ≈ `a² dz / 6`, below
//! [`crate::check::DEGENERATE_VOLUME_RATIO`] `dz³` once `a < 7.7·10⁻⁵ dz`.
//! [`closest_approach`] finds such a gap first, in time linear in the
//! features' length over the cell size (at most some 10⁷ samples), times
//! the segments that share a point's cells.

use std::collections::HashMap;

use super::TraceNetwork;
use super::traces::{bounds, nearest_on_segment};

/// Which feature a point or a segment belongs to.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Feature {
    /// The outline.
    Outline,
    /// A trace.
    Trace,
}

impl Feature {
    /// The feature in words.
    pub fn name(self) -> &'static str {
        match self {
            Feature::Outline => "the outline",
            Feature::Trace => "a trace",
        }
    }
}

/// A point of one feature close to a segment it does not end.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NearMiss {
    /// The distance, m.
    pub distance: f64,
    /// The point.
    pub point: [f64; 2],
    /// What it is a point of.
    pub point_of: Feature,
    /// The nearest point of the segment.
    pub nearest: [f64; 2],
    /// What the segment is part of.
    pub segment_of: Feature,
}

/// The point of `network` nearest to a segment that does not end at it,
/// when that distance lies in `(same, below)`: points within `same` are one
/// point to the network ([`super::TRACE_TOLERANCE`]). Every gap between
/// two features has a point of one of them at its narrowest (two segments
/// that do not cross come closest at an end of one), so checking the
/// points finds it. `cell` is the size of the grid that bins the segments
/// (the element size: a point looks in the 3 × 3 cells around its own).
pub fn closest_approach(network: &TraceNetwork, same: f64, below: f64, cell: f64) -> Option<NearMiss> {
    let n = network.outline.len();
    let mut segments: Vec<([f64; 2], [f64; 2], Feature)> =
        (0..n).map(|i| (network.outline[i], network.outline[(i + 1) % n], Feature::Outline)).collect();
    for piece in &network.pieces {
        segments.extend(piece.windows(2).map(|w| (w[0], w[1], Feature::Trace)));
    }
    let points = network
        .outline
        .iter()
        .map(|&p| (p, Feature::Outline))
        .chain(network.pieces.iter().flatten().map(|&p| (p, Feature::Trace)));
    // A point within `below` of a segment lies within `below + cell / 4` of
    // one of its samples (taken every `cell / 2`), so in the 3 × 3 cells
    // around the sample's when `below < 3 cell / 4`.
    // A larger cell is always correct, only slower per point: keep the
    // samples to about 10⁷ whatever the features' length.
    let total: f64 = segments.iter().map(|(a, b, _)| ((b[0] - a[0]).powi(2) + (b[1] - a[1]).powi(2)).sqrt()).sum();
    let cell = cell.max(2.0 * below).max(total / 1e7);
    let (lo, _) = bounds(&network.outline);
    let key = |p: [f64; 2]| [((p[0] - lo[0]) / cell).floor() as i64, ((p[1] - lo[1]) / cell).floor() as i64];
    let mut grid: HashMap<[i64; 2], Vec<u32>> = HashMap::new();
    for (s, &(a, b, _)) in segments.iter().enumerate() {
        let length = ((b[0] - a[0]).powi(2) + (b[1] - a[1]).powi(2)).sqrt();
        let samples = (2.0 * length / cell).ceil().max(1.0) as usize;
        for k in 0..=samples {
            let t = k as f64 / samples as f64;
            let cell_of = key([a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])]);
            let list = grid.entry(cell_of).or_default();
            if list.last() != Some(&(s as u32)) {
                list.push(s as u32);
            }
        }
    }
    let same_point = |p: [f64; 2], q: [f64; 2]| p.map(f64::to_bits) == q.map(f64::to_bits);
    let mut best: Option<NearMiss> = None;
    for (p, point_of) in points {
        let [i, j] = key(p);
        for di in -1..=1 {
            for dj in -1..=1 {
                for &s in grid.get(&[i + di, j + dj]).map_or(&[][..], Vec::as_slice) {
                    let (a, b, segment_of) = segments[s as usize];
                    if same_point(p, a) || same_point(p, b) {
                        continue;
                    }
                    let (nearest, distance) = nearest_on_segment(p, a, b);
                    if distance > same && distance < below && best.is_none_or(|m| distance < m.distance) {
                        best = Some(NearMiss { distance, point: p, point_of, nearest, segment_of });
                    }
                }
            }
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::trace_network;

    const SQUARE: [[f64; 2]; 4] = [[0.0, 0.0], [1.0, 0.0], [1.0, 0.6], [0.0, 0.6]];

    fn near(traces: &[Vec<[f64; 2]>]) -> Option<NearMiss> {
        let network = trace_network(&SQUARE, traces).unwrap();
        closest_approach(&network, 1e-9, 5e-6, 0.05)
    }

    #[test]
    fn a_trace_beside_the_outline_or_short_of_another_is_found() {
        let m = near(&[vec![[0.2, 1e-7], [0.8, 1e-7]]]).unwrap();
        assert!((m.distance - 1e-7).abs() < 1e-15, "{m:?}");
        assert_eq!((m.point_of, m.segment_of), (Feature::Trace, Feature::Outline));
        // A trace ending 10⁻⁶ m short of another, far from its samples' cells' corners.
        let m = near(&[vec![[0.1, 0.3], [0.9, 0.3]], vec![[0.433, 0.1], [0.433, 0.3 - 1e-6]]]).unwrap();
        assert!((m.distance - 1e-6).abs() < 1e-12 && m.segment_of == Feature::Trace, "{m:?}");
        assert!((m.nearest[0] - 0.433).abs() < 1e-15 && m.nearest[1] == 0.3, "{m:?}");
        // A notch of the outline 10⁻⁷ m wide.
        let notch = [[0.0, 0.0], [0.5, 0.0], [0.5, 0.4], [0.5 + 1e-7, 0.0], [1.0, 0.0], [1.0, 0.6], [0.0, 0.6]];
        let network = trace_network(&notch, &[]).unwrap();
        let m = closest_approach(&network, 1e-9, 5e-6, 0.05).unwrap();
        assert_eq!((m.point_of, m.segment_of), (Feature::Outline, Feature::Outline));
        assert!(m.distance < 1e-7, "{m:?}");
    }

    #[test]
    fn junctions_and_features_apart_are_not() {
        // An X-junction, a T-junction on a trace, traces ending on the outline.
        let traces = [
            vec![[0.0, 0.3], [1.0, 0.3]],
            vec![[0.2, 0.1], [0.8, 0.5]],
            vec![[0.5, 0.3], [0.5, 0.6]],
            vec![[0.9, 0.05], [0.95, 0.1]],
        ];
        assert_eq!(near(&traces), None);
        // A gap of 10⁻⁵ m is above `below` (5·10⁻⁶ m).
        assert_eq!(near(&[vec![[0.2, 1e-5], [0.8, 1e-5]]]), None);
        // A circle's outline alone.
        let circle: Vec<[f64; 2]> =
            (0..64).map(|i| (i as f64 * std::f64::consts::TAU / 64.0).sin_cos()).map(|(s, c)| [c, s]).collect();
        let network = trace_network(&circle, &[vec![[-0.5, 0.0], [0.5, 0.0]]]).unwrap();
        assert_eq!(closest_approach(&network, 1e-9, 5e-6, 0.05), None);
    }
}
