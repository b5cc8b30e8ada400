//! The device's pair contact (`femdem_gpu::pairs`, Eq. 17) against
//! `femdem_contact::tet_tet_contact`, on the pair kinds the CPU kernel's own
//! property tests use: random pairs from apart to deeply overlapping (flat
//! and needle-shaped tets among them), face-to-face contacts (the shallow
//! contact of a broken mesh: nodes shared exactly or moved by 10⁻¹⁷ to
//! 10⁻³, 10⁻¹⁶ to 0.3 deep or apart, slid along the face) and tets
//! sharing a vertex or an edge, at sizes 10⁻³ to 10² and up to 10⁵ sizes
//! from the origin.
//!
//! # The tolerance
//!
//! The kernel clips each sub-tet on its own where the CPU splits the face
//! by a tournament (`potential.rs`): the same pieces in exact arithmetic,
//! whose areas and moments round differently; and a driver may fuse a
//! product and a sum (Vulkan allows it unless told not to), so a
//! barycentric coordinate may round differently, and a vertex within
//! rounding of a clipping plane may be kept by one and dropped by the
//! other. That is the difference `femdem-contact`'s tests bound between its
//! two clippings: every nodal force within `1024 p L² ε` (`L²` the larger
//! tet's largest face area, `ε = u (1 + M (R + X))` the rounding of a
//! computed coordinate: the derivation is in `potential.rs`'s tests, with
//! the largest difference measured there, 5.2), and the contact centre
//! within what those force differences allow. The largest difference and
//! how many pairs agree to the last bit are printed.
//!
//! With a threshold `omit` (`pair_contacts_within` against
//! `tet_tet_contact_within`, what the solver's pass calls): the kernel
//! computes the pair's bound operation for operation, but lavapipe fuses
//! or reorders some of its last products and sums (measured: the box
//! area `2 (e_x e_y + e_y e_z + e_z e_x)` one ulp off the CPU's in some
//! pairs), so
//!
//! * a negligible pair's bound is asked to agree to 64 ε relative (about
//!   twelve roundings follow the overlap's points, each within ε/2; the
//!   points themselves come from coordinates computed alike, and their
//!   tests against the slack η ≥ 10⁻⁹ are far above any rounding of them);
//! * the verdict (negligible or not) must agree unless the CPU's bound lies
//!   within that tolerance of the threshold;
//! * the forces of a pair that is not negligible, on either side within
//!   `p · omit` of the full contact by the faces left out (`bound.rs`'s
//!   guarantee), are asked to agree to `1024 p L² ε + 2 p · omit`: a face
//!   whose bound lies within rounding of what is left of the budget may be
//!   left out on one side and kept on the other.
//!
//! How many agree to the last bit is printed.

use femdem_contact::{Bounded, tet_tet_contact, tet_tet_contact_within};
use femdem_core::tet::{FACES, signed_volume, triangle_area};
use femdem_core::{Mat3, Real, Vec3};
use femdem_gpu::pairs::{PairBounded, pair_contacts, pair_contacts_within};
use femdem_gpu::{Bulk, JointMesh, TetMesh};
use femdem_material::TetReference;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

use crate::gpu;

const PENALTY: Real = 3e10;
const FORCE_TOLERANCE: Real = 1024.0;

fn point(rng: &mut ChaCha8Rng) -> Vec3 {
    Vec3::new(rng.random_range(-1.0..1.0), rng.random_range(-1.0..1.0), rng.random_range(-1.0..1.0))
}

fn positive(mut t: [Vec3; 4]) -> [Vec3; 4] {
    if signed_volume(&t) < 0.0 {
        t.swap(1, 2);
    }
    t
}

fn tet(rng: &mut ChaCha8Rng, spread: Real) -> [Vec3; 4] {
    positive(std::array::from_fn(|_| point(rng) * spread))
}

/// `10^e` for `e` in `[lo, hi)`, or exactly zero one time in eight.
fn small(rng: &mut ChaCha8Rng, lo: Real, hi: Real) -> Real {
    if rng.random_range(0..8) == 0 { 0.0 } else { 10f64.powf(rng.random_range(lo..hi)) }
}

