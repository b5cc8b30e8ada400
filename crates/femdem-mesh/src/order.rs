//! A mesh's tets and nodes put in space-filling-curve order, for the
//! caches.
//!
//! A mesher's output order can be far from spatial: in the paper's
//! Gmsh disc two consecutive tets lie some 12 element sizes apart and two
//! tets that share a face some 8,000 places apart (median). The step then
//! reads every joint's six nodes and gathers every node's forces from
//! scattered memory. Sorting the tets along the Z-order (Morton) curve of
//! their centroids and numbering the nodes in order of first use keeps
//! neighbours near in memory; joint insertion orders the joints by their
//! faces' node ids, so they follow. The mesh is the same set of tets: only
//! the numbering changes, and with it the order of floating-point sums
//! (results move at round-off until joints fail; after that, which of two
//! nearly tied joints fails first may change) and of random draws per
//! joint.

use crate::{FaceRef, TetMesh};

/// Bits per axis of the Morton key (three axes in a `u64`).
const BITS: u32 = 21;

/// `mesh` with its tets sorted by the Morton key of their centroids in
/// the mesh's bounding box (ties, and tets in one cell of the 2²¹ grid per
/// axis, keep their order) and its nodes numbered in order of first use by
/// the sorted tets (an unused node keeps its relative order after them).
/// Regions, boundary groups and fracture faces follow their tets; a
/// group's faces keep their order in the group. Deterministic: the same
/// mesh gives the same order on any machine and thread count.
pub fn spatially_ordered(mesh: &TetMesh) -> TetMesh {
    let order = tet_order(mesh);
    let mut new_tet = vec![0u32; mesh.tets.len()];
    for (new, &old) in order.iter().enumerate() {
        new_tet[old as usize] = new as u32;
    }
    let mut new_node = vec![u32::MAX; mesh.coords.len()];
    let mut coords = Vec::with_capacity(mesh.coords.len());
    let mut take = |n: u32, coords: &mut Vec<[f64; 3]>| {
        if new_node[n as usize] == u32::MAX {
            new_node[n as usize] = coords.len() as u32;
            coords.push(mesh.coords[n as usize]);
        }
        new_node[n as usize]
    };
    let tets: Vec<[u32; 4]> = order.iter().map(|&t| mesh.tets[t as usize].map(|n| take(n, &mut coords))).collect();
    for n in 0..mesh.coords.len() as u32 {
        take(n, &mut coords);
    }
    let face = |f: &FaceRef| FaceRef { tet: new_tet[f.tet as usize], local: f.local };
    TetMesh {
        coords,
        tets,
        tet_region: order.iter().map(|&t| mesh.tet_region[t as usize]).collect(),
        regions: mesh.regions.clone(),
        boundary: mesh
            .boundary
            .iter()
            .map(|g| crate::BoundaryGroup { name: g.name.clone(), faces: g.faces.iter().map(face).collect() })
            .collect(),
        fracture_faces: mesh.fracture_faces.iter().map(face).collect(),
    }
}

/// The tets of `mesh` in Morton order of their centroids: old indices.
fn tet_order(mesh: &TetMesh) -> Vec<u32> {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for c in &mesh.coords {
        for d in 0..3 {
            lo[d] = lo[d].min(c[d]);
            hi[d] = hi[d].max(c[d]);
        }
    }
    let cells = f64::from((1u32 << BITS) - 1);
    let cell = |x: f64, d: usize| {
        let span = hi[d] - lo[d];
        let s = if span > 0.0 { (x - lo[d]) / span } else { 0.0 };
        // In [0, 1] up to rounding; the cast saturates, NaN gives 0.
        (s * cells).clamp(0.0, cells) as u64
    };
    let mut keyed: Vec<(u64, u32)> = (0..mesh.tets.len())
        .map(|t| {
            let p = mesh.tets[t].map(|n| mesh.coords[n as usize]);
            let c = |d: usize| 0.25 * (p[0][d] + p[1][d] + p[2][d] + p[3][d]);
            (morton(cell(c(0), 0), cell(c(1), 1), cell(c(2), 2)), t as u32)
        })
        .collect();
    keyed.sort_unstable();
    keyed.into_iter().map(|(_, t)| t).collect()
}

/// The Morton key of cell `(x, y, z)`, each below 2²¹: the bits
/// interleaved, x lowest.
fn morton(x: u64, y: u64, z: u64) -> u64 {
    spread(x) | (spread(y) << 1) | (spread(z) << 2)
}

