//! The tets around each original vertex (the node groups G1–G6 of Eq. 15,
//! where "sharing a node" means having the same original vertex) and how a
//! fracture splits them.
//!
//! Around a vertex `v`, two of its tets are *linked* when they share a face
//! (which then contains `v`) that is still continuous: an active joint, or
//! shared nodes (an unjointed region). The *pieces* of `v` are the classes
//! of tets linked by chains of such faces. An intact vertex has one piece;
//! a crack through `v` splits its tets into two or more pieces (one on each
//! side); a crack that ends at `v` (a crack front) leaves one piece, the
//! tets on either side still being linked around the front.

use super::pair::PairSet;
use crate::model::Model;

/// The stars of the original vertices and their pieces.
#[derive(Clone, Debug)]
pub(crate) struct Stars {
    /// Tets of vertex `v`: `tets[offsets[v]..offsets[v + 1]]`, ascending.
    offsets: Vec<u32>,
    tets: Vec<u32>,
    /// The piece of each entry of `tets` within its star (the position, in
    /// the star, of the piece's first tet).
    piece: Vec<u32>,
}

impl Stars {
    /// The stars of `model`'s original vertices, each in one piece.
    pub(crate) fn new(model: &Model) -> Stars {
        let n_vertices = model.origin.iter().copied().max().map_or(0, |v| v as usize + 1);
        let mut offsets = vec![0u32; n_vertices + 1];
        for tet in &model.tets {
            for &n in tet {
                offsets[model.origin[n as usize] as usize + 1] += 1;
            }
        }
        for v in 0..n_vertices {
            offsets[v + 1] += offsets[v];
        }
        let mut fill = offsets.clone();
        let mut tets = vec![0u32; offsets[n_vertices] as usize];
        for (t, tet) in model.tets.iter().enumerate() {
            for &n in tet {
                let v = model.origin[n as usize] as usize;
                tets[fill[v] as usize] = t as u32;
                fill[v] += 1;
            }
        }
        let piece = vec![0; tets.len()];
        Stars { offsets, tets, piece }
    }

    fn range(&self, v: u32) -> std::ops::Range<usize> {
        self.offsets[v as usize] as usize..self.offsets[v as usize + 1] as usize
    }

    /// The tets around original vertex `v`, ascending.
    pub(crate) fn of(&self, v: u32) -> &[u32] {
        &self.tets[self.range(v)]
    }

    /// The piece of tet `t` around vertex `v` (`t` must contain `v`).
    pub(crate) fn piece(&self, v: u32, t: u32) -> u32 {
        let r = self.range(v);
        let k = self.tets[r.clone()].binary_search(&t).expect("the tet contains the vertex");
        self.piece[r.start + k]
    }

    /// The piece of every entry, for a snapshot.
    pub(crate) fn pieces(&self) -> &[u32] {
        &self.piece
    }

    /// Puts back the pieces of a snapshot (checked for length by the
    /// caller).
    pub(crate) fn set_pieces(&mut self, piece: Vec<u32>) {
        self.piece = piece;
    }

    /// Finds the pieces of vertex `v` again, `bonded` being the tet pairs
    /// (smaller first) still joined by an active joint.
    pub(crate) fn split(&mut self, model: &Model, v: u32, bonded: &PairSet) {
        let r = self.range(v);
        let star = &self.tets[r.clone()];
        let k = star.len();
        // Union–find over the star's positions, the root the smallest.
        let mut parent: Vec<usize> = (0..k).collect();
        fn root(parent: &mut [usize], mut i: usize) -> usize {
            while parent[i] != i {
                parent[i] = parent[parent[i]];
                i = parent[i];
            }
            i
        }
        for i in 0..k {
            let ti = model.tets[star[i] as usize];
            let oi = ti.map(|n| model.origin[n as usize]);
            for j in i + 1..k {
                let tj = model.tets[star[j] as usize];
                let common = tj.iter().filter(|&&n| oi.contains(&model.origin[n as usize])).count();
                if common < 3 {
                    continue;
                }
                let linked = bonded.contains(&(star[i], star[j])) || ti.iter().any(|n| tj.contains(n));
                if linked {
                    let (a, b) = (root(&mut parent, i), root(&mut parent, j));
                    parent[a.max(b)] = a.min(b);
                }
            }
        }
        for i in 0..k {
            self.piece[r.start + i] = root(&mut parent, i) as u32;
        }
    }
}
