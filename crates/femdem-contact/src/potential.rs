//! The penalty-function potential contact force between two tetrahedra
//! (Munjiza & Andrews 2000; Munjiza 2004, ch. 2; reference paper Eq. 17).
//!
//! Each tet carries a potential `φ` that is 1 at its centroid and 0 on its
//! surface: `φ(p) = 4 min_i λ_i(p)`, `λ_i` the barycentric coordinates. It
//! is linear on each of the four sub-tets formed by a face and the centroid
//! (on sub-tet `i`, `φ = 4 λ_i`). The contact force of Eq. 17,
//! `f = p ∫_{A∩B} (∇φ_A − ∇φ_B) dV` on B, is turned by the divergence
//! theorem into integrals over the parts of each tet's boundary that lie in
//! the other (`φ` vanishes on the rest):
//!
//! ```text
//! f_A = −p ∫_{∂A ∩ B} φ_B n_A dS  +  p ∫_{∂B ∩ A} φ_A n_B dS,     f_B = −f_A,
//! ```
//!
//! `n` the outward unit normals and `p` the penalty (Pa). Each face of one
//! tet is clipped against the four sub-tets of the other (Sutherland–Hodgman
//! against the sub-tet's four planes); on each piece `φ` is linear, so its
//! integral is the piece's area times `φ` at the piece's centroid `P`. The
//! piece's force acts at `P`: on the face's three nodes by `P`'s barycentric
//! coordinates in the face, and, opposite, on the other tet's four nodes by
//! `P`'s barycentric coordinates in that tet. Both act at the same point, so
//! linear and angular momentum are conserved exactly.
//!
//! The pair's *contact centre* ([`TetTetContact::centre`]) is the mean of
//! the pieces' centroids weighted by the magnitudes of their forces,
//! `c = Σ |F_k| P_k / Σ |F_k|`: where the normal force acts, for a solver
//! to apply friction there. Every `P_k` lies in both tets (on one's
//! boundary, inside the other), and so does `c`, a convex combination of
//! points of the convex set `A ∩ B`.

use femdem_core::tet::FACES;
use femdem_core::{Mat3, Real, Vec3};

/// A convex polygon of at most 10 vertices (a triangle clipped by 4 planes
/// has at most 7).
#[derive(Clone, Copy)]
struct Polygon {
    v: [Vec3; 10],
    n: usize,
}

impl Polygon {
    /// Keeps the part where the linear function `f` (given by its values at
    /// the vertices through `eval`) is ≥ 0.
    fn clip(&self, eval: impl Fn(&Vec3) -> Real) -> Polygon {
        let mut out = Polygon { v: [Vec3::zeros(); 10], n: 0 };
        if self.n == 0 {
            return out;
        }
        for k in 0..self.n {
            let a = self.v[k];
            let b = self.v[(k + 1) % self.n];
            let (fa, fb) = (eval(&a), eval(&b));
            if fa >= 0.0 {
                out.push(a);
            }
            if (fa >= 0.0) != (fb >= 0.0) {
                let t = fa / (fa - fb);
                out.push(a + (b - a) * t);
            }
        }
        out
    }

    fn push(&mut self, p: Vec3) {
        if self.n < self.v.len() {
            self.v[self.n] = p;
            self.n += 1;
        }
    }

    /// Area (projected on `normal`) and area centroid.
    fn area_centroid(&self, normal: &Vec3) -> (Real, Vec3) {
        let mut area = 0.0;
        let mut moment = Vec3::zeros();
        for k in 1..self.n.saturating_sub(1) {
            let (a, b, c) = (self.v[0], self.v[k], self.v[k + 1]);
            let w = 0.5 * (b - a).cross(&(c - a)).dot(normal);
            area += w;
            moment += (a + b + c) * (w / 3.0);
        }
        if area > 0.0 { (area, moment / area) } else { (0.0, Vec3::zeros()) }
    }
}

/// Barycentric coordinates of a tet as affine functions: `λ(p) = m (p − x0)`
/// for `λ1..λ3`, `λ0 = 1 − λ1 − λ2 − λ3`.
struct Barycentric {
    x0: Vec3,
    m: Mat3,
}

impl Barycentric {
    fn new(x: &[Vec3; 4]) -> Option<Barycentric> {
        let t = Mat3::from_columns(&[x[1] - x[0], x[2] - x[0], x[3] - x[0]]);
        t.try_inverse().map(|m| Barycentric { x0: x[0], m })
    }

    #[inline]
    fn at(&self, p: &Vec3) -> [Real; 4] {
        let l = self.m * (p - self.x0);
        [1.0 - l.x - l.y - l.z, l.x, l.y, l.z]
    }
}

