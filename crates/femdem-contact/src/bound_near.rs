//! An upper bound on a pair's Eq. 17 contact forces that holds for every
//! configuration near a given one: once a pair is shown negligible with
//! it, the pair stays negligible until its nodes have moved (relative to
//! one another) by more than the radius, and need not be bounded again at
//! every step.
//!
//! **The neighbourhood.** Let `X = (a, b)` be two tets and `δ > 0`. The
//! bound holds for every pair `(a', b')` whose eight nodes are within `δ`
//! of those of `X` after one common translation `w`: `|a'_k − a_k − w| ≤ δ`
//! and `|b'_k − b_k − w| ≤ δ`. Eq. 17's forces do not change under a
//! common translation, so take `w = 0`.
//!
//! **The bound.** [`contact_bound`](crate::contact_bound) bounds the
//! forces of `(a', b')` by `p S' (max φ_{A'} + max φ_{B'})` over
//! `A' ∩ B'`, `S'` a bound on the area of `∂(A' ∩ B')` (its module
//! documentation). Each term is bounded from `X` alone:
//!
//! * *The moved tet lies in the inflated one.* A point of `A'` is
//!   `Σ μ_k a'_k = Σ μ_k a_k + Σ μ_k (a'_k − a_k)`, a point of `A` plus a
//!   vector of length at most `δ`, so `A' ⊂ A ⊕ B(δ) ⊂ A_δ`, the tet whose
//!   face planes are `A`'s moved outward by `δ`. `A_δ` is `A` scaled about
//!   its incentre `c` by `(r + δ) / r` (`r` the inradius: every face plane
//!   is `r` from `c`), with heights `h_j (1 + δ/r)`. So
//!   `A' ∩ B' ⊂ A_δ ∩ B_δ`, and `S'` is at most the area of the box of
//!   `A_δ ∩ B_δ`'s vertices, which [`contact_bound`](crate::contact_bound)
//!   computes for the pair `(A_δ, B_δ)`.
//! * *The potential of the moved tet.* `φ_{A'}(y) = 4 min_j λ'_j(y)` and
//!   `λ'_j(y) = d'_j(y) / h'_j`, `d'_j` the distance to face plane `j` of
//!   `A'`; at the nearest face, `min_j λ'_j ≤ d_{A'}(y) / h'_min`, `d_{A'}`
//!   the depth of `y` in `A'`. `A' ⊂ A_δ` gives `d_{A'}(y) ≤ d_{A_δ}(y) =
//!   min_j λ^{A_δ}_j(y) h^{A_δ}_j ≤ h^{A_δ}_max min_j λ^{A_δ}_j(y)`, whose
//!   largest value over `A_δ ∩ B_δ` the bound of `(A_δ, B_δ)` already
//!   takes (as `min_j max λ^{A_δ}_j` over the polytope's vertices).
//! * *The moved tet's smallest height.* Every height is at least twice
//!   the inradius (`h_j = 3V / A_j`, `r = 3V / Σ A_i`, and the other three
//!   faces' areas add up to at least `A_j`). The incentre moved with the
//!   nodes, `c' = Σ μ_k a'_k` (`μ` its barycentric weights), lies within
//!   `δ` of `c` and inside `A'`; each face triangle of `A'` lies in the
//!   original one grown by `δ`, which is at least `r` from `c`: so `c'` is
//!   at least `r − 2δ` from every face of `A'`, its inradius is at least
//!   `r − 2δ` (and `A'` cannot have turned inside out for `δ < r/2`), and
//!   `h'_min ≥ 2 (r − 2δ)`.
//!
//! Together, with `κ_A = h_max (1 + δ/r) / (2 (r − 2δ))` (`≥ 2`; larger for
//! a flat tet) and the same for `B`:
//!
//! ```text
//! Σ_k |F'_k| / p ≤ S_δ (κ_A φ^δ_A + κ_B φ^δ_B),
//! ```
//!
//! the bound of `(A_δ, B_δ)` with its two potential terms weighted by `κ`.
//! It is infinite for `δ ≥ r/2` of either tet, for a flat tet, for a
//! coordinate that is not finite, and wherever the bound of `(a, b)`
//! itself is (its rounding slack too large to trust).
//!
//! **Rounding.** The inflated tets' nodes are computed within a few ulps of
//! their coordinates; the bound of `(A_δ, B_δ)` accepts points beyond a
//! plane by its slack (`bound.rs`, at least 10⁻⁹ of a height and more than
//! 10³ ulps of the coordinates over a height), which covers that.

