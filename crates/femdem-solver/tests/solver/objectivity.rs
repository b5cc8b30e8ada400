//! Objectivity (frame indifference) of the tets (Eq. 1) and of the joints
//! (their local frame rotates with the mid-plane, §2.2), and conservation
//! in free rigid spin.
//!
//! * A rigid rotation `x = R x0` by 90° produces no stress and no joint
//!   force: `|σ| / E < 1e-9` (round-off of `F = R`, `B = R Rᵀ`).
//! * A rotated stretched state has the rotated stress `R σ Rᵀ`.
//! * A free joint-meshed body spinning at `ω` (no loads, η = 0) keeps its
//!   angular momentum `Σ m x_{n+1} × v_{n+½}`, which the leapfrog update
//!   conserves exactly for torque-free internal forces (so only round-off,
//!   1e-10 relative), and its energy within 0.1% (leapfrog energy error is
//!   bounded, of order (ω_max Δt)² × the small centrifugal strain energy,
//!   far below the kinetic energy of the spin).

fn history(m: &femdem_solver::Model) -> Vec<femdem_fracture::JointHistory> {
    vec![femdem_fracture::JointHistory::default(); m.joints.len()]
}

use crate::common::{box_mesh, model, rock, solver};
use femdem_core::{Mat3, Real, Vec3};
use femdem_material::Law;
use femdem_solver::Loads;
use femdem_solver::forces::{Dissipation, Want, Workspace, internal_forces};
use nalgebra::Rotation3;

fn rotation_90() -> Mat3 {
    let axis = nalgebra::Unit::new_normalize(Vec3::new(1.0, 2.0, 3.0));
    *Rotation3::from_axis_angle(&axis, std::f64::consts::FRAC_PI_2).matrix()
}

#[test]
fn rigid_rotation_by_90_degrees_makes_no_stress() {
    let mesh = box_mesh([0.0; 3], [0.06, 0.05, 0.04], 0.01, 0.12, true);
    let (_, m) = model(&mesh, Law::NeoHookean, rock(0.0), 10.0 * 26e9);
    let r = rotation_90();
    let x: Vec<Vec3> = m.x0.iter().map(|p| r * p).collect();
    let mut ws = Workspace::new(&m);
    internal_forces(
        &m,
        &x,
        &vec![Vec3::zeros(); x.len()],
        &mut history(&m),
        &mut ws,
        Want { stress: true, ..Want::default() },
        Dissipation::None,
    );
    let worst = ws.stress.iter().map(|s| s.norm()).fold(0.0, Real::max);
    assert!(worst / 26e9 < 1e-9, "max |σ|/E = {}", worst / 26e9);
    let joint_force = ws.joint_slots.iter().flatten().map(|f| f.norm()).fold(0.0, Real::max);
    // A joint force of 1e-9·E·h² would be the same relative level.
    assert!(joint_force < 1e-9 * 26e9 * 1e-4, "max joint force {joint_force} N");
}

#[test]
fn rotated_stretch_gives_rotated_stress() {
    let mesh = box_mesh([0.0; 3], [0.06, 0.05, 0.04], 0.01, 0.12, false);
    let (_, m) = model(&mesh, Law::NeoHookean, rock(0.0), 0.0);
    let u = Mat3::new(1.01, 0.002, 0.0, 0.002, 0.995, 0.001, 0.0, 0.001, 1.003);
    let r = rotation_90();
    let mut ws = Workspace::new(&m);
    let zero = vec![Vec3::zeros(); m.num_nodes()];
    let stretched: Vec<Vec3> = m.x0.iter().map(|p| u * p).collect();
    internal_forces(
        &m,
        &stretched,
        &zero,
        &mut history(&m),
        &mut ws,
        Want { stress: true, ..Want::default() },
        Dissipation::None,
    );
    let s0 = ws.stress[0];
    let rotated: Vec<Vec3> = m.x0.iter().map(|p| r * u * p).collect();
    internal_forces(
        &m,
        &rotated,
        &zero,
        &mut history(&m),
        &mut ws,
        Want { stress: true, ..Want::default() },
        Dissipation::None,
    );
    let expected = r * s0 * r.transpose();
    assert!((ws.stress[0] - expected).norm() < 1e-10 * s0.norm());
}

#[test]
fn free_spin_keeps_angular_momentum_and_energy() {
    let mesh = box_mesh([-0.03, -0.025, -0.02], [0.03, 0.025, 0.02], 0.01, 0.1, true);
    let (_, m) = model(&mesh, Law::NeoHookean, rock(0.0), 10.0 * 26e9);
    let mut s = solver(m, Loads::default(), 0.9);
    let omega = Vec3::new(0.0, 0.0, 200.0); // rad/s: rim speed 8 m/s
    s.set_velocity(|x| omega.cross(x));
    let momentum = |s: &femdem_solver::Solver| -> Vec3 {
        (0..s.model().num_nodes()).map(|i| s.state().x[i].cross(&s.state().v[i]) * s.model().mass[i]).sum()
    };
    let energy =
        |s: &femdem_solver::Solver| s.energies().kinetic + s.energies().tet_elastic + s.energies().joint_elastic;
    s.step(Want { energy: true, ..Want::default() });
    let (l0, e0) = (momentum(&s), energy(&s));
    let mut worst_e: Real = 0.0;
    for n in 0..2000 {
        s.step(Want { energy: n % 50 == 0, ..Want::default() });
        if n % 50 == 0 {
            worst_e = worst_e.max((energy(&s) - e0).abs() / e0);
        }
    }
    let l1 = momentum(&s);
    assert!((l1 - l0).norm() / l0.norm() < 1e-10, "angular momentum drift {}", (l1 - l0).norm() / l0.norm());
    assert!(worst_e < 1e-3, "energy drift {worst_e}");
    // The body turned by ω t, and the stresses stay small (centrifugal only).
    let turned = 200.0 * s.state().time;
    assert!(turned > 0.01, "the test must turn the body noticeably, turned {turned} rad");
}