/// Adds to `fa` (on the nodes of `a`) and `fb` (on the nodes of `b`) the
/// forces of `a`'s faces penetrating `b`'s potential, and to `centre` the
/// pieces' `Σ |F_k| P_k` and `Σ |F_k|`.
fn one_way(
    a: &[Vec3; 4],
    b: &[Vec3; 4],
    penalty: Real,
    fa: &mut [Vec3; 4],
    fb: &mut [Vec3; 4],
    centre: &mut (Vec3, Real),
) {
    let Some(bary) = Barycentric::new(b) else {
        return;
    };
    for face in FACES {
        let [p0, p1, p2] = face.map(|k| a[k]);
        let cross = (p1 - p0).cross(&(p2 - p0));
        let twice_area = cross.norm();
        if twice_area <= 0.0 {
            continue;
        }
        let n = cross / twice_area;
        let mut tri = Polygon { v: [Vec3::zeros(); 10], n: 0 };
        for p in [p0, p1, p2] {
            tri.push(p);
        }
        // Quick reject: the whole face on the outside of one of b's faces.
        let lam = [p0, p1, p2].map(|p| bary.at(&p));
        if (0..4).any(|i| lam.iter().all(|l| l[i] < 0.0)) {
            continue;
        }
        for i in 0..4 {
            // Sub-tet i: λ_i ≥ 0 and λ_j − λ_i ≥ 0 for j ≠ i.
            let mut poly = tri.clip(|p| bary.at(p)[i]);
            for j in (0..4).filter(|&j| j != i) {
                poly = poly.clip(|p| {
                    let l = bary.at(p);
                    l[j] - l[i]
                });
            }
            if poly.n < 3 {
                continue;
            }
            let (area, centroid) = poly.area_centroid(&n);
            if area <= 0.0 {
                continue;
            }
            let lb = bary.at(&centroid);
            let phi = 4.0 * lb[i].max(0.0);
            let magnitude = penalty * area * phi;
            let force = n * -magnitude;
            centre.0 += centroid * magnitude;
            centre.1 += magnitude;
            // On a's face nodes, by the centroid's coordinates in the face.
            let w1 = (centroid - p0).cross(&(p2 - p0)).dot(&cross) / (twice_area * twice_area);
            let w2 = (p1 - p0).cross(&(centroid - p0)).dot(&cross) / (twice_area * twice_area);
            let w = [1.0 - w1 - w2, w1, w2];
            for (k, &node) in face.iter().enumerate() {
                fa[node] += force * w[k];
            }
            for (k, f) in fb.iter_mut().enumerate() {
                *f -= force * lb[k];
            }
        }
    }
}

/// The contact between two tets: the forces on each one's nodes and the
/// point where they act.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TetTetContact {
    /// Forces on `a`'s four nodes, N.
    pub on_a: [Vec3; 4],
    /// Forces on `b`'s four nodes, N (their sum is minus that on `a`'s).
    pub on_b: [Vec3; 4],
    /// The contact centre `Σ |F_k| P_k / Σ |F_k|` over the clipped pieces
    /// (see the module documentation): a point of `A ∩ B`. `None` when no
    /// piece carries a force (then all the forces are zero).
    pub centre: Option<Vec3>,
}

/// The contact between tets `a` and `b` (node positions, positive
/// orientation) for penalty `penalty` (Pa): the forces on their nodes and
/// the contact centre. Zero forces and no centre when they do not overlap.
pub fn tet_tet_contact(a: &[Vec3; 4], b: &[Vec3; 4], penalty: Real) -> TetTetContact {
    let mut fa = [Vec3::zeros(); 4];
    let mut fb = [Vec3::zeros(); 4];
    let mut centre = (Vec3::zeros(), 0.0);
    one_way(a, b, penalty, &mut fa, &mut fb, &mut centre);
    one_way(b, a, penalty, &mut fb, &mut fa, &mut centre);
    let (moment, weight) = centre;
    TetTetContact { on_a: fa, on_b: fb, centre: (weight > 0.0).then(|| moment / weight) }
}

/// The contact forces between tets `a` and `b` (node positions, positive
/// orientation) for penalty `penalty` (Pa): returns the forces on `a`'s and
/// on `b`'s four nodes. Zero when they do not overlap.
pub fn tet_tet_forces(a: &[Vec3; 4], b: &[Vec3; 4], penalty: Real) -> ([Vec3; 4], [Vec3; 4]) {
    let c = tet_tet_contact(a, b, penalty);
    (c.on_a, c.on_b)
}