use femdem_core::{Real, Vec3};

use crate::bound::{weighted_bound, within_slack};
use crate::frame::Plain;
use crate::potential::Barycentric;

/// The tet scaled about its incentre so that each face plane moves
/// outward by `delta`, and the factor `κ = h_max (1 + δ/r) / (2 (r − 2δ))`
/// (the module documentation); `None` for a flat tet or `δ ≥ r/2`.
fn inflated(t: &[Vec3; 4], delta: Real) -> Option<([Vec3; 4], Real)> {
    let volume = (t[1] - t[0]).cross(&(t[2] - t[0])).dot(&(t[3] - t[0])) / 6.0;
    // The area of the face opposite each node.
    let area = |k: usize| {
        let [p, q, s] = femdem_core::tet::FACES[k].map(|i| t[i]);
        0.5 * (q - p).cross(&(s - p)).norm()
    };
    let areas = [area(0), area(1), area(2), area(3)];
    let total: Real = areas.iter().sum();
    let least = areas.iter().copied().fold(Real::INFINITY, Real::min);
    let r = 3.0 * volume / total;
    if !(r > 0.0 && least > 0.0 && delta >= 0.0 && r - 2.0 * delta > 0.0) {
        return None;
    }
    let centre = (t[0] * areas[0] + t[1] * areas[1] + t[2] * areas[2] + t[3] * areas[3]) / total;
    let scale = 1.0 + delta / r;
    let h_max = 3.0 * volume / least;
    let kappa = h_max * scale / (2.0 * (r - 2.0 * delta));
    Some((t.map(|p| centre + (p - centre) * scale), kappa))
}

/// An upper bound on `Σ_k |F_k| / p` (m²) over the pieces of the Eq. 17
/// contact of every pair of tets whose nodes are within `delta` of those
/// of `a` and `b` after one common translation: every nodal force and the
/// resultant of [`tet_tet_contact`](crate::tet_tet_contact) for such a
/// pair are at most `p` times it (the module documentation). At least
/// [`contact_bound`](crate::contact_bound)`(a, b)`; infinite where it
/// cannot bound (a flat tet, `delta` not below half an inradius, a
/// coordinate not finite).
pub fn contact_bound_near(a: &[Vec3; 4], b: &[Vec3; 4], delta: Real) -> Real {
    // Where the pair's own bound is beyond rounding, so is this one.
    if !within_slack(a, b) {
        return Real::INFINITY;
    }
    let (Some((a_out, kappa_a)), Some((b_out, kappa_b))) = (inflated(a, delta), inflated(b, delta)) else {
        return Real::INFINITY;
    };
    let bound = weighted_bound(
        Plain,
        &a_out,
        &b_out,
        Barycentric::new(&a_out).as_ref(),
        Barycentric::new(&b_out).as_ref(),
        [kappa_a, kappa_b],
    );
    if bound.is_nan() { Real::INFINITY } else { bound }
}

#[cfg(test)]
mod tests {
    //! Every pair near a certified one stays below the neighbourhood
    //! bound: random node moves of up to `δ` and a common translation of
    //! up to 100 sizes, on the families of `test_pairs` (tets sharing a
    //! vertex or an edge, face to face, random), `δ` from 10⁻⁶ to 10⁻²
    //! of the size; and the bound of a tet pair pressed at a shared vertex
    //! is small enough, over a radius that is not, to skip such pairs.

    use super::*;
    use crate::test_pairs::{face_pair, point, shared_pair, tet};
    use crate::{contact_bound, tet_tet_contact};
    use proptest::prelude::*;

    const P: Real = 3e10;

    /// The tets' size: the longest edge of `a`.
    fn size(a: &[Vec3; 4]) -> Real {
        femdem_core::tet::EDGES.iter().map(|&[p, q]| (a[p] - a[q]).norm()).fold(0.0, Real::max)
    }

