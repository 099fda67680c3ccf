//! A profiling driver for the runtime cut: `cut_at` of the bird, hit at its front, N
//! times (`cargo run --release -p shatter-sim --example cut_bird -- PIECES RUNS`; set
//! `RAYON_NUM_THREADS=1` for one core, as `shatter bench runtime` does).

use shatter_geom::{DVec3, model::Model, shapes};
use shatter_sim::runtime::{cut_at, fragment_model, whole};

fn main() {
    let mut args = std::env::args().skip(1);
    let pieces: u32 = args.next().and_then(|a| a.parse().ok()).unwrap_or(50);
    let runs: u64 = args.next().and_then(|a| a.parse().ok()).unwrap_or(20);
    let Ok(whole) = whole(&Model::from_mesh(shapes::bird())) else {
        eprintln!("the bird does not fracture");
        return;
    };
    let model = fragment_model(&whole, 0);
    let impact = model
        .mesh
        .positions
        .iter()
        .copied()
        .max_by(|a, b| a.z.total_cmp(&b.z).then(a.x.total_cmp(&b.x)))
        .unwrap_or(DVec3::ZERO);
    let mut times = Vec::new();
    let mut fragments = 0;
    for seed in 0..runs {
        let t = std::time::Instant::now();
        match cut_at(&model, impact, pieces, seed + 1) {
            Ok(cut) => fragments = cut.fragments.len(),
            Err(e) => eprintln!("seed {seed}: {e}"),
        }
        times.push(t.elapsed().as_secs_f64() * 1e3);
    }
    let mean = times.iter().sum::<f64>() / times.len().max(1) as f64;
    let min = times.iter().copied().fold(f64::INFINITY, f64::min);
    println!("bird-{pieces}: {fragments} fragments, mean {mean:.3} ms, min {min:.3} ms");
}
