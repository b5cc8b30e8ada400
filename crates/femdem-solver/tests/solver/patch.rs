//! Patch test (Irons; e.g. Zienkiewicz & Taylor, The Finite Element Method,
//! vol. 1, §9): a linear tet mesh under a displacement field that is linear
//! in space must reproduce the uniform stress of that strain exactly, and
//! every interior vertex must be in equilibrium.
//!
//! With `x = x0 + G x0`, `F = I + G` in every tet, so each tet's stress is
//! `σ(F)` of the law (checked to round-off, 1e-12 relative), and the nodal
//! forces of the tets around an interior vertex cancel to round-off. The
//! stress is computed from `F − I ≈ 1e-3`, which leaves about 13 significant
//! digits, and some 20 tet forces of size `|σ| h²` meet at a vertex, so the
//! net force is checked against 1e-10 `|σ| h²` (measured: ~1.5e-12). In a joint-meshed body the copies of
//! a vertex belong to different tets; the affine map keeps coincident joint
//! nodes coincident, so the joints carry nothing and the equilibrium of the
//! continuum holds on the sum over all copies (`origin`) of each vertex.

fn history(m: &femdem_solver::Model) -> Vec<femdem_fracture::JointHistory> {
    vec![femdem_fracture::JointHistory::default(); m.joints.len()]
}

use crate::common::{box_mesh, model, rock};
use femdem_core::{Mat3, Vec3};
use femdem_material::{Law, cauchy_stress};
use femdem_solver::forces::{Dissipation, Want, Workspace, internal_forces};

fn run_patch(breakable: bool, law: Law) {
    let mesh = box_mesh([0.0; 3], [0.1, 0.08, 0.06], 0.02, 0.12, breakable);
    let material = rock(0.0);
    let (jointed, m) = model(&mesh, law, material, 10.0 * 26e9);
    let g = Mat3::new(1.0e-3, 2.0e-4, -3.0e-4, 5.0e-4, -8.0e-4, 1.0e-4, -2.0e-4, 3.0e-4, 6.0e-4);
    let x: Vec<Vec3> = m.x0.iter().map(|p| p + g * p).collect();
    let v = vec![Vec3::zeros(); x.len()];
    let mut ws = Workspace::new(&m);
    internal_forces(&m, &x, &v, &mut history(&m), &mut ws, Want { stress: true, ..Want::default() }, Dissipation::None);

    let expected = cauchy_stress(law, &material, &(Mat3::identity() + g), &Mat3::zeros());
    let scale = expected.norm();
    for (t, s) in ws.stress.iter().enumerate() {
        assert!((s - expected).norm() <= 1e-12 * scale, "tet {t}: {s} vs {expected}");
    }

    // Sum the forces on the copies of each original vertex.
    let mut per_vertex = vec![Vec3::zeros(); mesh.num_nodes()];
    for (n, f) in ws.internal.iter().enumerate() {
        per_vertex[jointed.origin[n] as usize] += f;
    }
    let (lo, hi) = mesh.bounding_box().unwrap();
    let h = 0.02;
    let typical = scale * h * h;
    let mut interior = 0;
    for (vtx, f) in per_vertex.iter().enumerate() {
        let c = mesh.coords[vtx];
        if (0..3).all(|a| c[a] > lo[a] + 1e-9 && c[a] < hi[a] - 1e-9) {
            interior += 1;
            assert!(f.norm() <= 1e-10 * typical, "vertex {vtx}: net force {}", f.norm());
        }
    }
    assert!(interior > 10, "the patch must have interior vertices");
    if breakable {
        assert!(ws.joint_slots.iter().flatten().all(|f| f.norm() == 0.0), "affine motion opens no joint");
    }
}

#[test]
fn jointless_mesh_passes_the_neo_hookean_patch_test() {
    run_patch(false, Law::NeoHookean);
}

#[test]
fn jointless_mesh_passes_the_linear_patch_test() {
    run_patch(false, Law::LinearElastic);
}

#[test]
fn joint_meshed_body_passes_the_patch_test_on_its_vertices() {
    run_patch(true, Law::NeoHookean);
}
