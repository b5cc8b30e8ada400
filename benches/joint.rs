//! The joint kernel alone (Eq. 3–13), on 4,096 intact joints of the
//! paper's granite (Table 1) slightly opened, closed and slipped, below
//! their peaks — the state of nearly every joint in a step: the readable
//! law (`joint_update`), the scalar kernel of the force pass
//! (`joint_update_fast`, the same results bit for bit) and four joints at a
//! time in SIMD lanes (`joint_update_lanes`, likewise). Throughput in joints
//! per second.

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use femdem_core::{Real, Vec3};
use femdem_fracture::{Joint, JointHistory, KernelConsts, LANES, joint_update, joint_update_fast, joint_update_lanes};

const JOINTS: usize = 4096;

fn setup() -> (Vec<Joint>, Vec<[Vec3; 6]>) {
    let params = femdem_benches::brazilian_joints();
    let mut seed = 1u64;
    let mut uniform = move || {
        seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        (seed >> 11) as Real / (1u64 << 53) as Real - 0.5
    };
    let mut joints = Vec::with_capacity(JOINTS);
    let mut x = Vec::with_capacity(JOINTS);
    for _ in 0..JOINTS {
        let h = 1.2e-3 * (1.0 + 0.2 * uniform());
        let joint = Joint::new(params, h);
        let a = [Vec3::zeros(), Vec3::new(h, 0.0, 0.0), Vec3::new(0.3 * h, h, 0.1 * h)];
        let mut d = || Vec3::new(uniform(), uniform(), uniform()) * (0.5 * joint.delta_np);
        x.push([a[0], a[1], a[2], a[2] + d(), a[1] + d(), a[0] + d()]);
        joints.push(joint);
    }
    (joints, x)
}

fn joint_kernel(c: &mut Criterion) {
    let (joints, x) = setup();
    let consts = KernelConsts::new();
    let mut g = c.benchmark_group("joint_kernel");
    g.throughput(Throughput::Elements(JOINTS as u64));
    let mut hist = vec![JointHistory::default(); JOINTS];
    let mut forces = vec![[Vec3::zeros(); 6]; JOINTS];
    g.bench_function("law", |b| {
        b.iter(|| {
            for ((j, h), (xp, f)) in joints.iter().zip(&mut hist).zip(x.iter().zip(&mut forces)) {
                *f = joint_update(j, h, xp, false).forces;
            }
        })
    });
    g.bench_function("fast", |b| {
        b.iter(|| {
            for ((j, h), (xp, f)) in joints.iter().zip(&mut hist).zip(x.iter().zip(&mut forces)) {
                *f = joint_update_fast(&consts, j, h, xp, false).forces;
            }
        })
    });
    g.bench_function("lanes", |b| {
        b.iter(|| {
            let groups = joints.chunks_exact(LANES).zip(hist.chunks_exact_mut(LANES));
            for ((j, h), (xp, f)) in groups.zip(x.chunks_exact(LANES).zip(forces.chunks_exact_mut(LANES))) {
                let h: &mut [JointHistory; LANES] = h.try_into().expect("four");
                let xp: &[[Vec3; 6]; LANES] = xp.try_into().expect("four");
                let f: &mut [[Vec3; 6]; LANES] = f.try_into().expect("four");
                assert!(joint_update_lanes(&consts, [&j[0], &j[1], &j[2], &j[3]], h, xp, f));
            }
        })
    });
    g.finish();
}

criterion_group!(benches, joint_kernel);
criterion_main!(benches);
