//! A profiling driver for the runtime cut: `cut_fragment` of the intact bird, hit at its
//! front, N times (`cargo run --release -p shatter-sim --example cut_bird -- PIECES RUNS
//! [hulls]`; set `RAYON_NUM_THREADS=1` for one core, as `shatter bench runtime` does).
//! With `hulls`, each cut also builds its fragments' collision shapes, as the World's cut
//! thread does. With `obj DIR`, it writes `DIR/bird.obj` (the intact bird), `DIR/cut.obj`
//! (the first cut's fragments, one `o` each), `DIR/fragment.obj` (its largest fragment)
//! and `DIR/cut2.obj` (that fragment cut again into 12), for an independent check.

use glam::Vec3;
use shatter_geom::fracture::Fracture;
use shatter_geom::{DVec3, TriMesh, model::Model, shapes};
use shatter_sim::object::prepare::collision_shapes;
use shatter_sim::runtime::{cut_fragment, whole};

fn main() {
    let mut args = std::env::args().skip(1);
    let pieces: u32 = args.next().and_then(|a| a.parse().ok()).unwrap_or(50);
    let runs: u64 = args.next().and_then(|a| a.parse().ok()).unwrap_or(20);
    let mode = args.next();
    let hulls = mode.as_deref() == Some("hulls");
    let obj_dir = if mode.as_deref() == Some("obj") {
        args.next()
    } else {
        None
    };
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
    if let Some(dir) = obj_dir
        && let Err(e) = write_objs(&whole, impact, pieces, std::path::Path::new(&dir))
    {
        eprintln!("cannot write the OBJ files: {e}");
    }
    let mean = times.iter().sum::<f64>() / times.len().max(1) as f64;
    let min = times.iter().copied().fold(f64::INFINITY, f64::min);
    println!(
        "bird-{pieces}: {fragments} fragments, {convex} convex pieces of {points} points \
         ({shapes} hulls built), mean {mean:.3} ms, min {min:.3} ms"
    );
}

/// The intact bird, its cut at `impact` (seed 1), the cut's largest fragment and that
/// fragment cut again into 12 around its centroid, as OBJ files in `dir`.
fn write_objs(
    whole: &Fracture,
    impact: DVec3,
    pieces: u32,
    dir: &std::path::Path,
) -> std::io::Result<()> {
    let fail = |e: shatter_geom::fracture::FractureError| std::io::Error::other(e.to_string());
    let cut = cut_fragment(whole, 0, impact, pieces, 1).map_err(fail)?;
    let largest = (0..cut.fragments.len())
        .max_by(|&a, &b| cut.fragments[a].volume.total_cmp(&cut.fragments[b].volume))
        .unwrap_or(0);
    let centroid = cut.fragments[largest].centroid;
    let again = cut_fragment(&cut, largest, centroid, 12, 2).map_err(fail)?;
    let meshes = |f: &Fracture| {
        f.fragments
            .iter()
            .map(|g| g.mesh.clone())
            .collect::<Vec<_>>()
    };
    write_obj(&dir.join("bird.obj"), &meshes(whole))?;
    write_obj(&dir.join("cut.obj"), &meshes(&cut))?;
    write_obj(
        &dir.join("fragment.obj"),
        &[cut.fragments[largest].mesh.clone()],
    )?;
    write_obj(&dir.join("cut2.obj"), &meshes(&again))
}

/// `meshes` as one OBJ file, an `o` object each.
fn write_obj(path: &std::path::Path, meshes: &[TriMesh]) -> std::io::Result<()> {
    use std::io::Write;
    let mut out = std::io::BufWriter::new(std::fs::File::create(path)?);
    let mut base = 1;
    for (i, m) in meshes.iter().enumerate() {
        writeln!(out, "o fragment{i}")?;
        for p in &m.positions {
            writeln!(out, "v {:.17} {:.17} {:.17}", p.x, p.y, p.z)?;
        }
        for t in &m.triangles {
            writeln!(out, "f {} {} {}", t[0] + base, t[1] + base, t[2] + base)?;
        }
        base += m.positions.len() as u32;
    }
    out.flush()
}
