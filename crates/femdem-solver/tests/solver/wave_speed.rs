//! P-wave arrival in a laterally confined bar, of unbreakable tets and of
//! joint-meshed tets (reference paper §2.2, Eq. 1, 6–9, 11; §2.4, Eq. 19–20).
//!
//! # Closed form
//!
//! A bar along z whose four sides are on rollers (u_x = 0 on the x-sides,
//! u_y = 0 on the y-sides, tangential tractions free) is pushed at z = 0 by a
//! velocity drive. The front travels as a plane longitudinal wave in which
//! ε_xx = ε_yy = 0 (the rollers) and, since the rollers transmit no shear
//! traction and the bar (3 elements wide) is narrow compared with the front
//! (20 elements long), σ_yz = σ_xz = σ_xy = 0. Its speed is `c = √(M/ρ)` with
//! the constrained modulus `M = σ_zz/ε_zz` of that state. In Voigt form
//! (`ε = S σ`, engineering shears) eliminating σ_xx, σ_yy gives the Schur
//! complement
//!
//! ```text
//! 1/M = S_zz,zz − [S_zz,xx S_zz,yy] [[S_xx,xx S_xx,yy] [S_yy,xx S_yy,yy]]⁻¹ [S_xx,zz S_yy,zz]ᵀ
//! ```
//!
//! For isotropic tets this is `M = λ + 2μ`, `c_p = √((λ + 2μ)/ρ) ≈ 3514 m/s`
//! for the paper's rock (Table 1).
//!
//! Joint-meshed, every interior face carries a joint whose normal and shear
//! stiffness per unit area are both `p0/h` at small opening and slip (Eq. 6,
//! 7, 11: initial slope `2f/δp = p0/h`; in compression the normal branch is
//! exactly linear), `h` the mean edge length of the joint face. By the
//! average-strain theorem the mean strain of a body is the mean tet strain
//! plus `(1/V) Σ_j A_j sym(n_j ⊗ [u]_j)` over its joints. Assuming the same
//! stress σ in every tet (the joints then carry σ n_j, `[u]_j = (h_j/p0) σ n_j`),
//! the joints add the compliance
//!
//! ```text
//! S_j = (1/(p0 V)) Σ_j A_j h_j sym(n_j ⊗ (·) n_j),
//! ```
//!
//! built here from the actual joints of the mesh (reference areas, normals
//! and h; `crate::common::joint_compliance`), and `S = S_tet + S_j` goes into the
//! Schur complement above. The uniform-stress field is statically admissible,
//! so this is a (Reuss-type) upper bound on the compliance; the static test
//! `joint_compliance.rs` shows it is attained exactly on the regular
//! Freudenthal lattice and within 0.5 % of the joint part on the jittered one.
//! S_j of this lattice is anisotropic (its diagonal faces couple σ_zz to the
//! shears): with the other assumption, zero shear *strains*, M at p0 = E
//! would be 9 % stiffer (c 4 % faster), so the p0 = E case also checks that
//! the right state is used.
//!
//! # Measurement
//!
//! The drive's velocity rises linearly over `T_r` to `V0`. In a
//! non-dispersive bar the velocity at station z is that ramp delayed by z/c,
//! and reaches `V0/2` at `z/c + T_r/2`. We record the mass-weighted mean
//! z-velocity of the nodes of a thin slab (the lattice plane of nodes nearest
//! z, `|z − z_s| ≤ 0.3 h`; jitter moves nodes by ≤ 0.1 h) at two stations,
//! find the first time it reaches `V0/2` (linear interpolation between half
//! steps), and take speed = (distance between the slabs' mass-weighted mean
//! reference z) / (difference of the two times): the ramp, the start-up at
//! the piston and any common time offset cancel. Stations at 15 h and 45 h
//! in a 60 h bar: the echo from the free far end reaches the second station
//! after a travel of 75 h, the half-crossing there is at 45 h + 10 h.
//!
//! # Tolerance: 2 %
//!
//! - Dispersion: for linear elements with lumped mass and central
//!   differences `c(k)/c ≈ 1 − (kh)²(1 − C²)/24` (C the Courant number). The
//!   ramp front is `ℓ = c T_r = 20 h` long in every case; its spectrum
//!   (`∝ sinc(kℓ/2)/k`) lies at `kℓ ≲ 2π`, i.e. `kh ≲ 0.31`, where the phase
//!   error is below 0.4 %. The jointed lattice has the same spacing.
//! - Station positions are measured (no jitter error). A crossing time is
//!   interpolated on the rising front, which spans ≥ 30 steps and is nearly
//!   linear at its middle, so it errs by a small fraction of a step, against
//!   ≥ 50 steps between the two crossings (< 0.1 %).
//! - Amplitude: V0 = 1 mm/s gives strains ≈ V0/c ≤ 6·10⁻⁷, so the
//!   neo-Hookean law (Eq. 1, the paper's) is linear to ~10⁻⁶; every joint is
//!   in compression (all principal stresses of the front are compressive),
//!   so the normal branch is exactly linear, and the shear branch's secant
//!   stiffness `(1 − r/2) p0/h` with `r ≤ τ/(2 f_s) ≲ 10⁻⁴` is too.
//! - Jointed only: the uniform-stress estimate exceeds the true compliance
//!   of the joint part by < 0.5 % (static test), i.e. < 0.4 % of M, 0.2 % of c.
//!
//! These add to < 1 %; 2 % (the brief's requirement) leaves a margin.
//! Measured (this mesh): continuum +0.27 %; jointed p0 = 10 E +0.34 %,
//! p0 = E −0.12 % (predicted c_eff/c_p = 0.853 and 0.470).

