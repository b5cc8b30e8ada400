//! Contact transmits a compressive load (reference paper §2.3, Eq. 17–18).
//!
//! * Two cubes pressed face to face, on non-matching meshes: the lower one
//!   held at its base, a pressure `P` on the upper one's top. At rest
//!   (damped), equilibrium of each cube gives: the contact force on the
//!   lower cube and the base reaction both equal `P A` (`A` the loaded
//!   face). Checked within 1% (the residual of the damped settling).
//! * A jointed column under the same kind of load, whose mid-plane joints
//!   are then broken (`Solver::break_joints`): they are closed, so the
//!   contact between the two halves is ramped in over 10 steps (Eq. 18)
//!   while the load passes from joints to contact. The load path must
//!   survive: the base reaction stays within 10% of `P A` through the
//!   switch (when written: 192.6 to 210.9 N for 200 N, a band the residual
//!   ringing of the damped settling alone nearly fills), settles back to
//!   `P A` within 1%, and the contact then carries all of it across the cut
//!   (within 1%). The energy account still closes to 1% of the work done
//!   (0.1% when written; it was 7% while joint work was summed with the
//!   rectangle rule, which books the ringing of intact joints as fracture).
//! * The same column with its mid-plane broken, run on with every candidate
//!   pair evaluated (`negligible = 0`) and with negligible pairs skipped
//!   (the default): the tets that meet only at a vertex or an edge across
//!   the cut are skipped, and the two runs differ by far less than an
//!   order-of-magnitude allowance for what the skipped forces could move
//!   (see the test).

use crate::common::{at_step, box_mesh, joints, rock, stable};
use femdem_core::Vec3;
use femdem_material::{Law, critical_viscosity};
use femdem_mesh::{JointedMesh, insert_joints};
use femdem_solver::select::{NodeSelection, group_faces, select_nodes};
use femdem_solver::{
    ContactSettings, Loads, Model, Ramp, RegionBehaviour, Solver, SurfaceKind, SurfaceLoad, VelocityDrive, Want,
    contact_omega,
};

const P: f64 = 2e6;

/// Loads: the nodes at `z = 0` held by a zero-velocity drive, pressure `P`
/// on the faces of group `zmax` ramped over `ramp` s.
fn loads(jointed: &JointedMesh, ramp: f64) -> Loads {
    let z = |n: u32| jointed.mesh.coords[n as usize][2];
    let base: Vec<u32> = select_nodes(jointed, &NodeSelection { group: Some("zmin".into()), ..Default::default() })
        .unwrap()
        .into_iter()
        .filter(|&n| z(n) < 1e-12)
        .collect();
    let top = group_faces(jointed, "zmax").unwrap();
    let z_top = top.iter().map(|f| z(f[0])).fold(0.0, f64::max);
    let top = top.into_iter().filter(|f| z(f[0]) > z_top - 1e-9).collect();
    Loads {
        drives: vec![VelocityDrive {
            name: "base".into(),
            nodes: base,
            velocity: Vec3::zeros(),
            components: [true; 3],
            ramp: Ramp::STEP,
            start_time: None,
        }],
        surfaces: vec![SurfaceLoad {
            name: "top".into(),
            faces: top,
            kind: SurfaceKind::Pressure(P),
            ramp: Ramp { ramp_time: ramp, stop_time: None },
        }],
        ..Loads::default()
    }
}

fn start(model: Model, loads: Loads, settings: ContactSettings) -> Solver {
    let stable = stable(&model, &loads, 300).with_contact(contact_omega(&model, settings.penalty));
    let mut s = at_step(model, loads, 0.9 * stable.critical);
    s.enable_contact(settings, &[]);
    s
}

#[test]
fn cubes_pressed_face_to_face_transmit_the_load() {
    let h = 0.004;
    let mut mesh = box_mesh([0.0; 3], [0.02, 0.02, 0.02], h, 0.1, false);
    // The upper cube: smaller, offset, meshed differently.
    let n_lower = mesh.tets.len();
    let upper = box_mesh([0.003, 0.004, 0.02], [0.017, 0.016, 0.032], 0.003, 0.1, false);
    mesh.append(&upper);
    let jointed = insert_joints(&mesh).unwrap();
    let visc = critical_viscosity(h, 26e9, 2340.0);
    let behaviour = [RegionBehaviour::Deformable { law: Law::NeoHookean, material: rock(visc), joints: None }];
    let model = Model::new(&jointed, &behaviour, 1.0).unwrap();
    let area = 0.014 * 0.012;
    let mut s = start(model, loads(&jointed, 2e-5), ContactSettings::new(26e9));
    let mut lower_nodes: Vec<usize> = s.model().tets[..n_lower].iter().flatten().map(|&n| n as usize).collect();
    lower_nodes.sort_unstable();
    lower_nodes.dedup();
    let steps = (1.5e-4 / s.dt()) as usize;
    for _ in 0..steps {
        s.step(Want::default());
    }
    let contact = s.contact().unwrap();
    let on_lower: Vec3 = lower_nodes.iter().map(|&i| contact.force[i] + contact.friction_force[i]).sum();
    let reaction = s.record().drive_forces[0];
    let f = P * area;
    eprintln!(
        "applied {f:.2} N; contact force on the lower cube {on_lower:?}; base reaction {reaction:?}; {} pairs",
        contact.active_pairs
    );
    assert!((-on_lower.z / f - 1.0).abs() < 0.01, "contact {} vs {f}", -on_lower.z);
    assert!((reaction.z / f - 1.0).abs() < 0.01, "reaction {} vs {f}", reaction.z);
}

