//! Contact activation on fracture (reference paper §2.3, Eq. 14–16).
//!
//! When a joint fails, the paper searches contact among the tets that have
//! one of its nodes (by original vertex: the node groups G1–G6 of Eq. 15),
//! less the couples still joined by active joints (Eq. 16). femdem makes
//! those tets contactable and lets two tets that share a vertex touch where
//! a crack separates them around it (see `femdem_solver::contact`). A block
//! 20 × 10 × 20 mm of 2.5 mm Freudenthal cells (unjittered: `z = 10 mm`
//! and `x = 10 mm` are planes of faces), joints too strong to fail, bottom
//! held, contact penalty E; part of those planes is broken at 2 µs:
//!
//! * **a kink** — the L-shaped cut `z = 10 mm, x < 10 mm` then
//!   `x = 10 mm, z > 10 mm` frees the upper-left quarter; its top is pushed
//!   into the corner at (0.5, 0, −0.5) m/s (the rest of the top held). Its
//!   faces press on the crack faces below and to the right (~1000 N and
//!   ~650 N at 60 µs) and its corner sinks, by about their penetration
//!   depth δ ≈ 1 µm each way, into the tets diagonally across the kink,
//!   which have no face on the crack, only the kink's vertices. The crack
//!   separates them from the fragment around those vertices (the quarter's
//!   tets form a piece of their own there), so they are candidates now.
//!   Before (only a failed joint's two tets activated, and tets sharing a
//!   vertex touching only if both were): they were not contactable; no
//!   force; fragment ∩ those tets 6.3675e-14 m³, deepest node 1.0877e-6 m.
//!   After: they push on the fragment with (3.16, 0, −2.06) N, along the
//!   diagonal out of the corner as the geometry requires (asserted within
//!   26°); 6.2908e-14 m³, 1.0793e-6 m — 1.2% less (asserted: below 0.995
//!   of the value before). The reduction is small, and must be: the
//!   corner's overlap is a prism δ_x δ_z along the kink, second order in δ,
//!   and its potential force (`p` times the overlapping faces' area times
//!   `φ ~ 4δ/h`, a few N) is 0.3% of the face forces, far too weak to push
//!   the corner of an elastic body (stiffness ~E h) back; the faces'
//!   contacts set the overlap, the corner pair now takes its share of the
//!   load. The same run in a 1-thread pool with a 0.2 mm detection buffer
//!   (the nodes move less than 0.1 mm, so only the failures can trigger a
//!   detection: 2 in all) ends in the same bits.
//! * **a crack front** — the half plane `z = 10 mm, x < 10 mm` is cut and
//!   the whole top moves at (1, 0, −0.5) m/s (shear and compression). The
//!   tets ahead of the front share the front's vertices with the crack's
//!   tets but the crack ends there: around the front they are all linked
//!   by the active joints of the ligament ahead, so they stay excluded and
//!   feel no contact force. Their interpenetration with the crack's upper
//!   tets, 4.35e-14 m³ at 60 µs, is that of intact neighbours beside them
//!   above the cut (4.63e-14 m³; asserted within a factor 2): the joints'
//!   compliance, which a contact force would count twice. (Letting any two
//!   tets that share a cracked vertex touch — every couple within one of
//!   the paper's groups — such neighbours pushed on each other: 2188 pairs
//!   in contact against 430 before, in the kinked block cut at step 0, at
//!   0.1 ms; with the rule kept, 875 pairs at 60 µs against 430 before,
//!   the new ones across the crack.)

use std::collections::HashSet;

use crate::common::{at_step, box_mesh, rock, stable, tet_overlap};
use femdem_core::Vec3;
use femdem_material::{Law, critical_viscosity};
use femdem_mesh::insert_joints;
use femdem_solver::select::{NodeSelection, select_nodes};
use femdem_solver::{
    ContactSettings, Fixed, Loads, Model, Ramp, RegionBehaviour, Solver, VelocityDrive, Want, contact_omega,
};

/// Element size; the block is 0.02 × 0.01 × 0.02 m and the cut lies at
/// mid-height `z = C`, the crack front or the kink on the line `x = C`.
const H: f64 = 0.0025;
const C: f64 = 0.01;
/// Contact penalty, Pa (E).
const PENALTY: f64 = 26e9;