use crate::common::{at_step, box_mesh, isotropic_compliance, joint_compliance, model, nodes_in_box, rock, stable};
use femdem_core::Vec3;
use femdem_material::{Law, Material};
use femdem_solver::{Fixed, Loads, Model, Ramp, VelocityDrive, Want};
use nalgebra::{Matrix2, Matrix6, Vector2};

/// Lattice cell size, m.
const H: f64 = 0.005;
/// Cells across the bar.
const CELLS_ACROSS: f64 = 3.0;
/// Cells along the bar.
const CELLS_ALONG: f64 = 60.0;
/// Stations, in cells from the piston.
const STATIONS: [f64; 2] = [15.0, 45.0];
/// Length of the ramp front, in cells.
const FRONT_CELLS: f64 = 20.0;
/// Piston velocity, m/s.
const V0: f64 = 1e-3;

/// `σ_zz / ε_zz` with `ε_xx = ε_yy = 0` and no shear stress, for the Voigt
/// compliance `s`.
fn confined_modulus(s: &Matrix6<f64>) -> f64 {
    let a = Matrix2::new(s[(0, 0)], s[(0, 1)], s[(1, 0)], s[(1, 1)]);
    let b = Vector2::new(s[(0, 2)], s[(1, 2)]);
    let lateral = a.try_inverse().expect("lateral compliance is invertible") * b;
    1.0 / (s[(2, 2)] - b.dot(&lateral))
}

/// Mass-weighted mean of `f` over `nodes`.
fn mass_mean(model: &Model, nodes: &[u32], f: impl Fn(usize) -> f64) -> f64 {
    let m: f64 = nodes.iter().map(|&i| model.mass[i as usize]).sum();
    nodes.iter().map(|&i| model.mass[i as usize] * f(i as usize)).sum::<f64>() / m
}

/// A measured and a predicted wave speed, m/s.
struct Speeds {
    measured: f64,
    expected: f64,
}