/// Both tets scaled by 10⁻³, 1 or 10² and moved by up to 0, 1 or 100
/// times a unit (up to 10⁵ times their size).
fn place(rng: &mut ChaCha8Rng, pair: ([Vec3; 4], [Vec3; 4])) -> ([Vec3; 4], [Vec3; 4]) {
    let size = [1e-3, 1.0, 1e2][rng.random_range(0..3)];
    let offset = point(rng) * [0.0, 1.0, 100.0][rng.random_range(0..3)];
    let at = |t: [Vec3; 4]| t.map(|p| p * size + offset);
    (at(pair.0), at(pair.1))
}

/// Two random tets, apart to deeply overlapping.
fn random_pair(rng: &mut ChaCha8Rng) -> ([Vec3; 4], [Vec3; 4]) {
    let a = tet(rng, 1.0);
    let spread = [0.01, 0.3, 1.0][rng.random_range(0..3)];
    let shift = point(rng) * rng.random_range(0.0..1.5);
    let b = tet(rng, spread).map(|p| p + shift);
    place(rng, (a, positive(b)))
}

/// `b` built on face `f` of `a`, each node moved by up to `jitter`, slid
/// along the face and pushed in by `depth` or pulled away.
fn face_pair(rng: &mut ChaCha8Rng) -> ([Vec3; 4], [Vec3; 4]) {
    let a = tet(rng, 1.0);
    let [p0, p1, p2] = FACES[rng.random_range(0..4)].map(|k| a[k]);
    let n = (p1 - p0).cross(&(p2 - p0)).try_normalize(0.0).unwrap_or(Vec3::x());
    let apex = point(rng);
    let top = (p0 + p1 + p2) / 3.0 + n * (0.2 + apex.x.abs()) + (apex - n * apex.dot(&n)) * 0.5;
    let jitter = small(rng, -17.0, -3.0);
    let slide = point(rng);
    let slide_size = if rng.random_bool(0.5) { 0.0 } else { rng.random_range(0.0..0.5) };
    let depth = small(rng, -16.0, -0.5);
    let sign = if rng.random_bool(0.5) { 1.0 } else { -1.0 };
    let shift = (slide - n * slide.dot(&n)) * slide_size + n * (sign * depth);
    let mut b = positive([p0, p2, p1, top]);
    for p in &mut b {
        *p += point(rng) * jitter + shift;
    }
    place(rng, (a, positive(b)))
}

/// Tets sharing one or two nodes, each moved by up to `jitter`.
fn shared_pair(rng: &mut ChaCha8Rng) -> ([Vec3; 4], [Vec3; 4]) {
    let a = tet(rng, 1.0);
    let mut b = tet(rng, 1.0);
    let shared = rng.random_range(1..3);
    let first = rng.random_range(0..4);
    let jitter = small(rng, -17.0, -3.0);
    for (k, node) in b.iter_mut().enumerate().take(shared) {
        *node = a[(first + k) % 4] + point(rng) * jitter;
    }
    place(rng, (a, positive(b)))
}

/// `ε = u (1 + M (R + X))` of a coordinate of a point of `a` in `b`
/// (`femdem_contact`'s `Barycentric::rounding`), the larger of both ways.
fn rounding(a: &[Vec3; 4], b: &[Vec3; 4]) -> Real {
    let one = |a: &[Vec3; 4], b: &[Vec3; 4]| {
        let t = Mat3::from_columns(&[b[1] - b[0], b[2] - b[0], b[3] - b[0]]);
        t.try_inverse().map_or(0.0, |m| {
            let m: Real = m.iter().map(|x| x.abs()).sum();
            let (r, x) =
                a.iter().fold((0.0, 0.0), |(r, x): (Real, Real), p| (r + (p - b[0]).abs().sum(), x + p.abs().sum()));
            (Real::EPSILON / 2.0) * (1.0 + m * (r + x))
        })
    };
    one(a, b).max(one(b, a))
}

