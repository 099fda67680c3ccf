//! `mesh::repair` on a 100,000-triangle model: a sphere with a hole cut in it, every
//! 50th triangle flipped and 100 duplicated triangles. Target (issue 13): at most 1 s.

use criterion::{Criterion, criterion_group, criterion_main};
use shatter_geom::mesh::repair::{RepairOptions, repair};
use shatter_geom::model::Model;
use shatter_geom::{TriMesh, shapes};

fn damaged_sphere() -> TriMesh {
    let sphere = shapes::sphere(270, 201);
    let mut tris: Vec<[u32; 3]> = sphere
        .triangles
        .iter()
        .copied()
        .filter(|t| t.iter().all(|&i| sphere.positions[i as usize].y < 0.49))
        .collect();
    for t in tris.iter_mut().step_by(50) {
        t.swap(1, 2);
    }
    let dup: Vec<[u32; 3]> = tris.iter().step_by(997).take(100).copied().collect();
    tris.extend(dup);
    TriMesh::new(sphere.positions, tris)
}

fn bench(c: &mut Criterion) {
    let mesh = damaged_sphere();
    eprintln!("repair bench: {} triangles", mesh.triangles.len());
    let model = Model::from_mesh(mesh);
    let options = RepairOptions::default();
    let (_, report) = repair(&model, &options).expect("repairs");
    eprintln!("repair bench: {:?}", report.warnings());
    let mut group = c.benchmark_group("repair");
    group.sample_size(10);
    group.bench_function("sphere_100k_with_hole", |b| {
        b.iter(|| repair(&model, &options).expect("repairs"));
    });
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
