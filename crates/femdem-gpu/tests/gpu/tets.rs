//! The device's tet pass and gather against `femdem_material::tet_forces`.
//!
//! # The tolerance
//!
//! Device and CPU evaluate the same formulas (Eq. 1–2 with the floor of
//! `femdem_material::law`) in f64, but not in the same order everywhere:
//! matrix products may be summed in another order, a driver may fuse a
//! product and a sum (Vulkan allows it unless told not to), and `ln` is the
//! device's own (within 2 ulps, `math.rs`). Each of the ~150 operations
//! behind a force rounds once, by at most `ε = 2⁻⁵³` of a quantity no
//! larger than the force's *terms*: `V₀ ‖Dm⁻¹‖` times the stresses that
//! are summed, `μ ‖F‖`, `|U′(Ĵ)| ‖cof F‖` (or `(λ + 2μ)(1 + ‖F‖)` for the
//! linear law, whose strain `sym F − I` cancels) and `η ‖D‖ ‖cof F‖`. So a
//! force may differ by `c ε · scale` with `c` of the order of the operation
//! count; the tests allow `c = 256` (the measured worst is printed), and
//! the same for the stress (`scale / (V₀ ‖Dm⁻¹‖)`) and the energy
//! (`V₀ (λ + 2μ)(1 + ‖F‖²)`). A formula wrong in any term would be off by
//! that term, `10⁻² … 1` of the scale here, far beyond it.

use femdem_core::{Mat3, Real, Vec3};
use femdem_gpu::{Bulk, Evaluate, JointMesh, TetMesh};
use femdem_material::{
    ElasticParams, J_FLOOR, Law, Material, TetReference, deformation_gradient, tet_forces, velocity_gradient,
};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

use crate::gpu;

const C: Real = 256.0;

/// Random tets over a shared pool of nodes, in a random state: stretched,
/// sheared and rotated, some crushed below the floor or inverted, moving.
struct Scene {
    tets: Vec<[u32; 4]>,
    refs: Vec<TetReference>,
    material: Vec<Option<u16>>,
    materials: Vec<(Law, Material)>,
    x: Vec<Vec3>,
    v: Vec<Vec3>,
    offsets: Vec<u32>,
    slots: Vec<u32>,
    no_joints: Vec<u32>,
}

fn random_vec(rng: &mut ChaCha8Rng, r: Real) -> Vec3 {
    Vec3::new(rng.random_range(-r..r), rng.random_range(-r..r), rng.random_range(-r..r))
}

/// `n` tets: each a unit-ish tet of size `h` around a random centre, with
/// its own four nodes, then every node of a tet after the first shared with
/// a node of an earlier tet with probability ½ (so the gather sums several
/// slots per node). Positions: the reference mapped by a random affine
/// map per tet, and for shared nodes the first tet's, which distorts the
/// later tets further.
fn scene(n: usize, seed: u64) -> Scene {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let h = 0.01;
    let materials: Vec<(Law, Material)> = [
        (Law::NeoHookean, 2.0e9, 0.0),
        (Law::NeoHookean, 26e9, 5.0e4),
        (Law::LinearElastic, 10e9, 0.0),
        (Law::LinearElastic, 60e9, 1.0e5),
    ]
    .iter()
    .map(|&(law, young, viscosity)| {
        (law, ElasticParams { young, poisson: 0.25, density: 2600.0, viscosity }.validate().unwrap())
    })
    .collect();
    let (mut tets, mut refs, mut material, mut x0, mut x) = (vec![], vec![], vec![], vec![], vec![]);
    while tets.len() < n {
        let c = random_vec(&mut rng, 0.1);
        let corners = [Vec3::zeros(), Vec3::x(), Vec3::y(), Vec3::z()].map(|p| c + (p + random_vec(&mut rng, 0.2)) * h);
        let Some(r) = TetReference::new(&corners) else { continue };
        // A random state: F = R (I + G), G up to 5% (a tenth of the tets
        // crushed to J < J_FLOOR, some inverted), R a random rotation.
        let mut g = Mat3::from_fn(|_, _| rng.random_range(-0.05..0.05));
        if rng.random_bool(0.1) {
            g[(2, 2)] = rng.random_range(-1.5..-0.95);
        }
        let axis = random_vec(&mut rng, 1.0);
        let rot = nalgebra::Rotation3::new(axis * rng.random_range(0.0..1.0)).into_inner();
        let a = rot * (Mat3::identity() + g);
        let shift = random_vec(&mut rng, 0.01);
        let mut nodes = [0u32; 4];
        for (k, p) in corners.iter().enumerate() {
            let share = !x.is_empty() && rng.random_bool(0.5);
            let candidate = rng.random_range(0..x.len().max(1)) as u32;
            if share && !nodes[..k].contains(&candidate) {
                nodes[k] = candidate;
            } else {
                nodes[k] = x.len() as u32;
                x0.push(*p);
                x.push(a * (p - c) + c + shift);
            }
        }
        let mat = rng.random_range(0..=materials.len());
        tets.push(nodes);
        refs.push(r);
        material.push((mat < materials.len()).then_some(mat as u16));
    }
    let v = (0..x.len()).map(|_| random_vec(&mut rng, 2.0)).collect();
    // The gather table: node i's slots 4t + k in increasing order.
    let mut rows = vec![Vec::new(); x.len()];
    for (t, tet) in tets.iter().enumerate() {
        for (k, &node) in tet.iter().enumerate() {
            rows[node as usize].push((4 * t + k) as u32);
        }
    }
    let mut offsets = vec![0u32];
    let mut slots = vec![];
    for row in rows {
        slots.extend(row);
        offsets.push(slots.len() as u32);
    }
    let no_joints = vec![0; x.len() + 1];
    Scene { tets, refs, material, materials, x, v, offsets, slots, no_joints }
}

