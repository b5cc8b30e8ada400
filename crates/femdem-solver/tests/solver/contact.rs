//! Contact in the solver (reference paper §2.3, Eq. 17):
//!
//! * two elastic cubes colliding head-on, frictionless and undamped,
//!   conserve linear momentum to 1e-9 relative (every contact force has its
//!   equal and opposite reaction, and internal forces sum to zero), and
//!   keep their energy within 2% once apart: kinetic plus the elastic energy
//!   of the vibration the impact leaves in them (the penalty potential
//!   stores and returns the energy; p = E and a fifth of the bulk's critical
//!   step keep the contact spring well resolved);
//! * a block resting on a rigid plate under gravity carries its weight: the
//!   plate's reaction equals `m g` within 1% once the block has settled
//!   (damped), and the block sinks into the plate by the depth the penalty
//!   predicts: each base face overlaps a plate face of the same shape, and a
//!   shallow face-on overlap `δ` pushes with `p A (4δ/H_a + 4δ/H_b)`
//!   (`femdem-contact`'s closed-form test; both altitudes are `h` on these
//!   grids), so `δ = m g h / (8 p A)`; the mean depth of the base nodes
//!   matches it within 10% (5% for the closed form itself, the rest for
//!   the uneven pressure under an elastic block);
//! * a broken bar's two halves, pulled apart, exert no contact force, and
//!   no two tets on one side of the crack push on each other: no pair is
//!   in contact once they have separated.

use crate::common::{at_step, box_mesh, model, rock, stable};
use femdem_core::Vec3;
use femdem_material::Law;
use femdem_mesh::{Region, insert_joints};
use femdem_solver::select::{NodeSelection, select_nodes};
use femdem_solver::{ContactEnergy, ContactSettings, Loads, Model, Ramp, RegionBehaviour, Solver, VelocityDrive, Want};

fn momentum(s: &Solver) -> Vec3 {
    (0..s.model().num_nodes()).map(|i| s.state().v[i] * s.model().mass[i]).sum()
}

fn kinetic(s: &Solver) -> f64 {
    (0..s.model().num_nodes()).map(|i| 0.5 * s.model().mass[i] * s.state().v[i].norm_squared()).sum()
}

#[test]
fn colliding_cubes_conserve_momentum_and_energy() {
    let mut mesh = box_mesh([0.0; 3], [0.02, 0.02, 0.02], 0.005, 0.0, false);
    let other = box_mesh([0.021, 0.0, 0.0], [0.041, 0.02, 0.02], 0.005, 0.0, false);
    mesh.append(&other);
    let (_, m) = model(&mesh, Law::NeoHookean, rock(0.0), 0.0);
    // Contact stiffens the top frequency; a fifth of the step keeps it safe.
    let dt = 0.2 * stable(&m, &Loads::default(), 300).critical;
    let mut s = at_step(m, Loads::default(), dt);
    s.enable_contact(ContactSettings::new(26e9), &[]);
    s.set_velocity(|x| if x.x < 0.0205 { Vec3::new(1.0, 0.0, 0.0) } else { Vec3::new(-1.0, 0.0, 0.0) });
    let p0 = momentum(&s);
    let k0 = kinetic(&s);
    let scale = s.model().mass.iter().sum::<f64>() * 1.0;
    let mut touched = false;
    let mut apart = 0;
    for _ in 0..20_000 {
        s.step(Want::default());
        let pairs = s.contact().unwrap().active_pairs;
        touched |= pairs > 0;
        apart = if touched && pairs == 0 { apart + 1 } else { 0 };
        if apart > 200 {
            break;
        }
    }
    assert!(touched, "the cubes never met");
    let p1 = momentum(&s);
    assert!((p1 - p0).norm() <= 1e-9 * scale, "momentum changed by {}", (p1 - p0).norm());
    // Rigid-body kinetic energy of each cube after the bounce.
    let mut pv = [Vec3::zeros(); 2];
    let mut ms = [0.0; 2];
    for i in 0..s.model().num_nodes() {
        let k = usize::from(s.model().x0[i].x > 0.0205);
        pv[k] += s.state().v[i] * s.model().mass[i];
        ms[k] += s.model().mass[i];
    }
    let rigid: f64 = (0..2).map(|k| 0.5 * pv[k].norm_squared() / ms[k]).sum();
    s.step(Want { energy: true, ..Want::default() });
    let k1 = s.energies().kinetic + s.energies().tet_elastic;
    eprintln!(
        "KE before {k0:.4e}, after {k1:.4e} (rigid part {rigid:.4e}), v after {:?} {:?}",
        pv[0] / ms[0],
        pv[1] / ms[1]
    );
    assert!((k1 - k0).abs() <= 0.02 * k0, "kinetic + elastic energy {k1} vs {k0}");
    assert!(pv[0].x < 0.0 && pv[1].x > 0.0, "the cubes must bounce back");
}