/// The block, unjittered so that `z = C` and `x = C` are planes of faces,
/// with joints too strong to fail; the pre-cut broken, bottom held, and
/// driven at its top: with `kink`, the cut is L-shaped (`z = C` for
/// `x < C`, then `x = C` for `z > C`: the upper-left quarter a fragment),
/// whose top alone is pushed towards the corner at (0.5, 0, −0.5) m/s, the
/// rest of the top held; without, the cut is the half plane `z = C`,
/// `x < C` (a crack front along `x = C`) and the whole top moves at
/// (1, 0, −0.5) m/s (shear and compression).
fn block(kink: bool) -> (Solver, Vec<u32>) {
    let mesh = box_mesh([0.0; 3], [0.02, 0.01, 0.02], H, 0.0, true);
    let jointed = insert_joints(&mesh).unwrap();
    let params =
        femdem_fracture::JointParams { tensile_strength: 1e9, cohesion: 2e9, ..crate::common::joints(10.0 * 26e9) };
    let visc = critical_viscosity(H, 26e9, 2340.0) * 0.3;
    let behaviour = [RegionBehaviour::Deformable { law: Law::NeoHookean, material: rock(visc), joints: Some(params) }];
    let m = Model::new(&jointed, &behaviour, 1.0).unwrap();
    let sel = |g: &str| select_nodes(&jointed, &NodeSelection { group: Some(g.into()), ..Default::default() }).unwrap();
    let top = sel("zmax");
    let (left, right): (Vec<u32>, Vec<u32>) = top.iter().partition(|&&n| m.x0[n as usize].x < C - 1e-9);
    let (driven, held, velocity) = if kink {
        (left, vec![sel("zmin"), right], Vec3::new(0.5, 0.0, -0.5))
    } else {
        (top, vec![sel("zmin")], Vec3::new(1.0, 0.0, -0.5))
    };
    let loads = Loads {
        fixed: held.into_iter().map(|nodes| Fixed { nodes, components: [true; 3] }).collect(),
        drives: vec![VelocityDrive {
            name: "top".into(),
            nodes: driven,
            velocity,
            components: [true; 3],
            ramp: Ramp { ramp_time: 2e-5, stop_time: None },
            start_time: None,
        }],
        ..Loads::default()
    };
    let on = |q: &Vec3, x: bool| (if x { q.x } else { q.z } - C).abs() < 1e-9;
    let cut: Vec<u32> = (0..m.joints.len() as u32)
        .filter(|&j| {
            let p = m.joints[j as usize].map(|n| m.x0[n as usize]);
            let c = p.iter().sum::<Vec3>() / 6.0;
            (p.iter().all(|q| on(q, false)) && c.x < C) || (kink && p.iter().all(|q| on(q, true)) && c.z > C)
        })
        .collect();
    let st = stable(&m, &loads, 300).with_contact(contact_omega(&m, PENALTY));
    (at_step(m, loads, 0.9 * st.critical), cut)
}

/// Tet `t`'s quadrant: (centroid right of `x = C`, above `z = C`), at the
/// reference positions.
fn quadrant(s: &Solver, t: u32) -> (bool, bool) {
    let c = s.model().tets[t as usize].iter().map(|&n| s.model().x0[n as usize]).sum::<Vec3>() / 4.0;
    (c.x > C, c.z > C)
}

/// Whether tet `t` touches the line `x = z = C` (reference positions).
fn on_line(s: &Solver, t: u32) -> bool {
    s.model().tets[t as usize].iter().any(|&n| {
        let p = s.model().x0[n as usize];
        (p.x - C).abs() < 1e-9 && (p.z - C).abs() < 1e-9
    })
}

/// Whether tet `t` has a face on a failed joint.
fn on_crack(s: &Solver, t: u32) -> bool {
    (0..s.model().joints.len()).any(|j| s.state().joints[j].failed && s.model().joint_tets[j].contains(&t))
}

/// The interpenetration of the pairs `(a, b)` with `a` in `from` and `b` in
/// `to` that share an original vertex and no active joint: the summed
/// overlap volume (m³) and the deepest node (m).
fn overlap(s: &Solver, from: &[u32], to: &[u32]) -> (f64, f64) {
    let m = &s.model();
    let bonded: HashSet<(u32, u32)> = (0..m.joints.len())
        .filter(|&j| !s.state().joints[j].failed)
        .map(|j| {
            let [a, b] = m.joint_tets[j];
            (a.min(b), a.max(b))
        })
        .collect();
    let (mut volume, mut depth) = (0.0, 0.0f64);
    for &a in from {
        for &b in to {
            let oa = m.tets[a as usize].map(|n| m.origin[n as usize]);
            if a == b
                || bonded.contains(&(a.min(b), a.max(b)))
                || !m.tets[b as usize].iter().any(|&n| oa.contains(&m.origin[n as usize]))
            {
                continue;
            }
            let p = |t: u32| m.tets[t as usize].map(|n| s.state().x[n as usize]);
            let (v, d) = tet_overlap(&p(a), &p(b));
            volume += v;
            depth = depth.max(d);
        }
    }
    (volume, depth)
}

