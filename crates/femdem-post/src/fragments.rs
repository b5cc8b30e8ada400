//! The pieces a body has broken into: tets joined by a shared node (where
//! no joints were inserted) or by a joint that has not failed belong to
//! one fragment; pre-existing fracture faces and failed joints join
//! nothing. From the fragments, their size distribution as a sieve curve.
//!
//! The joint indices are those of `failures.csv` (column `joint`), which
//! index the jointed mesh the run was built from
//! (`femdem_case::prepare::prepare` rebuilds it from the case file).

use femdem_core::Vec3;
use femdem_core::tet::signed_volume;
use femdem_mesh::JointedMesh;

/// One connected piece.
#[derive(Debug, Clone, PartialEq)]
pub struct Fragment {
    /// Its tets, ascending.
    pub tets: Vec<u32>,
    /// Its volume in the reference configuration, m³.
    pub volume: f64,
}

impl Fragment {
    /// The diameter of the sphere of the same volume, `(6V/π)^(1/3)`, m.
    pub fn equivalent_diameter(&self) -> f64 {
        (6.0 * self.volume / std::f64::consts::PI).cbrt()
    }
}

/// Disjoint sets over tets, joined by union by size with path halving.
struct Sets {
    parent: Vec<u32>,
    size: Vec<u32>,
}

impl Sets {
    fn new(n: usize) -> Sets {
        Sets { parent: (0..n as u32).collect(), size: vec![1; n] }
    }

    fn root(&mut self, mut i: u32) -> u32 {
        while self.parent[i as usize] != i {
            let p = self.parent[i as usize];
            self.parent[i as usize] = self.parent[p as usize];
            i = self.parent[i as usize];
        }
        i
    }

    fn join(&mut self, a: u32, b: u32) {
        let (mut a, mut b) = (self.root(a), self.root(b));
        if a == b {
            return;
        }
        if self.size[a as usize] < self.size[b as usize] {
            std::mem::swap(&mut a, &mut b);
        }
        self.parent[b as usize] = a;
        self.size[a as usize] += self.size[b as usize];
    }
}

/// The fragments of `mesh` once the joints `failed` have failed (indices
/// into `mesh.joints`; repeats and order do not matter), optionally only
/// among the tets for which `keep` is true (e.g. one region: a platen is
/// not a fragment of the specimen). Sorted by volume, largest first (ties
/// by first tet).
///
/// # Errors
/// When a failed joint index is not a joint of `mesh` (results of another
/// mesh: another case, or the case run with other `--set` overrides).
pub fn fragments(
    mesh: &JointedMesh,
    failed: impl IntoIterator<Item = u32>,
    keep: impl Fn(u32) -> bool,
) -> anyhow::Result<Vec<Fragment>> {
    let m = &mesh.mesh;
    let mut sets = Sets::new(m.tets.len());
    // Tets sharing a node are one body (no joint between them).
    let mut first_at_node: Vec<u32> = vec![u32::MAX; m.coords.len()];
    for (t, tet) in m.tets.iter().enumerate() {
        for &n in tet {
            match first_at_node[n as usize] {
                u32::MAX => first_at_node[n as usize] = t as u32,
                other => sets.join(other, t as u32),
            }
        }
    }
    let mut broken = vec![false; mesh.joint_faces.len()];
    for j in failed {
        let n = broken.len();
        *broken.get_mut(j as usize).ok_or_else(|| {
            anyhow::anyhow!("failed joint {j} is not a joint of this mesh ({n} joints): results of another mesh?")
        })? = true;
    }
    for ((a, b), _) in mesh.joint_faces.iter().zip(&broken).filter(|(_, b)| !**b) {
        sets.join(a.tet, b.tet);
    }
    let mut by_root: std::collections::BTreeMap<u32, Fragment> = std::collections::BTreeMap::new();
    for t in (0..m.tets.len() as u32).filter(|&t| keep(t)) {
        let root = sets.root(t);
        let f = by_root.entry(root).or_insert_with(|| Fragment { tets: Vec::new(), volume: 0.0 });
        f.tets.push(t);
        f.volume += tet_volume(mesh, t);
    }
    let mut out: Vec<Fragment> = by_root.into_values().collect();
    out.sort_by(|a, b| b.volume.total_cmp(&a.volume).then(a.tets[0].cmp(&b.tets[0])));
    Ok(out)
}

/// The fragments of the breakable regions of `mesh` once the joints of
/// `failures` (a run's `failures.csv`, [`crate::failures::Failure::read_all`])
/// have failed: [`fragments`] without the unbreakable regions (platens,
/// supports), which are not pieces of the specimen.
///
/// # Errors
/// As [`fragments`].
pub fn breakable_fragments(mesh: &JointedMesh, failures: &[crate::failures::Failure]) -> anyhow::Result<Vec<Fragment>> {
    let m = &mesh.mesh;
    fragments(mesh, failures.iter().map(|f| f.joint), |t| m.regions[usize::from(m.tet_region[t as usize])].breakable)
}