#[test]
fn block_on_a_rigid_plate_carries_its_weight() {
    let h = 0.005;
    let mut mesh = box_mesh([0.0, 0.0, 0.0], [0.02, 0.02, 0.02], h, 0.0, false);
    let mut plate = box_mesh([-0.005, -0.005, -0.005], [0.025, 0.025, 0.0], h, 0.0, false);
    plate.regions[0] = Region { name: "plate".into(), breakable: false };
    mesh.append(&plate);
    let jointed = insert_joints(&mesh).unwrap();
    let visc = femdem_material::critical_viscosity(h, 26e9, 2340.0) * 1.0;
    let behaviour = [
        RegionBehaviour::Deformable { law: Law::NeoHookean, material: rock(visc), joints: None },
        RegionBehaviour::Rigid,
    ];
    let m = Model::new(&jointed, &behaviour, 1.0).unwrap();
    let plate_nodes =
        select_nodes(&jointed, &NodeSelection { region: Some("plate".into()), ..Default::default() }).unwrap();
    let g = 9.81 * 1000.0; // a strong gravity so the load is well above round-off
    let loads = Loads {
        gravity: Vec3::new(0.0, 0.0, -g),
        drives: vec![VelocityDrive {
            name: "plate".into(),
            nodes: plate_nodes,
            velocity: Vec3::zeros(),
            components: [true; 3],
            ramp: Ramp::STEP,
            start_time: None,
        }],
        ..Loads::default()
    };
    let dt = 0.2 * stable(&m, &loads, 300).critical;
    let mut s = at_step(m, loads, dt);
    let p = 10.0 * 26e9;
    s.enable_contact(ContactSettings::new(p), &[]);
    let weight = s.model().mass.iter().sum::<f64>() * g;
    let mut reaction = 0.0;
    for _ in 0..3_000 {
        s.step(Want::default());
        reaction = s.record().drive_forces[0].z;
    }
    // The plate pushes the block up: the force the plate's drive applies is
    // minus the contact force on the plate, i.e. −(−weight).
    let lowest = (0..s.model().num_nodes())
        .filter(|&i| s.model().mass[i] > 0.0)
        .map(|i| s.state().x[i].z)
        .fold(f64::INFINITY, f64::min);
    let base: Vec<usize> =
        (0..s.model().num_nodes()).filter(|&i| s.model().mass[i] > 0.0 && s.model().x0[i].z == 0.0).collect();
    let mean = -base.iter().map(|&i| s.state().x[i].z).sum::<f64>() / base.len() as f64;
    let predicted = weight * h / (8.0 * p * 0.02 * 0.02);
    eprintln!(
        "weight {weight:.4e} N, plate reaction {reaction:.4e} N, penetration {:.3e} m, mean {mean:.3e} vs {predicted:.3e}",
        -lowest
    );
    assert!((reaction.abs() / weight - 1.0).abs() < 0.01, "reaction {reaction} vs weight {weight}");
    assert!(-lowest > 0.0 && -lowest < 0.01 * h, "penetration {}", -lowest);
    assert!((mean / predicted - 1.0).abs() < 0.1, "mean penetration {mean} vs {predicted}");
}

