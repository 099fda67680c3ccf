//! What carrying a textured asset's attributes costs, counted in instructions: the
//! bird into 100 Voronoi cells (as `shatter bench fracture` cuts it), bare or painted
//! (`bench::fracture::paint`: UVs, smooth normals and colours on every corner, two
//! materials), `RUNS` times. Run each under callgrind and compare the totals, and the
//! inclusive count of `attach` (the attributes, computed after the geometry):
//!
//! ```sh
//! RAYON_NUM_THREADS=1 valgrind --tool=callgrind --callgrind-out-file=bare.cg \
//!     target/release/examples/attribute_cost bare 3
//! RAYON_NUM_THREADS=1 valgrind --tool=callgrind --callgrind-out-file=painted.cg \
//!     target/release/examples/attribute_cost painted 3
//! callgrind_annotate --inclusive=yes bare.cg | grep -E 'PROGRAM TOTALS|attach'
//! ```

use shatter_geom::fracture::{FractureParams, Method, Pattern, fracture_model};
use shatter_geom::model::Model;
use shatter_geom::shapes::Shape;
use shatter_lab::bench::fracture::paint;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let painted = match args.get(1).map(String::as_str) {
        Some("bare") => false,
        Some("painted") => true,
        _ => {
            eprintln!("usage: attribute_cost bare|painted [RUNS]");
            std::process::exit(2);
        }
    };
    let runs: u32 = match args.get(2).map(|r| r.parse()) {
        None => 1,
        Some(Ok(r)) => r,
        Some(Err(e)) => {
            eprintln!("RUNS: {e}");
            std::process::exit(2);
        }
    };
    let mut model = Model::from_mesh(Shape::Bird.mesh());
    if painted {
        paint(&mut model);
    }
    let params = FractureParams {
        method: Method::voronoi(100, Pattern::Uniform),
        seed: 0,
    };
    for _ in 0..runs {
        match fracture_model(&model, &params) {
            Ok(f) => println!("{} fragments", f.fragments.len()),
            Err(e) => {
                eprintln!("{e}");
                std::process::exit(1);
            }
        }
    }
}
