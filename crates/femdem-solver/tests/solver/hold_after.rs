//! A constraint that starts at a time ([`VelocityDrive::start_time`]): an
//! elastic column, its base fixed, is pressed by a pressure `P` on its top
//! face ramped over `t_r` and removed at `t_s = t_r`, and its top face's z
//! component is held (a zero-velocity drive) from `t_s` on — "ramp a
//! pressure, then hold the face where the ramp left it".
//!
//! Checked: before `t_s` the top moves as the free column does (the top
//! nodes' mean displacement is `−P L / E` to within the base's constraint
//! and the ramp's dynamics, below), and no reaction is recorded; from `t_s`
//! on the top nodes' z positions do not change at all; the hold's reaction
//! replaces the pressure's force to within the elastic oscillation the
//! ramp leaves; the energy account stays balanced.
//!
//! The oscillation bound. The column's fundamental axial period is
//! `T₁ = 4 L / c` (fixed–free bar, `c = √(E/ρ)`; the tets and the base's
//! lateral hold only stiffen it, shortening `T₁`). A linear ramp over `t_r`
//! leaves a single mode off its static displacement `u_s` by at most
//! `u_s · |sin ω t_r| / (ω t_r) ≤ u_s T₁ / (2π t_r)` and moving at most
//! `2 u_s / t_r`. Holding the top then (a) freezes that offset, a reaction
//! off by at most `T₁ / (2π t_r)` of `P A`, and (b) stops the top's
//! velocity, a stress wave of at most `ρ c · 2 u_s / t_r = P T₁ / (2 t_r)`.
//! So `|R − P A| ≤ (1/(2π) + 1/2) T₁ / t_r · P A < T₁ / t_r · P A`; with
//! `t_r = 20 T₁` the reaction lies within 5% of the pressure's force.

use crate::common::{box_mesh, model, rock, solver};
use femdem_core::Vec3;
use femdem_material::Law;
use femdem_solver::select::{NodeSelection, group_faces, select_nodes};
use femdem_solver::{Loads, Ramp, SurfaceKind, SurfaceLoad, VelocityDrive, Want};