/// The low 21 bits of `v` moved to every third bit.
fn spread(v: u64) -> u64 {
    let mut v = v & 0x1f_ffff;
    v = (v | (v << 32)) & 0x001f_0000_0000_ffff;
    v = (v | (v << 16)) & 0x001f_0000_ff00_00ff;
    v = (v | (v << 8)) & 0x100f_00f0_0f00_f00f;
    v = (v | (v << 4)) & 0x10c3_0c30_c30c_30c3;
    v = (v | (v << 2)) & 0x1249_2492_4924_9249;
    v
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Region;
    use crate::generate::{BoxSpec, generate_box};

    #[test]
    fn spread_moves_each_bit_to_every_third() {
        for bit in 0..BITS {
            assert_eq!(spread(1 << bit), 1 << (3 * bit), "bit {bit}");
        }
        assert_eq!(morton(1, 1, 1), 0b111);
        assert_eq!(morton(0b10, 0, 0), 0b1000);
    }

    /// A box mesh shuffled, then ordered: the same tets (by their corner
    /// positions, in their node order), regions and boundary faces, a
    /// mesh that passes the check, and consecutive tets near each other.
    #[test]
    fn ordering_a_shuffled_mesh_keeps_every_tet_and_face() {
        let mesh = generate_box(&BoxSpec {
            min: [0.0; 3],
            max: [1.0, 0.5, 0.25],
            element_size: 0.125,
            jitter: 0.1,
            seed: 1,
            region: Region { name: "b".into(), breakable: true },
        })
        .expect("box");
        // A fixed shuffle of the tets (Fisher–Yates with xorshift64).
        let n = mesh.tets.len();
        let mut perm: Vec<usize> = (0..n).collect();
        let mut state = 0x9e37_79b9_7f4a_7c15u64;
        for i in (1..n).rev() {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            perm.swap(i, (state % (i as u64 + 1)) as usize);
        }
        let mut inverse = vec![0u32; n];
        for (new, &old) in perm.iter().enumerate() {
            inverse[old] = new as u32;
        }
        let shuffled = TetMesh {
            tets: perm.iter().map(|&t| mesh.tets[t]).collect(),
            tet_region: perm.iter().map(|&t| mesh.tet_region[t]).collect(),
            boundary: mesh
                .boundary
                .iter()
                .map(|g| crate::BoundaryGroup {
                    name: g.name.clone(),
                    faces: g.faces.iter().map(|f| FaceRef { tet: inverse[f.tet as usize], local: f.local }).collect(),
                })
                .collect(),
            ..mesh.clone()
        };
        let ordered = spatially_ordered(&shuffled);
        crate::check::check(&ordered).expect("the ordered mesh is valid");
        let corners = |m: &TetMesh, t: usize| m.tets[t].map(|v| m.coords[v as usize].map(f64::to_bits));
        let mut a: Vec<_> = (0..n).map(|t| (corners(&mesh, t), mesh.tet_region[t])).collect();
        let mut b: Vec<_> = (0..n).map(|t| (corners(&ordered, t), ordered.tet_region[t])).collect();
        a.sort_unstable();
        b.sort_unstable();
        assert_eq!(a, b, "the same tets, each with its node order and region");
        assert_eq!(ordered.coords.len(), mesh.coords.len());
        for (g, h) in mesh.boundary.iter().zip(&ordered.boundary) {
            assert_eq!(g.name, h.name);
            let points = |m: &TetMesh, f: &FaceRef| f.nodes(&m.tets).map(|v| m.coords[v as usize].map(f64::to_bits));
            let mut p: Vec<_> = g.faces.iter().map(|f| points(&mesh, f)).collect();
            let mut q: Vec<_> = h.faces.iter().map(|f| points(&ordered, f)).collect();
            p.sort_unstable();
            q.sort_unstable();
            assert_eq!(p, q, "group {}", g.name);
        }
        let centroid = |m: &TetMesh, t: usize| {
            let p = m.tet_points(t);
            (p[0] + p[1] + p[2] + p[3]) / 4.0
        };
        let step = |m: &TetMesh| (1..n).map(|t| (centroid(m, t) - centroid(m, t - 1)).norm()).sum::<f64>() / n as f64;
        // Consecutive tets about a cell (0.125) apart once ordered; a
        // random order puts them about the box's mean distance apart.
        let (ordered_step, shuffled_step) = (step(&ordered), step(&shuffled));
        assert!(ordered_step < 0.1875 && shuffled_step > 2.0 * ordered_step, "{ordered_step} vs {shuffled_step}");
        assert_eq!(spatially_ordered(&ordered), ordered, "ordering is idempotent");
    }
}
