//! A tet–tet contact force that conserves energy: the exact gradient of the
//! energy of Eq. 17's potentials.
//!
//! Eq. 17 (`potential.rs`) takes the force between tets `A` and `B` from the
//! potentials `φ_A`, `φ_B` (1 at the centroid, 0 on the surface, linear on
//! each of the four sub-tets formed by a face and the centroid) and shares
//! each clipped piece's force among the nodes by the barycentric coordinates
//! of the piece's centroid. Its resultant is the gradient of
//!
//! ```text
//! W = p ∫_{A∩B} (φ_A + φ_B) dV
//! ```
//!
//! under a rigid translation of one tet (the divergence theorem turns
//! `∂W/∂u` into the two surface integrals of Eq. 17), but its nodal shares
//! are not `∂W/∂x` (they leave out how `φ_A` itself moves with `A`'s
//! nodes): the force field has a curl, and a closed cycle of contact gives
//! back more or less than it took (about 1% for a face landing flat,
//! `docs/fidelity.md`). Here the force on every node is `f = −∂W/∂x`
//! exactly, so the work of the contact forces over any path is `−ΔW`: a
//! contact that ends apart gives back what it took, up to the time
//! integration's own error. The resultant on each tet is Eq. 17's.
//!
//! **The derivation.** On sub-tet `S_i^A` (face `i` of `A` and the
//! centroid `c_A`), `φ_A = 4 λ_i^A` is the barycentric coordinate `μ_c` of
//! the apex `c_A` in `S_i^A`. So
//!
//! ```text
//! W = p [ Σ_i F(S_i^A, B) + Σ_j F(S_j^B, A) ],   F(T, U) = ∫_{T∩U} μ_c^T dV,
//! ```
//!
//! eight terms of one kind: a tet `T` with apex `c`, another tet `U`, and
//! the integral over their intersection of `T`'s apex coordinate. Moving a
//! vertex `t_k` of `T` moves `∂T` with velocity `μ_k^T` (Reynolds'
//! transport theorem) and changes `μ_c^T` at a fixed point by
//! `∂μ_c/∂t_k = −μ_k ∇μ_c` (differentiate `x = Σ_j μ_j t_j`); moving a
//! vertex `u_m` of `U` moves `∂U` with velocity `ν_m^U`. Hence
//!
//! ```text
//! ∂F/∂t_k = ∫_{∂T∩U} μ_c μ_k n_T dS − ∇μ_c ∫_{T∩U} μ_k dV,
//! ∂F/∂u_m = ∫_{∂U∩T} μ_c ν_m n_U dS,
//! ```
//!
//! `n` the outward unit normals. Their sum over the eight vertices is
//! `∫_{∂(T∩U)} μ_c n dS − ∫_{T∩U} ∇μ_c dV = 0` (divergence theorem): the
//! forces conserve linear momentum, and, `W` being invariant under
//! rotation, angular momentum. The apex `c_A` is the mean of `A`'s nodes,
//! so its gradient goes a quarter to each.
//!
//! **The integrals.** `∂T ∩ U` is each face of `T` clipped by `U`'s four
//! planes (`ν_m ≥ 0`), and `∂U ∩ T` each face of `U` clipped by `T`'s
//! (Sutherland–Hodgman; each polygon vertex carries its coordinates in
//! both tets, interpolated along the clipped edges). On a fan triangle of
//! area `a` the product of two affine functions `g h` integrates exactly to
//! `a/12 (Σ g_i h_i + Σ g_i Σ h_i)`. Over the polygons of `∂(T∩U)`, with
//! `d = n · x` constant on each, `V = ⅓ Σ d a` and `∫ x dV = ¼ Σ d a x̄`
//! (`x̄` the polygon's centroid; the divergence of `x ⊗ x` is `4x`); `μ_k`
//! is affine, so `∫ μ_k dV = V μ_k(x̄_V)` at the volume's centroid, and
//! `F = V μ_c(x̄_V)`, both computed as `V μ(o) + ∇μ · ∫ (x − o) dV` (no
//! division by a volume that may be rounding). Positions are taken
//! relative to a vertex `o` of `T`'s base (where `μ_c = 0`, so a shallow
//! overlap keeps its precision).
//!
//! The contact centre for friction is the centroid of `A ∩ B` (the union of
//! the `S_i^A ∩ B`), a point of both tets; where `A ∩ B` is thinner than
//! 10⁻⁹ of the smaller tet, the centroid of its boundary.

