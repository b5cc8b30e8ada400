//! Contact for the combined finite–discrete element method (reference
//! paper §2.3): the broad phase that finds which elements may touch, and
//! the normal force between two tets that do — stateless pieces
//! another solver can use on their own or together.
//!
//! # Code map
//!
//! - [`Nbs`] (`nbs.rs`): the NBS ("no binary search") detection of Munjiza
//!   & Andrews (1998) for bodies of similar size. It finds every pair of
//!   bounding spheres that overlap, grown by a margin, in time and memory
//!   linear in the number of spheres, and reports them as [`Pair`]s. Its
//!   buffers are kept between calls.
//! - [`tet_tet_forces`] (`potential.rs`): the normal force of the
//!   penalty-function potential contact between two tets (Eq. 17), on their
//!   eight nodes; [`tet_tet_contact`] also returns the force-weighted
//!   contact centre where it acts (for friction).
//! - [`tet_tet_gradient`] (`gradient.rs`): the energy-conserving
//!   alternative, the exact gradient `−∂W/∂x` on all eight nodes of
//!   `W = p ∫_{A∩B} (φ_A + φ_B) dV`, the energy whose rigid-translation
//!   derivative is Eq. 17's resultant; with `W` itself and the centroid of
//!   the overlap (for friction).
//! - [`contact_bound`] (`bound.rs`): an upper bound on a pair's Eq. 17
//!   forces from the vertices of the two tets' overlap, to skip pairs
//!   whose forces are negligible before clipping them;
//!   [`tet_tet_contact_within`] checks it and clips with the same
//!   barycentric coordinates, leaving out faces whose pieces are negligible.
//! - [`contact_bound_near`] (`bound_near.rs`): the same bound over every
//!   configuration whose nodes are within a radius of a given one (after a
//!   common translation), so that a pair shown negligible need not be
//!   bounded again until its nodes have moved that far.
//! - [`Frame`] (`frame.rs`): how the kernel calls its large functions (each
//!   direction of the clip and of the bound, each round of the sub-tet
//!   tournament), so that a caller can compile each for a wider vector unit
//!   as a function of its own; [`Plain`] is the baseline, and every
//!   function without a frame argument uses it. The same bits in every
//!   frame.
//! - [`separated_by_face_plane`] (`separation.rs`): a narrow-phase filter
//!   for detection — a face plane of one tet keeps the other more than a
//!   gap away, so the pair cannot touch before the next detection.
//!
//! What needs history or a mesh — which pairs are excluded (still bonded by
//! a joint, sharing a node), the activation on fracture (Eq. 14–16), the
//! Eq. 18 ramp, Coulomb friction — belongs to the caller; in femdem, to the
//! solver's contact pass (`femdem-solver`, module `contact`).
//!
//! # Conventions
//!
//! - SI units: positions, radii and margins in m, the penalty in Pa, forces
//!   in N.
//! - One point type, [`femdem_core::Vec3`], for sphere centres and tet
//!   nodes.
//! - Elements are `u32` indices into the caller's arrays of centres and
//!   radii. A [`Pair`] holds two distinct indices with `a < b`, which its
//!   constructor guarantees; pairs sort by `a`, then `b`.
//! - Tets are positively oriented as in [`femdem_core::tet`]:
//!   `(x₁ − x₀) · ((x₂ − x₀) × (x₃ − x₀)) > 0`, faces ordered outward as in
//!   [`femdem_core::tet::FACES`].
//! - Forces are those exerted **on** the nodes (add them to the nodal force
//!   vector). [`tet_tet_forces`]`(a, b, p)` returns `(f_a, f_b)`: they push
//!   the tets apart, their totals are equal and opposite and they exert no
//!   net torque.
//!
//! **Architecture invariant:** no mesh, no files, no time stepping: spheres
//! in, pairs out; two tets' node positions in, Eq. 17 forces out.
//!
//! # Using the two pieces in another solver
//!
//! 1. **Detect candidates with a margin.** Give every tet that may touch
//!    another a bounding sphere (its centroid and the largest distance from
//!    it to a node) and call [`Nbs::detect`] with a margin `m`: it keeps
//!    the pairs with `|c_i − c_j| ≤ r_i + r_j + 2m`. Two tets that overlap
//!    after every node has moved by at most `m` were such a pair, so the
//!    candidates stay valid, and detection can be skipped, until some node
//!    has moved more than `m` since the last one.
//! 2. **Filter and order.** Map the sphere indices back to your tets, drop
//!    the pairs your model excludes, and sort the rest: the order of
//!    [`Nbs::detect`] depends on its grid, so summing forces in sorted pair
//!    order makes the result independent of the margin (and, with the
//!    pairs evaluated in parallel and summed afterwards, of the thread
//!    count).
//! 3. **Evaluate pairs.** At every step, call [`tet_tet_forces`] with the
//!    current node positions of each candidate and add the forces to the
//!    nodes. It returns zeros for tets that do not overlap; an
//!    axis-aligned box test first is cheaper for the many candidates that
//!    do not. At detection, [`separated_by_face_plane`] with gap `2m`
//!    drops the candidates that cannot touch before the next one.
//!
//! # Example
//!
//! Tet 1 sits on tet 0, their faces in the plane `z = 0`, pushed 1 mm into
//! it; tet 2 is far away. NBS finds exactly the pair (0, 1), and the
//! contact force pushes tet 1 up and tet 0 down, equal and opposite.
//!
//! ```
//! use femdem_contact::{Nbs, Pair, tet_tet_forces};
//! use femdem_core::Vec3;
//! use femdem_core::tet::{centroid, signed_volume};
//!
//! let h = 0.01; // m
//! let below = [Vec3::zeros(), Vec3::new(0.0, h, 0.0), Vec3::new(h, 0.0, 0.0), Vec3::new(0.0, 0.0, -h)];
//! let above = [Vec3::zeros(), Vec3::new(h, 0.0, 0.0), Vec3::new(0.0, h, 0.0), Vec3::new(0.0, 0.0, h)];
//! let push = Vec3::new(0.0, 0.0, -0.001);
//! let tets = [below, above.map(|x| x + push), above.map(|x| x + Vec3::new(1.0, 0.0, 0.0))];
//! assert!(tets.iter().all(|t| signed_volume(t) > 0.0));
//!
//! // 1. Bounding spheres, then the candidates.
//! let centers: Vec<Vec3> = tets.iter().map(centroid).collect();
//! let radii: Vec<f64> =
//!     tets.iter().zip(&centers).map(|(t, c)| t.iter().map(|x| (x - c).norm()).fold(0.0, f64::max)).collect();
//! let mut pairs = Vec::new();
//! Nbs::new().detect(&centers, &radii, 0.0, &mut pairs);
//! pairs.sort_unstable();
//! assert_eq!(pairs, [Pair::new(1, 0).unwrap()]);
//! assert_eq!(pairs[0].indices(), (0, 1));
//!
//! // 3. The pair's Eq. 17 forces, penalty 26 GPa.
//! let (a, b) = pairs[0].indices();
//! let (fa, fb) = tet_tet_forces(&tets[a as usize], &tets[b as usize], 26e9);
//! let (total_a, total_b): (Vec3, Vec3) = (fa.iter().sum(), fb.iter().sum());
//! assert!(total_b.z > 0.0 && total_a.z < 0.0, "the tets are pushed apart");
//! assert!((total_a + total_b).norm() <= 1e-12 * total_b.norm());
//! ```

mod bound;
mod bound_near;
mod frame;
mod gradient;
mod nbs;
mod potential;
mod separation;
#[cfg(test)]
mod test_pairs;

pub use bound::{Bounded, MAX_SLACK, SLACK, contact_bound, tet_tet_contact_within, tet_tet_contact_within_in};
pub use bound_near::contact_bound_near;
pub use frame::{Frame, Plain};
pub use gradient::{GradientContact, tet_tet_gradient};
pub use nbs::{Nbs, Pair};
pub use potential::{TetTetContact, tet_tet_contact, tet_tet_forces};
pub use separation::separated_by_face_plane;
