//! `shatter fracture`, end to end through the real binary.
#![allow(clippy::unwrap_used)]

mod common;

use common::{reimport, rel, shatter, tetrahedron_obj};
use serde_json::Value;

fn volumes(json: &Value) -> (f64, f64, f64) {
    (
        json["mesh_volume"].as_f64().unwrap(),
        json["fragments_volume"].as_f64().unwrap(),
        json["min_fragment_volume"].as_f64().unwrap(),
    )
}

fn count_prefix(text: &str, prefix: &str) -> usize {
    text.lines().filter(|l| l.starts_with(prefix)).count()
}

#[test]
fn voronoi_obj_has_one_object_per_fragment_and_keeps_the_volume() {
    let dir = tempfile::tempdir().unwrap();
    let run = shatter(
        dir.path(),
        &[
            "fracture", "--shape", "bird", "--method", "voronoi", "--pieces", "30", "--out",
            "bird.obj", "--json",
        ],
    )
    .ok();
    let json = run.json();
    let fragments = json["fragments"].as_u64().unwrap() as usize;
    assert!(fragments >= 30, "30 seeds gave {fragments} fragments");
    assert!(json["bonds"].as_u64().unwrap() > 0);
    assert!(json["millis"].as_f64().unwrap() >= 0.0);
    let (mesh_v, frag_v, min_v) = volumes(&json);
    assert!(
        rel(frag_v, mesh_v) < 1e-6,
        "fragments {frag_v} vs mesh {mesh_v}"
    );
    assert!(min_v > 0.0);

    let text = std::fs::read_to_string(dir.path().join("bird.obj")).unwrap();
    assert_eq!(count_prefix(&text, "o fragment_"), fragments);
    assert!(text.lines().any(|l| l.trim() == "usemtl interior"));
    assert!(text.lines().any(|l| l.trim() == "usemtl surface"));
    let back = reimport(&dir.path().join("bird.obj"));
    assert!(rel(back.signed_volume(), mesh_v) < 1e-6);
}

#[test]
fn glb_output_reimports_with_the_volume() {
    let dir = tempfile::tempdir().unwrap();
    let run = shatter(
        dir.path(),
        &[
            "fracture", "--shape", "capsule", "--pieces", "12", "--out", "c.glb", "--json",
        ],
    )
    .ok();
    let json = run.json();
    let (mesh_v, frag_v, _) = volumes(&json);
    assert!(rel(frag_v, mesh_v) < 1e-6);
    let back = reimport(&dir.path().join("c.glb"));
    assert!(
        rel(back.signed_volume(), mesh_v) < 1e-6,
        "{}",
        back.signed_volume()
    );
}

#[test]
fn thesis_tetra_case_fills_the_cube() {
    let dir = tempfile::tempdir().unwrap();
    let run = shatter(
        dir.path(),
        &[
            "fracture",
            "--shape",
            "cube",
            "--method",
            "tetra",
            "--random-vertices",
            "500",
            "--placement",
            "thesis",
            "--center",
            "--json",
        ],
    )
    .ok();
    let json = run.json();
    // Slivers are merged into neighbours, so there are fewer fragments than tetrahedra.
    assert!(json["fragments"].as_u64().unwrap() > 1);
    let (mesh_v, frag_v, min_v) = volumes(&json);
    assert!(rel(mesh_v, 1.0) < 1e-12, "cube volume {mesh_v}");
    assert!(rel(frag_v, mesh_v) < 1e-9, "fragments {frag_v}");
    assert!(min_v > 0.0);
}

#[test]
fn every_method_and_pattern_runs_and_keeps_the_volume() {
    let dir = tempfile::tempdir().unwrap();
    let cases: &[&[&str]] = &[
        &["--method", "slice", "--pieces", "5"],
        &[
            "--method",
            "voronoi",
            "--pattern",
            "clustered",
            "--pieces",
            "15",
        ],
        &[
            "--method",
            "voronoi",
            "--pattern",
            "splinter",
            "--pieces",
            "15",
        ],
        &[
            "--method",
            "voronoi",
            "--pattern",
            "radial",
            "--pieces",
            "15",
            "--impact",
            "0,0,0.4",
        ],
    ];
    for extra in cases {
        let mut args = vec!["fracture", "--shape", "cylinder", "--json"];
        args.extend_from_slice(extra);
        let json = shatter(dir.path(), &args).ok().json();
        let (mesh_v, frag_v, _) = volumes(&json);
        assert!(json["fragments"].as_u64().unwrap() >= 2, "{extra:?}");
        assert!(
            rel(frag_v, mesh_v) < 1e-6,
            "{extra:?}: {frag_v} vs {mesh_v}"
        );
    }
}