fn face_area(a: &[Vec3; 4], b: &[Vec3; 4]) -> Real {
    [a, b].iter().flat_map(|t| FACES.map(|f| triangle_area(&t[f[0]], &t[f[1]], &t[f[2]]))).fold(0.0, Real::max)
}

/// `n` pairs from `make` on the device and on the CPU: every force within
/// the tolerance, every centre within what the force differences allow.
fn compare(name: &str, make: fn(&mut ChaCha8Rng) -> ([Vec3; 4], [Vec3; 4]), n: usize, seed: u64) {
    let Some(g) = gpu() else { return };
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let pairs: Vec<_> = (0..n).map(|_| make(&mut rng)).collect();
    let x: Vec<Vec3> = pairs.iter().flat_map(|(a, b)| a.iter().chain(b).copied()).collect();
    let tets: Vec<[u32; 4]> = (0..2 * n as u32).map(|t| std::array::from_fn(|k| 4 * t + k as u32)).collect();
    let list: Vec<[u32; 2]> = (0..n as u32).map(|k| [2 * k, 2 * k + 1]).collect();
    let device = pair_contacts(&g, &x, &tets, &list, PENALTY).unwrap();
    assert_eq!(device.len(), n, "{name}: one contact per pair");
    let (mut touching, mut identical, mut worst_force, mut worst_centre) = (0, 0, 0.0, 0.0);
    for ((a, b), dev) in pairs.iter().zip(&device) {
        let cpu = tet_tet_contact(a, b, PENALTY);
        let unit = PENALTY * face_area(a, b) * rounding(a, b);
        let forces = cpu.on_a.iter().zip(&dev.on_a).chain(cpu.on_b.iter().zip(&dev.on_b));
        let force = forces.map(|(x, y)| (x - y).norm() / unit).fold(0.0, Real::max);
        assert!(force <= FORCE_TOLERANCE, "{name}: force off by {force:e} p L² ε: {a:?} {b:?}");
        // The centre moves by at most the pieces' changes (up to 32 pieces,
        // each within the force tolerance) over Σ |F_k| (at least the
        // largest nodal force) times the pair's extent.
        let largest = cpu.on_a.iter().chain(&cpu.on_b).map(|f| f.norm()).fold(0.0, Real::max);
        let extent = a.iter().chain(b).map(|p| (p - a[0]).norm()).fold(0.0, Real::max);
        let allowed = 32.0 * FORCE_TOLERANCE * unit / largest * 2.0 * extent;
        let centre = match (cpu.centre, dev.centre) {
            (Some(x), Some(y)) => (x - y).norm() / allowed,
            (None, None) => 0.0,
            _ if allowed >= extent => 0.0,
            _ => Real::INFINITY,
        };
        assert!(centre <= 1.0, "{name}: centre off by {centre:e} of the allowance: {a:?} {b:?}");
        touching += usize::from(cpu.centre.is_some());
        identical += usize::from(cpu.on_a == dev.on_a && cpu.on_b == dev.on_b && cpu.centre == dev.centre);
        worst_force = Real::max(worst_force, force);
        worst_centre = Real::max(worst_centre, centre);
    }
    println!(
        "{name}: {touching} of {n} touch, {identical} equal to the last bit; largest force difference \
         {worst_force:.2} p L² ε, centre {worst_centre:.2e} of its allowance"
    );
    assert!(touching > n / 10, "{name}: the pairs touch ({touching} of {n})");
}

#[test]
fn random_pairs_agree_with_the_cpu() {
    compare("random", random_pair, 20_000, 1);
}

#[test]
fn face_to_face_pairs_agree_with_the_cpu() {
    compare("face to face", face_pair, 20_000, 2);
}

#[test]
fn node_sharing_pairs_agree_with_the_cpu() {
    compare("sharing nodes", shared_pair, 20_000, 3);
}