use femdem_core::tet::FACES;
use femdem_core::{Real, Vec3};

use crate::potential::{Barycentric, TetTetContact};

/// The contact between two tets by the exact gradient of the potentials'
/// energy: the forces on each one's nodes, the energy, and the centre.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GradientContact {
    /// The forces (`−∂W/∂x` on each node) and the contact centre (the
    /// centroid of `A ∩ B`; `None` when they do not overlap).
    pub contact: TetTetContact,
    /// `W = p ∫_{A∩B} (φ_A + φ_B) dV`, J.
    pub energy: Real,
    /// The volume of `A ∩ B`, m³ (to rounding: faces that touch give a
    /// volume of the order of `ε L³`, `L` the tets' size).
    pub volume: Real,
}

/// A polygon vertex: its position (relative to the common origin) and its
/// barycentric coordinates in `T` and in `U`.
#[derive(Clone, Copy, Default)]
struct Vertex {
    x: Vec3,
    t: [Real; 4],
    u: [Real; 4],
}

/// A convex polygon of at most 10 vertices (a triangle clipped by four
/// planes has at most 7).
#[derive(Clone, Copy)]
struct Polygon {
    v: [Vertex; 10],
    n: usize,
}

impl Polygon {
    fn triangle(v: [Vertex; 3]) -> Polygon {
        let mut p = Polygon { v: [Vertex::default(); 10], n: 3 };
        p.v[..3].copy_from_slice(&v);
        p
    }

    /// The part where `f ≥ 0` (Sutherland–Hodgman).
    fn clip(&self, f: impl Fn(&Vertex) -> Real) -> Polygon {
        let mut out = Polygon { v: [Vertex::default(); 10], n: 0 };
        let mut push = |v: Vertex| {
            // A triangle clipped by four planes has at most 7 vertices.
            debug_assert!(out.n < out.v.len(), "a clipped polygon of more than 10 vertices");
            if out.n < out.v.len() {
                out.v[out.n] = v;
                out.n += 1;
            }
        };
        let n = self.n;
        for k in 0..n {
            let (a, b) = (self.v[k], self.v[(k + 1) % n]);
            let (fa, fb) = (f(&a), f(&b));
            if fa >= 0.0 {
                push(a);
            }
            if (fa >= 0.0) != (fb >= 0.0) {
                let s = fa / (fa - fb);
                push(Vertex {
                    x: a.x + (b.x - a.x) * s,
                    t: [0, 1, 2, 3].map(|j| a.t[j] + (b.t[j] - a.t[j]) * s),
                    u: [0, 1, 2, 3].map(|j| a.u[j] + (b.u[j] - a.u[j]) * s),
                });
            }
        }
        out
    }
}

/// What one term `F(T, U)` adds up: its gradients, and the volume and
/// first moment of `T ∩ U`.
#[derive(Clone, Copy, Default)]
struct Term {
    value: Real,
    d_t: [Vec3; 4],
    d_u: [Vec3; 4],
    volume: Real,
    moment: Vec3,
    /// The area and first moment of `∂(T∩U)`, for a centre where the
    /// volume is too thin to give one.
    area: Real,
    surface_moment: Vec3,
}

/// The outward unit normal of face `f` (opposite vertex `f`) of `p`, and
/// the face's vertices in the order of `FACES[f]`.
fn outward(p: &[Vec3; 4], f: usize) -> Vec3 {
    let [i, j, k] = FACES[f];
    let n = (p[j] - p[i]).cross(&(p[k] - p[i]));
    let n = if n.dot(&(p[f] - p[i])) > 0.0 { -n } else { n };
    let len = n.norm();
    if len > 0.0 { n / len } else { n }
}

/// `∫ g h` over a polygon of `∂(T∩U)` for the affine `g = μ_c^T` (apex
/// `c`) and each `h` of `T`'s or `U`'s coordinates, with its area and
/// first moment.
struct Integrals {
    /// `∫ μ_c h_k dS` for `h` the coordinates of the polygon's own tet.
    products: [Real; 4],
    area: Real,
    moment: Vec3,
}