/// A bar pulled apart breaks (cohesive joints) and its halves, now in the
/// contact search (Eq. 14–16), separate: no contact force acts between them.
#[test]
fn broken_bar_halves_separate_without_contact_force() {
    let (w, len, h) = (0.01, 0.02, 0.0025);
    let mesh = box_mesh([0.0; 3], [w, w, len], h, 0.1, true);
    let jointed = insert_joints(&mesh).unwrap();
    let params = femdem_fracture::JointParams { gf_tension: 10.0, gf_shear: 10.0, ..crate::common::joints(2.6e11) };
    let visc = femdem_material::critical_viscosity(h, 26e9, 2340.0) * 0.1;
    let behaviour = [RegionBehaviour::Deformable { law: Law::NeoHookean, material: rock(visc), joints: Some(params) }];
    let m = Model::new(&jointed, &behaviour, 1.0).unwrap();
    let sel = |g: &str| select_nodes(&jointed, &NodeSelection { group: Some(g.into()), ..Default::default() }).unwrap();
    let loads = Loads {
        fixed: vec![femdem_solver::Fixed { nodes: sel("zmin"), components: [true; 3] }],
        drives: vec![VelocityDrive {
            name: "pull".into(),
            nodes: sel("zmax"),
            velocity: Vec3::new(0.0, 0.0, 0.1),
            components: [true; 3],
            ramp: Ramp { ramp_time: 2e-5, stop_time: None },
            start_time: None,
        }],
        ..Loads::default()
    };
    let dt = 0.9 * stable(&m, &loads, 300).critical;
    let mut s = at_step(m, loads, dt);
    s.enable_contact(ContactSettings { surfaces: false, ..ContactSettings::new(26e9) }, &[]);
    let mut peak: f64 = 0.0;
    // The reaction at the end, averaged over the last 20 µs (several periods
    // of the freed half's ringing, which carries no force across the crack).
    let (mut tail_sum, mut tail_n, mut tail_max) = (0.0, 0usize, 0.0f64);
    while s.state().time < 4e-4 {
        let r = s.step(Want::default()).drive_forces[0].z;
        peak = peak.max(r.abs());
        if s.state().time > 3.8e-4 {
            tail_sum += r;
            tail_n += 1;
            tail_max = tail_max.max(r.abs());
        }
    }
    let residual = tail_sum / tail_n as f64;
    eprintln!("reaction over the last 20 µs: mean {residual:.3e} N, largest {tail_max:.3e} N");
    assert!(!s.failures().is_empty(), "the bar must break");
    let contact = s.contact().unwrap();
    let largest = contact.touched().iter().map(|&n| contact.force[n as usize].norm()).fold(0.0, f64::max);
    eprintln!(
        "peak pull {peak:.4e} N, {} failures, {} contactable tets, {} pairs in contact, largest nodal contact force {largest:.3e} N",
        s.failures().len(),
        contact.contactable().len(),
        contact.active_pairs
    );
    // Exactly zero: no pair is in contact. (It was 4.2e-7 N, 1e-9 of the
    // peak pull, while any two tets on failed joints could touch: tets on
    // the same side of the crack sharing an edge touched along it as the
    // half deformed. Tets that no crack separates around a shared vertex
    // are now excluded; see `femdem_solver::contact`.)
    assert_eq!(contact.active_pairs, 0, "pairs in contact after separation");
    assert!(largest < 1e-6 * peak, "contact force {largest} N after separation (peak pull {peak} N)");
    assert!(residual.abs() < 1.0, "the halves still pull: {residual} N");
}

