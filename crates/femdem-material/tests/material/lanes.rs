//! The tet lanes (`tet_forces_lanes`) give the scalar kernel's forces bit
//! for bit: four random tets at a time, each with its own material (with and
//! without viscosity), stretched, sheared, compressed past the `J` floor
//! and inverted, with random velocities. Compared by `to_bits`, so a
//! difference in the sign of a zero counts; any law but neo-Hookean in a
//! group is refused.

use femdem_core::Vec3;
use femdem_material::{ElasticParams, Law, TET_LANES, TetReference, tet_forces, tet_forces_lanes};
use proptest::prelude::*;

fn tet(nodes: [[f64; 3]; 4]) -> [Vec3; 4] {
    nodes.map(|p| Vec3::new(p[0], p[1], p[2]))
}

/// A random tet near the unit corner tet (scaled to `size`), its current
/// nodes the reference ones under a random affine map (strains up to about
/// ±60%, `J` from below zero to about 4) plus a small random jitter, and
/// random velocities.
fn case() -> impl Strategy<Value = ([Vec3; 4], [Vec3; 4], [Vec3; 4], f64, f64)> {
    let v3 = || prop::array::uniform3(-1.0f64..1.0);
    (
        prop::array::uniform4(v3()),
        prop::array::uniform3(v3()),
        prop::array::uniform4(v3()),
        prop::array::uniform4(v3()),
        1e-3f64..1.0,
        prop::bool::ANY,
        1e9f64..80e9,
    )
        .prop_map(|(jitter0, map, jitter, vel, size, viscous, young)| {
            let corner = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
            let x0 = tet(corner.map(|p| p.map(|c| c * size)));
            let x0 = std::array::from_fn(|k| x0[k] + Vec3::from(jitter0[k]) * (0.1 * size));
            let m = nalgebra::Matrix3::from_fn(|r, c| (if r == c { 1.0 } else { 0.0 }) + 0.6 * map[r][c]);
            let x = std::array::from_fn(|k| m * x0[k] + Vec3::from(jitter[k]) * (0.05 * size));
            let v = vel.map(|p| Vec3::from(p) * 3.0);
            (x0, x, v, young, if viscous { 1e5 * size } else { 0.0 })
        })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(400))]

    #[test]
    fn lanes_give_the_scalar_kernels_forces_bit_for_bit(cases in prop::array::uniform4(case())) {
        let mut refs = Vec::new();
        let mut mats = Vec::new();
        for (x0, _, _, young, viscosity) in &cases {
            let Some(r) = TetReference::new(x0) else { return Ok(()) };
            refs.push(r);
            mats.push(ElasticParams { young: *young, poisson: 0.25, density: 2500.0, viscosity: *viscosity }.validate().unwrap());
        }
        let x: [[Vec3; 4]; TET_LANES] = std::array::from_fn(|l| cases[l].1);
        let v: [[Vec3; 4]; TET_LANES] = std::array::from_fn(|l| cases[l].2);
        let mut forces = [[Vec3::zeros(); 4]; TET_LANES];
        let laws = [Law::NeoHookean; TET_LANES];
        prop_assert!(tet_forces_lanes(laws, std::array::from_fn(|l| &mats[l]), std::array::from_fn(|l| &refs[l]), &x, &v, &mut forces));
        for l in 0..TET_LANES {
            let scalar = tet_forces(Law::NeoHookean, &mats[l], &refs[l], &x[l], &v[l]);
            for (a, b) in forces[l].iter().zip(&scalar.forces) {
                for (p, q) in a.iter().zip(b.iter()) {
                    prop_assert_eq!(p.to_bits(), q.to_bits(), "lane {}: {} against {}", l, p, q);
                }
            }
        }
    }
}

/// Past the floor and inverted: `J` of 0.5 %, of exactly zero and of −0.3
/// (one lane each, the fourth stretched) go through the continued law's
/// branch and still agree bit for bit.
#[test]
fn lanes_agree_below_the_floor_and_inverted() {
    let x0 = tet([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]);
    let squash = |s: f64| [x0[0], x0[1], x0[2], Vec3::new(0.1, 0.2, s)];
    let x = [squash(0.005), squash(0.0), squash(-0.3), squash(1.7)];
    let v = [[Vec3::new(0.1, -0.2, 0.3), Vec3::zeros(), Vec3::new(-0.5, 0.0, 0.2), Vec3::new(0.0, 1.0, 0.0)]; 4];
    let r = TetReference::new(&x0).unwrap();
    let m = ElasticParams { young: 26e9, poisson: 0.2, density: 2340.0, viscosity: 2e4 }.validate().unwrap();
    let mut forces = [[Vec3::zeros(); 4]; TET_LANES];
    assert!(tet_forces_lanes([Law::NeoHookean; 4], [&m; 4], [&r; 4], &x, &v, &mut forces));
    for l in 0..TET_LANES {
        let scalar = tet_forces(Law::NeoHookean, &m, &r, &x[l], &v[l]);
        assert!(scalar.forces.iter().all(|f| f.iter().all(|c| c.is_finite())));
        for (a, b) in forces[l].iter().zip(&scalar.forces) {
            assert!(a.iter().zip(b.iter()).all(|(p, q)| p.to_bits() == q.to_bits()), "lane {l}: {a:?} against {b:?}");
        }
    }
}

/// A group with a linear-elastic tet is refused, and nothing is written.
#[test]
fn lanes_refuse_other_laws() {
    let x0 = tet([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]);
    let r = TetReference::new(&x0).unwrap();
    let m = ElasticParams { young: 26e9, poisson: 0.2, density: 2340.0, viscosity: 0.0 }.validate().unwrap();
    let mut forces = [[Vec3::new(7.0, 7.0, 7.0); 4]; TET_LANES];
    let laws = [Law::NeoHookean, Law::NeoHookean, Law::LinearElastic, Law::NeoHookean];
    assert!(!tet_forces_lanes(laws, [&m; 4], [&r; 4], &[x0; 4], &[[Vec3::zeros(); 4]; 4], &mut forces));
    assert!(forces.iter().flatten().all(|f| *f == Vec3::new(7.0, 7.0, 7.0)));
}
