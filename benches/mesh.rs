//! Mesh generation and joint insertion, from 10⁴ to 10⁶ tets.
//!
//! Throughput is reported in tets per second (criterion `Elements`), so the
//! per-tet cost can be compared across sizes in one run.

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use femdem_benches::{box_with_tets, disc_extrusion};
use femdem_mesh::generate::generate_box;
use femdem_mesh::insert_joints;

fn generation(c: &mut Criterion) {
    let mut g = c.benchmark_group("generate");
    g.sample_size(10);
    for target in [10_000usize, 100_000, 1_000_000] {
        let spec = box_with_tets(target);
        let n = generate_box(&spec).unwrap().num_tets() as u64;
        g.throughput(Throughput::Elements(n));
        g.bench_with_input(BenchmarkId::new("box", n), &spec, |b, s| b.iter(|| generate_box(s).unwrap()));
    }
    let spec = disc_extrusion(1.2e-3);
    let n = femdem_mesh::generate::generate_extrusion(&spec).unwrap().num_tets() as u64;
    g.throughput(Throughput::Elements(n));
    g.bench_with_input(BenchmarkId::new("brazilian_disc_extrusion", n), &spec, |b, s| {
        b.iter(|| femdem_mesh::generate::generate_extrusion(s).unwrap())
    });
    g.finish();
}

fn joints(c: &mut Criterion) {
    let mut g = c.benchmark_group("insert_joints");
    g.sample_size(10);
    for target in [10_000usize, 100_000, 1_000_000] {
        let mesh = generate_box(&box_with_tets(target)).unwrap();
        g.throughput(Throughput::Elements(mesh.num_tets() as u64));
        g.bench_with_input(BenchmarkId::new("box", mesh.num_tets()), &mesh, |b, m| {
            b.iter(|| insert_joints(m).unwrap())
        });
    }
    g.finish();
}

criterion_group!(benches, generation, joints);
criterion_main!(benches);
