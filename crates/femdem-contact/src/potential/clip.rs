//! The polygons of Eq. 17's clipping in a face's coordinates, and the
//! tournament that cuts a face's part inside the other tet into the
//! sub-tets' regions (the derivation is in the parent module's
//! documentation, "In the face's own coordinates" and "Sub-tets by a
//! tournament").

use femdem_core::Real;

use crate::frame::Frame;

/// A convex polygon in a face's coordinates `μ` of at most 16 vertices (a
/// triangle clipped by the 4 planes of the other tet and then a sub-tet's 3
/// has at most 10; room is left for the duplicates that Sutherland–Hodgman
/// makes where a vertex lies on a plane, exactly at shared nodes or within
/// rounding), each with its barycentric
/// coordinates `λ` in the other tet.
#[derive(Clone, Copy)]
pub(super) struct Polygon {
    pub(super) mu: [[Real; 2]; 16],
    pub(super) lam: [[Real; 4]; 16],
    pub(super) n: usize,
}

impl Polygon {
    pub(super) const EMPTY: Polygon = Polygon { mu: [[0.0; 2]; 16], lam: [[0.0; 4]; 16], n: 0 };

    /// Writes into `out` the part of this polygon where the linear function
    /// `f` of the barycentric coordinates is ≥ 0 (Sutherland–Hodgman); a new
    /// vertex on an edge `a b` is `a + (b − a) t`, `t = f_a / (f_a − f_b)`,
    /// in `μ` and in `λ` alike. `out` is a buffer reused from clip to clip
    /// (its old vertices are overwritten, not cleared). Inlined into its
    /// caller, in the caller's frame (`frame.rs`): a call of its own per
    /// clip cost more than the wider unit gave.
    #[inline(always)]
    pub(super) fn clip_into(&self, out: &mut Polygon, f: impl Fn(&[Real; 4]) -> Real) {
        out.n = 0;
        let n = self.n.min(self.mu.len());
        if n == 0 {
            return;
        }
        let (mu, lam) = (&self.mu[..n], &self.lam[..n]);
        let mut fb = f(&lam[0]);
        for k in 0..n {
            let next = if k + 1 == n { 0 } else { k + 1 };
            let fa = fb;
            fb = f(&lam[next]);
            if fa >= 0.0 {
                out.push(mu[k], lam[k]);
            }
            if (fa >= 0.0) != (fb >= 0.0) {
                let t = fa / (fa - fb);
                let (ma, mb, la, lb) = (mu[k], mu[next], lam[k], lam[next]);
                let m = [ma[0] + (mb[0] - ma[0]) * t, ma[1] + (mb[1] - ma[1]) * t];
                let l = [0, 1, 2, 3].map(|j| la[j] + (lb[j] - la[j]) * t);
                out.push(m, l);
            }
        }
    }

    /// Area in `μ` (the real area divided by twice the face's; fan from
    /// the first vertex, as [`Moments::add`]).
    #[inline]
    pub(super) fn area(&self) -> Real {
        let m0 = self.mu[0];
        (1..self.n.saturating_sub(1)).map(|k| triangle_area(m0, self.mu[k], self.mu[k + 1])).sum()
    }

    #[inline]
    pub(super) fn push(&mut self, mu: [Real; 2], lam: [Real; 4]) {
        if self.n < self.mu.len() {
            self.mu[self.n] = mu;
            self.lam[self.n] = lam;
            self.n += 1;
        }
    }
}

/// The signed area in `μ` of the triangle `m0 m1 m2` (a fan's triangle).
#[inline]
fn triangle_area(m0: [Real; 2], m1: [Real; 2], m2: [Real; 2]) -> Real {
    0.5 * ((m1[0] - m0[0]) * (m2[1] - m0[1]) - (m1[1] - m0[1]) * (m2[0] - m0[0]))
}

/// The area (in `μ`) of a sub-tet's region of a face and its first
/// moments in `μ` and in `λ`, summed over the pieces the tournament cuts
/// it into.
#[derive(Clone, Copy)]
pub(super) struct Moments {
    pub(super) area: Real,
    pub(super) mu: [Real; 2],
    pub(super) lam: [Real; 4],
}

impl Moments {
    pub(super) const ZERO: Moments = Moments { area: 0.0, mu: [0.0; 2], lam: [0.0; 4] };

    /// Adds a polygon's area and moments (a fan from its first vertex).
    #[inline]
    pub(super) fn add(&mut self, poly: &Polygon) {
        let (m0, l0) = (poly.mu[0], poly.lam[0]);
        for k in 1..poly.n.saturating_sub(1) {
            let (m1, m2) = (poly.mu[k], poly.mu[k + 1]);
            let w = triangle_area(m0, m1, m2);
            self.area += w;
            let w3 = w / 3.0;
            for c in 0..2 {
                self.mu[c] += (m0[c] + m1[c] + m2[c]) * w3;
            }
            let (l1, l2) = (poly.lam[k], poly.lam[k + 1]);
            for c in 0..4 {
                self.lam[c] += (l0[c] + l1[c] + l2[c]) * w3;
            }
        }
    }

    /// The region's area, its centroid's `μ` and `λ`; `None` where the
    /// area is not positive.
    #[inline]
    pub(super) fn centroid(&self) -> Option<(Real, [Real; 2], [Real; 4])> {
        let a = self.area;
        (a > 0.0).then(|| (a, self.mu.map(|x| x / a), self.lam.map(|x| x / a)))
    }
}

/// Adds to `pieces[i]` the part of `poly` where `λ_i` is the least of the
/// coordinates, given that `λ_winner` is the least of those already
/// compared on all of `poly`: each challenger `c` splits the polygon into
/// where `λ_c − λ_w ≥ 0` (the winner stays) and where `λ_w − λ_c ≥ 0` (`c`
/// wins), a polygon wholly on one side passing on unsplit. `levels` are
/// the split halves' buffers, one pair per challenger. Each round runs
/// through `frame` (`frame.rs`).
#[inline(always)]
pub(super) fn tournament<F: Frame>(
    frame: F,
    poly: &Polygon,
    winner: usize,
    challengers: &[usize],
    levels: &mut [[Polygon; 2]],
    pieces: &mut [Moments; 4],
) {
    frame.call(
        #[inline(always)]
        |f| round(f, poly, winner, challengers, levels, pieces),
    )
}

/// A round of the [`tournament`], in `frame`'s work.
#[inline(always)]
fn round<F: Frame>(
    frame: F,
    poly: &Polygon,
    winner: usize,
    challengers: &[usize],
    levels: &mut [[Polygon; 2]],
    pieces: &mut [Moments; 4],
) {
    let (Some((&c, rest)), Some(([stays, wins], deeper))) = (challengers.split_first(), levels.split_first_mut())
    else {
        if poly.n >= 3 {
            pieces[winner].add(poly);
        }
        return;
    };
    let vertices = &poly.lam[..poly.n.min(poly.lam.len())];
    if vertices.iter().all(|l| l[c] - l[winner] >= 0.0) {
        return tournament(frame, poly, winner, rest, deeper, pieces);
    }
    if vertices.iter().all(|l| l[winner] - l[c] >= 0.0) {
        return tournament(frame, poly, c, rest, deeper, pieces);
    }
    poly.clip_into(stays, |l| l[c] - l[winner]);
    poly.clip_into(wins, |l| l[winner] - l[c]);
    tournament(frame, stays, winner, rest, deeper, pieces);
    tournament(frame, wins, c, rest, deeper, pieces);
}
