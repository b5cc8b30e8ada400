//! One explicit step of the Brazilian disc (≈63k tets at 1.2 mm), with
//! joints (≈123k, the paper's set-up) and without, on 1 and 2 threads in the
//! same run. Throughput is in tets per second (`Elements` = deformable
//! tets), i.e. tet-steps per second; the ratios between the four lines are
//! the point (joint cost, parallel speed-up).

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use femdem_benches::disc_solver;
use femdem_solver::Want;

fn step(c: &mut Criterion) {
    let mut g = c.benchmark_group("step");
    g.sample_size(20);
    for breakable in [true, false] {
        let label = if breakable { "disc_with_joints" } else { "disc_without_joints" };
        for threads in [1usize, 2] {
            let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().expect("pool");
            let mut s = disc_solver(1.2e-3, breakable);
            g.throughput(Throughput::Elements(s.model().num_deformable_tets() as u64));
            g.bench_function(BenchmarkId::new(label, format!("{threads}_threads")), |b| {
                pool.install(|| b.iter(|| s.step(Want::default()).time))
            });
        }
    }
    g.finish();
}

criterion_group!(benches, step);
criterion_main!(benches);
