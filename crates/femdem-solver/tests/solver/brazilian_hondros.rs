//! Stresses at the centre of a diametrically loaded disc (the elastic stage
//! of the reference paper's Brazilian test, §3.1, Table 1, Eq. 21 and 23).
//!
//! # Closed form
//!
//! A disc of diameter D and thickness t under two opposite line loads P
//! (total, along a diameter) has, in plane elasticity, the stress field of
//! two Flamant point loads plus a uniform in-plane tension (Hertz; Timoshenko
//! & Goodier, Theory of Elasticity, §41): from each load point, a radial
//! stress `σ_rr = −2P cos θ / (π t r)` (r the distance to the load point, θ
//! the angle from the load direction), plus `2P/(πDt)` in x and y. At the
//! centre this is the Hondros point-load limit
//!
//! ```text
//! σ_x = 2P/(πDt) (tension),   σ_y = −6P/(πDt).
//! ```
//!
//! (Hondros 1959 spreads the load over an arc 2α: the centre values are
//! multiplied by `(sin 2α ∓ α)/α` over `(2 ∓ 1)`, i.e. `1 − O(α²)`; here the
//! load reaches the disc through a line of nodes, α ≈ h/(2R), < 0.1 %.) The
//! 2D stress of a disc loaded by tractions does not depend on the elastic
//! constants (Michell), so it also holds for the joint-meshed disc as long as
//! its joints' compliance leaves it homogeneous and isotropic in the plane
//! on average.
//!
//! # Setup and measurement
//!
//! Disc of radius 20 mm and thickness 10 mm (`generate_extrusion`, circle
//! outline; the polygon has a vertex on each axis). The nodes of the two
//! contact lines (x = 0, y = ±R, all z; every node of a joint-meshed vertex)
//! are driven towards each other in y only (x and z free): two line loads.
//! P is Eq. 21, the mean of the two reactions (`report.drive_forces`), and
//! the centre stress the volume-weighted mean Cauchy stress of the tets whose
//! centroid lies within `a = 0.2 R` of the axis (all z: the through-thickness
//! mean, which is what the 2D solution describes). It is compared with the
//! closed-form field averaged over the same tets (at their centroids, with
//! the same weights), which removes the averaging bias: by Taylor expansion
//! the plain centre values exceed that average by about `(a/R)² = 4 %` (σ_x)
//! and `(a/R)²/3 = 1.3 %` (σ_y). a = 0.2 R holds 100–450 tets — each tet's
//! stress scatters about the smooth field by ~4 % of 2P/(πDt) in σ_x and
//! ~12 % in σ_y (measured, for both meshes), which the average brings to
//! ≲ 1 % — and stays 0.8 R from the loads. The mean over the tets within
//! 0.1 R (35–115 tets, bias 1 % and 0.3 %) is also compared with the plain
//! centre values 2P/(πDt) and −6P/(πDt), with the same tolerance.
//!
//! Unbreakable disc, h = 2 mm (11 280 tets), the paper's procedure: the
//! drives' velocity (1 mm/s) is ramped over `T_r` = 100 µs and held, with
//! Kelvin–Voigt viscosity `η = 0.2 η_crit(h)` (Eq. 1), and the disc is
//! measured at `t` = 250 µs. Quasi-static error: the lowest in-plane mode of
//! the disc has `ω₁ ≳ c_s/R` (c_s = √(μ/ρ) = 2150 m/s, c_s/R ≈ 1.1·10⁵ s⁻¹;
//! the wave transit R/c_s ≈ 9 µs), and a velocity ramp leaves a free
//! oscillation of relative amplitude at most `2/(ω₁² T_r (t − T_r/2))`
//! ≈ 0.9 % against the static response; after the ramp the quasi-static
//! field moves at constant rate and has no inertia. The viscous stress
//! `η D` has the same 2D shape (the field is independent of the constants)
//! and is ~10⁻³ of the elastic one. The same disc is also relaxed statically
//! (below) and the two must agree within 1 %.
//!
//! Joint-meshed disc (p0 = 10 E, h = 2.5 mm, two layers: 2 880 tets,
//! 5 176 joints). The joints make the stable step ~3.5× shorter, so the slow
//! ramp would cost ~4 000 steps; instead the drives (5 mm/s, ramped over
//! 10 µs) stop at 20 µs, and the held disc is brought to rest by
//! mass-proportional damping `v ← (1 − c Δt) v`, `c = 2 c_s/R` (about
//! critical for ω₁), until 120 µs; the static state does not depend on the
//! damping (P and the stresses change by < 10⁻³ over the last fifth; the
//! slow-ramp procedure gives the same stresses to 0.2 % on this mesh).
//! Two layers suffice: the in-plane field is uniform through the thickness
//! at leading order, and a linear tet reproduces a z-independent linear
//! field whatever its height.
//!
//! The amplitudes keep everything linear: strains ≤ 10⁻⁴ at the load
//! points and ~10⁻⁶ at the centre (the neo-Hookean Eq. 1 is linear there);
//! joint stresses ≲ 1 MPa, far below f_t = 3 MPa and c = 15 MPa (Eq. 5, 11).
//!
//! # Tolerance: 5 %
//!
//! - FE discretisation of the smooth centre field by constant-stress tets
//!   and of the point load: O((h/R)²) ≈ 1–1.6 %;
//! - 3D effects of a thick disc (t = D/4, ν = 0.2) on the through-thickness
//!   mean: O(ν t²/D²) ≈ 1 %;
//! - quasi-static error ≤ 0.9 % (dynamic run), < 0.1 % (relaxed runs);
//! - scatter of the tet stresses after averaging ≲ 1 % of σ_x.
//!
//! They add to ≲ 4 % (the 0.1 R comparison trades the averaging bias of
//! ≤ 1 % for more scatter, ≲ 2 %). Measured, against the averaged field
//! (0.2 R) and the centre values (0.1 R): unbreakable σ_x −1.1 % / −1.4 %,
//! σ_y −0.1 % / −0.1 % (slow ramp and relaxed alike, to 0.03 %);
//! joint-meshed σ_x +0.9 % / +2.3 %, σ_y +1.9 % / +0.2 %.

