//! Writing one FEMDEM-sized output step: 100 000 tets that each own their
//! four nodes (400 000 points, as after joint insertion), with displacement
//! and velocity on points and stress (9), damage and region on cells —
//! about 70 MB of raw data — for each compression.

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use femdem_vtk::{Compression, Field, Frame, VtuOptions, write_vtu_with};

fn write(c: &mut Criterion) {
    let tets_n = 100_000u32;
    let points: Vec<[f64; 3]> = (0..4 * tets_n)
        .map(|i| {
            let x = f64::from(i);
            [x.sin(), (0.5 * x).cos(), 1e-3 * x]
        })
        .collect();
    let tets: Vec<[u32; 4]> = (0..tets_n).map(|t| [4 * t, 4 * t + 1, 4 * t + 2, 4 * t + 3]).collect();
    let displacement: Vec<[f64; 3]> = points.iter().map(|p| p.map(|c| 1e-4 * c)).collect();
    let velocity: Vec<[f64; 3]> = points.iter().map(|p| p.map(|c| -0.3 * c)).collect();
    let stress: Vec<[f64; 9]> =
        (0..tets_n).map(|t| std::array::from_fn(|k| 1e6 * (f64::from(t) * 0.01 + k as f64).sin())).collect();
    let damage: Vec<f64> = (0..tets_n).map(|t| f64::from(t % 97) / 96.0).collect();
    let region: Vec<f64> = (0..tets_n).map(|t| f64::from(t % 3)).collect();
    let pf = [Field::vector("displacement", &displacement), Field::vector("velocity", &velocity)];
    let cf = [Field::tensor("stress", &stress), Field::scalar("damage", &damage), Field::scalar("region", &region)];
    let frame = Frame::new(&points, &tets).with_point_fields(&pf).with_cell_fields(&cf);
    let dir = std::env::temp_dir().join(format!("femdem-vtk-bench-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");

    let mut g = c.benchmark_group("write_vtu");
    g.sample_size(10);
    g.throughput(Throughput::Elements(u64::from(tets_n)));
    for (name, compression) in
        [("none", Compression::None), ("lz4", Compression::Lz4), ("zlib-1", Compression::Zlib { level: 1 })]
    {
        let path = dir.join(format!("{name}.vtu"));
        g.bench_function(BenchmarkId::from_parameter(name), |b| {
            b.iter(|| write_vtu_with(&path, &frame, VtuOptions { compression }).expect("write"))
        });
    }
    g.finish();
    let _ = std::fs::remove_dir_all(&dir);
}

criterion_group!(benches, write);
criterion_main!(benches);
