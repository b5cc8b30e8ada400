//! Shared fixtures of the integration tests: the paper's rock, random
//! well-shaped tets, rotations.

#![allow(dead_code)]

use femdem_core::tet::{aspect_ratio, edge_lengths, signed_volume};
use femdem_core::{Mat3, Real, Vec3};
use femdem_material::{ElasticParams, Material, TetReference};
use proptest::prelude::*;

/// Table 1 of the reference paper (Brazilian test rock), with viscosity
/// `eta` (Pa·s).
pub fn rock(eta: Real) -> Material {
    ElasticParams { young: 26e9, poisson: 0.2, density: 2340.0, viscosity: eta }.validate().unwrap()
}

/// A fixed, well-shaped, positive tet that is not axis-aligned.
pub fn skew_tet() -> [Vec3; 4] {
    [Vec3::new(0.1, 0.0, 0.2), Vec3::new(1.3, 0.1, 0.0), Vec3::new(0.2, 0.9, 0.1), Vec3::new(0.4, 0.3, 1.1)]
}

/// Rotation by `angle` (rad) about `axis` (any non-zero vector).
pub fn rotation(axis: Vec3, angle: Real) -> Mat3 {
    nalgebra::Rotation3::from_axis_angle(&nalgebra::Unit::new_normalize(axis), angle).into_inner()
}

/// Longest edge.
pub fn max_edge(x: &[Vec3; 4]) -> Real {
    edge_lengths(x).into_iter().fold(0.0, Real::max)
}

/// Applies `x ↦ a x + c` to every node.
pub fn map(x: &[Vec3; 4], a: &Mat3, c: &Vec3) -> [Vec3; 4] {
    x.map(|p| a * p + c)
}

/// A point of the cube `[-s, s]³`.
pub fn vec3(s: Real) -> impl Strategy<Value = Vec3> {
    (-s..s, -s..s, -s..s).prop_map(|(x, y, z)| Vec3::new(x, y, z))
}

/// Four points of `[-s, s]³`.
pub fn points(s: Real) -> impl Strategy<Value = [Vec3; 4]> {
    prop::array::uniform4(vec3(s))
}

/// A random positive tet in `[-1, 1]³` with aspect ratio at most 6 (so the
/// condition number of `Dm` is bounded and round-off estimates hold).
pub fn good_tet() -> impl Strategy<Value = [Vec3; 4]> {
    points(1.0)
        .prop_map(|mut x| {
            if signed_volume(&x) < 0.0 {
                x.swap(1, 2);
            }
            x
        })
        .prop_filter("well-shaped positive tet", |x| aspect_ratio(x) <= 6.0)
}

/// A random rotation (axis in the cube, angle in [0, 2π)).
pub fn any_rotation() -> impl Strategy<Value = Mat3> {
    (vec3(1.0), 0.0..std::f64::consts::TAU)
        .prop_filter("non-zero axis", |(a, _)| a.norm() > 1e-3)
        .prop_map(|(a, t)| rotation(a, t))
}

/// The reference data of a tet known to be positive.
pub fn reference(x0: &[Vec3; 4]) -> TetReference {
    TetReference::new(x0).expect("positive tet")
}
