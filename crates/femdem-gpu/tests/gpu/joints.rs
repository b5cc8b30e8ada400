//! The device's joint pass against `femdem_fracture::joint_update_fast`,
//! step by step, as joints are opened and slid through hardening,
//! softening and failure under every coupling and calibration.
//!
//! # The tolerance
//!
//! A joint's inputs, its openings and slips, are differences of nodal
//! coordinates: both sides round them relative to the coordinates `|x|`,
//! not to the opening, and may do so differently (a fused multiply-add, a
//! sum in another order). Every quantity the law derives from them divides
//! by `δ_np` (or `δ_sp`, `δ_nc − δ_np`, of the same order here), so it
//! carries a relative error of order `κ ε` with `κ = 1 + |x| / δ_np`, and
//! the device's `exp` adds its ulp to `z(D)`. Forces are compared against
//! `C κ ε` times the joint's force scale `A (f_t + c + |σ| + |τ|)`, damage
//! against `C κ ε`, the work against `C κ ε` times the joint's largest
//! `A (f_t + c) δ_nc`, with `C = 256` as for the tets; the failures must be
//! the same joints, at the same step, with the same label (a flip would
//! need a difference of `κ ε` to straddle a threshold, which random paths
//! make improbable).

use femdem_core::{Real, Vec3};
use femdem_fracture::{Coupling, GfCalibration, Joint, JointHistory, JointParams, KernelConsts, joint_update_fast};
use femdem_gpu::{Bulk, Evaluate, JointMesh, TetMesh};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

use crate::gpu;

const C: Real = 256.0;
const STEPS: usize = 60;

/// A joint's two faces and how its far face moves per step.
struct Path {
    face: [Vec3; 3],
    per_step: Vec3,
}

fn random_vec(rng: &mut ChaCha8Rng, r: Real) -> Vec3 {
    Vec3::new(rng.random_range(-r..r), rng.random_range(-r..r), rng.random_range(-r..r))
}

fn random_law(rng: &mut ChaCha8Rng) -> Joint {
    let ft = rng.random_range(2e6..1e7);
    let params = JointParams {
        penalty: rng.random_range(1e10..1e11),
        tensile_strength: ft,
        // Some at the Mohr–Coulomb apex (c <= ft tan phi), most not.
        cohesion: ft * rng.random_range(0.3..4.0),
        friction_angle: rng.random_range(0.1..1.2),
        gf_tension: rng.random_range(20.0..200.0),
        gf_shear: rng.random_range(50.0..500.0),
        calibration: if rng.random_bool(0.5) { GfCalibration::Paper } else { GfCalibration::Exact },
        coupling: [Coupling::Printed, Coupling::Multiplicative, Coupling::Capped][rng.random_range(0..3)],
    }
    .validate()
    .unwrap();
    Joint::new(params, rng.random_range(0.005..0.02))
}

/// The joint's nodes at step `n`: side a fixed, side b moved by
/// `n · per_step` (N6, N5, N4 opposite N1, N2, N3).
fn nodes(p: &Path, n: usize) -> [Vec3; 6] {
    let d = p.per_step * n as Real;
    [p.face[0], p.face[1], p.face[2], p.face[2] + d, p.face[1] + d, p.face[0] + d]
}

