//! A free body pushed on one face: the unbalanced load becomes a rigid
//! acceleration (inertia relief), and the statically started body
//! accelerates without ringing.
//!
//! # Closed form
//!
//! A free jointed block of mass `M` under a pressure `p` on its face
//! `z = 0` (area `A₀`) accelerates at `a = p A₀ / M` along +z (what the
//! static solve's inertia relief finds, on the reference geometry). The
//! explicit run applies the pressure on the current face, whose area `A`
//! the d'Alembert stress has grown by Poisson's effect (`≈ 2 ν p / E`,
//! 10⁻⁵): it accelerates at `p A / M`, `A` measured on the started state. Its
//! d'Alembert stress falls linearly from `−p` at the loaded face to zero
//! at the free one: that is the static solution under `f − M a`. Started
//! from it at rest, the explicit run keeps that stress and moves rigidly:
//! after time `t` its kinetic energy is `½ M (p A t / M)²`, and the elastic energy
//! stays where it started.
//!
//! # Tolerances
//!
//! The recorded kinetic energy is the leapfrog's `½ M v_{n−½}·v_{n+½}`;
//! started with `v_{−½} = 0` under a uniform acceleration, `v_{n−½} = a t_n`
//! and `v_{n+½} = a (t_n + Δt)`, which the closed form takes in. What departs
//! from it is the explicit model's out-of-balance force left by the static
//! start (below 10⁻⁷ of the load), whose vibration energy goes with its
//! square: we require 10⁻⁶ on the kinetic energy and 10⁻³ on the elastic
//! energy. A sudden (dynamic)
//! start under the same push rings with a vibration energy of the order
//! of the stored energy, checked as a contrast.

use femdem_core::{Real, Vec3};
use femdem_solver::{Loads, Ramp, SurfaceKind, Want};
use femdem_static::{StaticOptions, static_solve};

use crate::common::{jointed_box, limestone, model, solver, surface};

#[test]
fn a_pushed_free_body_accelerates_rigidly_from_the_static_start() {
    let size = [0.02, 0.02, 0.04];
    let mesh = jointed_box(size, 0.005);
    let m = model(&mesh, limestone(0.0));
    let p = 0.5e6;
    let loads =
        Loads { surfaces: vec![surface(&mesh, "zmin", SurfaceKind::Pressure(p), Ramp::STEP)], ..Default::default() };
    let solution = static_solve(&m, &loads, &[], &StaticOptions::default()).unwrap();
    assert_eq!(solution.free_bodies, 1);
    let total: Real = m.mass.iter().sum();
    let a = p * size[0] * size[1] / total;
    for acc in &solution.rigid_acceleration {
        assert!((acc - Vec3::new(0.0, 0.0, a)).norm() < 1e-9 * a, "{acc} vs {a}");
    }
    assert!(solution.unbalanced > 0.0);

    let mut statik = solver(m.clone(), loads.clone(), 0.9);
    let stored = statik.start_displaced(&solution.displacement).unwrap();
    let x = &statik.state().x;
    let area: Real = loads.surfaces[0]
        .faces
        .iter()
        .map(|f| {
            let [a, b, c] = f.map(|n| x[n as usize]);
            0.5 * (b - a).cross(&(c - a)).norm()
        })
        .sum();
    let a_current = p * area / total;
    let mut sudden = solver(m, loads, 0.9);
    let steps = 2000;
    let mut last = (0.0, 0.0, 0.0);
    let mut sudden_last = (0.0, 0.0);
    for _ in 0..steps {
        let r = statik.step(Want { energy: true, stress: false });
        last = (r.time, r.energies.kinetic, r.energies.tet_elastic + r.energies.joint_elastic);
        let e = sudden.step(Want { energy: true, stress: false }).energies;
        sudden_last = (e.kinetic, e.tet_elastic + e.joint_elastic);
    }
    let (t, kinetic, elastic) = last;
    let expected = 0.5 * total * a_current * a_current * t * (t + statik.dt());
    eprintln!(
        "pushed: kinetic {kinetic:.6e} J vs ½M a² t (t + Δt) = {expected:.6e} J; elastic {elastic:.4e} J (start {stored:.4e} J); \
         sudden start: kinetic {:.4e} J, elastic {:.4e} J",
        sudden_last.0, sudden_last.1
    );
    assert!((kinetic / expected - 1.0).abs() < 1e-6, "kinetic {kinetic:e} vs {expected:e}");
    assert!((elastic / stored - 1.0).abs() < 1e-3, "elastic {elastic:e} vs {stored:e}");
    let sudden_vibration = sudden_last.0 - expected;
    assert!(sudden_vibration.abs() > 0.1 * stored, "the sudden start should ring: {sudden_vibration:e} J");
}
