//! The force pass's kernel, `joint_update_fast`, against the readable law,
//! `joint_update` (Eq. 3–13): the same forces, output and history, bit for
//! bit, along random loading paths.
//!
//! Tolerance: none (bit equality). The fast kernel skips work (`z` of
//! Eq. 12 where the damage is zero or unchanged, the stored energy when
//! nobody asks, the failure label until a point breaks) but every value it
//! does compute is computed with the same operations in the same order as
//! `law.rs`, and IEEE arithmetic is deterministic; `z(0)` is one call of the
//! same function. A looser tolerance would hide a change of arithmetic, and
//! with it a change of which step a joint fails at (a failure is a
//! threshold crossing, so an ulp can move it).
//!
//! Paths: a random joint (every `Coupling` and `GfCalibration`, cohesion
//! from weak, `c < f_t tan φ`, to strong; `h` and `p0` over two decades) on
//! a random triangle, side b moved by random displacements from
//! `0.01 δnp` to `3 δnc` (compression, hardening, softening, failure, and
//! unloading between them), energy asked for at random steps.

use femdem_core::{Real, Vec3};
use femdem_fracture::{
    Coupling, GfCalibration, Joint, JointHistory, JointParams, KernelConsts, joint_update, joint_update_fast,
    joint_update_lanes,
};
use proptest::prelude::*;

fn joint_strategy() -> impl Strategy<Value = Joint> {
    (
        1e10f64..1e12,
        1e6f64..2e7,
        0.1f64..5.0,
        5.0f64..50.0,
        10.0f64..300.0,
        1.0f64..20.0,
        -4.0f64..-1.0,
        0usize..3,
        any::<bool>(),
    )
        .prop_map(|(penalty, ft, c_ratio, phi_deg, gf, gs_ratio, log_h, coupling, exact)| {
            let phi = phi_deg.to_radians();
            let params = JointParams {
                penalty,
                tensile_strength: ft,
                cohesion: ft * phi.tan() * c_ratio,
                friction_angle: phi,
                gf_tension: gf,
                gf_shear: gf * gs_ratio,
                calibration: if exact { GfCalibration::Exact } else { GfCalibration::Paper },
                coupling: [Coupling::Printed, Coupling::Multiplicative, Coupling::Capped][coupling],
            };
            Joint::new(params, 10f64.powf(log_h))
        })
}

/// One step of a path: a displacement of each node of side b, in units of
/// a length drawn on a log scale, and whether energy is asked for.
type Move = ([[Real; 3]; 3], Real, bool);

fn path_strategy() -> impl Strategy<Value = Vec<Move>> {
    prop::collection::vec(
        (prop::array::uniform3(prop::array::uniform3(-1.0f64..1.0)), 0.0f64..1.0, any::<bool>()),
        1..40,
    )
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(512))]

    #[test]
    fn fast_kernel_equals_the_law_bit_for_bit(
        joint in joint_strategy(),
        corners in prop::array::uniform3(prop::array::uniform3(-1.0f64..1.0)),
        path in path_strategy(),
    ) {
        let size = 3.0 * joint.h;
        let a = corners.map(|c| Vec3::new(c[0], c[1], c[2]) * size);
        prop_assume!((a[1] - a[0]).cross(&(a[2] - a[0])).norm() > 0.1 * size * size);
        let c = KernelConsts::new();
        let (mut h_law, mut h_fast) = (JointHistory::default(), JointHistory::default());
        // Displacement scale from 0.01 δnp to 3 δnc, log-uniform.
        let (lo, hi) = ((0.01 * joint.delta_np).ln(), (3.0 * joint.delta_nc).ln());
        for (step, (d, s, energy)) in path.iter().enumerate() {
            let scale: Real = (lo + s * (hi - lo)).exp();
            let d = d.map(|v| Vec3::new(v[0], v[1], v[2]) * scale);
            let x = [a[0], a[1], a[2], a[2] + d[2], a[1] + d[1], a[0] + d[0]];
            let law = joint_update(&joint, &mut h_law, &x, *energy);
            let fast = joint_update_fast(&c, &joint, &mut h_fast, &x, *energy);
            prop_assert_eq!(format!("{law:?}"), format!("{fast:?}"), "output at step {}", step);
            prop_assert_eq!(format!("{h_law:?}"), format!("{h_fast:?}"), "history at step {}", step);
        }
    }
}

