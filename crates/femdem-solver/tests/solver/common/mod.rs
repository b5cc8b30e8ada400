//! Builders shared by the solver's verification tests.
#![allow(dead_code)]

use femdem_core::Vec3;
use femdem_fracture::JointParams;
use femdem_material::{ElasticParams, Law, Material};
use femdem_mesh::generate::{BoxSpec, generate_box};
use femdem_mesh::{JointedMesh, Region, TetMesh, insert_joints};
use femdem_solver::select::{NodeSelection, select_nodes};
use femdem_solver::{
    ContactSettings, Fixed, Loads, Model, Ramp, RegionBehaviour, Solver, StableStep, StepParams, VelocityDrive,
    contact_omega, held_nodes, stable_time_step,
};

/// The paper's rock (Table 1): ρ = 2340 kg/m³, E = 26 GPa, ν = 0.2.
pub fn rock(viscosity: f64) -> Material {
    ElasticParams { young: 26e9, poisson: 0.2, density: 2340.0, viscosity }.validate().unwrap()
}

/// The paper's rock with Poisson's ratio `nu`.
pub fn rock_nu(viscosity: f64, nu: f64) -> Material {
    ElasticParams { young: 26e9, poisson: nu, density: 2340.0, viscosity }.validate().unwrap()
}

/// The paper's joint strengths with penalty `p0`.
pub fn joints(penalty: f64) -> JointParams {
    JointParams {
        penalty,
        tensile_strength: 3e6,
        cohesion: 15e6,
        friction_angle: 30f64.to_radians(),
        gf_tension: 50.0,
        gf_shear: 50.0,
        calibration: femdem_fracture::GfCalibration::Paper,
        coupling: femdem_fracture::Coupling::default(),
    }
}

/// A jittered box mesh, breakable or not.
pub fn box_mesh(min: [f64; 3], max: [f64; 3], h: f64, jitter: f64, breakable: bool) -> TetMesh {
    generate_box(&BoxSpec {
        min,
        max,
        element_size: h,
        jitter,
        seed: 11,
        region: Region { name: "rock".into(), breakable },
    })
    .unwrap()
}

/// The model of a one-region mesh with `law`, `material` and, if the region
/// is breakable, joints of penalty `p0`.
pub fn model(mesh: &TetMesh, law: Law, material: Material, p0: f64) -> (JointedMesh, Model) {
    let jointed = insert_joints(mesh).unwrap();
    let joints = mesh.regions[0].breakable.then(|| joints(p0));
    let model = Model::new(&jointed, &[RegionBehaviour::Deformable { law, material, joints }], 1.0).unwrap();
    (jointed, model)
}

/// A solver stepping at `safety` times the estimated critical step.
pub fn solver(model: Model, loads: Loads, safety: f64) -> Solver {
    let dt = safety * stable(&model, &loads, 400).critical;
    at_step(model, loads, dt)
}

/// The stable-step estimate of `model` under `loads` (`iterations` Lanczos
/// steps; the nodes the loads hold are left out).
pub fn stable(model: &Model, loads: &Loads, iterations: usize) -> StableStep {
    stable_time_step(model, &held_nodes(model, loads).unwrap(), iterations)
}

/// A solver stepping at `dt`.
pub fn at_step(model: Model, loads: Loads, dt: f64) -> Solver {
    Solver::new(model, loads, StepParams::new(dt).unwrap()).unwrap()
}

// ---------------------------------------------------------------------------
// Effective compliance of a joint-meshed solid (average-strain theorem).
// Voigt order xx, yy, zz, yz, xz, xy; strains with engineering shears
// (γ = 2ε), so that `ε_v = S σ_v` and `S` is symmetric.

/// The (row, column) of each Voigt component.
pub const VOIGT: [(usize, usize); 6] = [(0, 0), (1, 1), (2, 2), (1, 2), (0, 2), (0, 1)];

/// The unit stress tensor of Voigt component `k` (both off-diagonal
/// entries set for a shear).
pub fn voigt_unit_stress(k: usize) -> femdem_core::Mat3 {
    let (i, j) = VOIGT[k];
    let mut s = femdem_core::Mat3::zeros();
    s[(i, j)] = 1.0;
    s[(j, i)] = 1.0;
    s
}

/// A symmetric strain tensor in Voigt form with engineering shears.
pub fn voigt_strain(e: &femdem_core::Mat3) -> nalgebra::Vector6<f64> {
    nalgebra::Vector6::from_fn(|k, _| {
        let (i, j) = VOIGT[k];
        if i == j { e[(i, i)] } else { e[(i, j)] + e[(j, i)] }
    })
}