#[test]
fn joint_pass_matches_the_cpu_kernel_through_failure() {
    let Some(g) = gpu() else { return };
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    let n = 2000;
    let law: Vec<Joint> = (0..n).map(|_| random_law(&mut rng)).collect();
    let paths: Vec<Path> = law
        .iter()
        .map(|j| {
            let c = random_vec(&mut rng, 0.1);
            let face = [
                c,
                c + Vec3::x() * j.h + random_vec(&mut rng, 0.3 * j.h),
                c + Vec3::y() * j.h + random_vec(&mut rng, 0.3 * j.h),
            ];
            let normal = (face[1] - face[0]).cross(&(face[2] - face[0])).normalize();
            // Opening (or closing) and sliding mixed at random, reaching
            // about twice the critical opening by the last step.
            let tangent = (face[1] - face[0]).normalize();
            let mix = rng.random_range(-0.3..1.0);
            let dir = (normal * mix + tangent * (1.0 - mix.abs()) * rng.random_range(0.0..3.0)).normalize();
            Path { face, per_step: dir * (2.0 * j.delta_nc * rng.random_range(0.3..1.5) / STEPS as Real) }
        })
        .collect();
    let joints: Vec<[u32; 6]> = (0..n as u32).map(|j| std::array::from_fn(|k| 6 * j + k as u32)).collect();
    let offsets: Vec<u32> = (0..=6 * n as u32).collect();
    let slots: Vec<u32> = (0..6 * n as u32).collect();
    let no_tets = vec![0u32; 6 * n + 1];
    let history = vec![JointHistory::default(); n];
    let mut bulk = Bulk::new(
        &g,
        TetMesh {
            tets: &[],
            refs: &[],
            material: &[],
            materials: &[],
            num_nodes: 6 * n,
            gather_offsets: &no_tets,
            gather_slots: &[],
        },
        JointMesh { joints: &joints, law: &law, history: &history, gather_offsets: &offsets, gather_slots: &slots },
    )
    .unwrap();
    let consts = KernelConsts::new();
    let mut cpu = history.clone();
    let eps = Real::EPSILON / 2.0;
    let (mut worst_f, mut worst_d, mut worst_w, mut failures) = (0.0f64, 0.0f64, 0.0f64, [0usize; 4]);
    let v = vec![Vec3::zeros(); 6 * n];
    for step in 0..STEPS {
        let x: Vec<Vec3> = paths.iter().flat_map(|p| nodes(p, step)).collect();
        bulk.set_state(&x, &v);
        // Every other step without energies, as most steps of a run.
        let energy = step % 2 == 0;
        bulk.forces(Evaluate { energy, ..Evaluate::default() });
        let (slots_gpu, hist_gpu, failed_gpu, sums_gpu) =
            (bulk.joint_slots(), bulk.joint_history(), bulk.failed_now(), bulk.joint_sums());
        for j in 0..n {
            let xp: [Vec3; 6] = std::array::from_fn(|k| x[6 * j + k]);
            let was_failed = cpu[j].failed;
            let out = joint_update_fast(&consts, &law[j], &mut cpu[j], &xp, energy);
            assert_eq!(failed_gpu[j], out.failed, "joint {j} at step {step}: failure");
            assert_eq!(hist_gpu[j].failed, cpu[j].failed, "joint {j} at step {step}");
            if let Some(m) = out.failed {
                failures[m as usize] += 1;
            }
            let p = &law[j].params;
            let kappa = 1.0 + xp.iter().map(|p| p.amax()).fold(0.0, Real::max) / law[j].delta_np;
            let area = 0.5 * (paths[j].face[1] - paths[j].face[0]).cross(&(paths[j].face[2] - paths[j].face[0])).norm();
            let stresses = cpu[j].last_stress.iter().map(|s| s[0].abs() + s[1].abs()).fold(0.0, Real::max);
            let force_scale = area * (p.tensile_strength + p.cohesion + stresses);
            for (a, b) in slots_gpu[j].iter().zip(&out.forces) {
                worst_f = worst_f.max((a - b).norm() / (eps * kappa * force_scale));
            }
            for (a, b) in hist_gpu[j].damage.iter().zip(&cpu[j].damage) {
                worst_d = worst_d.max((a - b).abs() / (eps * kappa));
            }
            let work_scale = area * (p.tensile_strength + p.cohesion) * law[j].delta_nc * 10.0;
            for (a, b) in [
                (hist_gpu[j].work, cpu[j].work),
                (hist_gpu[j].dissipated, cpu[j].dissipated),
                (hist_gpu[j].released, cpu[j].released),
            ] {
                worst_w = worst_w.max((a - b).abs() / (eps * kappa * work_scale));
            }
            // The energy sums the solver takes (forces::joint_chunk).
            let fracture = if was_failed || cpu[j].failed { cpu[j].work } else { cpu[j].work - out.energy };
            if energy {
                worst_w = worst_w.max((sums_gpu[j][0] - out.energy).abs() / (eps * kappa * work_scale));
                worst_w = worst_w.max((sums_gpu[j][1] - fracture).abs() / (eps * kappa * work_scale));
            }
            assert_eq!(hist_gpu[j].softened, cpu[j].softened, "joint {j} at step {step}");
        }
    }
    println!(
        "joints: worst force {worst_f:.1}, damage {worst_d:.1}, work {worst_w:.1} kappa eps; failures (tensile, shear, mixed, collapsed) {failures:?}"
    );
    assert!(failures.iter().take(3).all(|&k| k > 20), "the paths break joints in every mode: {failures:?}");
    assert!(worst_f <= C && worst_d <= C && worst_w <= C, "{worst_f} {worst_d} {worst_w}");
}
