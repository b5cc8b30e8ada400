//! Friction at the contact (reference paper §2.3: Coulomb friction). Each
//! pair's friction acts at its contact centre (the point of the overlap
//! where the normal force acts), with the slip measured there; before, it
//! used the two tets' centroid velocities and acted at the centroids. Both
//! bodies rest on a rigid plate (contact penalty E, μ = 0.5, gravity
//! g = 9810 m/s² so that the forces stand well above round-off).
//!
//! * **Sliding block** (20 × 20 × 10 mm, 5 mm cells, gravity tilted by
//!   40°: it slides, as in `contact.rs`). A block that slides without
//!   rotating has no net moment about its centre of mass: friction `μ N`
//!   acts at the base, `H/2` below it, so the normal reaction's centre lies
//!   `e = μ H/2` ahead of it. At 0.4 ms: the friction's arm is
//!   4.99998 mm (1.0000 H/2; 3.74999 mm = 0.7500 H/2 before, the base
//!   tets' centroids being h/4 above the base) and the reaction's centre
//!   2.49999 mm ahead (1.0000 μ H/2; 1.87879 mm = 0.7515 before).
//!   Tolerances: 1% on the arm (the contact centres lie within the overlap,
//!   ~1 nm deep, the centre of mass moves by the elastic sag, ~1e-5 H),
//!   2% on `e` (the moment balance holds on average; the block rocks).
//!   Neither version spins the block: after 0.1 ms its angular velocity
//!   about y has mean −4.2e-4 rad/s and peaks at 4.9e-2 rad/s (before:
//!   −1.5e-4 and 1.7e-2; at the end −2.4e-5 and −9.1e-6) — rocking on the
//!   contact springs set off by gravity switched on at once, larger now
//!   that the reaction's centre has further to shift. The energy account
//!   closes to 1% of the work (−1.3e-6 J of 1.2e-2 J).
//! * **Spinning tet**: one tet, its base an equilateral triangle of side
//!   `s` = 20 mm (apex 12 mm above its centroid), on a plate of 2 mm faces,
//!   set spinning at 100 rad/s about the vertical axis through its centre
//!   of mass after 50 µs of settling. Uniform pressure gives the friction
//!   torque `μ m g r̄`, `r̄` = 0.26561 s the mean distance from the centroid
//!   over the triangle, and `α = μ m g r̄ / I_zz` with the lumped masses'
//!   `I_zz` (= m s²/4). Before, the centroid sat on the axis, the centroid
//!   slip was zero and nothing slowed the tet: ω stayed 100.0000 rad/s
//!   (friction dissipated 2e-19 J). Now α = 2.5864e5 rad/s² against
//!   2.6057e5 (−0.74%; asserted within 3%). The contact pass integrates
//!   the torque with one point per pair, which on this plate puts `r̄`
//!   0.48% low (computed from the plate's faces clipped by the base, in the
//!   test); the rest is the tet bouncing on the undamped contact spring (N
//!   oscillates about m g) and tilting under the friction forces. The
//!   energy account's balance moves by −4.3e-4 of the energy friction
//!   dissipated (asserted below 1%). (A meshed cube, 20 mm of 5 mm cells,
//!   spinning on the same plate was already slowed by centroid friction —
//!   its base tets' centroids are off the axis: α 2.6% below
//!   `μ m g r̄ / I` with `r̄` = 0.3826 of the side; now 1.8% below.)

use crate::common::{at_step, box_mesh, rock, stable};
use femdem_core::{Mat3, Vec3};
use femdem_material::{Law, critical_viscosity};
use femdem_mesh::{Region, TetMesh, insert_joints};
use femdem_solver::select::{NodeSelection, select_nodes};
use femdem_solver::{ContactSettings, Loads, Model, Ramp, RegionBehaviour, Solver, VelocityDrive, Want, contact_omega};

const E: f64 = 26e9;
/// A strong gravity, m/s², so that the contact forces stand well above
/// round-off (as in `contact.rs`).
const G: f64 = 9.81 * 1000.0;

