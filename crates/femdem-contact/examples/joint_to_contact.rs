//! From a cohesive joint to contact, without the femdem solver: two tets
//! bonded by one joint (`femdem-fracture`) are pulled apart by hand until
//! the joint fails, then pushed back together, and `femdem-contact` finds
//! the pair and pushes them apart.
//!
//! Run it with
//!
//! ```sh
//! cargo run --release --example joint_to_contact -p femdem-contact
//! ```
//!
//! The two tets share the face `z = 0`: tet A below, tet B above. The joint
//! ties A's copy of the face (`N1 N2 N3`) to B's (`N4 N5 N6`, with `N1–N6`,
//! `N2–N5`, `N3–N4` coincident; Fig. 2 of the reference paper). Each
//! increment moves B up by 1 µm and calls `joint_update`: the normal stress
//! rises to the tensile strength at `δnp`, softens, and the joint fails in
//! tension once the opening reaches `δnc` (Eq. 10: `3 G_f / f_t = 50 µm`).
//! B is then moved back down into A: bounding spheres and NBS give the
//! candidate pair, and `tet_tet_forces` (Eq. 17) gives a force that pushes
//! B up and A down, equal and opposite, where the failed joint gives none.

use femdem_contact::{Nbs, Pair, tet_tet_forces};
use femdem_core::Vec3;
use femdem_core::tet::{centroid, signed_volume};
use femdem_fracture::{Coupling, FailureMode, GfCalibration, Joint, JointHistory, JointParams, joint_update};

/// Edge of the tets' right-angle corner, m.
const H: f64 = 0.01;
/// Contact penalty, Pa (the Young's modulus of the paper's concrete).
const CONTACT_PENALTY: f64 = 26e9;
/// The tets' nodes: A = 0..4, B = 4..8.
const TETS: [[usize; 4]; 2] = [[0, 1, 2, 3], [4, 5, 6, 7]];
/// The joint `[N1, …, N6]`: A's face nodes counter-clockwise seen from
/// below (so `(N2 − N1) × (N3 − N1)` points from A to B), then B's nodes at
/// the positions of `N3`, `N2`, `N1`.
const JOINT: [usize; 6] = [0, 2, 1, 6, 5, 4];

/// The joint's parameters, all in one place: the paper's concrete (Table 1:
/// `f_t` = 3 MPa, `c` = 15 MPa, `φ` = 30°, `G_f` = 50 J/m²) with the penalty
/// `p0 = E` = 26 GPa, the low end of Eq. 9's range, so that the hardening
/// branch spans a few of the 1 µm increments.
fn joint_params() -> JointParams {
    JointParams {
        penalty: 26e9,
        tensile_strength: 3e6,
        cohesion: 15e6,
        friction_angle: 30f64.to_radians(),
        gf_tension: 50.0,
        gf_shear: 50.0,
        calibration: GfCalibration::Paper,
        coupling: Coupling::Capped,
    }
    .validate()
    .expect("the example's joint parameters are valid")
}

/// The eight nodes with B moved up by `dz` (negative: into A).
fn positions(dz: f64) -> [Vec3; 8] {
    let up = Vec3::new(0.0, 0.0, dz);
    [
        // A, below z = 0.
        Vec3::zeros(),
        Vec3::new(0.0, H, 0.0),
        Vec3::new(H, 0.0, 0.0),
        Vec3::new(0.0, 0.0, -H),
        // B, above z = 0.
        Vec3::zeros() + up,
        Vec3::new(H, 0.0, 0.0) + up,
        Vec3::new(0.0, H, 0.0) + up,
        Vec3::new(0.0, 0.0, H) + up,
    ]
}

fn gather<const N: usize>(x: &[Vec3; 8], nodes: [usize; N]) -> [Vec3; N] {
    nodes.map(|n| x[n])
}

