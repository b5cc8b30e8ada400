//! Face adjacency: which tet faces are shared and which lie on the boundary.
//!
//! Every tet contributes four faces keyed by their sorted vertex triple; a
//! parallel sort brings equal keys together, so the cost is O(N log N) in
//! the number of tets with no hash map, and the result does not depend on
//! the thread count (keys and values are unique, so the order is total).

use rayon::prelude::*;

use crate::{FaceRef, MeshError, TetMesh};

/// The faces of a mesh, classified.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct FaceAdjacency {
    /// Faces shared by two tets, `(a, b)` with `a.tet < b.tet`; sorted by
    /// the faces' vertex keys.
    pub interior: Vec<(FaceRef, FaceRef)>,
    /// Faces owned by one tet only.
    pub boundary: Vec<FaceRef>,
}

/// Packs a sorted vertex triple into one sortable key.
#[inline]
pub fn face_key(mut v: [u32; 3]) -> u128 {
    v.sort_unstable();
    (u128::from(v[0]) << 64) | (u128::from(v[1]) << 32) | u128::from(v[2])
}

/// Unpacks [`face_key`].
#[inline]
pub fn key_nodes(k: u128) -> [u32; 3] {
    [(k >> 64) as u32, (k >> 32) as u32, k as u32]
}

/// All four faces of every tet as `(key, tet * 4 + local)`, sorted.
pub fn sorted_face_keys(mesh: &TetMesh) -> Vec<(u128, u32)> {
    let mut keys: Vec<(u128, u32)> = mesh
        .tets
        .par_iter()
        .enumerate()
        .flat_map_iter(|(t, _)| {
            (0..4u8).map(move |l| {
                let f = FaceRef { tet: t as u32, local: l };
                (face_key(f.nodes(&mesh.tets)), t as u32 * 4 + u32::from(l))
            })
        })
        .collect();
    keys.par_sort_unstable();
    keys
}

#[inline]
fn face_of(slot: u32) -> FaceRef {
    FaceRef { tet: slot / 4, local: (slot % 4) as u8 }
}

/// Classifies every face as interior (shared by two tets) or boundary.
///
/// # Errors
/// [`MeshError::NonManifoldFace`] when three or more tets share a face.
pub fn face_adjacency(mesh: &TetMesh) -> Result<FaceAdjacency, MeshError> {
    let keys = sorted_face_keys(mesh);
    let mut adj = FaceAdjacency::default();
    let mut i = 0;
    while i < keys.len() {
        let mut j = i + 1;
        while j < keys.len() && keys[j].0 == keys[i].0 {
            j += 1;
        }
        match j - i {
            1 => adj.boundary.push(face_of(keys[i].1)),
            2 => adj.interior.push((face_of(keys[i].1), face_of(keys[i + 1].1))),
            count => {
                return Err(MeshError::NonManifoldFace { nodes: key_nodes(keys[i].0), count });
            }
        }
        i = j;
    }
    Ok(adj)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Region;

    fn two_tets() -> TetMesh {
        TetMesh {
            coords: vec![[0., 0., 0.], [1., 0., 0.], [0., 1., 0.], [0., 0., 1.], [1., 1., 1.]],
            tets: vec![[0, 1, 2, 3], [1, 2, 3, 4]],
            tet_region: vec![0, 0],
            regions: vec![Region { name: "r".into(), breakable: true }],
            ..Default::default()
        }
    }

    #[test]
    fn two_tets_share_one_face() {
        let adj = face_adjacency(&two_tets()).unwrap();
        assert_eq!(adj.interior.len(), 1);
        assert_eq!(adj.boundary.len(), 6);
        let (a, b) = adj.interior[0];
        assert_eq!((a.tet, b.tet), (0, 1));
    }

    #[test]
    fn three_tets_on_one_face_is_an_error() {
        let mut m = two_tets();
        m.coords.push([-1., -1., -1.]);
        m.tets.push([1, 2, 3, 5]);
        m.tet_region.push(0);
        assert!(matches!(face_adjacency(&m), Err(MeshError::NonManifoldFace { count: 3, .. })));
    }
}