/// `body` (deformable, damped) resting on a rigid plate `[lo, hi]` of
/// element size `hp` whose top is `z = 0`, under `gravity`, with friction
/// μ; the body's nodes come first.
fn on_plate(body: TetMesh, lo: [f64; 2], hi: [f64; 2], hp: f64, gravity: Vec3, mu: f64) -> Solver {
    let mut mesh = body;
    let mut plate = box_mesh([lo[0], lo[1], -hp], [hi[0], hi[1], 0.0], hp, 0.0, false);
    plate.regions[0] = Region { name: "plate".into(), breakable: false };
    mesh.append(&plate);
    let jointed = insert_joints(&mesh).unwrap();
    let visc = critical_viscosity(0.005, E, 2340.0) * 0.3;
    let behaviour = [
        RegionBehaviour::Deformable { law: Law::NeoHookean, material: rock(visc), joints: None },
        RegionBehaviour::Rigid,
    ];
    let m = Model::new(&jointed, &behaviour, 1.0).unwrap();
    let plate_nodes =
        select_nodes(&jointed, &NodeSelection { region: Some("plate".into()), ..Default::default() }).unwrap();
    let loads = Loads {
        gravity,
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
    let penalty = E;
    let st = stable(&m, &loads, 300).with_contact(contact_omega(&m, penalty));
    let mut s = at_step(m, loads, 0.5 * st.critical);
    s.enable_contact(ContactSettings { friction: mu, ..ContactSettings::new(penalty) }, &[]);
    s
}

/// The body's nodes (those with mass).
fn body(s: &Solver) -> Vec<usize> {
    (0..s.model().num_nodes()).filter(|&i| s.model().mass[i] > 0.0).collect()
}

/// Mass, centre of mass at `t_n` and rigid-body angular velocity (`I⁻¹ L`
/// about the centre of mass) of the nodes `nodes`, with the velocities
/// `v_{n+½}` of the last step.
fn rigid(s: &Solver, nodes: &[usize]) -> (f64, Vec3, Vec3) {
    let m = &s.model().mass;
    let total: f64 = nodes.iter().map(|&i| m[i]).sum();
    let x = |i: usize| s.recorded_position(i);
    let cm = nodes.iter().map(|&i| x(i) * m[i]).sum::<Vec3>() / total;
    let vcm = nodes.iter().map(|&i| s.state().v[i] * m[i]).sum::<Vec3>() / total;
    let (mut l, mut inertia) = (Vec3::zeros(), Mat3::zeros());
    for &i in nodes {
        let r = x(i) - cm;
        l += r.cross(&(s.state().v[i] - vcm)) * m[i];
        inertia += (Mat3::identity() * r.norm_squared() - r * r.transpose()) * m[i];
    }
    (total, cm, inertia.try_inverse().unwrap() * l)
}

/// One tet with an equilateral base of side `side` in the plane `z = 0`,
/// centred on the z axis, and its apex at height `height` on the axis.
fn tet(side: f64, height: f64) -> TetMesh {
    let r = side / 3f64.sqrt();
    let corner = |deg: f64| [r * deg.to_radians().cos(), r * deg.to_radians().sin(), 0.0];
    TetMesh {
        coords: vec![corner(90.0), corner(210.0), corner(330.0), [0.0, 0.0, height]],
        tets: vec![[0, 1, 2, 3]],
        tet_region: vec![0],
        regions: vec![Region { name: "body".into(), breakable: false }],
        ..TetMesh::default()
    }
}

/// Mean distance from the centroid over an equilateral triangle of side 1,
/// by the midpoint rule on `n²` similar sub-triangles.
fn mean_radius_of_unit_triangle(n: usize) -> f64 {
    let r = 1.0 / 3f64.sqrt();
    let p = [90.0f64, 210.0, 330.0].map(|d| Vec3::new(r * d.to_radians().cos(), r * d.to_radians().sin(), 0.0));
    let (e1, e2) = ((p[1] - p[0]) / n as f64, (p[2] - p[0]) / n as f64);
    let mut sum = 0.0;
    for i in 0..n {
        for j in 0..n - i {
            let a = p[0] + e1 * i as f64 + e2 * j as f64;
            sum += (a + (e1 + e2) / 3.0).norm();
            if i + j + 1 < n {
                sum += (a + (e1 + e2) * (2.0 / 3.0)).norm();
            }
        }
    }
    sum / (n * n) as f64
}

/// Spins `s`'s body at `omega` (rad/s) about the vertical axis through its
/// centre of mass once it has settled for `settle` s, then returns the
/// angular velocities ω_z at `t1` and `t2` after the start of the spin,
/// and the body's mass and `I_zz`.
fn spin_down(s: &mut Solver, settle: f64, omega: f64, t1: f64, t2: f64) -> (f64, f64, f64, f64, f64) {
    let nodes = body(s);
    while s.state().time < settle {
        s.step(Want::default());
    }
    let (mass, cm, _) = rigid(s, &nodes);
    for &i in &nodes {
        let r = s.state().x[i] - cm;
        s.kick(i, Vec3::new(-r.y, r.x, 0.0) * omega).unwrap();
    }
    let start = s.state().time;
    let izz: f64 = nodes.iter().map(|&i| s.model().mass[i] * ((s.state().x[i] - cm).xy().norm_squared())).sum();
    let mut w1 = 0.0;
    let e0 = {
        s.step(Want { energy: true, ..Want::default() });
        s.energies().balance()
    };
    while s.state().time < start + t2 {
        s.step(Want { energy: s.state().time >= start + t2 - 1.5 * s.dt(), ..Want::default() });
        if w1 == 0.0 && s.state().time >= start + t1 {
            w1 = rigid(s, &nodes).2.z;
        }
    }
    let w2 = rigid(s, &nodes).2.z;
    let e = s.energies();
    eprintln!(
        "  balance {:.4e} → {:.4e} J, friction dissipated {:.4e} J, contact {:.3e} J, kinetic {:.4e} J",
        e0,
        e.balance(),
        e.friction,
        e.contact,
        e.kinetic
    );
    (w1, w2, mass, izz, (e.balance() - e0) / e.friction)
}

/// The mean distance from the axis over the base `base` (a triangle in
/// `z = 0`, counter-clockwise) as the contact pass integrates it: one point
/// per plate face, the centroid of the face's part under the base —
/// `Σ A_j |c_j| / Σ A_j` over the plate's top faces clipped by the base.
fn mean_radius_by_plate_faces(s: &Solver, base: [Vec3; 3]) -> f64 {
    let (mut area, mut moment) = (0.0, 0.0);
    for (t, tet) in s.model().tets.iter().enumerate() {
        if s.model().mass[tet[0] as usize] > 0.0 || !s.model().tet_material[t].is_rigid() {
            continue;
        }
        for face in femdem_core::tet::FACES {
            let p = face.map(|k| s.model().x0[tet[k] as usize]);
            if p.iter().any(|q| q.z != 0.0) {
                continue;
            }
            let mut poly = p.to_vec();
            for k in 0..3 {
                let (a, b) = (base[k], base[(k + 1) % 3]);
                let inside = |q: &Vec3| (b - a).cross(&(q - a)).z;
                let mut out = Vec::new();
                for m in 0..poly.len() {
                    let (q, r) = (poly[m], poly[(m + 1) % poly.len()]);
                    let (fq, fr) = (inside(&q), inside(&r));
                    if fq >= 0.0 {
                        out.push(q);
                    }
                    if (fq >= 0.0) != (fr >= 0.0) {
                        out.push(q + (r - q) * (fq / (fq - fr)));
                    }
                }
                poly = out;
                if poly.is_empty() {
                    break;
                }
            }
            for m in 1..poly.len().saturating_sub(1) {
                let w = 0.5 * (poly[m] - poly[0]).cross(&(poly[m + 1] - poly[0])).z.abs();
                let c = (poly[0] + poly[m] + poly[m + 1]) / 3.0;
                area += w;
                moment += w * c.norm();
            }
        }
    }
    moment / area
}

/// A single tet spinning on its base (see the module documentation).
#[test]
fn spinning_tet_is_slowed_by_the_friction_torque() {
    let (side, height, mu, omega) = (0.02, 0.012, 0.5, 100.0);
    let mut s = on_plate(tet(side, height), [-0.016, -0.016], [0.016, 0.016], 0.002, Vec3::new(0.0, 0.0, -G), mu);
    let base = [0, 1, 2].map(|i| s.model().x0[i]);
    let (t1, t2) = (2e-5, 1.2e-4);
    let (w1, w2, mass, izz, drift) = spin_down(&mut s, 5e-5, omega, t1, t2);
    let alpha = (w1 - w2) / (t2 - t1);
    let rbar = mean_radius_of_unit_triangle(400) * side;
    let by_faces = mean_radius_by_plate_faces(&s, base);
    let expected = mu * mass * G * rbar / izz;
    eprintln!(
        "spinning tet: ω {w1:.4} → {w2:.4} rad/s, α = {alpha:.5e} rad/s² vs μ m g r̄ / I = {expected:.5e} ({:+.2}%); \
         r̄ = {rbar:.5e} m ({:.5} side), by plate faces {by_faces:.5e} m ({:+.2}%); balance drift {drift:.2e} of the \
         friction dissipated",
        100.0 * (alpha / expected - 1.0),
        rbar / side,
        100.0 * (by_faces / rbar - 1.0)
    );
    assert!((rbar / side - 0.2656).abs() < 1e-4, "mean radius of the triangle {}", rbar / side);
    assert!((alpha / expected - 1.0).abs() < 0.03, "α = {alpha} vs {expected}");
    assert!(drift.abs() < 0.01, "energy balance drifted by {drift} of the friction dissipated");
}

/// A block sliding down an incline (see the module documentation).
#[test]
fn sliding_block_feels_friction_at_its_base() {
    let (h, mu, theta, height) = (0.005, 0.5, 40f64.to_radians(), 0.01);
    let block = box_mesh([0.0, 0.0, 0.0], [0.02, 0.02, height], h, 0.0, false);
    let gravity = Vec3::new(G * theta.sin(), 0.0, -G * theta.cos());
    let mut s = on_plate(block, [-0.03, -0.03], [0.05, 0.05], 0.01, gravity, mu);
    let nodes = body(&s);
    let (mut w_max, mut w_sum, mut n) = (0.0f64, 0.0, 0);
    let end = 4e-4;
    while s.state().time < end {
        s.step(Want { energy: s.state().time > end - 1.5 * s.dt(), ..Want::default() });
        if s.state().time > 1e-4 {
            let w = rigid(&s, &nodes).2.y;
            w_max = w_max.max(w.abs());
            w_sum += w;
            n += 1;
        }
    }
    let (_, cm, w) = rigid(&s, &nodes);
    let c = s.contact().unwrap();
    let (mut friction, mut t_friction, mut normal, mut t_normal) =
        (Vec3::zeros(), Vec3::zeros(), Vec3::zeros(), Vec3::zeros());
    for &i in &nodes {
        let r = s.recorded_position(i) - cm;
        friction += c.friction_force[i];
        t_friction += r.cross(&c.friction_force[i]);
        normal += c.force[i];
        t_normal += r.cross(&c.force[i]);
    }
    let arm = -t_friction.y / friction.x;
    let ahead = -t_normal.y / normal.z;
    let e = s.energies();
    eprintln!(
        "sliding block: friction {:.4} N along x, its arm below the centre of mass {arm:.5e} m ({:.4} of H/2); \
         normal reaction {:.4} N, its centre {ahead:.5e} m ahead of the centre of mass ({:.4} of μ H/2); \
         ω_y after 0.1 ms: mean {:.2e}, largest {w_max:.2e}, at the end {:.2e} rad/s; balance {:.3e} J of {:.3e} J work",
        friction.x,
        arm / (0.5 * height),
        normal.z,
        ahead / (0.5 * mu * height),
        w_sum / n as f64,
        w.y,
        e.balance(),
        e.external_work
    );
    assert!((arm / (0.5 * height) - 1.0).abs() < 0.01, "friction arm {arm} vs H/2");
    assert!((ahead / (0.5 * mu * height) - 1.0).abs() < 0.02, "centre of pressure {ahead} vs μ H/2");
    assert!(e.balance().abs() < 0.01 * e.external_work, "balance {} vs work {}", e.balance(), e.external_work);
}
