//! probe
mod common;

use common::{box_mesh, isotropic_compliance, joint_compliance, model, nodes_in_box, rock};
use femdem_core::Vec3;
use femdem_material::Law;
use femdem_solver::{Fixed, Loads, Ramp, Solver, VelocityDrive, Want, stable_time_step};

const H: f64 = 0.005;
const NXY: f64 = 3.0;
const NZ: f64 = 60.0;

fn run(breakable: bool, p0f: f64, ramp_cells: f64, z1c: f64, z2c: f64) {
    let w = NXY * H;
    let l = NZ * H;
    let mesh = box_mesh([0.0; 3], [w, w, l], H, 0.1, breakable);
    let mat = rock(0.0);
    let (_jm, m) = model(&mesh, Law::NeoHookean, mat, p0f * mat.young());
    let tol = 1e-6 * H;
    let fixed = vec![
        Fixed {
            nodes: nodes_in_box(&m, [-tol, -1.0, -1.0], [tol, 1.0, 1.0]),
            components: [true, false, false],
        },
        Fixed {
            nodes: nodes_in_box(&m, [w - tol, -1.0, -1.0], [w + tol, 1.0, 1.0]),
            components: [true, false, false],
        },
        Fixed {
            nodes: nodes_in_box(&m, [-1.0, -tol, -1.0], [1.0, tol, 1.0]),
            components: [false, true, false],
        },
        Fixed {
            nodes: nodes_in_box(&m, [-1.0, w - tol, -1.0], [1.0, w + tol, 1.0]),
            components: [false, true, false],
        },
    ];
    let c = mat.p_wave_speed();
    let v0 = 0.01;
    let t_ramp = ramp_cells * H / c;
    let drive = VelocityDrive {
        name: "piston".into(),
        nodes: nodes_in_box(&m, [-1.0, -1.0, -tol], [1.0, 1.0, tol]),
        velocity: Vec3::new(0.0, 0.0, v0),
        components: [false, false, true],
        ramp: Ramp {
            ramp_time: t_ramp,
            stop_time: None,
        },
    };
    let loads = Loads {
        fixed,
        drives: vec![drive],
        ..Default::default()
    };
    // expected
    let vol = w * w * l;
    let s_tet = isotropic_compliance(&mat);
    let s_j = joint_compliance(&m, vol, |_| true);
    let c_eff = (s_tet + s_j).try_inverse().unwrap();
    let m_full = c_eff[(2, 2)];
    // confined only in xx, yy: shear stresses free
    let mut ss = s_tet + s_j;
    // strains: xx=yy=0, shear stresses zero, sigma zz. Solve reduced: unknown sxx, syy with ezz.
    let a = nalgebra::Matrix2::new(ss[(0, 0)], ss[(0, 1)], ss[(1, 0)], ss[(1, 1)]);
    let b = nalgebra::Vector2::new(-ss[(0, 2)], -ss[(1, 2)]);
    let sxy = a.try_inverse().unwrap() * b;
    let ezz = ss[(2, 2)] + ss[(2, 0)] * sxy[0] + ss[(2, 1)] * sxy[1];
    let m_free_shear = 1.0 / ezz;
    ss[(0, 0)] += 0.0;
    eprintln!("S_j*E = {:.4?}", (s_j * mat.young()).as_slice());
    eprintln!(
        "M = {:.4e}, M_eff(full) = {:.4e}, M_eff(shear free) = {:.4e}, c = {c:.1}, c_eff = {:.1} / {:.1}",
        mat.p_wave_modulus(),
        m_full,
        m_free_shear,
        (m_full / mat.density()).sqrt(),
        (m_free_shear / mat.density()).sqrt()
    );

    let mut s = Solver::new(m, loads, 1.0).unwrap();
    let st = stable_time_step(&s.model, &s.held_nodes(), 400);
    s.dt = 0.9 * st.critical;
    eprintln!(
        "dt = {:.3e} = {:.3} h/c, tets {}, joints {}",
        s.dt,
        s.dt * c / H,
        s.model.tets.len(),
        s.model.joints.len()
    );
    let slab = |zc: f64| {
        nodes_in_box(
            &s.model,
            [-1.0, -1.0, zc * H - 0.3 * H],
            [1.0, 1.0, zc * H + 0.3 * H],
        )
    };
    let st1 = slab(z1c);
    let st2 = slab(z2c);
    let zmean = |n: &[u32]| {
        let mm: f64 = n.iter().map(|&i| s.model.mass[i as usize]).sum();
        n.iter()
            .map(|&i| s.model.mass[i as usize] * s.model.x0[i as usize].z)
            .sum::<f64>()
            / mm
    };
    let (za, zb) = (zmean(&st1), zmean(&st2));
    let mut cross = [None, None];
    let mut prev = [0.0, 0.0];
    let t_end = (z2c + 0.5 * ramp_cells + 10.0) * H / (m_free_shear / mat.density()).sqrt();
    let t0 = std::time::Instant::now();
    while s.state.time < t_end {
        s.step(Want::default());
        let t = s.state.time - 0.5 * s.dt;
        for (k, n) in [&st1, &st2].iter().enumerate() {
            let mm: f64 = n.iter().map(|&i| s.model.mass[i as usize]).sum();
            let v = n
                .iter()
                .map(|&i| s.model.mass[i as usize] * s.state.v[i as usize].z)
                .sum::<f64>()
                / mm;
            if cross[k].is_none() && v >= 0.5 * v0 {
                let f = (0.5 * v0 - prev[k]) / (v - prev[k]);
                cross[k] = Some(t - s.dt + f * s.dt);
            }
            prev[k] = v;
        }
    }
    let (t1, t2) = (cross[0].unwrap(), cross[1].unwrap());
    let speed = (zb - za) / (t2 - t1);
    eprintln!(
        "steps {} in {:?}; t1 = {t1:.4e} (expect {:.4e}), speed {speed:.1}, /c = {:.4}, /c_eff(full) = {:.4}",
        s.state.step,
        t0.elapsed(),
        za / c + 0.5 * t_ramp,
        speed / c,
        speed / (m_full / mat.density()).sqrt()
    );
}

#[test]
fn probe() {
    for rc in [10.0, 20.0] {
        run(false, 10.0, rc, 15.0, 45.0);
    }
    for p in [1.0, 10.0, 100.0] {
        run(true, p, 20.0, 15.0, 45.0);
    }
}