/// The contact force (normal and friction) on the nodes of `tets`, N.
fn force_on(s: &Solver, tets: &[u32]) -> Vec3 {
    let c = s.contact().unwrap();
    tets.iter()
        .flat_map(|&t| s.model().tets[t as usize])
        .map(|n| c.force[n as usize] + c.friction_force[n as usize])
        .sum()
}

/// The tets touching the line `x = z = C` in quadrant `q`.
fn at_line(s: &Solver, q: (bool, bool)) -> Vec<u32> {
    (0..s.model().tets.len() as u32).filter(|&t| on_line(s, t) && quadrant(s, t) == q).collect()
}

/// Runs `block(kink)` with contact on (detection buffer `buffer`, m): the
/// cut is broken at step 40 (2 µs, while the drive ramps up), then the run
/// goes on to 60 µs. Returns the solver and the tets at the line
/// `x = z = C` by quadrant: upper left, upper right, lower right.
fn run(kink: bool, buffer: f64) -> (Solver, [Vec<u32>; 3]) {
    let (mut s, cut) = block(kink);
    s.enable_contact(ContactSettings { surfaces: false, buffer, ..ContactSettings::new(PENALTY) }, &[]);
    for _ in 0..40 {
        s.step(Want::default());
    }
    s.break_joints(&cut);
    while s.state().time < 6e-5 {
        s.step(Want::default());
    }
    let quads = [(false, true), (true, true), (true, false)].map(|q| at_line(&s, q));
    (s, quads)
}

#[test]
fn tets_across_a_kink_push_back_on_the_fragment() {
    let pool = |n| rayon::ThreadPoolBuilder::new().num_threads(n).build().unwrap();
    let (s, [ul, _, lr]) = pool(2).install(|| run(true, 0.0));
    assert!(lr.iter().all(|&t| !on_crack(&s, t)), "the lower-right tets have no face on the crack");
    assert!(!lr.is_empty() && ul.iter().any(|&t| on_crack(&s, t)));
    let push = force_on(&s, &lr);
    let on_fragment = force_on(&s, &ul);
    let (volume, depth) = overlap(&s, &ul, &lr);
    eprintln!(
        "kink: {} pairs in contact; force on the lower-right tets {push:?} N (on the fragment's tets at the kink \
         {on_fragment:?} N); fragment ∩ lower right: {volume:.4e} m³, deepest node {depth:.4e} m",
        s.contact().unwrap().active_pairs
    );
    let away = Vec3::new(1.0, 0.0, -1.0).normalize();
    assert!(push.norm() > 0.0 && push.dot(&away) > 0.9 * push.norm(), "no push across the kink: {push:?}");
    assert!(volume < 0.995 * TODAY_KINK_OVERLAP, "interpenetration across the kink {volume:e} m³");
    // The failures mid-run must trigger a detection (the buffer alone never
    // would: the nodes move less than b/2 = 0.1 mm), and nothing may depend
    // on the thread count.
    let (buffered, _) = pool(1).install(|| run(true, 2e-4));
    let detections = buffered.contact().unwrap().detections;
    eprintln!("kink: {detections} detections with a 0.2 mm buffer, {} without", s.contact().unwrap().detections);
    assert!(detections <= 3, "{detections} detections");
    assert_eq!(s.state(), buffered.state(), "the buffer or the thread count changed the result");
}

/// The fragment ∩ lower-right overlap at 60 µs before the tets around a
/// failed joint's vertices were activated (see the module documentation).
const TODAY_KINK_OVERLAP: f64 = 6.368e-14;

#[test]
fn tets_across_a_crack_front_stay_bonded() {
    let (s, [ul, ur, lr]) = run(false, 0.0);
    let across = overlap(&s, &ul, &lr);
    let beside = overlap(&s, &ul, &ur);
    let ahead: Vec<u32> = ur.iter().chain(&lr).copied().collect();
    eprintln!(
        "front: {} pairs in contact; force on the tets ahead of the front {:?} N; overlap across the front {:.4e} m³ \
         (deepest node {:.4e} m), beside it (intact neighbours above the cut) {:.4e} m³ ({:.4e} m)",
        s.contact().unwrap().active_pairs,
        force_on(&s, &ahead),
        across.0,
        across.1,
        beside.0,
        beside.1
    );
    assert!(!ul.is_empty() && !ur.is_empty() && !lr.is_empty());
    assert_eq!(force_on(&s, &ahead), Vec3::zeros(), "the tets ahead of the front must not touch");
    let ratio = across.0 / beside.0;
    assert!(ratio > 0.5 && ratio < 2.0, "overlap across the front is {ratio} times that of intact neighbours");
}