fn mesh(s: &Scene) -> TetMesh<'_> {
    TetMesh {
        tets: &s.tets,
        refs: &s.refs,
        material: &s.material,
        materials: &s.materials,
        num_nodes: s.x.len(),
        gather_offsets: &s.offsets,
        gather_slots: &s.slots,
    }
}

/// The scales of a tet's force, stress and energy: the magnitudes of the
/// terms each is summed from (module documentation).
struct Scales {
    force: Real,
    stress: Real,
    energy: Real,
}

fn scales(law: Law, m: &Material, r: &TetReference, x: &[Vec3; 4], v: &[Vec3; 4]) -> Scales {
    let f = deformation_gradient(r, x);
    let j = f.determinant();
    let jh = j.max(J_FLOOR);
    // F = Ds Dm^-1 rounds relative to |Ds| |Dm^-1| (more than |F| where Dm
    // is ill-conditioned), cof F and J relative to its square and cube.
    let ds = Mat3::from_columns(&[x[1] - x[0], x[2] - x[0], x[3] - x[0]]);
    let fa = ds.norm() * r.inv_dm.norm();
    let dv = Mat3::from_columns(&[v[1] - v[0], v[2] - v[0], v[3] - v[0]]);
    let fa_dot = dv.norm() * r.inv_dm.norm();
    // |D| <= |L^| = |F' cof^T| / J^, and L^'s rounding is relative to that.
    let d = fa_dot * fa * fa / jh;
    let (lambda, mu, eta) = (m.lambda(), m.mu(), m.viscosity());
    let ln = jh.ln();
    let du = (lambda * ln.abs() + mu) / jh;
    // J rounds by ε fa³, which moves ln Ĵ and U′ by λ ε fa³ / Ĵ.
    let dj = lambda * fa.powi(3) / (jh * jh);
    let (piola, stress, energy) = match law {
        Law::NeoHookean => (
            mu * fa + (du + dj) * fa * fa + eta * d * fa * fa,
            mu * fa * fa / jh + (du + dj) * 3f64.sqrt() + eta * d,
            0.5 * mu * (fa * fa + 3.0)
                + (0.5 * lambda * ln.abs() + mu) * ln.abs()
                + du * (j - jh).abs()
                + dj * fa.powi(3),
        ),
        Law::LinearElastic => {
            let s = (lambda + 2.0 * mu) * (1.0 + fa) * 3.0 + eta * d;
            (s, s, (lambda + 2.0 * mu) * (1.0 + fa).powi(2))
        }
    };
    Scales { force: r.volume * r.inv_dm.norm() * piola, stress, energy: r.volume * energy }
}

/// The solver's viscous dissipation rate of a tet (`femdem_solver`'s tet
/// pass: `R = η D(v) : D(v̄) V₀ J`, `v̄ = ½ (v + v_before)`), and its
/// scale: `η V₀ |J|` times the two rates of deformation's magnitudes as
/// they are rounded, `‖Δv‖ ‖cof Ds‖ / |det Ds|` each, times the
/// conditioning of `det Ds`, `‖Ds‖³ / |det Ds|`.
fn dissipation(m: &Material, r: &TetReference, x: &[Vec3; 4], v: &[Vec3; 4], before: &[Vec3; 4]) -> (Real, Real) {
    let l = velocity_gradient(x, v);
    let d = (l + l.transpose()) * 0.5;
    let mean: [Vec3; 4] = std::array::from_fn(|k| (v[k] + before[k]) * 0.5);
    let lm = velocity_gradient(x, &mean);
    let dm = (lm + lm.transpose()) * 0.5;
    let j = deformation_gradient(r, x).determinant();
    let rate = m.viscosity() * d.dot(&dm) * r.volume * j;
    let ds = Mat3::from_columns(&[x[1] - x[0], x[2] - x[0], x[3] - x[0]]);
    let det = ds.determinant().abs();
    let cof = ds.norm().powi(2);
    let edges = |w: &[Vec3; 4]| Mat3::from_columns(&[w[1] - w[0], w[2] - w[0], w[3] - w[0]]).norm();
    let scale = m.viscosity()
        * r.volume
        * j.abs()
        * (edges(v) * cof / det)
        * (edges(&mean) * cof / det)
        * (1.0 + ds.norm().powi(3) / det);
    (rate, scale)
}

