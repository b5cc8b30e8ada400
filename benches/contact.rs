//! NBS detection on clouds of 10⁴ to 10⁶ bounding spheres at a constant
//! density (about one sphere per cell of the grid, as in a fragmented
//! mesh). The time per element (criterion's `Elements` throughput) should
//! stay flat: the target is within 1.5× from 10⁴ to 10⁶.

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use femdem_contact::{Nbs, tet_tet_forces};
use femdem_core::Vec3;

/// `n` spheres of radius 0.5 on a jittered cubic lattice of spacing 1.
fn cloud(n: usize) -> (Vec<Vec3>, Vec<f64>) {
    let side = (n as f64).cbrt().ceil() as usize;
    let mut state = 0x2545_f491_4f6c_dd1du64;
    let mut rnd = || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64 - 0.5
    };
    let centers: Vec<Vec3> = (0..n)
        .map(|i| {
            Vec3::new(
                (i % side) as f64 + 0.3 * rnd(),
                ((i / side) % side) as f64 + 0.3 * rnd(),
                (i / side / side) as f64 + 0.3 * rnd(),
            )
        })
        .collect();
    (centers, vec![0.5; n])
}

fn nbs(c: &mut Criterion) {
    let mut g = c.benchmark_group("nbs");
    g.sample_size(10);
    for n in [10_000usize, 100_000, 1_000_000] {
        let (centers, radii) = cloud(n);
        let mut search = Nbs::new();
        let mut pairs = Vec::new();
        g.throughput(Throughput::Elements(n as u64));
        g.bench_function(BenchmarkId::from_parameter(n), |b| {
            b.iter(|| {
                pairs.clear();
                search.detect(&centers, &radii, 0.0, &mut pairs);
                pairs.len()
            })
        });
    }
    g.finish();
}

/// One tet–tet potential contact evaluation (both passes: 8 faces clipped
/// against 4 sub-tets each) for a shallow and a deep overlap.
fn kernel(c: &mut Criterion) {
    let a =
        [Vec3::new(1.0, 1.0, 1.0), Vec3::new(1.0, -1.0, -1.0), Vec3::new(-1.0, -1.0, 1.0), Vec3::new(-1.0, 1.0, -1.0)]
            .map(|v| v * 0.5);
    let d = -Vec3::new(1.0, 1.0, 1.0).normalize();
    let r_in = 2f64.sqrt() / (2.0 * 6f64.sqrt());
    let mut g = c.benchmark_group("tet_tet_forces");
    for (name, delta) in [("shallow", 0.01), ("deep", 0.3)] {
        let mut b = a.map(|v| -v + d * (2.0 * r_in - delta));
        b.swap(2, 3);
        g.bench_function(name, |bench| bench.iter(|| tet_tet_forces(&a, &b, 1e9)));
    }
    g.finish();
}

/// Five steps of the quick polyaxial cube (`femdem_benches::polyaxial_cube`,
/// 4,993 tets) from step 3,400, once some 630 joints have failed and more
/// fail at nearly every step: detection is redone at most steps and some
/// 3,700 pairs are in contact. Each sample restores the same snapshot, so
/// every iteration runs the same five steps; throughput in tet-steps.
fn fragmented(c: &mut Criterion) {
    use femdem_solver::Want;
    let mut s = femdem_benches::polyaxial_cube_at(3400);
    let bytes = s.snapshot();
    let tets = s.model.num_deformable_tets() as u64;
    let mut g = c.benchmark_group("contact_fragmented_cube");
    g.sample_size(10);
    g.throughput(Throughput::Elements(5 * tets));
    for threads in [1usize, 2] {
        let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().expect("pool");
        g.bench_function(BenchmarkId::new("5_steps", format!("{threads}_threads")), |b| {
            pool.install(|| {
                b.iter(|| {
                    s.restore(&bytes).expect("restore");
                    (0..5).map(|_| s.step(Want::default()).contact_pairs).sum::<usize>()
                })
            })
        });
    }
    g.finish();
}

criterion_group!(benches, nbs, kernel, fragmented);
criterion_main!(benches);