/// `KernelConsts::z0` is `z(0)` of Eq. 12 (1 up to round-off).
#[test]
fn z0_is_z_of_zero() {
    assert_eq!(KernelConsts::new().z0.to_bits(), femdem_fracture::softening::z(0.0).to_bits());
    assert!((KernelConsts::new().z0 - 1.0).abs() < 1e-15);
}

/// The same comparison on 600 seeded paths (a plain generator, so the
/// coverage can be counted): the paths must reach every regime the fast
/// kernel treats apart — damage growing, damaged points unloading with
/// the damage unchanged (`z(D_hist)` reused), failure — under every
/// coupling, and agree bit for bit throughout.
#[test]
fn seeded_paths_cover_damage_and_failure() {
    let mut seed = 12345u64;
    let mut uniform = move || {
        seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        (seed >> 11) as Real / (1u64 << 53) as Real
    };
    let c = KernelConsts::new();
    let (mut growing, mut held, mut failed) = ([0usize; 3], [0usize; 3], [0usize; 3]);
    for case in 0..600 {
        let coupling = case % 3;
        let phi: Real = (5.0 + 45.0 * uniform()).to_radians();
        let ft = 1e6 + 1.9e7 * uniform();
        let params = JointParams {
            penalty: 1e10 * 100f64.powf(uniform()),
            tensile_strength: ft,
            cohesion: ft * phi.tan() * (0.1 + 4.9 * uniform()),
            friction_angle: phi,
            gf_tension: 10.0 + 290.0 * uniform(),
            gf_shear: 10.0 + 2000.0 * uniform(),
            calibration: if uniform() < 0.5 { GfCalibration::Paper } else { GfCalibration::Exact },
            coupling: [Coupling::Printed, Coupling::Multiplicative, Coupling::Capped][coupling],
        };
        let joint = Joint::new(params, 10f64.powf(-4.0 + 3.0 * uniform()));
        let size = 3.0 * joint.h;
        let a = [Vec3::zeros(), Vec3::new(size, 0.0, 0.0), Vec3::new(0.3 * size, size, 0.1 * size)];
        let (mut h_law, mut h_fast) = (JointHistory::default(), JointHistory::default());
        // A ramp towards a random direction to 1.5 δnc, with random
        // unloading steps on the way.
        let dir = Vec3::new(uniform() - 0.5, uniform() - 0.5, uniform() - 0.2).normalize();
        for step in 0..60 {
            let back = if uniform() < 0.2 { uniform() } else { 1.0 };
            let d = dir * (1.5 * joint.delta_nc * step as Real / 59.0 * back);
            let x = [a[0], a[1], a[2], a[2] + d, a[1] + d, a[0] + d];
            let before = h_law.damage;
            let energy = uniform() < 0.3;
            let law = joint_update(&joint, &mut h_law, &x, energy);
            let fast = joint_update_fast(&c, &joint, &mut h_fast, &x, energy);
            assert_eq!(format!("{law:?}"), format!("{fast:?}"), "case {case} step {step}");
            assert_eq!(format!("{h_law:?}"), format!("{h_fast:?}"), "case {case} step {step}");
            if h_law.failed {
                failed[coupling] += 1;
                break;
            }
            for (b, d) in before.iter().zip(h_law.damage) {
                if d > *b {
                    growing[coupling] += 1;
                } else if d > 0.0 {
                    held[coupling] += 1;
                }
            }
        }
    }
    for k in 0..3 {
        assert!(growing[k] > 100 && held[k] > 100 && failed[k] > 50, "{k}: {growing:?} {held:?} {failed:?}");
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    /// Four joints in lanes (`joint_update_lanes`) against the law, bit for
    /// bit, whenever the lanes take the four (same tolerance and reason as
    /// above: the same operations in the same order). Displacements from
    /// 1e-4 δnp to 2 δnp: mostly elastic, so the lanes are used, and now
    /// and then past a peak, where they must decline and leave the
    /// histories untouched.
    #[test]
    fn lanes_equal_the_law_bit_for_bit(
        joints in prop::array::uniform4(joint_strategy()),
        corners in prop::array::uniform4(prop::array::uniform3(prop::array::uniform3(-1.0f64..1.0))),
        path in prop::collection::vec(
            (prop::array::uniform4(prop::array::uniform3(prop::array::uniform3(-1.0f64..1.0))), 0.0f64..1.0),
            1..20,
        ),
        same_coupling in any::<bool>(),
    ) {
        let mut joints = joints;
        if same_coupling {
            let coupling = joints[0].params.coupling;
            for j in &mut joints {
                j.params.coupling = coupling;
            }
        }
        let mut base = [[Vec3::zeros(); 3]; 4];
        for l in 0..4 {
            let size = 3.0 * joints[l].h;
            base[l] = corners[l].map(|c| Vec3::new(c[0], c[1], c[2]) * size);
            let b = base[l];
            prop_assume!((b[1] - b[0]).cross(&(b[2] - b[0])).norm() > 0.1 * size * size);
        }
        let c = KernelConsts::new();
        let mut h_law = [JointHistory::default(); 4];
        let mut h_lanes = h_law;
        let mut taken = 0;
        for (step, (d, s)) in path.iter().enumerate() {
            let x: [[Vec3; 6]; 4] = std::array::from_fn(|l| {
                let scale = joints[l].delta_np * (1e-4f64.ln() * (1.0 - s) + 2f64.ln() * s).exp();
                let d = d[l].map(|v| Vec3::new(v[0], v[1], v[2]) * scale);
                let a = base[l];
                [a[0], a[1], a[2], a[2] + d[2], a[1] + d[1], a[0] + d[0]]
            });
            let law: [_; 4] = std::array::from_fn(|l| joint_update(&joints[l], &mut h_law[l], &x[l], false));
            let before = h_lanes;
            let mut forces = [[Vec3::zeros(); 6]; 4];
            if joint_update_lanes(&c, [&joints[0], &joints[1], &joints[2], &joints[3]], &mut h_lanes, &x, &mut forces) {
                taken += 1;
                for l in 0..4 {
                    prop_assert_eq!(format!("{:?}", law[l].forces), format!("{:?}", forces[l]), "step {} lane {}", step, l);
                }
            } else {
                prop_assert_eq!(format!("{before:?}"), format!("{h_lanes:?}"), "declined but wrote, step {}", step);
                for l in 0..4 {
                    joint_update_fast(&c, &joints[l], &mut h_lanes[l], &x[l], false);
                }
            }
            prop_assert_eq!(format!("{h_law:?}"), format!("{h_lanes:?}"), "history at step {}", step);
        }
        let _ = taken;
    }
}

/// The lanes take four intact joints loaded below their peaks — opened,
/// closed (compression) and slipped, for each coupling — and give the law's
/// forces and histories bit for bit, step after step.
#[test]
fn lanes_take_intact_joints() {
    let c = KernelConsts::new();
    for coupling in [Coupling::Printed, Coupling::Multiplicative, Coupling::Capped] {
        let params = JointParams {
            penalty: 2.6e11,
            tensile_strength: 3e6,
            cohesion: 15e6,
            friction_angle: 30f64.to_radians(),
            gf_tension: 50.0,
            gf_shear: 50.0,
            calibration: GfCalibration::Paper,
            coupling,
        };
        let joints: [Joint; 4] = std::array::from_fn(|l| Joint::new(params, 1e-3 * (1.0 + 0.1 * l as Real)));
        let a = [Vec3::zeros(), Vec3::new(1e-3, 0.0, 0.0), Vec3::new(0.2e-3, 1e-3, 0.1e-3)];
        let mut h_law = [JointHistory::default(); 4];
        let mut h_lanes = h_law;
        for step in 0..10 {
            let x: [[Vec3; 6]; 4] = std::array::from_fn(|l| {
                let s = (step as Real - 4.0) / 5.0 * joints[l].delta_np * 0.9;
                let d = Vec3::new(0.3 * s.abs(), -0.2 * s.abs(), s);
                [a[0], a[1], a[2], a[2] + d, a[1] + d * 1.1, a[0] + d * 0.9]
            });
            let law: [_; 4] = std::array::from_fn(|l| joint_update(&joints[l], &mut h_law[l], &x[l], false));
            let mut forces = [[Vec3::zeros(); 6]; 4];
            let refs = [&joints[0], &joints[1], &joints[2], &joints[3]];
            assert!(joint_update_lanes(&c, refs, &mut h_lanes, &x, &mut forces), "{coupling:?} step {step}");
            for l in 0..4 {
                assert_eq!(format!("{:?}", law[l].forces), format!("{:?}", forces[l]), "{coupling:?} step {step}");
            }
            assert_eq!(format!("{h_law:?}"), format!("{h_lanes:?}"), "{coupling:?} step {step}");
        }
    }
}