fn main() {
    let x0 = positions(0.0);
    assert!(TETS.iter().all(|&t| signed_volume(&gather(&x0, t)) > 0.0), "positive tets");
    let face = gather(&x0, [JOINT[0], JOINT[1], JOINT[2]]);
    let h = ((face[1] - face[0]).norm() + (face[2] - face[1]).norm() + (face[0] - face[2]).norm()) / 3.0;
    let joint = Joint::new(joint_params(), h);
    let ft = joint.params.tensile_strength;
    println!("Two tets bonded by one joint (mean edge h = {:.2} mm), B pulled up 1 µm per increment:", h * 1e3);
    println!("peak at δnp = {:.2} µm, failure at δnc = {:.1} µm\n", joint.delta_np * 1e6, joint.delta_nc * 1e6);
    println!("{:>5}  {:>11}  {:>8}  {:>7}  {:>15}", "step", "opening, µm", "σ, MPa", "damage", "joint on B, N");

    // 1. Pull B away from A until the joint fails.
    let mut history = JointHistory::default();
    let mut step = 0;
    let (opening, mode) = loop {
        let dz = step as f64 * 1e-6;
        let out = joint_update(&joint, &mut history, &gather(&positions(dz), JOINT), false);
        let on_b: Vec3 = out.forces[3..].iter().sum();
        let damage = history.damage.iter().copied().fold(0.0, f64::max);
        if step == 1 {
            // The hardening branch of Eq. 11: σ = (2r − r²) f_t, r = δ/δnp.
            let r = dz / joint.delta_np;
            assert!((out.normal_stress / ((2.0 * r - r * r) * ft) - 1.0).abs() < 1e-6);
        }
        if let Some(mode) = out.failed {
            println!("{step:>5}  {:>11.3}  {:>8}  {:>7}  {:>15}", dz * 1e6, "-", "1", format!("failed: {mode:?}"));
            break (dz, mode);
        }
        if step < 5 || step % 10 == 0 {
            println!(
                "{step:>5}  {:>11.3}  {:>8.3}  {:>7.4}  {:>15.3}",
                dz * 1e6,
                out.normal_stress * 1e-6,
                damage,
                on_b.z
            );
        }
        step += 1;
    };
    assert_eq!(mode, FailureMode::Tensile);
    assert!(opening >= joint.delta_nc && opening < joint.delta_nc + 1.5e-6);

    // 2. Contact takes over: detect the pair with a margin, as a solver
    //    would once the joint has failed.
    let x = positions(opening);
    let tets = TETS.map(|t| gather(&x, t));
    let centers = tets.map(|t| centroid(&t));
    let radii: Vec<f64> =
        tets.iter().zip(&centers).map(|(t, c)| t.iter().map(|p| (p - c).norm()).fold(0.0, f64::max)).collect();
    let margin = 1e-4;
    let mut pairs = Vec::new();
    Nbs::new().detect(&centers, &radii, margin, &mut pairs);
    assert_eq!(pairs, [Pair::new(0, 1).unwrap()]);
    let found: Vec<(u32, u32)> = pairs.iter().map(|p| p.indices()).collect();
    println!("\nThe joint has failed. NBS candidate pairs (margin {} mm): {found:?}", margin * 1e3);

    // 3. Push B back down through its starting position into A, and
    //    evaluate the pair at each position.
    println!(
        "\n{:>10}  {:>13}  {:>13}  {:>13}  {:>14}",
        "B at, µm", "joint on B, N", "contact on B", "contact on A", "|sum|, N"
    );
    let (a, b) = pairs[0].indices();
    for dz_um in [20.0, 0.0, -10.0, -50.0, -100.0, -200.0] {
        let x = positions(dz_um * 1e-6);
        let joint_out = joint_update(&joint, &mut history, &gather(&x, JOINT), false);
        let (fa, fb) = tet_tet_forces(&gather(&x, TETS[a as usize]), &gather(&x, TETS[b as usize]), CONTACT_PENALTY);
        let (on_a, on_b): (Vec3, Vec3) = (fa.iter().sum(), fb.iter().sum());
        let on_b_from_joint: Vec3 = joint_out.forces[3..].iter().sum();
        println!(
            "{dz_um:>10.1}  {:>13.3}  {:>13.4e}  {:>13.4e}  {:>14.3e}",
            on_b_from_joint.z,
            on_b.z,
            on_a.z,
            (on_a + on_b).norm()
        );
        assert_eq!(on_b_from_joint, Vec3::zeros(), "a failed joint exerts nothing");
        assert!((on_a + on_b).norm() <= 1e-12 * on_b.norm().max(1e-300), "equal and opposite");
        if dz_um < 0.0 {
            assert!(on_b.z > 0.0 && on_a.z < 0.0, "overlapping tets are pushed apart");
        } else {
            assert_eq!(on_b, Vec3::zeros(), "no overlap, no force");
        }
    }
    println!("\n(forces in N along z; \"B at\" is B's offset from its bonded position, negative: into A)");
}