/// Builds the confined bar (joint-meshed with penalty `p0` if `breakable`),
/// predicts its wave speed from the compliances and measures it.
fn wave_speed(breakable: bool, p0: f64) -> Speeds {
    let (w, l) = (CELLS_ACROSS * H, CELLS_ALONG * H);
    let mesh = box_mesh([0.0; 3], [w, w, l], H, 0.1, breakable);
    let mat: Material = rock(0.0);
    let (_, m) = model(&mesh, Law::NeoHookean, mat, p0);

    let mut s = isotropic_compliance(&mat);
    if breakable {
        s += joint_compliance(&m, w * w * l, |_| true);
    }
    let expected = (confined_modulus(&s) / mat.density()).sqrt();

    let tol = 1e-6 * H;
    let side = |axis: usize, at: f64| {
        let (mut lo, mut hi) = ([-1.0; 3], [1.0; 3]);
        lo[axis] = at - tol;
        hi[axis] = at + tol;
        nodes_in_box(&m, lo, hi)
    };
    let fixed = vec![
        Fixed { nodes: side(0, 0.0), components: [true, false, false] },
        Fixed { nodes: side(0, w), components: [true, false, false] },
        Fixed { nodes: side(1, 0.0), components: [false, true, false] },
        Fixed { nodes: side(1, w), components: [false, true, false] },
    ];
    let t_ramp = FRONT_CELLS * H / expected;
    let piston = VelocityDrive {
        name: "piston".into(),
        nodes: side(2, 0.0),
        velocity: Vec3::new(0.0, 0.0, V0),
        components: [false, false, true],
        ramp: Ramp { ramp_time: t_ramp, stop_time: None },
        start_time: None,
    };
    let slabs = STATIONS.map(|z| nodes_in_box(&m, [-1.0, -1.0, (z - 0.3) * H], [1.0, 1.0, (z + 0.3) * H]));
    assert!(slabs.iter().all(|s| !s.is_empty()));
    let z = slabs.clone().map(|n| mass_mean(&m, &n, |i| m.x0[i].z));

    let loads = Loads { fixed, drives: vec![piston], ..Default::default() };
    let dt = 0.9 * stable(&m, &loads, 400).critical;
    let mut solver = at_step(m, loads, dt);

    let mut crossing = [None; 2];
    let mut previous = [0.0; 2];
    let t_max = 2.0 * (STATIONS[1] + FRONT_CELLS) * H / expected;
    while crossing[1].is_none() && solver.state().time < t_max {
        solver.step(Want::default());
        let dt = solver.dt();
        // The velocities just computed are v_{n+½}.
        let t_half = solver.state().time - 0.5 * dt;
        for k in 0..2 {
            let v = mass_mean(solver.model(), &slabs[k], |i| solver.state().v[i].z);
            if crossing[k].is_none() && v >= 0.5 * V0 {
                let f = (0.5 * V0 - previous[k]) / (v - previous[k]);
                crossing[k] = Some(t_half - dt + f * dt);
            }
            previous[k] = v;
        }
    }
    let [Some(t1), Some(t2)] = crossing else {
        panic!("the front did not reach both stations: {crossing:?}");
    };
    Speeds { measured: (z[1] - z[0]) / (t2 - t1), expected }
}

#[test]
fn constrained_modulus_of_isotropic_tets_is_lambda_plus_two_mu() {
    let mat = rock(0.0);
    let m = confined_modulus(&isotropic_compliance(&mat));
    assert!((m / mat.p_wave_modulus() - 1.0).abs() < 1e-12, "{m}");
}

#[test]
fn p_wave_in_a_confined_bar_of_unbreakable_tets_travels_at_c_p() {
    let mat = rock(0.0);
    let s = wave_speed(false, 10.0 * mat.young());
    assert!((s.expected / mat.p_wave_speed() - 1.0).abs() < 1e-12);
    let err = s.measured / s.expected - 1.0;
    eprintln!("continuum: measured {:.1} m/s, c_p {:.1} m/s ({:+.3} %)", s.measured, s.expected, 100.0 * err);
    assert!(err.abs() < 0.02, "measured {} vs c_p {}", s.measured, s.expected);
}

#[test]
fn p_wave_in_a_joint_meshed_bar_is_slowed_by_the_joint_compliance() {
    let mat = rock(0.0);
    for p0_over_e in [10.0, 1.0] {
        let s = wave_speed(true, p0_over_e * mat.young());
        let err = s.measured / s.expected - 1.0;
        eprintln!(
            "p0 = {p0_over_e} E: measured {:.1} m/s, predicted {:.1} m/s ({:+.3} %), c_p {:.1} m/s",
            s.measured,
            s.expected,
            100.0 * err,
            mat.p_wave_speed()
        );
        assert!(err.abs() < 0.02, "p0 = {p0_over_e} E: measured {} vs predicted {}", s.measured, s.expected);
        // The joints' effect is far larger than the tolerance: the test sees it.
        assert!(s.measured < 0.9 * mat.p_wave_speed());
    }
}