/// The 6×6 compliance of an isotropic linear solid:
/// `ε = ((1 + ν) σ − ν tr σ I) / E`.
pub fn isotropic_compliance(m: &Material) -> nalgebra::Matrix6<f64> {
    let (e, nu) = (m.young(), m.poisson());
    let mut s = nalgebra::Matrix6::zeros();
    for k in 0..6 {
        let sigma = voigt_unit_stress(k);
        let eps = (sigma * (1.0 + nu) - femdem_core::Mat3::identity() * (nu * sigma.trace())) / e;
        s.set_column(k, &voigt_strain(&eps));
    }
    s
}

/// The extra compliance of the intact joints of `model` over a solid of
/// volume `volume`, assuming the same uniform stress `σ` in every tet:
/// a joint of reference area `A`, unit normal `n` and mean edge length `h`
/// carries the traction `σ n` with the jump `[u] = (h / p0) σ n` (normal
/// and shear stiffness `p0 / h`), and by the average-strain theorem adds
/// `ε_j = (1/V) Σ A sym(n ⊗ [u])`, i.e.
/// `S_j = (1/V) Σ (A h / p0) sym(n ⊗ (·) n)`. Geometry is taken from the
/// reference positions of the joint's side-a face `N1 N2 N3`; `keep`
/// chooses the joints counted (by the centroid of that face).
pub fn joint_compliance(model: &Model, volume: f64, keep: impl Fn(&Vec3) -> bool) -> nalgebra::Matrix6<f64> {
    let mut s = nalgebra::Matrix6::zeros();
    for (j, nodes) in model.joints.iter().enumerate() {
        let [a, b, c] = [nodes[0], nodes[1], nodes[2]].map(|n| model.x0[n as usize]);
        if !keep(&((a + b + c) / 3.0)) {
            continue;
        }
        let cross = (b - a).cross(&(c - a));
        let area = 0.5 * cross.norm();
        let n = cross.normalize();
        let h = ((b - a).norm() + (c - b).norm() + (a - c).norm()) / 3.0;
        let w = area * h / (model.joint_law[j].params.penalty * volume);
        for k in 0..6 {
            let t = voigt_unit_stress(k) * n;
            let jump = n * t.transpose();
            let eps = (jump + jump.transpose()) * (0.5 * w);
            let col = s.column(k) + voigt_strain(&eps);
            s.set_column(k, &col);
        }
    }
    s
}

/// The nodes whose reference position lies in the box `[lo, hi]`.
pub fn nodes_in_box(model: &Model, lo: [f64; 3], hi: [f64; 3]) -> Vec<u32> {
    (0..model.num_nodes() as u32)
        .filter(|&i| {
            let p = model.x0[i as usize];
            (0..3).all(|a| p[a] >= lo[a] && p[a] <= hi[a])
        })
        .collect()
}

/// The part of triangle `tri` inside every half-space `(q − p)·n ≤ 0` of
/// `planes` (`(p, n)`, `n` outward), by Sutherland–Hodgman.
fn clip_triangle(tri: [Vec3; 3], planes: &[(Vec3, Vec3); 4]) -> Vec<Vec3> {
    let mut poly = tri.to_vec();
    for (p, n) in planes {
        let mut out = Vec::with_capacity(poly.len() + 1);
        for k in 0..poly.len() {
            let (a, b) = (poly[k], poly[(k + 1) % poly.len()]);
            let (fa, fb) = (-(a - p).dot(n), -(b - p).dot(n));
            if fa >= 0.0 {
                out.push(a);
            }
            if (fa >= 0.0) != (fb >= 0.0) {
                out.push(a + (b - a) * (fa / (fa - fb)));
            }
        }
        poly = out;
        if poly.is_empty() {
            break;
        }
    }
    poly
}

/// The outward face planes `(point, normal)` of a positive tet.
fn face_planes(t: &[Vec3; 4]) -> [(Vec3, Vec3); 4] {
    femdem_core::tet::FACES.map(|[i, j, k]| (t[i], (t[j] - t[i]).cross(&(t[k] - t[i]))))
}

