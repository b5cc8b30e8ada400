//! Energy conservation of the undamped explicit update (Eq. 19–20 with the
//! central-difference scheme): a free, joint-meshed block set vibrating by
//! an initial velocity field, with η = 0 and no loads, keeps
//! `E = kinetic + tet elastic + joint elastic` within 0.5% over 10,000
//! steps (the bound). Leapfrog is symplectic: its energy error
//! oscillates with amplitude O((ω Δt)²) and does not drift; at 0.9 of the
//! critical step the oscillation is a fraction of a percent for the
//! low modes that carry the energy here.
//!
//! Also: with damping (η > 0) and a drive, the balance
//! `kinetic + elastic + dissipated − work` stays at its initial value to
//! within 1% of the work done (the account centred on `t_n` is exact up
//! to the nonlinear laws' truncation; `energy_guard.rs` bounds it
//! tighter).

use crate::common::{box_mesh, model, rock, solver};
use femdem_core::{Real, Vec3};
use femdem_material::Law;
use femdem_solver::select::{NodeSelection, select_nodes};
use femdem_solver::{Loads, Ramp, VelocityDrive, Want};

#[test]
fn undamped_energy_drifts_less_than_half_a_percent_over_10000_steps() {
    let mesh = box_mesh([0.0; 3], [0.05, 0.04, 0.03], 0.01, 0.1, true);
    let (_, m) = model(&mesh, Law::NeoHookean, rock(0.0), 10.0 * 26e9);
    let mut s = solver(m, Loads::default(), 0.9);
    // A smooth initial velocity field of about 0.05 m/s (small strain).
    s.set_velocity(|x| Vec3::new((x.y * 60.0).sin(), (x.z * 70.0).cos(), (x.x * 50.0).sin()) * 0.05);
    let energy =
        |s: &femdem_solver::Solver| s.energies().kinetic + s.energies().tet_elastic + s.energies().joint_elastic;
    s.step(Want { energy: true, ..Want::default() });
    let e0 = energy(&s);
    let mut worst: Real = 0.0;
    for n in 1..10_000 {
        let want = n % 100 == 0;
        s.step(Want { energy: want, ..Want::default() });
        if want {
            worst = worst.max((energy(&s) - e0).abs() / e0);
        }
    }
    assert!(worst < 5e-3, "energy drift {worst}");
    assert!(s.energies().joint_elastic > 0.0 && s.energies().tet_elastic > 0.0);
}

#[test]
fn damped_driven_block_balances_its_energy_account() {
    let mesh = box_mesh([0.0; 3], [0.05, 0.04, 0.03], 0.01, 0.1, true);
    let (jointed, m) = model(&mesh, Law::NeoHookean, rock(300.0), 10.0 * 26e9);
    let loads = base_and_top(&jointed, 0.02, Ramp { ramp_time: 2e-5, stop_time: None });
    let mut s = solver(m, loads, 0.9);
    for n in 0..3000 {
        s.step(Want { energy: n % 100 == 99, ..Want::default() });
    }
    let e = s.energies();
    assert!(e.external_work > 0.0 && e.damping > 0.0);
    assert!(e.balance().abs() < 0.01 * e.external_work, "balance {} vs work {}", e.balance(), e.external_work);
}

/// A wave of strain about 10⁻⁹ (a top drive at 10 µm/s for 5 µs against a
/// fixed base: 5·10⁻¹¹ m on the 0.03 m block) balances its account as a
/// large one does: the stored energy is of second order in the strain and
/// must be computed without cancelling its first-order terms
/// (`femdem_material::law`, "Energy at small strains"); computed as
/// `μ/2 (tr B − 3) − μ ln J + …` the balance came out at 7.7 times the
/// work done. The tolerance, 10⁻⁵ of the work: for a linear body
/// the centred account is exact (its nonlinearity at this strain is
/// 10⁻⁹), so what is left is the positions' round-off, an ulp of
/// |x| ≤ 0.05 m (7·10⁻¹⁸ m) against displacements of some 5·10⁻¹¹ m,
/// 1.4·10⁻⁷ of the energy at first order, and against the joints'
/// openings, ten times smaller (penalty 10 E), 1.4·10⁻⁶ (measured:
/// 2.9·10⁻⁷ without joints, 2.6·10⁻⁷ with them).
#[test]
fn a_wave_of_strain_1e_9_balances_its_energy_account() {
    for jointed in [false, true] {
        let mesh = box_mesh([0.0; 3], [0.05, 0.04, 0.03], 0.01, 0.1, jointed);
        let (jointed_mesh, m) = model(&mesh, Law::NeoHookean, rock(0.0), 10.0 * 26e9);
        let loads = base_and_top(&jointed_mesh, 1e-5, Ramp { ramp_time: 2e-6, stop_time: Some(6e-6) });
        let mut s = solver(m, loads, 0.9);
        let mut worst: Real = 0.0;
        for n in 0..2000 {
            let want = n % 50 == 49;
            s.step(Want { energy: want, ..Want::default() });
            if want {
                worst = worst.max(s.energies().balance().abs());
            }
        }
        let e = s.energies();
        assert!(e.external_work > 0.0 && e.tet_elastic > 0.0);
        assert!(worst < 1e-5 * e.external_work, "jointed {jointed}: balance {worst:e} vs work {:e}", e.external_work);
    }
}

/// A fixed base (`zmin`) and a top (`zmax`) driven along z at `speed`
/// (m/s) by `ramp`.
fn base_and_top(mesh: &femdem_mesh::JointedMesh, speed: Real, ramp: Ramp) -> Loads {
    let group = |g: &str| select_nodes(mesh, &NodeSelection { group: Some(g.into()), ..Default::default() }).unwrap();
    let drive = |name: &str, nodes, velocity, components, ramp| VelocityDrive {
        name: String::from(name),
        nodes,
        velocity,
        components,
        ramp,
        start_time: None,
    };
    Loads {
        drives: vec![
            drive("base", group("zmin"), Vec3::zeros(), [true; 3], Ramp::STEP),
            drive("top", group("zmax"), Vec3::new(0.0, 0.0, speed), [false, false, true], ramp),
        ],
        ..Loads::default()
    }
}