#[test]
fn tetra_with_skipped_vertices_stays_inside_the_mesh() {
    // Skipping surface vertices shrinks the tetrahedralized hull: the fragments fill
    // less than the mesh, never more.
    let dir = tempfile::tempdir().unwrap();
    let json = shatter(
        dir.path(),
        &[
            "fracture",
            "--shape",
            "cylinder",
            "--method",
            "tetra",
            "--random-vertices",
            "40",
            "--skip",
            "1",
            "--json",
        ],
    )
    .ok()
    .json();
    let (mesh_v, frag_v, min_v) = volumes(&json);
    assert!(json["fragments"].as_u64().unwrap() >= 2);
    assert!(frag_v <= mesh_v * (1.0 + 1e-9), "{frag_v} > {mesh_v}");
    assert!(frag_v > 0.5 * mesh_v, "{frag_v} of {mesh_v}");
    assert!(min_v > 0.0);
}

#[test]
fn same_seed_gives_the_same_fracture() {
    let dir = tempfile::tempdir().unwrap();
    // Same file name in different folders: the OBJ names its MTL file.
    let run = |seed: &str, sub: &str| {
        std::fs::create_dir(dir.path().join(sub)).unwrap();
        let out = format!("{sub}/torus.obj");
        shatter(
            dir.path(),
            &[
                "fracture", "--shape", "torus", "--pieces", "10", "--seed", seed, "--out", &out,
            ],
        )
        .ok();
        std::fs::read_to_string(dir.path().join(out)).unwrap()
    };
    let (a, b, c) = (run("4", "a"), run("4", "b"), run("5", "c"));
    assert!(a == b, "seed 4 gave two different fractures");
    assert!(a != c, "seeds 4 and 5 gave the same fracture");
}

#[test]
fn mesh_files_and_scale_are_accepted() {
    let dir = tempfile::tempdir().unwrap();
    shatter(dir.path(), &["shape", "cube", "--out", "cube.obj"]).ok();
    let json = shatter(
        dir.path(),
        &[
            "fracture", "cube.obj", "--scale", "2,2,2", "--pieces", "8", "--json",
        ],
    )
    .ok()
    .json();
    let (mesh_v, frag_v, _) = volumes(&json);
    assert!(rel(mesh_v, 8.0) < 1e-9, "scaled cube volume {mesh_v}");
    assert!(rel(frag_v, 8.0) < 1e-6);
}

#[test]
fn seeds_file_gives_one_cell_per_seed_in_a_convex_mesh() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("seeds.xyz"),
        "# four seeds inside the unit cube\n-0.2 -0.2 -0.2\n0.2 0.2 0.2\n-0.2 0.2 0.0\n0.2 -0.2 0.0\n",
    )
    .unwrap();
    let json = shatter(
        dir.path(),
        &[
            "fracture",
            "--shape",
            "cube",
            "--seeds-file",
            "seeds.xyz",
            "--json",
        ],
    )
    .ok()
    .json();
    assert_eq!(json["fragments"], 4);
}

#[test]
fn inward_mesh_is_flipped_with_a_warning() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("inward.obj"), tetrahedron_obj(true)).unwrap();
    let run = shatter(
        dir.path(),
        &["fracture", "inward.obj", "--pieces", "3", "--json"],
    )
    .ok();
    assert!(run.stderr.contains("warning:"), "{}", run.stderr);
    assert!(run.stderr.contains("inward"), "{}", run.stderr);
    let json = run.json();
    let (mesh_v, frag_v, _) = volumes(&json);
    assert!(rel(mesh_v, 1.0 / 6.0) < 1e-12);
    assert!(rel(frag_v, mesh_v) < 1e-6);
}

