//! NBS detection on clouds of 10⁴ to 10⁶ bounding spheres at a constant
//! density (about one sphere per cell of the grid, as in a fragmented
//! mesh). The time per element (criterion's `Elements` throughput) should
//! stay flat: the target is within 1.5× from 10⁴ to 10⁶.

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use femdem_contact::{Nbs, contact_bound, tet_tet_contact_within, tet_tet_forces, tet_tet_gradient};
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
/// to the other tet and cut into its 4 sub-tets' regions) for a shallow and
/// a deep overlap.
fn kernel(c: &mut Criterion) {
    let a =
        [Vec3::new(1.0, 1.0, 1.0), Vec3::new(1.0, -1.0, -1.0), Vec3::new(-1.0, -1.0, 1.0), Vec3::new(-1.0, 1.0, -1.0)]
            .map(|v| v * 0.5);
    let d = -Vec3::new(1.0, 1.0, 1.0).normalize();
    let r_in = 2f64.sqrt() / (2.0 * 6f64.sqrt());
    // Eq. 17, and the energy-conserving model on the same pairs.
    let mut g = c.benchmark_group("tet_tet_forces");
    for (name, delta) in [("shallow", 0.01), ("deep", 0.3)] {
        let mut b = a.map(|v| -v + d * (2.0 * r_in - delta));
        b.swap(2, 3);
        g.bench_function(name, |bench| bench.iter(|| tet_tet_forces(&a, &b, 1e9)));
        g.bench_function(format!("{name}, gradient"), |bench| bench.iter(|| tet_tet_gradient(&a, &b, 1e9)));
    }
    g.finish();
}

/// The negligible-pair bound (`contact_bound`) against the kernel it
/// saves, on the commonest pair of a fracture network: two unit tets that
/// meet at a vertex from either side of a plane, pressed together by 10⁻⁴
/// (a speck of overlap at the vertex), on two that share an edge (a sliver
/// along it) and on a face-to-face pair pressed by as much; and the two
/// together as the solver calls them (`tet_tet_contact_within`, negligible
/// faces left out, in either order).
fn bound(c: &mut Criterion) {
    let s = 3f64.sqrt() / 2.0;
    let ring = |z: f64| [Vec3::new(1.0, 0.0, z), Vec3::new(-0.5, s, z), Vec3::new(-0.5, -s, z)];
    let [l0, l1, l2] = ring(-1.0);
    let [u0, u1, u2] = ring(1.0).map(|p| Vec3::new(p.x * 0.7 + 0.2, p.y * 0.7, p.z));
    let down = Vec3::new(0.0, 0.0, 1e-4);
    let vertex = ([Vec3::zeros(), l0, l1, l2], [Vec3::zeros(), u0, u2, u1].map(|p| p - down));
    let [r0, r1, r2] = ring(0.0);
    let face = ([Vec3::new(0.0, 0.0, -1.0), r0, r2, r1], [Vec3::new(0.0, 0.0, 1.0), r0, r1, r2].map(|p| p - down));
    let positive = |mut t: [Vec3; 4]| {
        if femdem_core::tet::signed_volume(&t) < 0.0 {
            t.swap(2, 3);
        }
        t
    };
    // Two tets sharing the edge from (−1, 0, 0) to (1, 0, 0) from either
    // side of z = 0, pressed by as much: a sliver along the edge.
    let (e0, e1) = (Vec3::new(-1.0, 0.0, 0.0), Vec3::new(1.0, 0.0, 0.0));
    let edge = (
        [e0, e1, Vec3::new(0.0, 1.0, -1.0), Vec3::new(0.1, -1.0, -1.0)],
        [e0, e1, Vec3::new(0.0, 0.8, 1.0), Vec3::new(-0.1, -1.0, 1.0)].map(|p| p - down),
    );
    let mut g = c.benchmark_group("contact_bound");
    for (name, (a, b)) in [("vertex", vertex), ("edge", edge), ("face", face)] {
        let (a, b) = (positive(a), positive(b));
        let (a, b) = (std::hint::black_box(a), std::hint::black_box(b));
        g.bench_function(format!("{name}/bound"), |bench| bench.iter(|| contact_bound(&a, &b)));
        g.bench_function(format!("{name}/kernel"), |bench| bench.iter(|| tet_tet_forces(&a, &b, 1e9)));
        // As the solver calls it at the default `negligible`: bound, then
        // the clip with negligible faces left out; and clip first.
        let omit = 1e-10 * femdem_core::tet::signed_volume(&a).min(femdem_core::tet::signed_volume(&b)).cbrt().powi(2);
        for clip_first in [false, true] {
            let order = if clip_first { "clip first" } else { "bound first" };
            g.bench_function(format!("{name}/within, {order}"), |bench| {
                bench.iter(|| tet_tet_contact_within(&a, &b, 1e9, omit, clip_first))
            });
        }
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
    let tets = s.model().num_deformable_tets() as u64;
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

criterion_group!(benches, nbs, kernel, bound, fragmented);
criterion_main!(benches);