/// A block on a rigid plate under gravity tilted by θ (the incline, without
/// rotating the mesh), friction μ = 0.5: for tan θ < μ it stays put (it
/// creeps only by the friction spring's stretch, `m g sin θ / k_t`, far below
/// the element size); for tan θ > μ it slides with `a = g (sin θ − μ cos θ)`
/// within 3% (measured from the block's mean velocity between two times
/// after the start-up).
#[test]
fn block_on_an_incline_sticks_below_and_slides_above_the_friction_angle() {
    let h = 0.005;
    let mu = 0.5;
    let run = |theta: f64| -> (f64, f64) {
        let mut mesh = box_mesh([0.0, 0.0, 0.0], [0.02, 0.02, 0.01], h, 0.0, false);
        let mut plate = box_mesh([-0.03, -0.03, -0.005], [0.05, 0.05, 0.0], 0.01, 0.0, false);
        plate.regions[0] = Region { name: "plate".into(), breakable: false };
        mesh.append(&plate);
        let jointed = insert_joints(&mesh).unwrap();
        let visc = femdem_material::critical_viscosity(h, 26e9, 2340.0) * 0.3;
        let behaviour = [
            RegionBehaviour::Deformable { law: Law::NeoHookean, material: rock(visc), joints: None },
            RegionBehaviour::Rigid,
        ];
        let m = Model::new(&jointed, &behaviour, 1.0).unwrap();
        let plate_nodes =
            select_nodes(&jointed, &NodeSelection { region: Some("plate".into()), ..Default::default() }).unwrap();
        let g = 9.81 * 1000.0;
        let loads = Loads {
            gravity: Vec3::new(g * theta.sin(), 0.0, -g * theta.cos()),
            drives: vec![VelocityDrive {
                name: "plate".into(),
                nodes: plate_nodes,
                velocity: Vec3::zeros(),
                components: [true; 3],
                ramp: Ramp::STEP,
                start_time: None,
            }],
            ..Loads::default()
        };
        let dt = 0.2 * stable(&m, &loads, 300).critical;
        let mut s = at_step(m, loads, dt);
        s.enable_contact(ContactSettings { friction: mu, ..ContactSettings::new(26e9) }, &[]);
        let block_v = |s: &Solver| -> f64 {
            let (mut p, mut m) = (0.0, 0.0);
            for i in 0..s.model().num_nodes() {
                p += s.model().mass[i] * s.state().v[i].x;
                m += s.model().mass[i];
            }
            p / m
        };
        let (t1, t2) = (2e-4, 4e-4);
        let mut v1 = 0.0;
        while s.state().time < t2 {
            s.step(Want::default());
            if v1 == 0.0 && s.state().time >= t1 {
                v1 = block_v(&s);
            }
        }
        let a = (block_v(&s) - v1) / (s.state().time - t1);
        let slide = (0..s.model().num_nodes())
            .filter(|&i| s.model().mass[i] > 0.0)
            .map(|i| s.state().x[i].x - s.model().x0[i].x)
            .sum::<f64>()
            / s.model().mass.iter().filter(|&&m| m > 0.0).count() as f64;
        (a, slide)
    };
    let g = 9.81 * 1000.0;
    let stick = 20f64.to_radians(); // tan 20° = 0.36 < 0.5
    let (a, slide) = run(stick);
    eprintln!("θ = 20°: a = {a:.4e} m/s², slide {slide:.3e} m");
    assert!(a.abs() < 0.01 * g * stick.sin(), "the block accelerates at {a} m/s² below the friction angle");
    assert!(slide.abs() < 0.01 * h, "the block slid {slide} m below the friction angle");
    let slip = 40f64.to_radians(); // tan 40° = 0.84 > 0.5
    let (a, _) = run(slip);
    let expected = g * (slip.sin() - mu * slip.cos());
    eprintln!("θ = 40°: a = {a:.4e} m/s² vs {expected:.4e}");
    assert!((a / expected - 1.0).abs() < 0.03, "a = {a} vs {expected}");
}

/// One jointed 1 cm cube of rock (joints of p0 = 10 E): the model, the two
/// tets of joint 0 and the unit normal of their common face, from side a
/// to side b.
fn jointed_cube() -> (Model, [u32; 2], Vec3) {
    let mesh = box_mesh([0.0; 3], [0.01; 3], 0.01, 0.0, true);
    let (jointed, m) = model(&mesh, Law::NeoHookean, rock(0.0), 2.6e11);
    let jn = jointed.joints[0];
    let p = |k: usize| m.x0[jn[k] as usize];
    let n = (p(1) - p(0)).cross(&(p(2) - p(0))).normalize();
    let tets = m.joint_tets[0];
    (m, tets, n)
}

/// The cube's positions with tet `b` pushed `depth` (m) along `−n`, into
/// its neighbour across joint 0.
fn pushed(m: &Model, b: u32, n: Vec3, depth: f64) -> Vec<Vec3> {
    let mut x = m.x0.clone();
    for &node in &m.tets[b as usize] {
        x[node as usize] -= n * depth;
    }
    x
}

