//! NBS finds exactly the pairs that a brute-force check of every pair finds
//! (Munjiza & Andrews 1998: the half-neighbourhood search over cells of the
//! largest diameter misses no overlapping pair and reports none twice), and
//! every pair it reports is a [`Pair`] with `a < b`.

use std::collections::BTreeSet;

use femdem_contact::{Nbs, Pair};
use femdem_core::Vec3;
use proptest::prelude::*;

fn brute(centers: &[Vec3], radii: &[f64], margin: f64) -> BTreeSet<Pair> {
    let mut out = BTreeSet::new();
    for i in 0..centers.len() {
        for j in i + 1..centers.len() {
            let d2: f64 = (0..3).map(|k| (centers[i][k] - centers[j][k]).powi(2)).sum();
            let reach = radii[i] + radii[j] + 2.0 * margin;
            if d2 <= reach * reach {
                out.insert(Pair::new(i as u32, j as u32).unwrap());
            }
        }
    }
    out
}

fn nbs(centers: &[Vec3], radii: &[f64], margin: f64) -> Vec<Pair> {
    let mut pairs = Vec::new();
    Nbs::new().detect(centers, radii, margin, &mut pairs);
    assert!(pairs.iter().all(|p| p.a() < p.b() && (p.b() as usize) < centers.len()));
    pairs
}

fn cloud() -> impl Strategy<Value = (Vec<Vec3>, Vec<f64>, f64)> {
    (1usize..300, 0.1f64..5.0, 0.0f64..0.2).prop_flat_map(|(n, extent, margin)| {
        (
            prop::collection::vec(prop::array::uniform3(-extent..extent).prop_map(Vec3::from), n),
            prop::collection::vec(0.01f64..0.3, n),
            Just(margin),
        )
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]

    #[test]
    fn nbs_finds_exactly_the_brute_force_pairs((centers, radii, margin) in cloud()) {
        let pairs = nbs(&centers, &radii, margin);
        let set: BTreeSet<Pair> = pairs.iter().copied().collect();
        prop_assert_eq!(set.len(), pairs.len(), "a pair was reported twice");
        prop_assert_eq!(set, brute(&centers, &radii, margin));
    }

    /// Clusters far apart (the grid spans many empty cells) and points on
    /// cell boundaries and on top of each other.
    #[test]
    fn sparse_and_degenerate_clouds(n in 2usize..100, gap in 10.0f64..1e4, snap in any::<bool>()) {
        let mut centers = Vec::new();
        for i in 0..n {
            let c = if i % 2 == 0 { 0.0 } else { gap };
            let v = (i as f64 * 0.37).fract();
            let v = if snap { (v * 4.0).round() * 0.25 } else { v };
            centers.push(Vec3::new(c + v, c - v, v));
        }
        let radii = vec![0.25; n];
        let pairs = nbs(&centers, &radii, 0.0);
        let set: BTreeSet<Pair> = pairs.iter().copied().collect();
        prop_assert_eq!(set.len(), pairs.len());
        prop_assert_eq!(set, brute(&centers, &radii, 0.0));
    }

    /// `Pair::new` puts the smaller index first, refuses an element paired
    /// with itself, and pairs order like the tuples `(a, b)`.
    #[test]
    fn a_pair_is_sorted_by_construction(i in 0u32..50, j in 0u32..50, k in 0u32..50, l in 0u32..50) {
        match Pair::new(i, j) {
            None => prop_assert_eq!(i, j),
            Some(p) => {
                prop_assert_eq!(p.indices(), (i.min(j), i.max(j)));
                prop_assert!(p.a() < p.b());
                prop_assert_eq!(Pair::new(j, i), Some(p));
                prop_assert_eq!(<[u32; 2]>::from(p), [p.a(), p.b()]);
                if let Some(q) = Pair::new(k, l) {
                    prop_assert_eq!(p.cmp(&q), p.indices().cmp(&q.indices()));
                }
            }
        }
    }
}

#[test]
fn the_same_searcher_can_be_reused() {
    let mut s = Nbs::new();
    let c1 = [Vec3::zeros(), Vec3::new(0.5, 0.0, 0.0), Vec3::new(5.0, 5.0, 5.0)];
    let mut p = Vec::new();
    s.detect(&c1, &[0.3; 3], 0.0, &mut p);
    assert_eq!(p, vec![Pair::new(0, 1).unwrap()]);
    let c2 = [Vec3::zeros(), Vec3::new(3.0, 0.0, 0.0)];
    p.clear();
    s.detect(&c2, &[0.3; 2], 0.0, &mut p);
    assert!(p.is_empty());
    s.detect(&c2, &[0.3; 2], 1.2, &mut p);
    assert_eq!(p, vec![Pair::new(0, 1).unwrap()]);
}
