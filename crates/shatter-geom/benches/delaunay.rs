//! Criterion benchmarks of `tetrahedralize` on uniform random points (1k, 10k, 100k).

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use shatter_geom::delaunay::tetrahedralize;
use shatter_geom::sampling::uniform;

fn bench(c: &mut Criterion) {
    let mut group = c.benchmark_group("delaunay_uniform");
    group.sample_size(10);
    for n in [1_000usize, 10_000, 100_000] {
        let pts = uniform(n, 1);
        group.throughput(Throughput::Elements(n as u64));
        group.bench_with_input(BenchmarkId::from_parameter(n), &pts, |b, pts| {
            b.iter(|| tetrahedralize(pts).expect("uniform points are in general position"))
        });
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