/// Every tet's slots, stress and energy against the CPU kernel, within
/// `C ε` of its scale; rigid tets exactly zero.
#[test]
fn tet_pass_matches_the_cpu_kernel() {
    let Some(g) = gpu() else { return };
    let s = scene(4000, 1);
    let mut bulk = Bulk::new(&g, mesh(&s), JointMesh::none(&s.no_joints)).unwrap();
    bulk.set_state(&s.x, &s.v);
    let mut rng = ChaCha8Rng::seed_from_u64(3);
    let before: Vec<Vec3> = s.v.iter().map(|v| v + random_vec(&mut rng, 0.5)).collect();
    bulk.set_before(&before);
    bulk.forces(Evaluate { stress: true, energy: true, dissipation: true });
    let (slots, stresses, energies) = (bulk.tet_slots(), bulk.stresses(), bulk.tet_energies());
    let rates = bulk.tet_rates();
    let mut worst_r = 0.0f64;
    let eps = Real::EPSILON / 2.0;
    let (mut worst_f, mut worst_s, mut worst_e, mut crushed) = (0.0f64, 0.0f64, 0.0f64, 0);
    for t in 0..s.tets.len() {
        let xp = s.tets[t].map(|n| s.x[n as usize]);
        let vp = s.tets[t].map(|n| s.v[n as usize]);
        let Some(m) = s.material[t] else {
            assert_eq!(slots[t], [Vec3::zeros(); 4], "rigid tet {t}");
            assert_eq!(energies[t], 0.0, "rigid tet {t}");
            continue;
        };
        let (law, mat) = &s.materials[m as usize];
        let cpu = tet_forces(*law, mat, &s.refs[t], &xp, &vp);
        let sc = scales(*law, mat, &s.refs[t], &xp, &vp);
        if deformation_gradient(&s.refs[t], &xp).determinant() < J_FLOOR {
            crushed += 1;
        }
        for (gpu_f, cpu_f) in slots[t].iter().zip(&cpu.forces) {
            worst_f = worst_f.max((gpu_f - cpu_f).norm() / (eps * sc.force));
        }
        let e_s = (stresses[t] - cpu.stress).norm() / (eps * sc.stress);
        worst_s = worst_s.max(e_s);
        worst_e = worst_e.max((energies[t] - cpu.energy).abs() / (eps * sc.energy));
        if mat.viscosity() > 0.0 {
            let (rate, scale) = dissipation(mat, &s.refs[t], &xp, &vp, &s.tets[t].map(|n| before[n as usize]));
            if rate.is_finite() {
                worst_r = worst_r.max((rates[t] - rate).abs() / (eps * scale));
            }
        }
    }
    println!(
        "tets: worst force {worst_f:.1} eps, stress {worst_s:.1} eps, energy {worst_e:.1} eps, dissipation rate {worst_r:.1} eps of the scale; {crushed} crushed"
    );
    assert!(worst_r <= C, "dissipation rates {worst_r} eps of their scale apart");
    assert!(crushed > 100, "the scene crushes some tets below the floor ({crushed})");
    assert!(worst_f <= C, "forces {worst_f} eps of their scale apart");
    assert!(worst_s <= C, "stresses {worst_s} eps of their scale apart");
    assert!(worst_e <= C, "energies {worst_e} eps of their scale apart");
}

/// Each node's gathered force is the sum of its slots in increasing slot
/// order, bit for bit (the device's own slots summed on the CPU in that
/// order), and two evaluations give the same bytes.
#[test]
fn gather_sums_in_slot_order_and_repeats_exactly() {
    let Some(g) = gpu() else { return };
    let s = scene(3000, 2);
    let mut bulk = Bulk::new(&g, mesh(&s), JointMesh::none(&s.no_joints)).unwrap();
    bulk.set_state(&s.x, &s.v);
    bulk.forces(Evaluate::default());
    let (slots, internal) = (bulk.tet_slots(), bulk.internal());
    let flat: Vec<Vec3> = slots.iter().flatten().copied().collect();
    let mut shared = 0;
    for (i, f) in internal.iter().enumerate() {
        let row = &s.slots[s.offsets[i] as usize..s.offsets[i + 1] as usize];
        shared += usize::from(row.len() > 1);
        let mut sum = Vec3::zeros();
        for &k in row {
            sum += flat[k as usize];
        }
        assert_eq!(sum.map(Real::to_bits), f.map(Real::to_bits), "node {i}");
    }
    assert!(shared > 1000, "the scene shares nodes ({shared})");
    bulk.forces(Evaluate::default());
    assert_eq!(bulk.internal(), internal);
    assert_eq!(bulk.tet_slots(), slots);
}
