//! Extreme magnitudes and `--validate`, end to end through the real binary (issue 14
//! parts 3 and 5): right answers or exit code 2 naming the limit, never a wrong answer.
#![allow(clippy::unwrap_used)]

mod common;

use common::{rel, shatter};

/// `fracture --shape bird --scale SCALE --json`. (Not `--validate`: some of these
/// fragments have an edge where merged parts touch, issue 14 part 1.)
fn fracture_json(dir: &std::path::Path, scale: &str) -> serde_json::Value {
    shatter(
        dir,
        &["fracture", "--shape", "bird", "--scale", scale, "--json"],
    )
    .ok()
    .json()
}

#[test]
fn stretched_and_squashed_birds_give_bonds_and_volumes_that_add_up() {
    let dir = tempfile::tempdir().unwrap();
    let unit = fracture_json(dir.path(), "1,1,1");
    let unit_volume = unit["mesh_volume"].as_f64().unwrap();
    for (scale, factor) in [
        ("1e-200,1,1", 1e-200),
        ("1e15,1,1", 1e15),
        ("1e-12,1,1", 1e-12),
    ] {
        let j = fracture_json(dir.path(), scale);
        let v = j["mesh_volume"].as_f64().unwrap();
        assert!(rel(v, unit_volume * factor) < 1e-9, "{scale}: {v}");
        assert!(
            rel(j["fragments_volume"].as_f64().unwrap(), v) < 1e-9,
            "{scale}: {j}"
        );
        assert!(j["bonds"].as_u64().unwrap() > 0, "{scale}: no bonds");
        assert!(j["fragments"].as_u64().unwrap() >= 10, "{scale}: {j}");
    }
    // Uniform scales within range give the unit fracture.
    for (scale, factor) in [("1e-50,1e-50,1e-50", 1e-150), ("1e50,1e50,1e50", 1e150)] {
        let j = fracture_json(dir.path(), scale);
        assert_eq!(j["fragments"], unit["fragments"], "{scale}");
        assert_eq!(j["bonds"], unit["bonds"], "{scale}");
        let v = j["fragments_volume"].as_f64().unwrap();
        assert!(rel(v, unit_volume * factor) < 1e-9, "{scale}: {v}");
    }
}

#[test]
fn sizes_beyond_f64_are_refused_with_the_limit() {
    let dir = tempfile::tempdir().unwrap();
    for (scale, needles) in [
        (
            "1e200,1e200,1e200",
            &["the mesh's volume would be about 1e600", "1.8e308"][..],
        ),
        (
            "1e-200,1e-200,1e-200",
            &["the mesh's volume would be about 1e-600", "2.2e-308"],
        ),
        (
            "1e200,1,1",
            &["the mesh's inertia tensor would be about 1e"],
        ),
    ] {
        let run = shatter(
            dir.path(),
            &["fracture", "--shape", "bird", "--scale", scale],
        );
        let run = run.bad_input(needles);
        for wrong in ["zero volume", "intersect"] {
            assert!(!run.stderr.contains(wrong), "{scale}: {}", run.stderr);
        }
    }
}

#[test]
fn a_huge_shape_says_its_volume_is_beyond_f64_instead_of_nan() {
    let dir = tempfile::tempdir().unwrap();
    let run = shatter(
        dir.path(),
        &[
            "shape",
            "cube",
            "--scale",
            "1e300,1e300,1e300",
            "--out",
            "c.obj",
        ],
    )
    .ok();
    assert!(
        run.stdout
            .contains("volume about 1e900, beyond the range of f64"),
        "{}",
        run.stdout
    );
    assert!(!run.stdout.contains("NaN"));
}

#[test]
fn validate_passes_a_good_fracture_and_reports_a_defect_as_internal() {
    let dir = tempfile::tempdir().unwrap();
    shatter(
        dir.path(),
        &["fracture", "--shape", "cube", "--pieces", "8", "--validate"],
    )
    .ok();
    // Slicing keeps merged parts' shared faces today (issue 14 part 1): validation says
    // so with exit code 1, naming the fragment. Once merging is fixed this run passes.
    let run = shatter(
        dir.path(),
        &[
            "fracture",
            "--shape",
            "cube",
            "--method",
            "slice",
            "--pieces",
            "8",
            "--seed",
            "1",
            "--validate",
        ],
    );
    if run.code != 0 {
        assert_eq!(run.code, 1, "{}", run.stderr);
        assert!(
            run.stderr.contains("failed validation: fragment "),
            "{}",
            run.stderr
        );
    }
    let out = tempfile::tempdir().unwrap();
    let out_dir = out.path().to_str().unwrap();
    shatter(
        dir.path(),
        &[
            "fracture",
            "a.obj",
            "b.obj",
            "--out-dir",
            out_dir,
            "--validate",
        ],
    )
    .bad_input(&["--validate applies to one MESH"]);
}
