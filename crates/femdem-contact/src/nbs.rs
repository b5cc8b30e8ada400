//! NBS contact detection (Munjiza & Andrews 1998, "NBS contact detection
//! algorithm for bodies of similar size", IJNME 43).
//!
//! Each element is represented by its bounding sphere and mapped to the
//! cell of a uniform grid that holds its centre; the cell edge `d` is the
//! largest sphere diameter (plus twice the margin), so two spheres can only
//! overlap if their cells differ by at most one in each direction. Instead
//! of sorting or hashing, elements are threaded on singly linked lists:
//! per layer (`iz`), then, for the layer at hand and the one below, per row
//! (`iy`), then, for the row at hand and its neighbours already visited, per
//! cell (`ix`). Each element is then checked against its own cell and the 13
//! cells of a half neighbourhood (one of each mirror pair), so each pair is
//! found once. The head arrays have one entry per layer, row or column of
//! the grid and are reset by walking the lists, not by clearing: the cost is
//! `O(N + n_x + n_y + n_z)` in time and memory, with no `log N`.

use femdem_core::{Real, Vec3};

const NONE: u32 = u32::MAX;

/// Two distinct element indices in ascending order: [`Pair::a`] `<`
/// [`Pair::b`]. [`Nbs::detect`] reports its candidates as pairs.
///
/// The order is a guarantee of the type: the fields are private and the
/// only constructor, [`Pair::new`], sorts, so a pair names each unordered
/// couple of elements exactly once and can serve as a map key without
/// normalising. Pairs compare by `a`, then `b` (the order of the tuple
/// `(a, b)`), so sorting a list of pairs gives a canonical order whatever
/// order they were found in.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct Pair {
    a: u32,
    b: u32,
}

impl Pair {
    /// The pair of elements `i` and `j`, smaller index first; `None` when
    /// `i == j` (an element is never its own contact partner).
    #[inline]
    pub fn new(i: u32, j: u32) -> Option<Pair> {
        (i != j).then(|| Pair { a: i.min(j), b: i.max(j) })
    }

    /// The smaller index.
    #[inline]
    pub fn a(self) -> u32 {
        self.a
    }

    /// The larger index.
    #[inline]
    pub fn b(self) -> u32 {
        self.b
    }

    /// `(a, b)`, with `a < b`.
    #[inline]
    pub fn indices(self) -> (u32, u32) {
        (self.a, self.b)
    }
}

impl From<Pair> for (u32, u32) {
    fn from(p: Pair) -> (u32, u32) {
        p.indices()
    }
}

impl From<Pair> for [u32; 2] {
    fn from(p: Pair) -> [u32; 2] {
        [p.a, p.b]
    }
}

/// Reusable buffers of the NBS search (sized on first use, reused after).
#[derive(Clone, Debug, Default)]
pub struct Nbs {
    cell: Vec<[u32; 3]>,
    head_z: Vec<u32>,
    next_z: Vec<u32>,
    head_y: [Vec<u32>; 2],
    next_y: Vec<u32>,
    head_x: [Vec<u32>; 5],
    next_x: Vec<u32>,
    row_stamp: Vec<u32>,
}

impl Nbs {
    /// An empty searcher.
    pub fn new() -> Nbs {
        Nbs::default()
    }

    /// Finds every pair of spheres `i ≠ j` (centres `centers`, radii
    /// `radii`, indices into both) that overlap once each radius is grown by
    /// `margin`: `|c_i − c_j| ≤ r_i + r_j + 2 margin`. Each such pair is
    /// appended to `pairs` exactly once, as a [`Pair`] (smaller index
    /// first); `pairs` is not cleared. The order of the appended pairs is
    /// deterministic (a function of the input alone) but otherwise
    /// unspecified: sort them for a canonical order.
    ///
    /// # Panics
    /// If `centers` and `radii` differ in length, or a centre is not finite.
    pub fn detect(&mut self, centers: &[Vec3], radii: &[Real], margin: Real, pairs: &mut Vec<Pair>) {
        assert_eq!(centers.len(), radii.len(), "one radius per centre");
        let n = centers.len();
        if n < 2 {
            return;
        }
        let r_max = radii.iter().fold(0.0, |a: Real, &r| a.max(r)) + margin;
        let d = (2.0 * r_max).max(Real::MIN_POSITIVE);
        let mut lo = [Real::INFINITY; 3];
        let mut hi = [Real::NEG_INFINITY; 3];
        for c in centers {
            for k in 0..3 {
                assert!(c[k].is_finite(), "non-finite centre");
                lo[k] = lo[k].min(c[k]);
                hi[k] = hi[k].max(c[k]);
            }
        }
        let dims = [0, 1, 2].map(|k| (((hi[k] - lo[k]) / d).floor() as usize).saturating_add(1));
        let [nx, ny, nz] = dims;
        self.cell.clear();
        self.cell.extend(
            centers.iter().map(|c| [0, 1, 2].map(|k| (((c[k] - lo[k]) / d).floor() as usize).min(dims[k] - 1) as u32)),
        );
        reset(&mut self.head_z, nz);
        reset(&mut self.next_z, n);
        reset(&mut self.next_y, n);
        reset(&mut self.next_x, n);
        for h in &mut self.head_y {
            reset(h, ny);
        }
        for h in &mut self.head_x {
            reset(h, nx);
        }
        reset(&mut self.row_stamp, ny);
        // Layer lists, filled in reverse so each list runs in increasing index.
        for e in (0..n as u32).rev() {
            let iz = self.cell[e as usize][2] as usize;
            self.next_z[e as usize] = self.head_z[iz];
            self.head_z[iz] = e;
        }
        let mut stamp = 0u32;
        // Walk the occupied layers in the order of the first element of each
        // (deterministic), visiting each layer once.
        let mut layers: Vec<u32> = Vec::new();
        for e in 0..n {
            let iz = self.cell[e][2];
            if self.head_z[iz as usize] == e as u32 {
                layers.push(iz);
            }
        }
        for &iz in &layers {
            let iz = iz as usize;
            self.build_rows(0, iz);
            let below = iz > 0 && self.head_z[iz - 1] != NONE;
            if below {
                self.build_rows(1, iz - 1);
            }
            stamp = stamp.wrapping_add(1);
            let mut e = self.head_z[iz];
            while e != NONE {
                let iy = self.cell[e as usize][1] as usize;
                if self.row_stamp[iy] != stamp {
                    self.row_stamp[iy] = stamp;
                    self.search_row(iy, below, centers, radii, margin, pairs);
                }
                e = self.next_z[e as usize];
            }
            self.clear_rows(0, iz);
            if below {
                self.clear_rows(1, iz - 1);
            }
        }
    }

