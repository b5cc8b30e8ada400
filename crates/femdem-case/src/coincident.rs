//! Parts meshed in the same place. Two parts whose tets coincide exactly
//! (the same four corner positions: an MSH file given as two parts, a box
//! without jitter listed twice; a jittered box listed twice gets another
//! seed and is another mesh) are two bodies in one place: their mass counts
//! twice, and contact cannot see them, since Eq. 17's potential `φ` is zero
//! on a tet's own faces, so coinciding tets push each other with no force
//! and the warning of tets overlapping at t = 0 (which measures that
//! potential's depth) stays silent. A copy moved far enough to overlap by
//! more than 10⁻⁹ of an element's altitude is warned of there; this check
//! finds the exact copy. A copy moved by less (10⁻¹² m in the test below)
//! is seen by neither.

use std::collections::hash_map::DefaultHasher;
use std::hash::{Hash, Hasher};
use std::ops::Range;

use femdem_mesh::TetMesh;

/// A tet's corners as bits, sorted: equal for two tets with the same four
/// corner positions, whatever their node order.
fn corners(mesh: &TetMesh, tet: usize) -> [[u64; 3]; 4] {
    // `+ 0.0` makes −0 the same as +0.
    let mut c = mesh.tets[tet].map(|n| mesh.coords[n as usize].map(|x| (x + 0.0).to_bits()));
    c.sort_unstable();
    c
}

/// For each pair of parts (`parts[k]`: the tets of part k in `mesh`, in
/// order, not overlapping) where tets of the later part coincide exactly
/// with tets of the earlier: `(earlier, later, how many of the later's
/// tets)`, ordered by the later part, then the earlier. Tets within one
/// part are not compared (the mesh check refuses those).
pub fn coinciding_parts(mesh: &TetMesh, parts: &[Range<usize>]) -> Vec<(usize, usize, usize)> {
    if parts.len() < 2 {
        return Vec::new();
    }
    let part_of = |t: usize| parts.partition_point(|r| r.end <= t);
    let mut keyed: Vec<(u64, u32)> = parts
        .iter()
        .flat_map(Range::clone)
        .map(|t| {
            let mut h = DefaultHasher::new();
            corners(mesh, t).hash(&mut h);
            (h.finish(), t as u32)
        })
        .collect();
    keyed.sort_unstable();
    let mut counts: Vec<(usize, usize, usize)> = Vec::new();
    for run in keyed.chunk_by(|a, b| a.0 == b.0).filter(|run| run.len() > 1) {
        for (k, &(_, t)) in run.iter().enumerate() {
            let (t, p) = (t as usize, part_of(t as usize));
            let key = corners(mesh, t);
            // The earliest other part holding a tet with the same corners.
            let earlier = run[..k]
                .iter()
                .chain(&run[k + 1..])
                .map(|&(_, s)| s as usize)
                .filter(|&s| part_of(s) < p && corners(mesh, s) == key)
                .map(part_of)
                .min();
            if let Some(e) = earlier {
                match counts.iter_mut().find(|c| (c.0, c.1) == (e, p)) {
                    Some(c) => c.2 += 1,
                    None => counts.push((e, p, 1)),
                }
            }
        }
    }
    counts.sort_unstable_by_key(|&(e, p, _)| (p, e));
    counts
}

#[cfg(test)]
mod tests {
    use femdem_mesh::Region;
    use femdem_mesh::generate::{BoxSpec, generate_box};

    use super::*;

    fn cube(min: [f64; 3], seed: u64) -> TetMesh {
        generate_box(&BoxSpec {
            min,
            max: [min[0] + 0.02, min[1] + 0.02, min[2] + 0.02],
            element_size: 0.01,
            jitter: 0.1,
            seed,
            region: Region { name: "rock".into(), breakable: true },
        })
        .expect("a box")
    }

    fn assembled(bodies: &[TetMesh]) -> (TetMesh, Vec<Range<usize>>) {
        let mut mesh = TetMesh::default();
        let mut parts = Vec::new();
        for b in bodies {
            let first = mesh.num_tets();
            mesh.append(b);
            parts.push(first..mesh.num_tets());
        }
        (mesh, parts)
    }

    /// A cube given twice coincides tet for tet; a copy moved by 10⁻¹² m,
    /// a cube jittered with another seed, and a cube beside it (sharing
    /// face positions but no tet) do not; with three parts, the third
    /// copy is counted against the first.
    #[test]
    fn an_exact_copy_of_a_part_is_found_and_nothing_else_is() {
        let a = cube([0.0; 3], 1);
        let n = a.num_tets();
        let (mesh, parts) = assembled(&[a.clone(), a.clone()]);
        assert_eq!(coinciding_parts(&mesh, &parts), vec![(0, 1, n)]);
        let mut moved = a.clone();
        moved.coords.iter_mut().for_each(|c| c[0] += 1e-12);
        let other = cube([0.0; 3], 2);
        let beside = cube([0.02, 0.0, 0.0], 1);
        for b in [moved, other, beside] {
            let (mesh, parts) = assembled(&[a.clone(), b]);
            assert_eq!(coinciding_parts(&mesh, &parts), vec![]);
        }
        let (mesh, parts) = assembled(&[a.clone(), cube([0.05, 0.0, 0.0], 1), a.clone()]);
        assert_eq!(coinciding_parts(&mesh, &parts), vec![(0, 2, n)]);
        let (mesh, parts) = assembled(&[a]);
        assert_eq!(coinciding_parts(&mesh, &parts), vec![]);
    }
}
