//! probe
mod common;

use common::{box_mesh, isotropic_compliance, joint_compliance, model, nodes_in_box, rock};
use femdem_core::Vec3;
use femdem_material::Law;
use femdem_solver::select::group_faces;
use femdem_solver::{Fixed, Loads, Ramp, Solver, SurfaceKind, SurfaceLoad, Want, stable_time_step};

const H: f64 = 0.005;

fn run(
    breakable: bool,
    p0f: f64,
    n: [f64; 3],
    dur: f64,
    cf: f64,
    rigid: bool,
    sigma: f64,
    jit: f64,
) {
    let size = [n[0] * H, n[1] * H, n[2] * H];
    let mesh = box_mesh([0.0; 3], size, H, jit, breakable);
    let mat = rock(0.0);
    let (jm, m) = model(&mesh, Law::LinearElastic, mat, p0f * mat.young());
    let tol = 1e-6 * H;
    let [lx, ly, lz] = size;
    // 3-2-1 supports on the nodes of the tet nearest the centre.
    let centre = Vec3::new(lx / 2.0, ly / 2.0, lz / 2.0);
    let t = (0..m.tets.len())
        .min_by(|&a, &b| {
            let ca: Vec3 = m.tets[a].iter().map(|&i| m.x0[i as usize]).sum::<Vec3>() / 4.0;
            let cb: Vec3 = m.tets[b].iter().map(|&i| m.x0[i as usize]).sum::<Vec3>() / 4.0;
            (ca - centre)
                .norm()
                .partial_cmp(&(cb - centre).norm())
                .unwrap()
        })
        .unwrap();
    let [a, b, c, _] = m.tets[t];
    let d = m.x0[b as usize] - m.x0[a as usize];
    let k = d.iamax();
    let mut comp_b = [true; 3];
    comp_b[k] = false;
    let e = m.x0[c as usize] - m.x0[a as usize];
    // rotation about d: displacement of c ~ d x e; fix its largest component.
    let kc = d.cross(&e).iamax();
    let mut comp_c = [false; 3];
    comp_c[kc] = true;
    let fixed = vec![
        Fixed {
            nodes: vec![a],
            components: [true; 3],
        },
        Fixed {
            nodes: vec![b],
            components: comp_b,
        },
        Fixed {
            nodes: vec![c],
            components: comp_c,
        },
    ];
    let top = group_faces(&jm, "zmax").unwrap();
    let bottom = group_faces(&jm, "zmin").unwrap();
    let _ = fixed;
    let loads = Loads {
        surfaces: vec![
            SurfaceLoad {
                name: "top".into(),
                faces: top.clone(),
                kind: SurfaceKind::Pressure(sigma),
                ramp: Ramp::STEP,
            },
            SurfaceLoad {
                name: "bottom".into(),
                faces: bottom.clone(),
                kind: SurfaceKind::Pressure(sigma),
                ramp: Ramp::STEP,
            },
        ],
        ..Default::default()
    };
    let vol = lx * ly * lz;
    let s_tet = isotropic_compliance(&mat);
    let s_j = joint_compliance(&m, vol, |_| true);
    let eps_c = s_tet[(2, 2)] * sigma;
    let eps_r = (s_tet[(2, 2)] + s_j[(2, 2)]) * sigma;
    let e_eff = 1.0 / (s_tet[(2, 2)] + s_j[(2, 2)]);
    let omega1 = 0.5 * std::f64::consts::PI * (e_eff / mat.density()).sqrt() / lz;
    let mut s = Solver::new(m, loads, 1.0).unwrap();
    let st = stable_time_step(&s.model, &s.held_nodes(), 400);
    s.dt = 0.9 * st.critical;
    let damp = 1.0 - cf * omega1 * s.dt;
    let t_end = dur / omega1;
    let mean_uz = |s: &Solver, faces: &[[u32; 3]]| {
        let mut a = 0.0;
        let mut u = 0.0;
        for f in faces {
            let p = f.map(|i| s.model.x0[i as usize]);
            let ar = 0.5 * (p[1] - p[0]).cross(&(p[2] - p[0])).norm();
            a += ar;
            u += ar
                * f.iter()
                    .map(|&i| s.state.x[i as usize].z - s.model.x0[i as usize].z)
                    .sum::<f64>()
                / 3.0;
        }
        u / a
    };
    let strain = |s: &Solver| (mean_uz(s, &bottom) - mean_uz(s, &top)) / lz;
    let t0 = std::time::Instant::now();
    let mut hist = vec![];
    while s.state.time < t_end {
        s.step(Want::default());
        for v in s.state.v.iter_mut() {
            *v *= damp;
        }
        if rigid {
            remove_rigid(&mut s);
        }
        if s.state.step % 200 == 0 {
            hist.push((s.state.time * omega1, strain(&s)));
        }
    }
    let eps = strain(&s);
    eprintln!(
        "p0={p0f}E tets {} joints {} steps {} {:?}: eps/eps_c = {:.5}, eps_R/eps_c = {:.5}, q = {:.5}",
        s.model.tets.len(),
        s.model.joints.len(),
        s.state.step,
        t0.elapsed(),
        eps / eps_c,
        eps_r / eps_c,
        (eps - eps_c) / (eps_r - eps_c)
    );
    let l = hist.len();
    for h in &hist[l.saturating_sub(40)..] {
        eprint!("({:.1},{:.6}) ", h.0, h.1 / eps_c);
    }
    eprintln!();
}

#[test]
fn probe() {
    for p in [1.0, 10.0, 100.0] {
        run(true, p, [4.0, 4.0, 8.0], 15.0, 2.0, true, 1e4, 0.0);
    }
    for p in [1.0, 10.0] {
        run(true, p, [4.0, 4.0, 8.0], 15.0, 2.0, true, 1e4, 0.05);
        run(true, p, [4.0, 4.0, 8.0], 15.0, 2.0, true, 1e4, 0.15);
    }
}

fn remove_rigid(s: &mut Solver) {
    let m = &s.model.mass;
    let x = &s.state.x;
    let mt: f64 = m.iter().sum();
    let xc: Vec3 = x.iter().zip(m).map(|(p, &w)| p * w).sum::<Vec3>() / mt;
    let p: Vec3 = s.state.v.iter().zip(m).map(|(v, &w)| v * w).sum();
    let vc = p / mt;
    let mut l = Vec3::zeros();
    let mut inertia = femdem_core::Mat3::zeros();
    for ((xi, vi), &w) in x.iter().zip(&s.state.v).zip(m) {
        let r = xi - xc;
        l += r.cross(&(vi - vc)) * w;
        inertia += (femdem_core::Mat3::identity() * r.norm_squared() - r * r.transpose()) * w;
    }
    let omega = inertia.try_inverse().unwrap() * l;
    for (xi, vi) in x.iter().zip(s.state.v.iter_mut()) {
        *vi -= vc + omega.cross(&(xi - xc));
    }
}