    /// Checks the bound near `(a, b)` against the forces of `(a, b)` with
    /// each node moved by `moves` (scaled to at most `delta`) and all by
    /// `shift`.
    fn check(a: &[Vec3; 4], b: &[Vec3; 4], rel: Real, moves: &[Vec3; 8], shift: Vec3) -> Result<(), TestCaseError> {
        let delta = rel * size(a);
        let near = contact_bound_near(a, b, delta);
        let here = contact_bound(a, b);
        // The inflated pair's overlap contains the pair's.
        prop_assert!(near >= here * (1.0 - 1e-9), "near {near} below here {here}");
        let within = |p: Vec3, m: &Vec3| p + m * (delta / 3f64.sqrt()) + shift * size(a) * 100.0;
        let a2: [Vec3; 4] = std::array::from_fn(|k| within(a[k], &moves[k]));
        let b2: [Vec3; 4] = std::array::from_fn(|k| within(b[k], &moves[4 + k]));
        let c = tet_tet_contact(&a2, &b2, P);
        let largest = c.on_a.iter().chain(&c.on_b).map(|f| f.norm()).fold(0.0, Real::max);
        let resultant = c.on_b.iter().sum::<Vec3>().norm();
        // The kernel's own rounding: a relative 10⁻⁹, as `bound.rs`'s test.
        prop_assert!(
            largest.max(resultant) <= P * near * (1.0 + 1e-9),
            "{largest} > p · {near}: {a:?} {b:?} δ {delta}"
        );
        Ok(())
    }

    fn moves() -> impl Strategy<Value = [Vec3; 8]> {
        proptest::collection::vec(point(), 8).prop_map(|v| std::array::from_fn(|k| v[k]))
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(3000))]
        #[test]
        fn pairs_near_a_shared_node_pair_stay_below((a, b) in shared_pair(), e in -6.0..-2.0f64, m in moves(), s in point()) {
            check(&a, &b, 10f64.powf(e), &m, s)?;
        }

        #[test]
        fn pairs_near_a_face_pair_stay_below((a, b) in face_pair(), e in -6.0..-2.0f64, m in moves(), s in point()) {
            check(&a, &b, 10f64.powf(e), &m, s)?;
        }

        #[test]
        fn pairs_near_a_random_pair_stay_below(a in tet(1.0), b in tet(1.0), e in -6.0..-2.0f64, m in moves(), s in point()) {
            check(&a, &b, 10f64.powf(e), &m, s)?;
        }
    }

    /// Two unit tets sharing their apex at the origin, one below and one
    /// above `z = 0`, the upper pressed down by `d`: the pair a fracture
    /// network has most of.
    fn at_a_vertex(d: Real) -> ([Vec3; 4], [Vec3; 4]) {
        let s = 3.0_f64.sqrt() / 2.0;
        let ring =
            |z: Real, k: Real| [Vec3::new(k, 0.0, z), Vec3::new(-0.5 * k, s * k, z), Vec3::new(-0.5 * k, -s * k, z)];
        let [l0, l1, l2] = ring(-1.0, 1.0);
        let [u0, u1, u2] = ring(1.0, 0.7);
        let a = crate::test_pairs::positive([Vec3::zeros(), l0, l1, l2]);
        let b = crate::test_pairs::positive([Vec3::zeros(), u0, u1, u2]);
        (a, b.map(|p| p - Vec3::new(0.0, 0.0, d)))
    }

    /// Pressed by 10⁻⁵ of their size at a shared vertex, the pair's bound
    /// over a radius of 10⁻⁵ is within a thousand times the bound at the
    /// point (510 when written) (both third order in the overlap, which the radius doubles and
    /// the shape factors and the box multiply), and it grows as the cube of
    /// the radius once that dominates: small enough to certify such pairs as
    /// negligible (10⁻¹⁰ of `p ℓ²` in the solver) for moves of 10⁻⁵ of
    /// their size.
    #[test]
    fn near_a_pressed_vertex_the_bound_grows_as_the_cube_of_the_radius() {
        let (a, b) = at_a_vertex(1e-5);
        let here = contact_bound(&a, &b);
        let near = |delta: Real| contact_bound_near(&a, &b, delta);
        let (n5, n4, n3) = (near(1e-5), near(1e-4), near(1e-3));
        eprintln!("here {here:e}; near 1e-5 {n5:e}, 1e-4 {n4:e}, 1e-3 {n3:e}");
        assert!(here > 0.0 && n5 > here, "here {here}, near {n5}");
        assert!(n5 < 1e3 * here, "near {n5} against here {here}");
        let volume = femdem_core::tet::signed_volume(&a).min(femdem_core::tet::signed_volume(&b));
        let negligible = 1e-10 * volume.powf(2.0 / 3.0);
        assert!(n5 < negligible, "near {n5}: not negligible at 1e-10 of p l² ({negligible})");
        let order = (n3 / n4).log10();
        assert!((order - 3.0).abs() < 0.1, "order {order}");
        // No bound at or beyond half the inradius.
        assert_eq!(near(0.5), Real::INFINITY);
    }
}