use crate::common::{at_step, model, nodes_in_box, rock, stable};
use femdem_core::{Mat3, Vec3};
use femdem_material::Law;
use femdem_mesh::Region;
use femdem_mesh::generate::{ExtrusionSpec, Outline, generate_extrusion};
use femdem_solver::{Loads, Ramp, Solver, VelocityDrive, Want};
use std::f64::consts::PI;

/// Disc radius, m.
const R: f64 = 0.02;
/// Disc thickness, m.
const T: f64 = 0.01;
/// Averaging radius as a fraction of R (compared with the averaged field).
const A_OVER_R: f64 = 0.2;
/// Smaller radius, compared with the plain centre values.
const A_NEAR_OVER_R: f64 = 0.1;

/// The plane point-load solution for total load `p` (N) at `(x, y)`: a
/// Flamant radial stress from each load point plus `2P/(πDt)` in-plane.
fn point_load_stress(p: f64, x: f64, y: f64) -> Mat3 {
    let mut s = Mat3::from_diagonal(&Vec3::new(1.0, 1.0, 0.0)) * (2.0 * p / (PI * 2.0 * R * T));
    // Load points and the direction each load pushes in.
    for (at, push) in [(R, -1.0), (-R, 1.0)] {
        let r = Vec3::new(x, y - at, 0.0);
        let e = r / r.norm();
        let cos_theta = e.y * push;
        s += e * e.transpose() * (-2.0 * p * cos_theta / (PI * T * r.norm()));
    }
    s
}

/// How the disc is loaded.
enum Loading {
    /// Velocity `v` ramped over `ramp` and held, with viscosity ratio `xi`
    /// (of Munjiza's critical value for the element size), until `end`.
    SlowRamp { v: f64, ramp: f64, xi: f64, end: f64 },
    /// Velocity `v` ramped over `ramp` and stopped at `stop`, then mass
    /// damping `c` until `end`.
    Relaxed { v: f64, ramp: f64, stop: f64, c: f64, end: f64 },
}

/// Centre stresses and load of one run.
#[derive(Debug)]
struct Centre {
    /// Eq. 21, N.
    load: f64,
    /// Mean Cauchy stress of the centre tets.
    measured: Mat3,
    /// The closed-form field averaged over the same tets.
    exact: Mat3,
    /// Number of centre tets.
    tets: usize,
    /// Mean Cauchy stress of the tets within `A_NEAR_OVER_R · R`.
    near: Mat3,
    /// Their number.
    near_tets: usize,
}