/// A jointed column (10 × 10 × 20 mm, 2.5 mm lattice, damped) pressed by
/// `P` on its top and settled, with the joints of its mid-plane; contact
/// with `settings`.
pub(crate) fn pressed_column(settings: impl FnOnce(ContactSettings) -> ContactSettings) -> (Solver, Vec<u32>) {
    let h = 0.0025;
    // Unjittered, so that the mid-plane is a plane of faces.
    let mesh = box_mesh([0.0; 3], [0.01, 0.01, 0.02], h, 0.0, true);
    let jointed = insert_joints(&mesh).unwrap();
    let visc = critical_viscosity(h, 26e9, 2340.0);
    let behaviour =
        [RegionBehaviour::Deformable { law: Law::NeoHookean, material: rock(visc), joints: Some(joints(10.0 * 26e9)) }];
    let model = Model::new(&jointed, &behaviour, 1.0).unwrap();
    let mid: Vec<u32> = (0..model.joints.len() as u32)
        .filter(|&j| model.joints[j as usize].iter().all(|&n| (model.x0[n as usize].z - 0.01).abs() < 1e-9))
        .collect();
    assert_eq!(mid.len(), 2 * 4 * 4, "two triangles per grid square of the mid-plane");
    let mut s = start(model, loads(&jointed, 2e-5), settings(ContactSettings::new(26e9)));
    let settle = (1.0e-4 / s.dt()) as usize;
    for _ in 0..settle {
        s.step(Want::default());
    }
    (s, mid)
}

#[test]
fn load_passes_from_joints_to_contact_when_the_mid_plane_breaks() {
    let (mut s, mid) = pressed_column(|c| c);
    let f = P * 1e-4;
    let settle = (1.0e-4 / s.dt()) as usize;
    let before = s.record().drive_forces[0].z;
    s.break_joints(&mid);
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for _ in 0..settle {
        s.step(Want { energy: true, ..Want::default() });
        let r = s.record().drive_forces[0].z;
        lo = lo.min(r);
        hi = hi.max(r);
    }
    let after = s.record().drive_forces[0].z;
    let (balance, work) = (s.energies().balance(), s.energies().external_work);
    let contact = s.contact().unwrap();
    // The nodes of the lower half's tets (those at the cut included).
    let lower: Vec<usize> = {
        let mut v: Vec<usize> = (s.model().tets.iter())
            .filter(|t| t.iter().map(|&n| s.model().x0[n as usize].z).sum::<f64>() < 0.04)
            .flatten()
            .map(|&n| n as usize)
            .collect();
        v.sort_unstable();
        v.dedup();
        v
    };
    let across: f64 = lower.iter().map(|&i| contact.force[i].z + contact.friction_force[i].z).sum();
    eprintln!(
        "applied {f:.2} N; base reaction {before:.3} before, {lo:.3} to {hi:.3} through the switch, {after:.3} after; \
         contact across the cut {across:.3} N ({} pairs); energy balance {balance:.3e} J of {work:.3e} J of work; \
         contact energy {:.3e} J",
        contact.active_pairs,
        s.energies().contact
    );
    assert!(s.state().joints.iter().filter(|h| h.failed).count() == mid.len(), "only the mid-plane is broken");
    assert!((before / f - 1.0).abs() < 0.01, "before: {before} vs {f}");
    assert!(lo > 0.9 * f && hi < 1.1 * f, "reaction left [{lo}, {hi}] around {f}");
    assert!((after / f - 1.0).abs() < 0.01, "after: {after} vs {f}");
    assert!((-across / f - 1.0).abs() < 0.01, "contact across the cut {across} vs {f}");
    assert!(balance.abs() < 0.01 * work, "energy balance {balance} vs work {work}");
}

