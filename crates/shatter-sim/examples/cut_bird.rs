//! A profiling driver for the runtime cut: `cut_fragment` of the intact bird, hit at its
//! front, N times (`cargo run --release -p shatter-sim --example cut_bird -- PIECES RUNS
//! [hulls]`; set `RAYON_NUM_THREADS=1` for one core, as `shatter bench runtime` does).
//! With `hulls`, each cut also builds its fragments' collision shapes, as the World's cut
//! thread does.

use glam::Vec3;
use shatter_geom::{DVec3, model::Model, shapes};
use shatter_sim::object::prepare::collision_shapes;
use shatter_sim::runtime::{cut_fragment, whole};

fn main() {
    let mut args = std::env::args().skip(1);
    let pieces: u32 = args.next().and_then(|a| a.parse().ok()).unwrap_or(50);
    let runs: u64 = args.next().and_then(|a| a.parse().ok()).unwrap_or(20);
    let hulls = args.next().is_some_and(|a| a == "hulls");
    let Ok(whole) = whole(&Model::from_mesh(shapes::bird())) else {
        eprintln!("the bird does not fracture");
        return;
    };
    let impact = whole.fragments[0]
        .mesh
        .positions
        .iter()
        .copied()
        .max_by(|a, b| a.z.total_cmp(&b.z).then(a.x.total_cmp(&b.x)))
        .unwrap_or(DVec3::ZERO);
    let mut times = Vec::new();
    let (mut fragments, mut convex, mut points, mut shapes) = (0, 0, 0, 0);
    for seed in 0..runs {
        let t = std::time::Instant::now();
        match cut_fragment(&whole, 0, impact, pieces, seed + 1) {
            Ok(cut) => {
                fragments = cut.fragments.len();
                convex = cut.fragments.iter().map(|f| f.convex_pieces.len()).sum();
                points = cut
                    .fragments
                    .iter()
                    .flat_map(|f| f.convex_pieces.iter().map(Vec::len))
                    .sum();
                if hulls {
                    shapes = collision_shapes(&cut, Vec3::ONE).iter().map(Vec::len).sum();
                }
            }
            Err(e) => eprintln!("seed {seed}: {e}"),
        }
        times.push(t.elapsed().as_secs_f64() * 1e3);
    }
    let mean = times.iter().sum::<f64>() / times.len().max(1) as f64;
    let min = times.iter().copied().fold(f64::INFINITY, f64::min);
    println!(
        "bird-{pieces}: {fragments} fragments, {convex} convex pieces of {points} points \
         ({shapes} hulls built), mean {mean:.3} ms, min {min:.3} ms"
    );
}
