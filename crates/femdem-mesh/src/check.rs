//! Mesh validity checks.

use femdem_core::tet::{edge_lengths, signed_volume};
use rayon::prelude::*;

use crate::{MeshError, TetMesh, face_adjacency};

/// A tet whose volume is at most this fraction of its longest edge cubed is
/// degenerate (a regular tet has `V = ℓ³ / (6√2) ≈ 0.118 ℓ³`).
pub const DEGENERATE_VOLUME_RATIO: f64 = 1e-9;

/// The bookkeeping part of [`check`], without geometry: array lengths
/// agree, region ids and node ids are in range, and there is a tet. Enough
/// for a mesh assembled from parts that [`check`] has passed one by one
/// (appending renumbers nodes and regions but changes no tet's shape or
/// neighbours).
///
/// # Errors
/// The [`MeshError`] that describes the first problem.
pub fn consistent(mesh: &TetMesh) -> Result<(), MeshError> {
    if mesh.tet_region.len() != mesh.tets.len() {
        return Err(MeshError::Inconsistent(format!(
            "{} tets but {} region ids",
            mesh.tets.len(),
            mesh.tet_region.len()
        )));
    }
    if let Some(t) = mesh.tet_region.iter().position(|&r| r as usize >= mesh.regions.len()) {
        return Err(MeshError::Inconsistent(format!(
            "tet {t} has region id {} but only {} regions exist",
            mesh.tet_region[t],
            mesh.regions.len()
        )));
    }
    if mesh.tets.is_empty() {
        return Err(MeshError::Inconsistent("the mesh has no tets: it meshes no volume".into()));
    }
    let n = mesh.coords.len();
    for (t, tet) in mesh.tets.iter().enumerate() {
        if let Some(&node) = tet.iter().find(|&&v| v as usize >= n) {
            return Err(MeshError::NodeOutOfRange { tet: t, node, num_nodes: n });
        }
    }
    Ok(())
}

/// Checks that the mesh can be simulated: array lengths agree, node and
/// region ids are in range, every tet has positive, non-degenerate volume,
/// every node is used by some tet, no face is shared by more than two
/// tets, and the two tets that share a face lie on its two sides. Returns
/// the first problem found (lowest tet index first, for each kind).
///
/// # Errors
/// The [`MeshError`] that describes the first problem.
pub fn check(mesh: &TetMesh) -> Result<(), MeshError> {
    consistent(mesh)?;
    let n = mesh.coords.len();
    let bad = mesh.tets.par_iter().enumerate().find_first(|(t, _)| {
        let p = mesh.tet_points(*t);
        let lmax = edge_lengths(&p).into_iter().fold(0.0, f64::max);
        // A volume that is not a number (coordinates so large that their
        // products overflow) is bad too.
        let volume = signed_volume(&p);
        volume.is_nan() || volume <= DEGENERATE_VOLUME_RATIO * lmax.powi(3)
    });
    if let Some((t, _)) = bad {
        let volume = signed_volume(&mesh.tet_points(t));
        let kind = if volume < 0.0 { "inverted" } else { "degenerate" };
        return Err(MeshError::BadTet { tet: t, kind, volume });
    }
    let mut used = vec![false; n];
    for tet in &mesh.tets {
        for &v in tet {
            used[v as usize] = true;
        }
    }
    let unused = used.iter().filter(|&&u| !u).count();
    if unused > 0 {
        let first = used.iter().position(|&u| !u).unwrap_or(0) as u32;
        return Err(MeshError::UnreferencedNodes { count: unused, first });
    }
    let adjacency = face_adjacency(mesh)?;
    match adjacency.interior.par_iter().find_first(|(a, b)| !opposite(a.nodes(&mesh.tets), b.nodes(&mesh.tets))) {
        Some((a, b)) => {
            let mut nodes = a.nodes(&mesh.tets);
            nodes.sort_unstable();
            Err(MeshError::TangledFace { a: a.tet as usize, b: b.tet as usize, nodes })
        }
        None => Ok(()),
    }
}

/// Whether two positive tets that share a face lie on its two sides: each
/// lists the face counter-clockwise seen from outside itself
/// ([`femdem_core::tet::FACES`]), so the two lists run in opposite cyclic
/// orders exactly when the tets are on opposite sides. Combinatorial: no
/// rounding, however flat the tets.
fn opposite(a: [u32; 3], b: [u32; 3]) -> bool {
    // Rotate each list to start at its smallest node; the orders are then
    // opposite when the other two nodes come in swapped order.
    let start = |f: [u32; 3]| {
        let i = (0..3).min_by_key(|&i| f[i]).unwrap_or(0);
        [f[i], f[(i + 1) % 3], f[(i + 2) % 3]]
    };
    let (a, b) = (start(a), start(b));
    a[0] == b[0] && a[1] == b[2] && a[2] == b[1]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Region;

    fn one_tet(d: [f64; 3]) -> TetMesh {
        TetMesh {
            coords: vec![[0., 0., 0.], [1., 0., 0.], [0., 1., 0.], d],
            tets: vec![[0, 1, 2, 3]],
            tet_region: vec![0],
            regions: vec![Region { name: "r".into(), breakable: true }],
            ..Default::default()
        }
    }

    #[test]
    fn positive_tet_passes() {
        assert_eq!(check(&one_tet([0., 0., 1.])), Ok(()));
    }

    #[test]
    fn inverted_tet_is_reported() {
        assert!(matches!(check(&one_tet([0., 0., -1.])), Err(MeshError::BadTet { tet: 0, kind: "inverted", .. })));
    }

    #[test]
    fn flat_tet_is_degenerate() {
        assert!(matches!(check(&one_tet([0.3, 0.3, 0.0])), Err(MeshError::BadTet { kind: "degenerate", .. })));
    }

    /// Two positive tets on opposite sides of face 1–2–3 pass; moving the
    /// second one's apex through that face puts both on one side. Its node
    /// order made positive again (as a reader reorients a tet), it is no
    /// longer inverted, but the pair overlaps: refused as tangled.
    #[test]
    fn tets_on_one_side_of_their_face_are_tangled() {
        let mut m = one_tet([0., 0., 1.]);
        m.coords.push([1., 1., 1.]);
        m.tets.push([1, 2, 3, 4]);
        m.tet_region.push(0);
        assert_eq!(check(&m), Ok(()));
        m.coords[4] = [0.1, 0.1, 0.1];
        assert!(matches!(check(&m), Err(MeshError::BadTet { tet: 1, kind: "inverted", .. })));
        m.tets[1] = [1, 3, 2, 4];
        assert_eq!(check(&m), Err(MeshError::TangledFace { a: 0, b: 1, nodes: [1, 2, 3] }));
        // The same tet written twice: its four faces each shared by two
        // tets on one side.
        let mut twice = one_tet([0., 0., 1.]);
        twice.tets.push([1, 2, 0, 3]);
        twice.tet_region.push(0);
        assert!(matches!(check(&twice), Err(MeshError::TangledFace { a: 0, b: 1, .. })));
    }

    #[test]
    fn unused_node_is_reported() {
        let mut m = one_tet([0., 0., 1.]);
        m.coords.push([5., 5., 5.]);
        assert_eq!(check(&m), Err(MeshError::UnreferencedNodes { count: 1, first: 4 }));
    }

    #[test]
    fn node_out_of_range_is_reported() {
        let mut m = one_tet([0., 0., 1.]);
        m.tets[0][3] = 9;
        assert!(matches!(check(&m), Err(MeshError::NodeOutOfRange { node: 9, .. })));
    }
}