/// The pairs skipped by their certificates (`contact/certify.rs`) on the
/// column broken at its mid-plane and pressed: at every step, each is
/// clipped here at the positions of the pass that skipped it, and its
/// every nodal force is below the `negligible` threshold `ε p ℓ²` that the
/// certificate vouched for (there are such pairs at most steps, asserted).
/// With certificates off the run differs by less than the allowance of the
/// test below.
#[test]
fn pairs_skipped_by_their_certificates_are_negligible_where_skipped() {
    let (mut s, mid) = pressed_column(|c| c);
    s.break_joints(&mid);
    let penalty = 26e9;
    let (mut checked, mut steps_with, mut worst) = (0_usize, 0, 0.0_f64);
    let steps = (1.0e-4 / s.dt()) as usize;
    for _ in 0..steps {
        let x = s.state().x.clone();
        s.step(Want::default());
        let contact = s.contact().unwrap();
        let mut any = false;
        for (a, b) in contact.certified_skips() {
            let at = |t: u32| s.model().tets[t as usize].map(|n| x[n as usize]);
            let c = femdem_contact::tet_tet_contact(&at(a), &at(b), penalty);
            let largest = c.on_a.iter().chain(&c.on_b).map(|f| f.norm()).fold(0.0, f64::max);
            let volume = s.model().tet_ref[a as usize].volume.min(s.model().tet_ref[b as usize].volume);
            let threshold = femdem_solver::NEGLIGIBLE * penalty * volume.powf(2.0 / 3.0);
            assert!(largest <= threshold, "pair ({a}, {b}): force {largest} N above {threshold} N");
            worst = worst.max(largest / threshold);
            checked += 1;
            any = true;
        }
        steps_with += usize::from(any);
    }
    eprintln!(
        "{checked} certified skips over {steps} steps ({steps_with} with some); largest force {worst:.3e} of the threshold"
    );
    assert!(2 * steps_with > steps, "certified skips at {steps_with} of {steps} steps");
}

/// The certificates are part of a checkpoint: the broken column, stepped
/// while pairs are skipped by their certificates (asserted), snapshot and
/// restored into a second solver built the same way, continues bit for bit
/// with the first, and ends with the same snapshot.
#[test]
fn a_restored_column_continues_bit_for_bit_with_its_certificates() {
    let (mut a, mid) = pressed_column(|c| c);
    a.break_joints(&mid);
    for _ in 0..200 {
        a.step(Want::default());
    }
    let certified = a.contact().unwrap().certified_skips().count();
    assert!(certified > 0, "no pair skipped by its certificate at the snapshot");
    let snap = a.snapshot();
    let (mut b, _) = pressed_column(|c| c);
    b.restore(&snap).unwrap();
    for _ in 0..300 {
        a.step(Want::default());
        b.step(Want::default());
    }
    assert_eq!(a.state(), b.state(), "positions, velocities, joint histories");
    assert_eq!(a.record(), b.record());
    assert!(a.snapshot() == b.snapshot(), "the whole state, certificates included, differs");
}

/// Skipping the pairs whose forces are provably negligible (the default
/// `negligible`) against evaluating every pair, on the column broken at
/// its mid-plane and pressed: some pairs are skipped, and the base
/// reaction and every node's position differ by much less than an
/// order-of-magnitude allowance (not a derived bound): each skipped pair's
/// normal forces are below `ε p ℓ²` (`ε = 1e-10`, `ℓ³` the tet's volume:
/// 4.9e-6 N here), `n` skipped pairs drop less than `n ε p ℓ²` in all,
/// and the allowance is twice that for the base reaction and that over the
/// column's axial stiffness `E A / L` for a node (a node alone is about
/// twice as soft, and the dropped forces are self-balanced pairs switching
/// on and off, not one step load; measured, the runs differ by some 10⁻³ of
/// the allowance).
#[test]
fn skipping_negligible_pairs_moves_the_broken_column_by_less_than_their_bound() {
    let run = |negligible: f64| {
        let (mut s, mid) = pressed_column(|c| ContactSettings { negligible, ..c });
        s.break_joints(&mid);
        let mut skipped_at_most = 0;
        let mut active = 0;
        for _ in 0..(1.0e-4 / s.dt()) as usize {
            s.step(Want::default());
            active = s.contact().unwrap().active_pairs;
            skipped_at_most = skipped_at_most.max(s.contact().unwrap().candidates().len() - active);
        }
        (s, active, skipped_at_most)
    };
    let (every, active_every, _) = run(0.0);
    let (skipping, active_skipping, candidates_not_in_contact) = run(femdem_solver::NEGLIGIBLE);
    let volume = every.model().tet_ref.iter().map(|t| t.volume).fold(0.0, f64::max);
    let per_pair = femdem_solver::NEGLIGIBLE * 26e9 * volume.powf(2.0 / 3.0);
    let force = 2.0 * candidates_not_in_contact as f64 * per_pair;
    let reaction = (skipping.record().drive_forces[0] - every.record().drive_forces[0]).norm();
    let moved =
        (0..every.model().num_nodes()).map(|i| (skipping.state().x[i] - every.state().x[i]).norm()).fold(0.0, f64::max);
    let stiffness = 26e9 * 1e-4 / 0.02;
    eprintln!(
        "pairs in contact {active_every} evaluating all, {active_skipping} skipping; skipped forces below {force:.3e} N; \
         base reaction {reaction:.3e} N apart, nodes up to {moved:.3e} m (allowed {:.3e} m)",
        force / stiffness
    );
    assert!(active_skipping < active_every, "no pair skipped: {active_skipping} of {active_every}");
    assert!(reaction <= force, "base reaction {reaction} N apart, allowed {force} N");
    assert!(moved <= force / stiffness, "nodes {moved} m apart, allowed {} m", force / stiffness);
}
