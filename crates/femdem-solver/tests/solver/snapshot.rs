//! A solver restored from a snapshot continues bit for bit as the one that
//! took it (`Solver::snapshot`, `Solver::restore`): a jointed block sheared
//! and pressed by its top until joints fail, with contact (friction 0.6,
//! a detection buffer, so the last detection's candidates and positions
//! are part of the state) stepped 300 steps, snapshot, then 300 more; a
//! second solver built the same way and restored from the snapshot takes
//! the same 300 steps and ends in the same bits — positions, velocities,
//! joint histories, energies and the watch on their balance, the failure
//! record, the step record and the contact pass's whole state (its own
//! snapshot). The snapshot is taken
//! while joints fail and pairs are in contact (asserted), and the steps
//! ask for energies and stresses on an irregular schedule, as a run's
//! output does.

use crate::common::{box_mesh, joints, rock, stable};
use femdem_core::Vec3;
use femdem_material::{Law, critical_viscosity};
use femdem_mesh::insert_joints;
use femdem_solver::select::{NodeSelection, select_nodes};
use femdem_solver::{
    ContactSettings, Fixed, Loads, Model, Ramp, RegionBehaviour, Solver, SolverError, StepParams, VelocityDrive, Want,
    contact_omega,
};

const H: f64 = 0.0025;
const PENALTY: f64 = 26e9;

/// The block, bottom held, top driven at `(5, 0, −2)` m/s, contact on.
fn block(size: [f64; 3]) -> Solver {
    let mesh = box_mesh([0.0; 3], size, H, 0.15, true);
    let jointed = insert_joints(&mesh).unwrap();
    let visc = critical_viscosity(H, 26e9, 2340.0) * 0.1;
    // Weak joints (a tenth of the paper's strengths) break within the test.
    let params = femdem_fracture::JointParams { tensile_strength: 3e5, cohesion: 1.5e6, ..joints(10.0 * 26e9) };
    let behaviour = [RegionBehaviour::Deformable { law: Law::NeoHookean, material: rock(visc), joints: Some(params) }];
    let m = Model::new(&jointed, &behaviour, 1.0).unwrap();
    let sel = |g: &str| select_nodes(&jointed, &NodeSelection { group: Some(g.into()), ..Default::default() }).unwrap();
    let loads = Loads {
        fixed: vec![Fixed { nodes: sel("zmin"), components: [true; 3] }],
        drives: vec![VelocityDrive {
            name: "top".into(),
            nodes: sel("zmax"),
            velocity: Vec3::new(5.0, 0.0, -2.0),
            components: [true; 3],
            ramp: Ramp { ramp_time: 2e-6, stop_time: None },
            start_time: None,
        }],
        ..Loads::default()
    };
    let st = stable(&m, &loads, 300).with_contact(contact_omega(&m, PENALTY));
    let mut s = Solver::new(m, loads, StepParams::new(0.9 * st.critical).unwrap()).unwrap();
    let settings = ContactSettings { surfaces: false, friction: 0.6, buffer: 2e-4, ..ContactSettings::new(PENALTY) };
    s.enable_contact(settings, &[]);
    s
}

fn want(n: u64) -> Want {
    Want { energy: n % 7 == 0, stress: n % 50 == 3 }
}

#[test]
fn a_restored_solver_continues_bit_for_bit() {
    let size = [0.02, 0.01, 0.02];
    let mut a = block(size);
    for n in 0..300 {
        a.step(want(n));
    }
    let failed = a.failures().len();
    let pairs = a.contact().unwrap().active_pairs;
    assert!(failed > 0 && pairs > 0, "the snapshot must be taken with joints failed ({failed}) and contacts ({pairs})");
    let snap = a.snapshot();

    let mut b = block(size);
    b.restore(&snap).unwrap();
    assert!(b.snapshot() == snap, "restoring then snapshotting gives other bytes");
    for n in 300..600 {
        a.step(want(n));
        b.step(want(n));
    }
    assert!(a.failures().len() > failed, "joints keep failing after the snapshot");
    assert_eq!(a.state, b.state, "positions, velocities, joint histories");
    assert_eq!(a.energies(), b.energies());
    assert_eq!(a.imbalance(), b.imbalance(), "the energy watch");
    assert_eq!(a.failures(), b.failures());
    assert_eq!(a.record(), b.record());
    assert!(a.snapshot() == b.snapshot(), "the whole state, contact included, differs");
}

#[test]
fn a_snapshot_of_another_model_or_a_truncated_one_is_refused() {
    let mut a = block([0.02, 0.01, 0.02]);
    a.step(Want::default());
    let snap = a.snapshot();
    let mut other = block([0.02, 0.01, 0.01]);
    let err = other.restore(&snap).unwrap_err();
    assert!(matches!(err, SolverError::Snapshot(_)), "{err}");
    let before = other.snapshot();
    let mut same = block([0.02, 0.01, 0.02]);
    for cut in [0, 4, snap.len() / 2, snap.len() - 1] {
        let err = same.restore(&snap[..cut]).unwrap_err();
        assert!(err.to_string().starts_with("snapshot: "), "cut at {cut}: {err}");
    }
    assert!(other.snapshot() == before, "a refused snapshot changed the solver");
}
