//! The tet kernel alone (Eq. 1–2): the neo-Hookean viscoelastic Cauchy
//! stress and the nodal forces of 4,096 tets of the paper's granite
//! (Table 1, 5% damping) under a random small deformation and velocity —
//! the call the force pass makes for every tet of a step
//! (`femdem_material::tet_forces`). Throughput in tets per second; the
//! step bench (`step/disc_without_joints`) is this plus the gather and the
//! update.

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use femdem_core::{Real, Vec3};
use femdem_material::{ElasticParams, Law, TetReference, tet_forces};

const TETS: usize = 4096;

fn tet_kernel(c: &mut Criterion) {
    let h = 1.2e-3;
    let viscosity = 0.05 * femdem_material::critical_viscosity(h, 26e9, 2340.0);
    let material = ElasticParams { young: 26e9, poisson: 0.2, density: 2340.0, viscosity }.validate().expect("rock");
    let mut seed = 7u64;
    let mut uniform = move || {
        seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        (seed >> 11) as Real / (1u64 << 53) as Real - 0.5
    };
    let corner = [Vec3::zeros(), Vec3::new(h, 0.0, 0.0), Vec3::new(0.0, h, 0.0), Vec3::new(0.0, 0.0, h)];
    let mut tets = Vec::with_capacity(TETS);
    for _ in 0..TETS {
        let x0 = corner.map(|p| p + Vec3::new(uniform(), uniform(), uniform()) * (0.2 * h));
        let reference = TetReference::new(&x0).expect("a tet of positive volume");
        let x = x0.map(|p| p + Vec3::new(uniform(), uniform(), uniform()) * (1e-4 * h));
        let v = x0.map(|_| Vec3::new(uniform(), uniform(), uniform()) * 0.1);
        tets.push((reference, x, v));
    }
    let mut g = c.benchmark_group("tet_kernel");
    g.throughput(Throughput::Elements(TETS as u64));
    g.bench_function("neo_hookean", |b| {
        b.iter(|| {
            let mut sum = Vec3::zeros();
            for (reference, x, v) in &tets {
                let out = tet_forces(Law::NeoHookean, &material, reference, x, v);
                sum += out.forces[0];
            }
            std::hint::black_box(sum)
        })
    });
    g.finish();
}

criterion_group!(benches, tet_kernel);
criterion_main!(benches);