fn integrate(poly: &Polygon, n: &Vec3, apex: usize, own: impl Fn(&Vertex) -> [Real; 4]) -> Integrals {
    let mut out = Integrals { products: [0.0; 4], area: 0.0, moment: Vec3::zeros() };
    if poly.n < 3 {
        return out;
    }
    let v0 = poly.v[0];
    for k in 1..poly.n - 1 {
        let (v1, v2) = (poly.v[k], poly.v[k + 1]);
        // Signed along `n`: the fan triangles of a convex polygon share one
        // orientation, and a sliver of rounding keeps its sign (the sum
        // is made positive below).
        let a = 0.5 * n.dot(&(v1.x - v0.x).cross(&(v2.x - v0.x)));
        out.area += a;
        out.moment += (v0.x + v1.x + v2.x) * (a / 3.0);
        let g = [v0.t[apex], v1.t[apex], v2.t[apex]];
        let (h0, h1, h2) = (own(&v0), own(&v1), own(&v2));
        let gs = g[0] + g[1] + g[2];
        for m in 0..4 {
            let h = [h0[m], h1[m], h2[m]];
            out.products[m] += a / 12.0 * (g[0] * h[0] + g[1] * h[1] + g[2] * h[2] + gs * (h[0] + h[1] + h[2]));
        }
    }
    if out.area < 0.0 {
        out.area = -out.area;
        out.moment = -out.moment;
        out.products = out.products.map(|x| -x);
    }
    out
}

/// `F(T, U) = ∫_{T∩U} μ_c^T dV` and its gradients (see the module
/// documentation), positions relative to the common origin.
fn term(t: &[Vec3; 4], apex: usize, u: &[Vec3; 4]) -> Option<Term> {
    // Positions relative to a vertex of T's base (`μ_c = 0` there): the
    // apex coordinate of the centroid of a shallow overlap is small, and
    // relative to a far origin it would be lost to the rounding of the
    // first moment.
    let base = t[if apex == 0 { 1 } else { 0 }];
    let t = &t.map(|p| p - base);
    let u = &u.map(|p| p - base);
    let (bt, bu) = (Barycentric::new(t)?, Barycentric::new(u)?);
    let in_u = t.map(|p| bu.at(&p));
    let in_t = u.map(|p| bt.at(&p));
    // Empty when one tet lies outside a face plane of the other.
    if (0..4).any(|j| in_u.iter().all(|l| l[j] < 0.0)) || (0..4).any(|j| in_t.iter().all(|l| l[j] < 0.0)) {
        return None;
    }
    let unit = |k: usize| {
        let mut e = [0.0; 4];
        e[k] = 1.0;
        e
    };
    // Faces in one plane: `coplanar[f][g]` when face `f` of U lies in the
    // plane of face `g` of T, to rounding. Neither is clipped by the
    // other's plane (the sign of a coordinate that is zero but for rounding
    // would decide what is kept), and each copy counts half: `W` has a
    // kink there, and half of each one-sided derivative is their mean.
    // With outward normals alike the piece is one piece of `∂(T∩U)` found
    // twice; with opposite normals the tets touch there (a zero-volume
    // `T∩U` whose surface terms still count where `μ_c ≠ 0`: a face of U in
    // an inner plane of A, through its centroid), and the two copies
    // cancel in the volume.
    let tol = 64.0 * bt.rounding(u);
    let normals_t = [0, 1, 2, 3].map(|g| outward(t, g));
    let normals_u = [0, 1, 2, 3].map(|f| outward(u, f));
    let mut coplanar = [[false; 4]; 4];
    let (mut half_t, mut half_u) = ([false; 4], [false; 4]);
    for f in 0..4 {
        for g in 0..4 {
            if FACES[f].iter().all(|&k| in_t[k][g].abs() <= tol) {
                coplanar[f][g] = true;
                half_t[g] = true;
                half_u[f] = true;
            }
        }
    }
    let mut out = Term::default();
    let mut d_v = 0.0;
    // T's faces inside U, then U's faces inside T.
    for own_is_t in [true, false] {
        let (p, coords, normals, half) =
            if own_is_t { (t, &in_u, &normals_t, &half_t) } else { (u, &in_t, &normals_u, &half_u) };
        for f in 0..4 {
            let n = normals[f];
            let corners = FACES[f].map(|k| {
                if own_is_t {
                    Vertex { x: p[k], t: unit(k), u: coords[k] }
                } else {
                    Vertex { x: p[k], t: coords[k], u: unit(k) }
                }
            });
            let mut poly = Polygon::triangle(corners);
            // The other tet's planes, but one this face lies in.
            let planes = (0..4).filter(|&j| if own_is_t { !coplanar[j][f] } else { !coplanar[f][j] });
            for j in planes {
                poly = if own_is_t { poly.clip(|v| v.u[j]) } else { poly.clip(|v| v.t[j]) };
                if poly.n < 3 {
                    break;
                }
            }
            if poly.n < 3 {
                continue;
            }
            let own = |v: &Vertex| if own_is_t { v.t } else { v.u };
            let i = integrate(&poly, &n, apex, own);
            let w = if half[f] { 0.5 } else { 1.0 };
            let d = n.dot(&poly.v[0].x);
            d_v += w * d * i.area;
            out.moment += i.moment * (0.25 * d * w);
            out.area += w * i.area;
            out.surface_moment += i.moment * w;
            let grad = if own_is_t { &mut out.d_t } else { &mut out.d_u };
            for (g, &s) in grad.iter_mut().zip(&i.products) {
                *g += n * (w * s);
            }
        }
    }
    out.volume = d_v / 3.0;
    // `∫ μ_k dV = V μ_k(0) + ∇μ_k · ∫ x dV` (μ affine; the origin is T's
    // base vertex): no division by a volume that may be rounding.
    let rows = [0, 1, 2].map(|r| bt.m.row(r).transpose());
    let grads = [-(rows[0] + rows[1] + rows[2]), rows[0], rows[1], rows[2]];
    let at_origin = bt.at(&Vec3::zeros());
    let (volume, moment) = (out.volume, out.moment);
    let moments = [0, 1, 2, 3].map(|k| volume * at_origin[k] + grads[k].dot(&moment));
    out.value = moments[apex];
    for (g, m) in out.d_t.iter_mut().zip(moments) {
        *g -= grads[apex] * m;
    }
    // The first moments about the caller's origin.
    out.moment += base * out.volume;
    out.surface_moment += base * out.area;
    Some(out)
}