#[test]
fn open_mesh_is_refused_with_the_count_of_boundary_edges_when_strict() {
    let dir = tempfile::tempdir().unwrap();
    let mut text = tetrahedron_obj(false);
    // Drop the last face: three boundary edges.
    let cut = text.trim_end().rfind('\n').unwrap();
    text.truncate(cut + 1);
    std::fs::write(dir.path().join("open.obj"), text).unwrap();
    shatter(dir.path(), &["fracture", "open.obj", "--strict"])
        .bad_input(&["open.obj", "3 boundary edges"]);
    // Without --strict, repair tries: the hole is a third of the surface or more, too
    // large to fill (RepairOptions::max_hole_area), so the tetrahedron is an open sheet.
    shatter(dir.path(), &["fracture", "open.obj"])
        .bad_input(&["open.obj", "1 open sheet and no closed part"]);
}

#[test]
fn missing_empty_and_unreadable_meshes_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    shatter(dir.path(), &["fracture", "nope.obj"]).bad_input(&["nope.obj"]);
    std::fs::write(dir.path().join("empty.obj"), "# nothing\n").unwrap();
    shatter(dir.path(), &["fracture", "empty.obj"]).bad_input(&["empty.obj"]);
    std::fs::write(dir.path().join("junk.stl"), "this is not an stl").unwrap();
    shatter(dir.path(), &["fracture", "junk.stl"]).bad_input(&["junk.stl"]);
    std::fs::write(dir.path().join("junk.glb"), [0u8, 1, 2, 3]).unwrap();
    shatter(dir.path(), &["fracture", "junk.glb"]).bad_input(&["junk.glb"]);
    std::fs::write(dir.path().join("mesh.ply"), "ply\n").unwrap();
    shatter(dir.path(), &["fracture", "mesh.ply"]).bad_input(&["mesh.ply"]);
}

#[test]
fn bad_flags_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    shatter(dir.path(), &["fracture"]).bad_input(&["--shape"]);
    shatter(
        dir.path(),
        &["fracture", "--shape", "cube", "--pieces", "0"],
    )
    .bad_input(&["--pieces 0"]);
    shatter(dir.path(), &["fracture", "--shape", "teapot"]).bad_input(&["teapot"]);
    shatter(
        dir.path(),
        &["fracture", "--shape", "cube", "--scale", "1,2"],
    )
    .bad_input(&["found 2"]);
    shatter(
        dir.path(),
        &["fracture", "--shape", "cube", "--scale", "0,1,1"],
    )
    .bad_input(&["greater than 0"]);
    shatter(
        dir.path(),
        &["fracture", "--shape", "cube", "--random-vertices", "5"],
    )
    .bad_input(&["--random-vertices applies to --method tetra"]);
    shatter(
        dir.path(),
        &[
            "fracture", "--shape", "cube", "--method", "tetra", "--pieces", "5",
        ],
    )
    .bad_input(&["--pieces applies to --method voronoi and slice"]);
    shatter(
        dir.path(),
        &[
            "fracture",
            "--shape",
            "cube",
            "--method",
            "slice",
            "--pattern",
            "radial",
        ],
    )
    .bad_input(&["--pattern applies to --method voronoi"]);
    shatter(
        dir.path(),
        &["fracture", "--shape", "cube", "--impact", "0,0,0"],
    )
    .bad_input(&["--impact applies to --pattern radial"]);
    shatter(
        dir.path(),
        &["fracture", "--shape", "cube", "--method", "chop"],
    )
    .bad_input(&["chop"]);
    shatter(
        dir.path(),
        &["fracture", "--shape", "cube", "--out", "x.stl"],
    )
    .bad_input(&["x.stl", "unknown output format"]);
    shatter(
        dir.path(),
        &["fracture", "--shape", "cube", "--out", "no/dir/x.obj"],
    )
    .bad_input(&["no/dir/x.obj"]);
}

#[test]
fn bad_seeds_file_names_its_line() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("seeds.xyz"), "0 0 0\n0.1 0.1\n").unwrap();
    shatter(
        dir.path(),
        &["fracture", "--shape", "cube", "--seeds-file", "seeds.xyz"],
    )
    .bad_input(&["seeds.xyz:2: expected 3 coordinates, found 2"]);
    shatter(
        dir.path(),
        &[
            "fracture",
            "--shape",
            "cube",
            "--seeds-file",
            "seeds.xyz",
            "--pieces",
            "3",
        ],
    )
    .bad_input(&["cannot be used with"]);
}