/// A face of `a` exactly on the plane `λ_1 = λ_2` of `b`, the unit corner
/// tet (`femdem-contact`'s `a_face_on_a_sub_tet_boundary_counts_once`):
/// the part of the face there is counted once on the device too, not
/// once for each of the two sub-tets whose closed regions hold it.
fn boundary_pair(_: &mut ChaCha8Rng) -> ([Vec3; 4], [Vec3; 4]) {
    let a = [Vec3::new(0.1, 0.1, 0.3), Vec3::new(0.2, 0.2, 0.3), Vec3::new(0.1, 0.1, 0.6), Vec3::new(0.3, 0.0, 0.4)];
    (positive(a), [Vec3::zeros(), Vec3::x(), Vec3::y(), Vec3::z()])
}

#[test]
fn a_face_on_a_sub_tet_boundary_counts_once_on_the_device() {
    compare("a face on a sub-tet boundary", boundary_pair, 2, 4);
}

/// Relative tolerance of a bound (module documentation).
const BOUND_TOLERANCE: Real = 64.0 * Real::EPSILON;

/// `n` pairs from `make` with thresholds from 0 to a tenth of a face's
/// area: the device's verdicts, bounds and forces against the CPU's.
fn compare_within(name: &str, make: fn(&mut ChaCha8Rng) -> ([Vec3; 4], [Vec3; 4]), n: usize, seed: u64) {
    let Some(g) = gpu() else { return };
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let pairs: Vec<_> = (0..n).map(|_| make(&mut rng)).collect();
    // Thresholds (m²) of 10⁻¹⁴ to 10⁻¹ of the larger face area, and zero
    // one time in eight.
    let omits: Vec<Real> = pairs.iter().map(|(a, b)| small(&mut rng, -14.0, -1.0) * face_area(a, b)).collect();
    let x: Vec<Vec3> = pairs.iter().flat_map(|(a, b)| a.iter().chain(b).copied()).collect();
    let tets: Vec<[u32; 4]> = (0..2 * n as u32).map(|t| std::array::from_fn(|k| 4 * t + k as u32)).collect();
    let list: Vec<[u32; 2]> = (0..n as u32).map(|k| [2 * k, 2 * k + 1]).collect();
    let device = pair_contacts_within(&g, &x, &tets, &list, &omits, PENALTY).unwrap();
    assert_eq!(device.len(), n, "{name}: one result per pair");
    let (mut negligible, mut trimmed, mut identical, mut flipped) = (0, 0, 0, 0);
    let (mut worst_bound, mut worst_force) = (0.0, 0.0);
    for (((a, b), &omit), dev) in pairs.iter().zip(&omits).zip(&device) {
        let cpu = tet_tet_contact_within(a, b, PENALTY, omit, false);
        let near = |bound: Real| (bound - omit).abs() <= BOUND_TOLERANCE * omit;
        match (cpu, dev) {
            (Bounded::Negligible(cpu), PairBounded::Negligible(dev)) => {
                let off = (cpu - dev).abs() / (BOUND_TOLERANCE * cpu.max(Real::MIN_POSITIVE));
                assert!(off <= 1.0, "{name}: bound {cpu:e} on the CPU, {dev:e} on the device: {a:?} {b:?}");
                worst_bound = Real::max(worst_bound, off);
                negligible += 1;
                identical += usize::from(cpu.to_bits() == dev.to_bits());
            }
            (Bounded::Contact(cpu), PairBounded::Contact(dev)) => {
                let unit = PENALTY * face_area(a, b) * rounding(a, b);
                let allowed = FORCE_TOLERANCE * unit + 2.0 * PENALTY * omit;
                let forces = cpu.on_a.iter().zip(&dev.on_a).chain(cpu.on_b.iter().zip(&dev.on_b));
                let force = forces.map(|(x, y)| (x - y).norm() / allowed).fold(0.0, Real::max);
                assert!(force <= 1.0, "{name}: force off by {force:e} of its allowance: {a:?} {b:?} omit {omit:e}");
                worst_force = Real::max(worst_force, force);
                trimmed += usize::from(cpu != tet_tet_contact(a, b, PENALTY));
                identical += usize::from(cpu.on_a == dev.on_a && cpu.on_b == dev.on_b && cpu.centre == dev.centre);
            }
            (Bounded::Negligible(bound), PairBounded::Contact(_)) if near(bound) => flipped += 1,
            (Bounded::Contact(_), PairBounded::Negligible(bound)) if near(*bound) => flipped += 1,
            (cpu, dev) => panic!("{name}: the CPU found {cpu:?}, the device {dev:?}: {a:?} {b:?} omit {omit:e}"),
        }
    }
    println!(
        "{name}, with thresholds: {negligible} of {n} negligible, {trimmed} with faces left out, {flipped} \
         decided otherwise at the threshold, {identical} equal to the last bit; largest bound difference \
         {worst_bound:.2} and force difference {worst_force:.2e} of their allowances"
    );
    assert!(negligible > n / 20 && trimmed > n / 100, "{name}: both branches ({negligible} and {trimmed} of {n})");
}