/// The contact between tets `a` and `b` (node positions, either
/// orientation) for penalty `penalty` (Pa) by the exact gradient of
/// `W = p ∫_{A∩B} (φ_A + φ_B) dV` (see the module documentation). Zero
/// forces, zero energy and no centre when they do not overlap.
pub fn tet_tet_gradient(a: &[Vec3; 4], b: &[Vec3; 4], penalty: Real) -> GradientContact {
    let nothing = GradientContact {
        contact: TetTetContact { on_a: [Vec3::zeros(); 4], on_b: [Vec3::zeros(); 4], centre: None },
        energy: 0.0,
        volume: 0.0,
    };
    if !a.iter().chain(b).all(|p| p.iter().all(|c| c.is_finite())) {
        return nothing;
    }
    let origin = (a[0] + a[1] + a[2] + a[3]) * 0.25;
    let a = a.map(|p| p - origin);
    let b = b.map(|p| p - origin);
    let mut on_a = [Vec3::zeros(); 4];
    let mut on_b = [Vec3::zeros(); 4];
    let (energy_a, sum) = side(&a, &b, penalty, &mut on_a, &mut on_b);
    let (energy_b, _) = side(&b, &a, penalty, &mut on_b, &mut on_a);
    let volume = sum.volume;
    if energy_a + energy_b == 0.0 && [on_a, on_b].iter().flatten().all(|f| *f == Vec3::zeros()) {
        return nothing;
    }
    // The centroid of `A ∩ B`; below 10⁻⁹ of the smaller tet that is a
    // quotient of rounding (faces touching, a speck at a vertex), and the
    // centroid of the overlap's boundary serves (a point of its closure,
    // so of both tets).
    let least = femdem_core::tet::signed_volume(&a).abs().min(femdem_core::tet::signed_volume(&b).abs());
    let centre = if volume > 1e-9 * least {
        Some(origin + sum.moment / volume)
    } else {
        (sum.area > 0.0).then(|| origin + sum.surface_moment / sum.area)
    };
    GradientContact { contact: TetTetContact { on_a, on_b, centre }, energy: penalty * (energy_a + energy_b), volume }
}