    /// Threads the elements of layer `iz` on the row lists of slot `slot`.
    fn build_rows(&mut self, slot: usize, iz: usize) {
        let mut e = self.head_z[iz];
        while e != NONE {
            let iy = self.cell[e as usize][1] as usize;
            self.next_y[e as usize] = self.head_y[slot][iy];
            self.head_y[slot][iy] = e;
            e = self.next_z[e as usize];
        }
    }

    fn clear_rows(&mut self, slot: usize, iz: usize) {
        let mut e = self.head_z[iz];
        while e != NONE {
            self.head_y[slot][self.cell[e as usize][1] as usize] = NONE;
            e = self.next_z[e as usize];
        }
    }

    /// Threads the elements of row `iy` of slot `slot` on the cell lists of
    /// `x_slot`.
    fn build_cells(&mut self, x_slot: usize, slot: usize, iy: usize) {
        let mut e = self.head_y[slot][iy];
        while e != NONE {
            let ix = self.cell[e as usize][0] as usize;
            self.next_x[e as usize] = self.head_x[x_slot][ix];
            self.head_x[x_slot][ix] = e;
            e = self.next_y[e as usize];
        }
    }

    fn clear_cells(&mut self, x_slot: usize, slot: usize, iy: usize) {
        let mut e = self.head_y[slot][iy];
        while e != NONE {
            self.head_x[x_slot][self.cell[e as usize][0] as usize] = NONE;
            e = self.next_y[e as usize];
        }
    }

    /// Finds the pairs of every element of row `iy` of the current layer.
    fn search_row(
        &mut self,
        iy: usize,
        below: bool,
        centers: &[Vec3],
        radii: &[Real],
        margin: Real,
        pairs: &mut Vec<Pair>,
    ) {
        let ny = self.head_y[0].len();
        // Row lists of the half neighbourhood: (layer, row) as (slot, iy).
        let mut rows: [Option<(usize, usize)>; 5] = [Some((0, iy)), None, None, None, None];
        if iy > 0 {
            rows[1] = Some((0, iy - 1));
        }
        if below {
            rows[2] = (iy > 0).then(|| (1, iy - 1));
            rows[3] = Some((1, iy));
            rows[4] = (iy + 1 < ny).then_some((1, iy + 1));
        }
        for (k, row) in rows.iter().enumerate() {
            if let Some((slot, y)) = *row {
                self.build_cells(k, slot, y);
            }
        }
        let nx = self.head_x[0].len();
        let mut e = self.head_y[0][iy];
        while e != NONE {
            let ix = self.cell[e as usize][0] as usize;
            let test = |j: u32, pairs: &mut Vec<Pair>| {
                let (a, b) = (&centers[e as usize], &centers[j as usize]);
                let reach = radii[e as usize] + radii[j as usize] + 2.0 * margin;
                let d2 = (a.x - b.x).powi(2) + (a.y - b.y).powi(2) + (a.z - b.z).powi(2);
                if d2 <= reach * reach {
                    // j ≠ e: j follows e in e's cell, or lies in another cell.
                    pairs.push(Pair { a: e.min(j), b: e.max(j) });
                }
            };
            // Own cell: the elements after e in its list.
            let mut j = self.next_x[e as usize];
            while j != NONE {
                test(j, pairs);
                j = self.next_x[j as usize];
            }
            // Same row: the cell on the left.
            if ix > 0 {
                let mut j = self.head_x[0][ix - 1];
                while j != NONE {
                    test(j, pairs);
                    j = self.next_x[j as usize];
                }
            }
            // The other rows: three cells each.
            for (k, row) in rows.iter().enumerate().skip(1) {
                if row.is_none() {
                    continue;
                }
                for x in ix.saturating_sub(1)..(ix + 2).min(nx) {
                    let mut j = self.head_x[k][x];
                    while j != NONE {
                        test(j, pairs);
                        j = self.next_x[j as usize];
                    }
                }
            }
            e = self.next_y[e as usize];
        }
        for (k, row) in rows.iter().enumerate() {
            if let Some((slot, y)) = *row {
                self.clear_cells(k, slot, y);
            }
        }
    }
}

fn reset(v: &mut Vec<u32>, n: usize) {
    v.clear();
    v.resize(n, NONE);
}