/// The sieve curve of `fragments`: for each distinct equivalent diameter
/// `d` (ascending), the share of the total volume in fragments of
/// diameter ≤ `d` (the "passing" fraction of a grading curve).
pub fn passing(fragments: &[Fragment]) -> Vec<(f64, f64)> {
    let total: f64 = fragments.iter().map(|f| f.volume).sum();
    let mut d: Vec<(f64, f64)> = fragments.iter().map(|f| (f.equivalent_diameter(), f.volume)).collect();
    d.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut out: Vec<(f64, f64)> = Vec::with_capacity(d.len());
    let mut sum = 0.0;
    for (di, v) in d {
        sum += v;
        match out.last_mut() {
            Some(last) if last.0 == di => last.1 = sum / total,
            _ => out.push((di, sum / total)),
        }
    }
    out
}

/// A tet's reference volume, m³ (for callers that weigh tets themselves).
pub fn tet_volume(mesh: &JointedMesh, t: u32) -> f64 {
    let p: [Vec3; 4] = mesh.mesh.tet_points(t as usize);
    signed_volume(&p).abs()
}

#[cfg(test)]
mod tests {
    use super::*;
    use femdem_mesh::generate::{BoxSpec, generate_box};
    use femdem_mesh::{Region, insert_joints, insert_joints_within};

    fn cube(breakable: bool) -> femdem_mesh::TetMesh {
        generate_box(&BoxSpec {
            min: [0.0; 3],
            max: [1.0, 1.0, 1.0],
            element_size: 0.25,
            jitter: 0.1,
            seed: 3,
            region: Region { name: "rock".into(), breakable },
        })
        .unwrap()
    }

    #[test]
    fn an_intact_body_is_one_fragment_of_its_whole_volume() {
        for jointed in [insert_joints(&cube(true)).unwrap(), insert_joints(&cube(false)).unwrap()] {
            let f = fragments(&jointed, [], |_| true).unwrap();
            assert_eq!(f.len(), 1);
            assert_eq!(f[0].tets.len(), jointed.mesh.tets.len());
            assert!((f[0].volume - 1.0).abs() < 1e-12, "{}", f[0].volume);
            assert_eq!(passing(&f), vec![(f[0].equivalent_diameter(), 1.0)]);
        }
    }

    #[test]
    fn failing_every_joint_frees_every_tet_and_failing_a_plane_cuts_the_body_in_two() {
        let mesh = cube(true);
        let jointed = insert_joints(&mesh).unwrap();
        let n = jointed.joints.len() as u32;
        let all = fragments(&jointed, 0..n, |_| true).unwrap();
        assert_eq!(all.len(), jointed.mesh.tets.len());
        let total: f64 = all.iter().map(|f| f.volume).sum();
        assert!((total - 1.0).abs() < 1e-12);
        let curve = passing(&all);
        assert!((curve.last().unwrap().1 - 1.0).abs() < 1e-12);
        assert!(curve.windows(2).all(|w| w[0].0 < w[1].0 && w[0].1 < w[1].1), "ascending");

        // Fail the joints between a tet whose centroid lies below x = 0.5
        // and one whose centroid lies above: the body parts in two.
        let centroid_x = |t: u32| jointed.mesh.tet_points(t as usize).iter().map(|p| p.x).sum::<f64>() / 4.0;
        let cut: Vec<u32> = jointed
            .joint_faces
            .iter()
            .enumerate()
            .filter(|(_, (a, b))| (centroid_x(a.tet) < 0.5) != (centroid_x(b.tet) < 0.5))
            .map(|(j, _)| j as u32)
            .collect();
        let two = fragments(&jointed, cut.iter().copied(), |_| true).unwrap();
        assert_eq!(two.len(), 2, "{:?}", two.iter().map(|f| f.tets.len()).collect::<Vec<_>>());
        let below: f64 =
            (0..jointed.mesh.tets.len() as u32).filter(|&t| centroid_x(t) < 0.5).map(|t| tet_volume(&jointed, t)).sum();
        let small = two[1].volume;
        assert!((small - below.min(1.0 - below)).abs() < 1e-12, "{small} vs {below}");
        // Keeping only one side counts only its pieces.
        let left = fragments(&jointed, cut.iter().copied(), |t| centroid_x(t) < 0.5).unwrap();
        assert_eq!(left.len(), 1);
        assert!((left[0].volume - below).abs() < 1e-12);
    }

    #[test]
    fn tets_without_joints_stay_together_through_their_shared_nodes() {
        // Joints only in the lower half (x < 0.5): failing all of them frees
        // each lower tet, and the upper half stays one piece.
        let mesh = cube(true);
        let cx = |t: usize| mesh.tet_points(t).iter().map(|p| p.x).sum::<f64>() / 4.0;
        let zone: Vec<bool> = (0..mesh.tets.len()).map(|t| cx(t) < 0.5).collect();
        let jointed = insert_joints_within(&mesh, &zone).unwrap();
        let f = fragments(&jointed, 0..jointed.joints.len() as u32, |_| true).unwrap();
        let lower = zone.iter().filter(|z| **z).count();
        assert_eq!(f.len(), lower + 1, "every zoned tet alone, the rest one piece");
        assert_eq!(f[0].tets.len(), mesh.tets.len() - lower);
        let n = jointed.joints.len() as u32;
        let err = fragments(&jointed, [n], |_| true).unwrap_err().to_string();
        assert!(err.contains(&format!("failed joint {n} is not a joint of this mesh")), "{err}");
    }
}