/// Interpenetration of two tets (positive orientation): the volume of
/// `A ∩ B`, by the divergence theorem `V = ⅓ ∮ x·n dS` over the parts of
/// each tet's faces inside the other (each part a clipped polygon, on which
/// `x·n` is constant), and the depth of the deepest node of either tet
/// inside the other (its distance to the other's nearest face plane; 0 if
/// none is inside).
pub fn tet_overlap(a: &[Vec3; 4], b: &[Vec3; 4]) -> (f64, f64) {
    let origin = a.iter().sum::<Vec3>() / 4.0;
    let a = a.map(|p| p - origin);
    let b = b.map(|p| p - origin);
    let mut volume = 0.0;
    for (s, t) in [(&a, &b), (&b, &a)] {
        let planes = face_planes(t);
        for [i, j, k] in femdem_core::tet::FACES {
            let poly = clip_triangle([s[i], s[j], s[k]], &planes);
            if poly.len() < 3 {
                continue;
            }
            let n = (s[j] - s[i]).cross(&(s[k] - s[i])).normalize();
            let area: f64 =
                (1..poly.len() - 1).map(|m| 0.5 * (poly[m] - poly[0]).cross(&(poly[m + 1] - poly[0])).dot(&n)).sum();
            volume += area * n.dot(&s[i]) / 3.0;
        }
    }
    let mut depth: f64 = 0.0;
    for (s, t) in [(&a, &b), (&b, &a)] {
        let planes = face_planes(t);
        for q in s {
            let d = planes.iter().map(|(p, n)| -(q - p).dot(n) / n.norm()).fold(f64::INFINITY, f64::min);
            depth = depth.max(d);
        }
    }
    (volume.max(0.0), depth)
}

/// The loads of a square bar `w` wide pulled along z: its base `zmin` held
/// along z, with roller supports (x held on the edge x = 0, y on the edge
/// y = 0) so that it may contract freely, and its top `zmax` driven at
/// `v` (m/s) along z after a 50 µs ramp (the drive is named `pull`).
pub fn pulled_bar_loads(jointed: &JointedMesh, w: f64, v: f64) -> Loads {
    use femdem_solver::select::{NodeSelection, select_nodes};
    use femdem_solver::{Fixed, Ramp, VelocityDrive};
    let sel = |group: &str, within: Option<([f64; 3], [f64; 3])>| {
        select_nodes(jointed, &NodeSelection { group: Some(group.into()), within, ..Default::default() }).unwrap()
    };
    let eps = 1e-9;
    Loads {
        fixed: vec![
            Fixed { nodes: sel("zmin", None), components: [false, false, true] },
            Fixed { nodes: sel("zmin", Some(([-eps; 3], [eps, w + eps, eps]))), components: [true, false, false] },
            Fixed { nodes: sel("zmin", Some(([-eps; 3], [w + eps, eps, eps]))), components: [false, true, false] },
        ],
        drives: vec![VelocityDrive {
            name: "pull".into(),
            nodes: sel("zmax", None),
            velocity: Vec3::new(0.0, 0.0, v),
            components: [false, false, true],
            ramp: Ramp { ramp_time: 5e-5, stop_time: None },
            start_time: None,
        }],
        ..Loads::default()
    }
}

/// A jointed block of `size` (m, element size 2.5 mm) with weak joints (a
/// tenth of the paper's strengths), bottom held, top driven at `(5, 0, −2)`
/// m/s: joints fail at most steps from about step 100 on. Contact without
/// surfaces, friction 0.6, detection buffer `buffer` (m), incremental
/// detection after failures as `incremental` says.
pub fn sheared_block(size: [f64; 3], buffer: f64, incremental: bool) -> Solver {
    const H: f64 = 0.0025;
    const PENALTY: f64 = 26e9;
    let mesh = box_mesh([0.0; 3], size, H, 0.15, true);
    let jointed = insert_joints(&mesh).unwrap();
    let visc = femdem_material::critical_viscosity(H, 26e9, 2340.0) * 0.1;
    let params = JointParams { tensile_strength: 3e5, cohesion: 1.5e6, ..joints(10.0 * 26e9) };
    let behaviour = [RegionBehaviour::Deformable { law: Law::NeoHookean, material: rock(visc), joints: Some(params) }];
    let m = Model::new(&jointed, &behaviour, 1.0).unwrap();
    let sel = |g: &str| select_nodes(&jointed, &NodeSelection { group: Some(g.into()), ..Default::default() }).unwrap();
    let loads = Loads {
        fixed: vec![Fixed { nodes: sel("zmin"), components: [true; 3] }],
        drives: vec![VelocityDrive {
            name: "top".into(),
            nodes: sel("zmax"),
            velocity: Vec3::new(5.0, 0.0, -2.0),
            components: [true; 3],
            ramp: Ramp { ramp_time: 2e-6, stop_time: None },
            start_time: None,
        }],
        ..Loads::default()
    };
    let st = stable(&m, &loads, 300).with_contact(contact_omega(&m, PENALTY));
    let mut s = Solver::new(m, loads, StepParams::new(0.9 * st.critical).unwrap()).unwrap();
    let settings =
        ContactSettings { surfaces: false, friction: 0.6, buffer, incremental, ..ContactSettings::new(PENALTY) };
    s.enable_contact(settings, &[]);
    s
}