/// Eq. 18: when a joint fails in compression, the contact force between its
/// two tets rises linearly from zero to its full value over `n_total` steps
/// (the paper's 10, the case's `ramp_steps`), so the force carried across
/// the face does not jump; `n_total = 0` applies it at once. (With
/// `Activation::Paper`, the paper's rule; the default settling start is
/// the next test.)
#[test]
fn contact_force_of_a_joint_failed_in_compression_is_ramped_in() {
    let (m, [a, b], n) = jointed_cube();
    // Push tet b 1 µm into tet a, across their common face.
    let x = pushed(&m, b, n, 1e-6);
    let v = vec![Vec3::zeros(); x.len()];
    let pa = m.tets[a as usize].map(|k| x[k as usize]);
    let pb = m.tets[b as usize].map(|k| x[k as usize]);
    let full: Vec3 = femdem_contact::tet_tet_forces(&pa, &pb, 26e9).1.iter().sum();
    assert!(full.norm() > 0.0);
    // The paper's 10 steps, a shorter ramp, and none.
    for n_total in [femdem_solver::RAMP_STEPS, 4, 0] {
        let settings = ContactSettings {
            surfaces: false,
            ramp_steps: n_total,
            activation: femdem_solver::Activation::Paper,
            ..ContactSettings::new(26e9)
        };
        let mut contact = femdem_solver::Contact::new(&m, settings, &[]);
        contact.joint_failed(&m, 0, true, 0.0, &mut ContactEnergy::default());
        for step in 0..=n_total + 2 {
            contact.pass(&m, &x, &v, 1e-8);
            let on_b: Vec3 = m.tets[b as usize].iter().map(|&k| contact.force[k as usize]).sum();
            let expected = if n_total == 0 { 1.0 } else { f64::from(step.min(n_total)) / f64::from(n_total) };
            assert!(
                (on_b - full * expected).norm() <= 1e-12 * full.norm(),
                "n_total {n_total}, step {step}: {on_b} vs {expected} × {full}"
            );
        }
    }
}

/// `Activation::Settle`: the couple of a joint failed in compression
/// starts with its first resultant `N₀` as an offset that shrinks to zero
/// over the Eq. 18 steps, `N_off = N₀ (1 − n_c / n_total)`. Held where it
/// failed, its force rises as Eq. 18's, `N₀ n_c / n_total`; pressed a
/// further 1 µm at step 3 of 10, it carries the extra force at once in
/// full, `N(δ₀ + δ) − 0.7 N₀`, where Eq. 18 would carry 0.3 of all of it.
#[test]
fn a_settling_couple_ramps_its_first_overlap_and_carries_more_at_once() {
    let (m, [a, b], n) = jointed_cube();
    let pushed = |depth: f64| pushed(&m, b, n, depth);
    let resultant = |x: &[Vec3]| -> Vec3 {
        let pa = m.tets[a as usize].map(|k| x[k as usize]);
        let pb = m.tets[b as usize].map(|k| x[k as usize]);
        femdem_contact::tet_tet_forces(&pa, &pb, 26e9).1.iter().sum()
    };
    let (x0, x1) = (pushed(1e-6), pushed(2e-6));
    let (n0, n1) = (resultant(&x0), resultant(&x1));
    assert!(n1.norm() > n0.norm() && n0.norm() > 0.0);
    let v = vec![Vec3::zeros(); x0.len()];
    let settings = ContactSettings {
        surfaces: false,
        activation: femdem_solver::Activation::Settle,
        ..ContactSettings::new(26e9)
    };
    let total = f64::from(femdem_solver::RAMP_STEPS);
    let mut contact = femdem_solver::Contact::new(&m, settings, &[]);
    contact.joint_failed(&m, 0, true, 0.0, &mut ContactEnergy::default());
    let on_b = |c: &femdem_solver::Contact| -> Vec3 { m.tets[b as usize].iter().map(|&k| c.force[k as usize]).sum() };
    for step in 0..3 {
        contact.pass(&m, &x0, &v, 1e-8);
        let expected = n0 * (f64::from(step) / total);
        assert!(
            (on_b(&contact) - expected).norm() <= 1e-9 * n0.norm(),
            "step {step}: {} vs {expected}",
            on_b(&contact)
        );
    }
    contact.pass(&m, &x1, &v, 1e-8);
    let settled = n1 - n0 * (1.0 - 3.0 / total);
    let eq18 = n1 * (3.0 / total);
    assert!((on_b(&contact) - settled).norm() <= 1e-9 * n1.norm(), "{} vs {settled}", on_b(&contact));
    assert!(settled.norm() > eq18.norm());
}