#[test]
fn pairs_with_a_threshold_agree_with_the_cpu() {
    compare_within("random", random_pair, 10_000, 4);
    compare_within("face to face", face_pair, 10_000, 5);
    compare_within("sharing nodes", shared_pair, 10_000, 6);
}

/// A maker of pairs of tets.
type Maker = fn(&mut ChaCha8Rng) -> ([Vec3; 4], [Vec3; 4]);

/// `Bulk::pair_geometry`, the solver's way in (pairs of the model's tets at
/// the device's positions, buffers kept from call to call), gives what
/// `pair_contacts_within` and `pair_contacts` give for the same pairs: with
/// thresholds, then fewer pairs (buffers reused), then without thresholds,
/// then more pairs (buffers grown).
#[test]
fn a_bulk_computes_its_pairs_as_the_pair_kernel_does() {
    let Some(g) = gpu() else { return };
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    let makers: [Maker; 3] = [random_pair, face_pair, shared_pair];
    let pairs: Vec<_> = (0..3000).map(|k| makers[k % 3](&mut rng)).collect();
    let omits: Vec<Real> = pairs.iter().map(|(a, b)| small(&mut rng, -14.0, -1.0) * face_area(a, b)).collect();
    let x: Vec<Vec3> = pairs.iter().flat_map(|(a, b)| a.iter().chain(b).copied()).collect();
    let n = pairs.len();
    let tets: Vec<[u32; 4]> = (0..2 * n as u32).map(|t| std::array::from_fn(|k| 4 * t + k as u32)).collect();
    let list: Vec<[u32; 2]> = (0..n as u32).map(|k| [2 * k, 2 * k + 1]).collect();
    // The tet pass is not run: any reference and no material will do.
    let unit = TetReference::new(&[Vec3::zeros(), Vec3::x(), Vec3::y(), Vec3::z()]).unwrap();
    let (refs, material) = (vec![unit; tets.len()], vec![None; tets.len()]);
    let offsets = vec![0u32; x.len() + 1];
    let mesh = TetMesh {
        tets: &tets,
        refs: &refs,
        material: &material,
        materials: &[],
        num_nodes: x.len(),
        gather_offsets: &offsets,
        gather_slots: &[],
    };
    let mut bulk = Bulk::new(&g, mesh, JointMesh::none(&offsets)).unwrap();
    bulk.set_state(&x, &vec![Vec3::zeros(); x.len()]);
    let within = pair_contacts_within(&g, &x, &tets, &list, &omits, PENALTY).unwrap();
    let plain: Vec<PairBounded> =
        pair_contacts(&g, &x, &tets, &list, PENALTY).unwrap().into_iter().map(PairBounded::Contact).collect();
    assert!(within.iter().any(|r| matches!(r, PairBounded::Negligible(_))), "some pairs are negligible");
    assert_eq!(bulk.pair_geometry(&list, Some(&omits), PENALTY).unwrap(), within);
    let few = n / 3;
    assert_eq!(bulk.pair_geometry(&list[..few], Some(&omits[..few]), PENALTY).unwrap(), within[..few]);
    assert_eq!(bulk.pair_geometry(&list[..few], None, PENALTY).unwrap(), plain[..few]);
    assert_eq!(bulk.pair_geometry(&list, None, PENALTY).unwrap(), plain);
    assert_eq!(bulk.pair_geometry(&[], None, PENALTY).unwrap(), []);
}