impl Centre {
    /// `2P/(πDt)`.
    fn unit(&self) -> f64 {
        2.0 * self.load / (PI * 2.0 * R * T)
    }

    /// Relative errors of σ_x and σ_y against the averaged closed form.
    fn errors(&self) -> [f64; 2] {
        [0, 1].map(|k| self.measured[(k, k)] / self.exact[(k, k)] - 1.0)
    }

    /// Relative errors of σ_x and σ_y near the centre against the centre
    /// values `2P/(πDt)` and `−6P/(πDt)`.
    fn centre_errors(&self) -> [f64; 2] {
        [(0, 1.0), (1, -3.0)].map(|(k, f)| self.near[(k, k)] / (f * self.unit()) - 1.0)
    }

    fn report(&self, what: &str) {
        let [ex, ey] = self.errors();
        eprintln!(
            "{what}: P = {:.3} N, {} tets; σx = {:.4}, σy = {:.4} × 2P/(πDt) \
             (closed form averaged: {:.4}, {:.4}; at the centre 1, −3): errors {:+.2} %, {:+.2} %",
            self.load,
            self.tets,
            self.measured[(0, 0)] / self.unit(),
            self.measured[(1, 1)] / self.unit(),
            self.exact[(0, 0)] / self.unit(),
            self.exact[(1, 1)] / self.unit(),
            100.0 * ex,
            100.0 * ey
        );
        let [cx, cy] = self.centre_errors();
        eprintln!(
            "    within {A_NEAR_OVER_R} R ({} tets): σx = {:.4}, σy = {:.4} × 2P/(πDt): errors {:+.2} %, {:+.2} % against 1, −3",
            self.near_tets,
            self.near[(0, 0)] / self.unit(),
            self.near[(1, 1)] / self.unit(),
            100.0 * cx,
            100.0 * cy
        );
    }

    /// Both comparisons within `tol`.
    fn check(&self, tol: f64) {
        let e = self.errors().into_iter().chain(self.centre_errors());
        assert!(e.into_iter().all(|e| e.abs() < tol), "{self:?}");
    }
}

