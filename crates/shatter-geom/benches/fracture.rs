//! Criterion benchmarks of fracture: the bird into 100 Voronoi cells (compare with
//! Blender's Cell Fracture) and the thesis's creation case (cube, 500 random points,
//! tetra); rough cut faces on the bird's 100 cells; the runtime cut (issue 16: the bird
//! into 50 radial cells around a hit on its front, 4 ms on one core is the budget; run
//! with `RAYON_NUM_THREADS=1` for that figure).

use criterion::{Criterion, criterion_group, criterion_main};
use shatter_geom::fracture::{
    FractureParams, Method, Pattern, Placement, Roughness, Seeds, fracture, roughen,
};
use shatter_geom::shapes;

fn bench(c: &mut Criterion) {
    let bird = shapes::bird();
    let voronoi = FractureParams {
        method: Method::Voronoi {
            seeds: Seeds::count(100),
        },
        seed: 1,
    };
    c.bench_function("fracture/voronoi_bird_100", |b| {
        b.iter(|| fracture(&bird, &voronoi).expect("bird fractures"))
    });

    // As `shatter_sim::runtime::cut_at` cuts the bird hit on its front (the vertex
    // farthest along +z, as `shatter bench runtime` hits it).
    let front = bird
        .positions
        .iter()
        .copied()
        .max_by(|a, b| a.z.total_cmp(&b.z).then(a.x.total_cmp(&b.x)))
        .expect("the bird has vertices");
    let radial = FractureParams {
        method: Method::Voronoi {
            seeds: Seeds::Pattern {
                count: 50,
                pattern: Pattern::Radial,
                impact: Some(front),
            },
        },
        seed: 1,
    };
    c.bench_function("fracture/radial_bird_50_at_front", |b| {
        b.iter(|| fracture(&bird, &radial).expect("bird fractures"))
    });

    let cells = fracture(&bird, &voronoi).expect("bird fractures");
    let stone = Roughness {
        amplitude: 0.02,
        frequency: 2.0,
        ..Roughness::STONE
    };
    c.bench_function("fracture/roughen_bird_100", |b| {
        b.iter(|| {
            let mut rough = cells.clone();
            roughen(&mut rough, &stone).expect("valid roughness")
        })
    });

    let cube = shapes::cube();
    for (name, placement) in [
        ("fracture/tetra_cube_500_interior", Placement::Interior),
        ("fracture/tetra_cube_500_thesis", Placement::Thesis),
    ] {
        let tetra = FractureParams {
            method: Method::Tetra {
                random_vertices: 500,
                skip: 0,
                center: true,
                placement,
            },
            seed: 1,
        };
        c.bench_function(name, |b| {
            b.iter(|| fracture(&cube, &tetra).expect("cube fractures"))
        });
    }
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(20);
    targets = bench
}
criterion_main!(benches);
