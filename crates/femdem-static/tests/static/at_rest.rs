//! A free jointed cube under balanced polyaxial pressures, started
//! statically, stays at rest; ramped dynamically, it rings.
//!
//! # Case
//!
//! The polyaxial test of the reference paper (§3.2, Test 1: limestone,
//! c = 0.5 MPa, φ = 33.4°, 5 % damping ratio) on a 40 mm jointed cube in
//! 5 mm cells (3072 tets), at a tenth of its pressures (0.375, 1.5,
//! 0.9375 MPa along x, y, z: below the joints' strength, so nothing may
//! break) and with no support: the pressures balance, and the static solve
//! removes the six rigid modes (inertia relief).
//!
//! - dynamic: the pressures ramped over 15 P-wave transits of the cube (as
//!   `cases/paper/polyaxial.toml`), then held;
//! - static: [`femdem_static::static_solve`] under the held pressures, then
//!   [`femdem_solver::Solver::start_displaced`].
//!
//! Both are watched for the same 10 transits, the dynamic one once its
//! ramp is over: the largest kinetic energy, and the mean elastic energy.
//!
//! # Tolerances
//!
//! The static start is corrected to the explicit model's own equilibrium
//! to 10⁻⁷ of the load (`femdem_static::StaticOptions::model_tolerance`);
//! without the correction it would be off by 15 % of the load, for the
//! joints work at up to `r ≈ 0.3` of their hardening parabola, whose
//! secant is `1 − r/2` of the initial tangent. What is left to move it is
//! that residual and the pressures' net force and torque on the deformed
//! faces (balanced exactly on the reference faces only). "At rest" is
//! asked as a vibration amplitude below 10⁻⁴ of the static displacement,
//! i.e. a kinetic energy below 10⁻⁸ of the stored energy, and below 10⁻⁴ of
//! the dynamic ramp's (measured: 2·10⁻¹¹ and 3·10⁻⁸).
//! The dynamic run rings about the same state: its mean elastic energy
//! over the window is within 1 % of the static one (the elastic energy
//! oscillates at first order in the vibration's amplitude, by a few % for
//! a kinetic energy of 6·10⁻⁴ of the stored; measured 0.2 %). No joint may
//! fail in either run, and the energy account starts balanced.

use femdem_core::Real;
use femdem_solver::{Loads, Ramp, Solver, Want};
use femdem_static::{StaticOptions, hold_surface_loads, static_solve};

use crate::common::{jointed_box, limestone, model, pressures, solver, viscosity};

const SIZE: Real = 0.04;
const H: Real = 0.005;

/// The largest kinetic energy over `steps` steps, and the mean elastic
/// energy.
fn watch(s: &mut Solver, steps: u64) -> (Real, Real) {
    let mut peak: Real = 0.0;
    let mut elastic = 0.0;
    for _ in 0..steps {
        let e = s.step(Want { energy: true, stress: false }).energies;
        peak = peak.max(e.kinetic);
        elastic += (e.tet_elastic + e.joint_elastic) / steps as Real;
    }
    (peak, elastic)
}

#[test]
fn a_statically_started_cube_under_balanced_pressures_stays_at_rest() {
    let mesh = jointed_box([SIZE; 3], H);
    let material = limestone(viscosity(0.05, H));
    let transit = SIZE / material.p_wave_speed();
    let ramp = Ramp { ramp_time: 15.0 * transit, stop_time: None };
    let loads = Loads { surfaces: pressures(&mesh, [0.375e6, 1.5e6, 0.9375e6], ramp), ..Default::default() };

    let mut dynamic = solver(model(&mesh, material), loads.clone(), 0.9);
    let dt = dynamic.dt();
    let window = (10.0 * transit / dt).ceil() as u64;
    let ramp_steps = (ramp.ramp_time / dt).ceil() as u64;
    watch(&mut dynamic, ramp_steps);
    let (dynamic_kinetic, dynamic_elastic) = watch(&mut dynamic, window);

    let mut held = loads;
    hold_surface_loads(&mut held);
    let m = model(&mesh, material);
    let solution = static_solve(&m, &held, &[], &StaticOptions::default()).unwrap();
    assert_eq!((solution.bodies, solution.free_bodies), (1, 1));
    assert!(
        solution.residual < 1e-10 && solution.unbalanced < 1e-12,
        "residual {:e}, unbalanced {:e}",
        solution.residual,
        solution.unbalanced
    );
    let mut statik = solver(m, held, 0.9);
    assert_eq!(statik.dt(), dt);
    let stored = statik.start_displaced(&solution.displacement).unwrap();
    let (static_kinetic, static_elastic) = watch(&mut statik, window);

    eprintln!(
        "at rest: kinetic energy {static_kinetic:.3e} J (static start) vs {dynamic_kinetic:.3e} J (dynamic ramp) over \
         {window} steps; elastic {static_elastic:.4e} J vs {dynamic_elastic:.4e} J (start: {stored:.4e} J)"
    );
    assert!(dynamic.failures().is_empty() && statik.failures().is_empty());
    assert!(static_kinetic < 1e-8 * static_elastic, "{static_kinetic:e} J against {static_elastic:e} J stored");
    assert!(static_kinetic < 1e-4 * dynamic_kinetic, "{static_kinetic:e} J against {dynamic_kinetic:e} J");
    // The same loaded state: the elastic energies agree.
    assert!((static_elastic / dynamic_elastic - 1.0).abs() < 1e-2, "{static_elastic:e} vs {dynamic_elastic:e}");
    // The account starts balanced: the stored energy is booked as work done.
    let balance = statik.energies().balance();
    assert!(balance.abs() < 1e-3 * stored, "balance {balance:e} J against {stored:e} J");
}