#[test]
fn a_face_held_from_the_end_of_a_pressure_ramp_stays_put_and_carries_the_pressure() {
    let (w, l, p) = (0.01, 0.04, 10e6);
    let mesh = box_mesh([0.0; 3], [w, w, l], 0.005, 0.1, false);
    let mat = rock(0.0);
    let (jointed, m) = model(&mesh, Law::NeoHookean, mat, 0.0);
    let c = (mat.young() / mat.density()).sqrt();
    let t1 = 4.0 * l / c;
    let t_r = 20.0 * t1;
    let t_s = t_r;
    let sel = |g: &str| select_nodes(&jointed, &NodeSelection { group: Some(g.into()), ..Default::default() }).unwrap();
    let top = sel("zmax");
    let loads = Loads {
        fixed: vec![femdem_solver::Fixed { nodes: sel("zmin"), components: [true; 3] }],
        drives: vec![VelocityDrive {
            name: "hold".into(),
            nodes: top.clone(),
            velocity: Vec3::zeros(),
            components: [false, false, true],
            ramp: Ramp::STEP,
            start_time: Some(t_s),
        }],
        surfaces: vec![SurfaceLoad {
            name: "press".into(),
            faces: group_faces(&jointed, "zmax").unwrap(),
            kind: SurfaceKind::Pressure(p),
            ramp: Ramp { ramp_time: t_r, stop_time: Some(t_s) },
        }],
        ..Loads::default()
    };
    let mut s = solver(m, loads, 0.9);
    // Free before t_s: no node of the column is held for the stable step.
    assert!(top.iter().all(|&i| !s.held_nodes()[i as usize]));

    let mean_top_z =
        |s: &femdem_solver::Solver| top.iter().map(|&i| s.state().x[i as usize].z).sum::<f64>() / top.len() as f64;
    let mut pressure_force = 0.0;
    while s.state().time < t_s {
        let dt = s.dt();
        let r = s.step(Want::default());
        // The step from t_n prescribes v_{n+½}: held once t_n + Δt/2 ≥ t_s.
        if r.time + 0.5 * dt < t_s {
            assert_eq!(r.drive_forces[0], Vec3::zeros(), "a reaction before the start, at t = {}", r.time);
        }
        pressure_force = r.surface_forces[0].z;
    }
    // Moved as the free column does: `−P L / E`, stiffened by at most the
    // fully confined modulus's `M / E = 1.11` (ν = 0.2), off by the ramp's
    // dynamics by at most `T₁ / (2π t_r) = 0.8%`.
    let static_u = -p * l / mat.young();
    let moved = (mean_top_z(&s) - l) / static_u;
    assert!((0.89 * (1.0 - 0.008)..=1.008).contains(&moved), "top moved {moved} × P L / E");
    assert!(pressure_force < 0.0 && (pressure_force / (-p * w * w) - 1.0).abs() < 1e-3, "{pressure_force}");

    let held: Vec<f64> = top.iter().map(|&i| s.state().x[i as usize].z).collect();
    let (mut worst, mut sum, mut count) = (0.0f64, 0.0, 0);
    while s.state().time < t_s + 5.0 * t1 {
        let r = s.step(Want { energy: true, ..Want::default() }).clone();
        assert_eq!(r.surface_forces[0], Vec3::zeros(), "the pressure is removed after t_s");
        let ratio = r.drive_forces[0].z / pressure_force;
        worst = worst.max((ratio - 1.0).abs());
        sum += ratio;
        count += 1;
        let now: Vec<f64> = top.iter().map(|&i| s.state().x[i as usize].z).collect();
        assert_eq!(now, held, "the held face moved at t = {}", r.time);
    }
    println!("reaction / pressure force: mean {}, worst deviation {worst} over {count} steps", sum / count as f64);
    assert!(worst < 0.05, "reaction off the pressure's force by {worst}");
    let e = s.energies();
    println!("balance {} J of the work {} J", e.balance(), e.external_work);
    assert!(e.external_work > 0.0);
    // The account is exact up to round-off and the tets' nonlinearity at
    // strains of 4e-4 (measured: 6e-11 of the work).
    assert!(e.balance().abs() < 1e-6 * e.external_work, "balance {} vs work {}", e.balance(), e.external_work);
}

/// A static start hands over a displacement that may move a component
/// whose constraint starts later (it is free at t = 0), but not one held
/// from the start; and only the latter counts as held for the stable step.
#[test]
fn a_constraint_that_starts_later_is_free_at_the_start() {
    let mesh = box_mesh([0.0; 3], [0.01, 0.01, 0.02], 0.005, 0.1, false);
    let (jointed, m) = model(&mesh, Law::NeoHookean, rock(0.0), 0.0);
    let sel = |g: &str| select_nodes(&jointed, &NodeSelection { group: Some(g.into()), ..Default::default() }).unwrap();
    let top = sel("zmax");
    let loads = |start_time| Loads {
        fixed: vec![femdem_solver::Fixed { nodes: sel("zmin"), components: [true; 3] }],
        drives: vec![VelocityDrive {
            name: "hold".into(),
            nodes: top.clone(),
            velocity: Vec3::zeros(),
            components: [true; 3],
            ramp: Ramp::STEP,
            start_time,
        }],
        ..Loads::default()
    };
    let u: Vec<Vec3> = m.x0.iter().map(|x| Vec3::new(0.0, 0.0, -1e-7 * x.z / 0.02)).collect();
    let mut later = solver(m.clone(), loads(Some(1e-3)), 0.9);
    assert!(top.iter().all(|&i| !later.held_nodes()[i as usize]));
    later.start_displaced(&u).expect("a later constraint leaves its components free at t = 0");
    let mut now = solver(m, loads(None), 0.9);
    assert!(top.iter().all(|&i| now.held_nodes()[i as usize]));
    let err = now.start_displaced(&u).unwrap_err().to_string();
    assert!(err.contains("is prescribed but displaced"), "{err}");
}
