//! The static start agrees with the long-damped explicit solution (issue
//! 13's "done when": within 1 %).
//!
//! # Case
//!
//! A jointed limestone column, 20 × 20 × 40 mm in 5 mm cells (768 tets,
//! about 1400 joints at p0 = 10 E), fixed on its base, under a pressure of
//! 0.2 MPa and a shear traction of 0.05 MPa on its top and a body force
//! along −z whose weight per area, `ρ g L = 0.1 MPa`, is of the order of
//! the pressure (g = 926 m/s²: at the true g the weight of a 40 mm column
//! would be lost in round-off). It is compressed, sheared and bent: the
//! tets, the joints' normal and shear stiffness and the body force all
//! enter.
//!
//! # Reference
//!
//! The explicit solver (neo-Hookean tets, Eq. 1; the joints of Eq. 11;
//! loads applied at once on the current geometry) relaxed by
//! mass-proportional damping `v ← (1 − c Δt) v` with `c = ω_R`, the
//! Rayleigh estimate `ω_R² = fᵀu / uᵀMu` of the first (bending) mode from
//! the static deflection; every mode decays at least as `e^{−ω₁² t / c}`
//! or `e^{−c t / 2}`, so at `t = 60/ω_R` the transient is below `e^{−20}`
//! of the load's displacement; the test checks that the displacement
//! changed by less than 10⁻⁶ over the last fifth. The damping does not
//! change the static state.
//!
//! # Tolerances
//!
//! The linear solve (the static start: small-strain tets, the
//! joints' initial tangent `p0/h`) and the explicit run solve the same
//! discrete equilibrium, the first linearised at the reference state. They
//! differ by the explicit model's nonlinearity: geometric and material
//! terms of the order of the strain (≈ 10⁻⁵), and the joints' hardening
//! parabola (Eq. 11), whose secant is `(1 − r/2) p0/h` at `r = δ/δp`. The
//! bending tension at the base, `6 M / a³ ≈ 0.6 MPa` against the weak
//! cohesion's cut-off `c / tan φ = 0.76 MPa`, puts the base joints at
//! `r ≈ 0.2`: the linear answer is off by about a percent (measured
//! 0.96 %), within the 1 % at these loads and no better. The
//! corrected static start (modified Newton on the explicit model's own
//! forces, to `10⁻⁷` of the load) is that equilibrium: it must agree with
//! the damped run to its convergence, `10⁻⁶` (measured 4.7·10⁻¹¹ with
//! `Solver::damp`, which moves `x_{n+1}` with `v`; a few 10⁻¹⁰ when the
//! damping scaled `v` alone).

use femdem_core::{Real, Vec3};
use femdem_solver::{Loads, Ramp, SurfaceKind, Want};
use femdem_static::{StaticOptions, static_solve};

use crate::common::{displacement, fixed, jointed_box, limestone, model, relative_difference, solver, surface};

#[test]
fn static_start_agrees_with_the_long_damped_explicit_solution() {
    let size = [0.02, 0.02, 0.04];
    let mesh = jointed_box(size, 0.005);
    let material = limestone(0.0);
    let m = model(&mesh, material);
    let g = 0.1e6 / (material.density() * size[2]);
    let loads = Loads {
        gravity: Vec3::new(0.0, 0.0, -g),
        fixed: vec![fixed(&mesh, "zmin")],
        surfaces: vec![
            surface(&mesh, "zmax", SurfaceKind::Pressure(0.2e6), Ramp::STEP),
            surface(&mesh, "zmax", SurfaceKind::Traction(Vec3::new(0.05e6, 0.0, 0.0)), Ramp::STEP),
        ],
        ..Default::default()
    };
    let linear = StaticOptions { correct: false, ..Default::default() };
    let solution = static_solve(&m, &loads, &[], &linear).unwrap();
    assert_eq!((solution.bodies, solution.free_bodies), (1, 0));
    assert!(solution.residual < 1e-10 && solution.unbalanced == 0.0);
    let u_static = solution.displacement;
    let corrected = static_solve(&m, &loads, &[], &StaticOptions::default()).unwrap();
    eprintln!(
        "column: corrected in {} steps: {:?}, joints {:?}",
        corrected.corrections, corrected.model_residual, corrected.joints
    );

    // Rayleigh's estimate of the first mode from the static deflection.
    let f = femdem_static_loads(&m, &loads);
    let work: Real = f.iter().zip(&u_static).map(|(f, u)| f.dot(u)).sum();
    let inertia: Real = m.mass.iter().zip(&u_static).map(|(m, u)| m * u.norm_squared()).sum();
    let omega = (work / inertia).sqrt();

    let mut s = solver(m, loads, 0.9);
    let keep = 1.0 - omega * s.dt();
    let t_end = 60.0 / omega;
    let mut at_four_fifths = None;
    while s.state().time < t_end {
        s.step(Want::default());
        s.damp(keep).unwrap();
        if at_four_fifths.is_none() && s.state().time >= 0.8 * t_end {
            at_four_fifths = Some(displacement(&s));
        }
    }
    let u_explicit = displacement(&s);
    let drift = relative_difference(&u_explicit, &at_four_fifths.unwrap());
    assert!(drift < 1e-6, "not at rest: the displacement changed by {drift:e} over the last fifth");
    assert!(s.failures().is_empty());
    let difference = relative_difference(&u_static, &u_explicit);
    let corrected_difference = relative_difference(&corrected.displacement, &u_explicit);
    eprintln!(
        "column: static vs damped explicit {difference:.3e}, corrected ({} corrections) {corrected_difference:.3e} \
         ({} steps of the explicit run, ω_R = {omega:.4e} rad/s)",
        corrected.corrections,
        s.state().step
    );
    assert!(difference < 1e-2, "linear static and explicit differ by {difference:e}");
    assert!(corrected_difference < 1e-6, "corrected static and explicit differ by {corrected_difference:e}");
    assert!(corrected.model_residual.unwrap() < 1e-7 && corrected.joints.past_peak == 0);
}

/// The nodal loads as the static solve takes them (surface loads on the
/// reference geometry, gravity on the physical mass).
fn femdem_static_loads(m: &femdem_solver::Model, loads: &Loads) -> Vec<Vec3> {
    let mut f: Vec<Vec3> = m.mass.iter().map(|&mi| loads.gravity * (mi / m.mass_scaling)).collect();
    for load in &loads.surfaces {
        femdem_solver::loads::surface_forces(load, &m.x0, 1.0, |n, force| f[n as usize] += force);
    }
    f
}