/// Loads a disc of element size `h` (`layers` through the thickness, or the
/// generator's choice), joint-meshed with p0 = 10 E if `breakable`, and
/// measures its centre stresses at the end.
fn brazilian(breakable: bool, h: f64, layers: Option<usize>, loading: Loading) -> Centre {
    let mesh = generate_extrusion(&ExtrusionSpec {
        outline: Outline::Circle { center: [0.0, 0.0], radius: R },
        traces: vec![],
        z0: 0.0,
        thickness: T,
        element_size: h,
        layers,
        region: Region { name: "disc".into(), breakable },
    })
    .unwrap();
    let eta = match loading {
        Loading::SlowRamp { xi, .. } => xi * rock(0.0).critical_viscosity(h),
        Loading::Relaxed { .. } => 0.0,
    };
    let mat = rock(eta);
    let (_, m) = model(&mesh, Law::NeoHookean, mat, 10.0 * mat.young());

    let (v, ramp, end) = match loading {
        Loading::SlowRamp { v, ramp, end, .. } => (v, Ramp { ramp_time: ramp, stop_time: None }, end),
        Loading::Relaxed { v, ramp, stop, end, .. } => (v, Ramp { ramp_time: ramp, stop_time: Some(stop) }, end),
    };
    let tol = 1e-3 * h;
    let line = |y: f64| nodes_in_box(&m, [-tol, y - tol, -1.0], [tol, y + tol, 1.0]);
    let drive = |name: &str, y: f64, vy: f64| VelocityDrive {
        name: name.into(),
        nodes: line(y),
        velocity: Vec3::new(0.0, vy, 0.0),
        components: [false, true, false],
        ramp,
        start_time: None,
    };
    let drives = vec![drive("top", R, -v), drive("bottom", -R, v)];
    assert!(drives.iter().all(|d| d.nodes.len() > (T / h) as usize), "a contact line is missing nodes");

    let a = A_OVER_R * R;
    let centroid = |t: usize| m.tets[t].iter().map(|&i| m.x0[i as usize]).sum::<Vec3>() / 4.0;
    let centre: Vec<usize> = (0..m.tets.len()).filter(|&t| centroid(t).xy().norm() <= a).collect();
    let centroids: Vec<Vec3> = centre.iter().map(|&t| centroid(t)).collect();
    let near: Vec<usize> = centre.iter().copied().filter(|&t| centroid(t).xy().norm() <= A_NEAR_OVER_R * R).collect();

    let loads = Loads { drives, ..Default::default() };
    let dt = 0.9 * stable(&m, &loads, 400).critical;
    let mut s = at_step(m, loads, dt);
    let keep = match loading {
        Loading::Relaxed { c, .. } => 1.0 - c * s.dt(),
        Loading::SlowRamp { .. } => 1.0,
    };
    let stop = match loading {
        Loading::Relaxed { stop, .. } => stop,
        Loading::SlowRamp { .. } => end,
    };

    let measure = |s: &Solver| {
        let f = &s.record().drive_forces;
        let load = 0.5 * (-f[0].y + f[1].y);
        let (mut vol, mut measured, mut exact) = (0.0, Mat3::zeros(), Mat3::zeros());
        for (&t, c) in centre.iter().zip(&centroids) {
            let w = s.model().tet_ref[t].volume;
            vol += w;
            measured += s.workspace().stress[t] * w;
            exact += point_load_stress(load, c.x, c.y) * w;
        }
        let mean = |tets: &[usize]| {
            let v: f64 = tets.iter().map(|&t| s.model().tet_ref[t].volume).sum();
            tets.iter().map(|&t| s.workspace().stress[t] * s.model().tet_ref[t].volume).sum::<Mat3>() / v
        };
        Centre {
            load,
            measured: measured / vol,
            exact: exact / vol,
            tets: centre.len(),
            near: mean(&near),
            near_tets: near.len(),
        }
    };
    let want = Want { stress: true, ..Default::default() };
    let mut earlier = None;
    while s.state().time < end {
        s.step(want);
        if s.state().time > stop {
            s.damp(keep).unwrap();
        }
        if earlier.is_none() && s.state().time >= 0.8 * end {
            earlier = Some(measure(&s));
        }
    }
    let last = measure(&s);
    if let Loading::Relaxed { .. } = loading {
        // At rest: the load and the stresses no longer change.
        let before = earlier.unwrap();
        let change = (last.load / before.load - 1.0).abs();
        let drift = (last.measured - before.measured).abs().max() / last.unit();
        assert!(change < 1e-3 && drift < 1e-3, "not at rest: ΔP/P = {change:e}, Δσ = {drift:e} × 2P/(πDt)");
        // A body at rest: the two reactions balance.
        let f = &s.record().drive_forces;
        assert!((f[0].y + f[1].y).abs() < 1e-2 * last.load, "{f:?}");
    }
    last
}

/// Mass damping about critical for the disc's lowest in-plane mode.
fn relax_rate() -> f64 {
    2.0 * (rock(0.0).mu() / rock(0.0).density()).sqrt() / R
}

#[test]
fn unbreakable_disc_centre_stresses_match_the_point_load_solution() {
    let slow = brazilian(false, 0.002, None, Loading::SlowRamp { v: 1e-3, ramp: 100e-6, xi: 0.2, end: 250e-6 });
    slow.report("unbreakable, slow ramp");
    let relaxed = brazilian(
        false,
        0.002,
        None,
        Loading::Relaxed { v: 5e-3, ramp: 10e-6, stop: 20e-6, c: relax_rate(), end: 120e-6 },
    );
    relaxed.report("unbreakable, relaxed");
    slow.check(0.05);
    relaxed.check(0.05);
    // The slow ramp is quasi-static: σ/P as in the static state, to 1 %.
    for k in 0..2 {
        let ratio = (slow.measured[(k, k)] / slow.load) / (relaxed.measured[(k, k)] / relaxed.load);
        assert!((ratio - 1.0).abs() < 0.01, "component {k}: dynamic/static = {ratio}");
    }
}

#[test]
fn joint_meshed_disc_centre_stresses_match_the_point_load_solution() {
    let c = brazilian(
        true,
        0.0025,
        Some(2),
        Loading::Relaxed { v: 5e-3, ramp: 10e-6, stop: 20e-6, c: relax_rate(), end: 120e-6 },
    );
    c.report("joint-meshed (p0 = 10 E), relaxed");
    c.check(0.05);
}