/// Adds `−p ∂/∂x Σ_i F(S_i^first, second)` to the forces and returns
/// `Σ_i F`, and the volume and first moment of `first ∩ second` (the union
/// of the `S_i ∩ second`) with the area and first moment of the
/// boundaries of the `S_i ∩ second`.
fn side(
    first: &[Vec3; 4],
    second: &[Vec3; 4],
    penalty: Real,
    f_first: &mut [Vec3; 4],
    f_second: &mut [Vec3; 4],
) -> (Real, Term) {
    let centre = (first[0] + first[1] + first[2] + first[3]) * 0.25;
    let mut value = 0.0;
    let mut sum = Term::default();
    for face in &FACES {
        let sub = [first[face[0]], first[face[1]], first[face[2]], centre];
        let Some(tm) = term(&sub, 3, second) else {
            continue;
        };
        value += tm.value;
        sum.volume += tm.volume;
        sum.moment += tm.moment;
        sum.area += tm.area;
        sum.surface_moment += tm.surface_moment;
        for (k, &node) in face.iter().enumerate() {
            f_first[node] -= tm.d_t[k] * penalty;
        }
        for f in f_first.iter_mut() {
            *f -= tm.d_t[3] * (0.25 * penalty);
        }
        for (f, d) in f_second.iter_mut().zip(&tm.d_u) {
            *f -= d * penalty;
        }
    }
    (value, sum)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::potential::tet_tet_forces;
    use crate::test_pairs::{face_pair, tet};
    use proptest::prelude::*;

    fn regular() -> [Vec3; 4] {
        [Vec3::new(0.0, 0.0, 0.0), Vec3::new(1.0, 0.0, 0.0), Vec3::new(0.0, 1.0, 0.0), Vec3::new(0.0, 0.0, 1.0)]
    }

    fn forces(c: &GradientContact) -> [Vec3; 8] {
        let [a0, a1, a2, a3] = c.contact.on_a;
        let [b0, b1, b2, b3] = c.contact.on_b;
        [a0, a1, a2, a3, b0, b1, b2, b3]
    }

    /// The largest nodal force and the scale `p L²` of a pair.
    fn scale(a: &[Vec3; 4], b: &[Vec3; 4], p: Real) -> Real {
        let l = a.iter().chain(b).flat_map(|x| a.iter().chain(b).map(move |y| (x - y).norm())).fold(0.0, Real::max);
        p * l * l
    }

    /// Every nodal force is minus the derivative of the energy, by central
    /// differences with step `h = 10⁻⁶ L`. `W` is C¹ (its gradient is
    /// continuous where the clipped polygons change shape) and piecewise
    /// smooth, so the difference is off by `O(h²)` from the smooth pieces,
    /// `O(h)` only across a kink: `10⁻⁵ p L²` allows it; a force that
    /// missed a term (the interior `−∇μ_c ∫ μ_k dV`, a quarter of the apex)
    /// is off by a fraction of `p L²` on random deep pairs.
    /// Flat tets are left out: their coordinates, and so `W`, are not
    /// differentiable (a node moved by `h` makes a tet of a flat one).
    fn check_gradient(a: [Vec3; 4], b: [Vec3; 4]) -> Result<(), TestCaseError> {
        let p = 1.0;
        let c = tet_tet_gradient(&a, &b, p);
        // Apart, everything is zero and there is nothing to check.
        prop_assume!(c.contact.centre.is_some());
        let f = forces(&c);
        let s = scale(&a, &b, p);
        let l = (s / p).sqrt();
        for t in [&a, &b] {
            let edge = t.iter().flat_map(|x| t.iter().map(move |y| (x - y).norm())).fold(0.0, Real::max);
            prop_assume!(femdem_core::tet::signed_volume(t).abs() >= 1e-3 * edge * edge * edge);
        }
        let h = 1e-6 * l;
        for node in 0..8 {
            for axis in 0..3 {
                let energy = |d: Real| {
                    let (mut a, mut b) = (a, b);
                    let x = if node < 4 { &mut a[node] } else { &mut b[node - 4] };
                    x[axis] += d;
                    tet_tet_gradient(&a, &b, p).energy
                };
                let fd = -(energy(h) - energy(-h)) / (2.0 * h);
                prop_assert!(
                    (fd - f[node][axis]).abs() <= 1e-5 * s,
                    "node {node} axis {axis}: force {:e} vs −dW/dx {fd:e} (p L² {s:e})",
                    f[node][axis]
                );
            }
        }
        Ok(())
    }

    proptest! {
        // Pairs apart and flat tets are skipped (`check_gradient`).
        #![proptest_config(ProptestConfig { max_global_rejects: 100_000, ..ProptestConfig::with_cases(200) })]

        #[test]
        fn forces_are_minus_the_gradient_of_the_energy(a in tet(1.0), b in tet(1.0)) {
            check_gradient(a, b)?;
        }

        #[test]
        fn face_to_face_forces_are_minus_the_gradient_of_the_energy(pair in face_pair()) {
            // Moved back to the origin: the difference step must not vanish
            // against the coordinates (the pairs far from it test the other
            // properties).
            let (a, b) = pair;
            let o = a[0];
            check_gradient(a.map(|x| x - o), b.map(|x| x - o))?;
        }

        /// The resultant on each tet is Eq. 17's (`potential.rs`): both are
        /// the derivative of `W` under a rigid translation. Momentum is
        /// conserved (`Σ f = 0`, `Σ x × f = 0`) and the centre lies in both
        /// tets. To the rounding of the clippings, `10⁻¹⁰ p L²`.
        #[test]
        fn the_resultant_is_eq_17s_and_momentum_is_conserved(a in tet(1.0), b in tet(1.0)) {
            check_resultant(a, b)?;
        }

        /// The same for face-to-face pairs (shallow, shared nodes, slid),
        /// moved back to the origin.
        #[test]
        fn face_to_face_resultant_is_eq_17s(pair in face_pair()) {
            let (a, b) = pair;
            let o = a[0];
            check_resultant(a.map(|x| x - o), b.map(|x| x - o))?;
        }
    }

    fn check_resultant(a: [Vec3; 4], b: [Vec3; 4]) -> Result<(), TestCaseError> {
        {
            let p = 3.0e9;
            let c = tet_tet_gradient(&a, &b, p);
            let s = scale(&a, &b, p);
            let (eq17_a, eq17_b) = tet_tet_forces(&a, &b, p);
            let on_b: Vec3 = c.contact.on_b.iter().sum();
            let on_a: Vec3 = c.contact.on_a.iter().sum();
            let want_b: Vec3 = eq17_b.iter().sum();
            let want_a: Vec3 = eq17_a.iter().sum();
            prop_assert!((on_b - want_b).norm() <= 1e-10 * s, "{on_b} vs Eq. 17 {want_b}");
            prop_assert!((on_a - want_a).norm() <= 1e-10 * s, "{on_a} vs Eq. 17 {want_a}");
            prop_assert!((on_a + on_b).norm() <= 1e-10 * s);
            let l = (s / p).sqrt();
            let torque: Vec3 =
                a.iter().zip(&c.contact.on_a).chain(b.iter().zip(&c.contact.on_b)).map(|(x, f)| x.cross(f)).sum();
            prop_assert!(torque.norm() <= 1e-10 * s * l, "torque {torque}");
            prop_assert!(c.energy >= -1e-12 * s * l, "energy {:e}", c.energy);
            if let Some(centre) = c.contact.centre {
                // The centroid of a sliver is the first moment over the
                // volume, both sums of boundary terms of size `L⁴`: its
                // rounding grows as `ε L⁴ / V` (measured: 5e-5 outside for
                // a wedge of 6e-9 of the tet).
                let least = femdem_core::tet::signed_volume(&a).abs().min(femdem_core::tet::signed_volume(&b).abs());
                let tolerance = 1e-12 * (least / c.volume).max(1.0);
                for t in [&a, &b] {
                    let bary = Barycentric::new(t).unwrap();
                    prop_assert!(
                        bary.at(&centre).iter().all(|&x| x >= -tolerance),
                        "centre outside a tet: {:?}",
                        bary.at(&centre)
                    );
                }
            } else {
                // No overlap, or less than 10⁻⁹ of a tet (faces touching, or
                // pressed by ~10⁻⁹ of their size): forces of that order.
                prop_assert!(c.energy <= 1e-10 * s * l, "energy {:e} without overlap", c.energy);
                prop_assert!(forces(&c).iter().all(|f| f.norm() <= 1e-8 * s), "forces without overlap");
            }
        }
        Ok(())
    }

    /// Tet `b` is `a` mirrored through its face `z = 0`, then pushed `δ`
    /// into `a`: the overlap is a slab of thickness `δ` over the face, where
    /// both potentials rise linearly from 0, so `W` grows as `δ²` for a
    /// shallow overlap (the force is continuous at touching and the
    /// stiffness finite, as the time step needs), and is 0 with the faces
    /// just touching. The slab narrows with its thickness, so the ratio is
    /// 4 up to `O(δ)`.
    #[test]
    fn a_shallow_face_overlap_costs_energy_quadratic_in_its_depth() {
        let a = regular();
        let b = a.map(|x| Vec3::new(x.x, x.y, -x.z));
        let b = [b[0], b[2], b[1], b[3]];
        assert_eq!(tet_tet_gradient(&a, &b, 1.0).energy, 0.0);
        // (Exactly 0 when touching: `z = 0` is exactly representable, and
        // every coordinate of the touching face is exactly 0.)
        let at = |d: Real| tet_tet_gradient(&a, &b.map(|x| x + Vec3::new(0.0, 0.0, d)), 1.0).energy;
        // Measured: 4 − 1.4e-3 at δ = 10⁻⁴, 4 − 1.4e-5 at δ = 10⁻⁶.
        for delta in [1e-4, 1e-6] {
            let (w1, w2) = (at(delta), at(2.0 * delta));
            assert!(w1 > 0.0);
            assert!((w2 / w1 - 4.0).abs() < 20.0 * delta, "δ {delta}: W(2δ)/W(δ) = {}", w2 / w1);
        }
    }

    /// A face of `b` in an inner plane of `a` (through `a`'s centroid and
    /// its edge 0–1: `y = z`), `b` on the side `y > z`: `W` has a kink
    /// there, and the coplanar copies, half each, give the mean of the
    /// one-sided derivatives, which central differences measure. (Counted
    /// whole, the copy on the far side of the plane, a zero-volume
    /// overlap, made `b`'s forces 1.5 or 0.5 times the right ones.)
    #[test]
    fn a_face_in_an_inner_plane_gets_the_mean_of_the_one_sided_derivatives() {
        let a = regular();
        let b =
            [Vec3::new(0.1, 0.3, 0.3), Vec3::new(0.5, 0.2, 0.2), Vec3::new(0.2, 0.05, 0.05), Vec3::new(0.2, 0.5, 0.0)];
        let c = tet_tet_gradient(&a, &b, 1.0);
        assert!(c.volume > 0.0);
        let f = forces(&c);
        let h = 1e-6;
        for node in 0..8 {
            for axis in 0..3 {
                let energy = |d: Real| {
                    let (mut a, mut b) = (a, b);
                    let x = if node < 4 { &mut a[node] } else { &mut b[node - 4] };
                    x[axis] += d;
                    tet_tet_gradient(&a, &b, 1.0).energy
                };
                let fd = -(energy(h) - energy(-h)) / (2.0 * h);
                assert!((fd - f[node][axis]).abs() <= 1e-6, "node {node} axis {axis}: {:e} vs {fd:e}", f[node][axis]);
            }
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(100))]

        /// The same pair 10³ sizes from the origin: the forces and the
        /// energy are those at the origin to `10⁻⁸ p L²` (and `p L³`): the
        /// shifts to a local origin keep the rounding at that of the
        /// coordinates' own (about 10⁻¹³ relative there).
        #[test]
        fn far_from_the_origin_the_forces_are_the_same(a in tet(1.0), b in tet(1.0), dir in crate::test_pairs::point()) {
            let near = tet_tet_gradient(&a, &b, 1.0);
            let o = dir * 1e3;
            let far = tet_tet_gradient(&a.map(|x| x + o), &b.map(|x| x + o), 1.0);
            let s = scale(&a, &b, 1.0);
            let l = s.sqrt();
            prop_assert!((near.energy - far.energy).abs() <= 1e-8 * s * l, "{} vs {}", near.energy, far.energy);
            for (x, y) in forces(&near).iter().zip(&forces(&far)) {
                prop_assert!((x - y).norm() <= 1e-8 * s, "{x} vs {y}");
            }
        }
    }
}
