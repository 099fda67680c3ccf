//! `shatter bench delaunay` and `shatter bench fracture`, end to end (small sizes: these
//! tests check the reports, not the speed).
#![allow(clippy::unwrap_used)]

mod common;

use common::shatter;

#[test]
fn bench_delaunay_reports_every_size() {
    let dir = tempfile::tempdir().unwrap();
    let json = shatter(
        dir.path(),
        &[
            "bench", "delaunay", "--sizes", "100,2000", "--seed", "1", "--json",
        ],
    )
    .ok()
    .json();
    let rows = json["rows"].as_array().unwrap();
    assert_eq!(rows.len(), 2);
    for (row, n) in rows.iter().zip([100, 2000]) {
        assert_eq!(row["points"], n);
        assert_eq!(row["unique_points"], n);
        // A Delaunay tetrahedralization of n random points has roughly 6.5 n tetrahedra.
        let tets = row["tetrahedra"].as_u64().unwrap();
        assert!(
            tets as f64 > 3.0 * n as f64,
            "{n} points gave {tets} tetrahedra"
        );
        assert!(row["points_per_second"].as_f64().unwrap() > 0.0);
        // The result holds at least its tetrahedra's vertex indices and adjacency.
        let held = row["result_bytes_per_point"].as_f64().unwrap() * n as f64;
        assert!(
            held >= tets as f64 * 16.0,
            "{held} bytes for {tets} tetrahedra"
        );
    }
}

#[test]
fn bench_delaunay_table_has_a_row_per_size() {
    let dir = tempfile::tempdir().unwrap();
    let run = shatter(dir.path(), &["bench", "delaunay", "--sizes", "50,60,70"]).ok();
    assert_eq!(run.stdout.lines().count(), 5, "{}", run.stdout);
}

#[test]
fn bench_delaunay_of_too_few_points_is_an_input_error_with_several_sizes_too() {
    let dir = tempfile::tempdir().unwrap();
    for sizes in ["3", "3,100", "100,3"] {
        shatter(dir.path(), &["bench", "delaunay", "--sizes", sizes])
            .bad_input(&["3 random uniform points", "at least 4"]);
    }
}

#[test]
fn bench_bad_sizes_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    shatter(dir.path(), &["bench", "delaunay", "--sizes", "10,0"]).bad_input(&["at least 1"]);
    shatter(dir.path(), &["bench", "delaunay", "--sizes", "10,abc"]).bad_input(&["'abc'"]);
    shatter(dir.path(), &["bench", "fracture", "--runs", "0"]).bad_input(&["--runs"]);
}

#[test]
fn bench_fracture_reports_the_thesis_and_blender_cases() {
    let dir = tempfile::tempdir().unwrap();
    let json = shatter(dir.path(), &["bench", "fracture", "--runs", "1", "--json"])
        .ok()
        .json();
    let rows = json["rows"].as_array().unwrap();
    let case = |name: &str| {
        rows.iter()
            .find(|r| r["case"] == name)
            .unwrap_or_else(|| panic!("no case {name}"))
    };
    assert!(case("bird voronoi 100")["fragments"].as_u64().unwrap() >= 100);
    // Painting the bird adds attributes, not geometry: the same cut.
    for key in ["fragments", "bonds"] {
        assert_eq!(
            case("bird voronoi 100 painted")[key],
            case("bird voronoi 100")[key]
        );
    }
    assert!(case("cube tetra 500 thesis")["fragments"].as_u64().unwrap() > 1);
    for r in rows {
        assert!(r["mean_ms"].as_f64().unwrap() >= r["min_ms"].as_f64().unwrap());
        assert!(r["max_ms"].as_f64().unwrap() >= r["mean_ms"].as_f64().unwrap());
    }
}

#[test]
fn bench_stress_reports_the_20000_bond_graph_and_skips_it_when_settled() {
    let dir = tempfile::tempdir().unwrap();
    // Few iterations: this test checks the report, not the speed (debug build).
    let json = shatter(
        dir.path(),
        &[
            "bench",
            "stress",
            "--runs",
            "1",
            "--max-iterations",
            "30",
            "--json",
        ],
    )
    .ok()
    .json();
    assert!(json["bonds"].as_u64().unwrap() >= 20_000);
    for key in ["cold", "hit", "after_hit", "bond_broken"] {
        let it = json[key]["iterations"].as_f64().unwrap();
        assert!((1.0..=30.0).contains(&it), "{key}: {json}");
        assert!(json[key]["residual"].as_f64().unwrap() > 0.0, "{key}");
    }
    // 30 iterations do not reach the tolerance, so the second solve goes on from there
    // instead of skipping a settled island.
    assert_eq!(json["cold"]["converged"], false);
    assert!(json["settled"]["iterations"].as_f64().unwrap() > 0.0);
    assert_eq!(json["preconditioner"], "multigrid");
    // As the World runs it: every case converges, one solve at a time within the
    // budgets, and the mean per solve is reported.
    let world = &json["world"];
    for key in ["cold", "hit", "bond_broken"] {
        assert_eq!(world[key]["converged"], true, "{key}: {world}");
        assert!(
            world[key]["solves"].as_f64().unwrap() > 1.0,
            "{key}: {world}"
        );
    }
    assert!(world["per_solve_ms"].as_f64().unwrap() > 0.0, "{world}");
    assert_eq!(world["spring_budget"], 24_000);
    shatter(dir.path(), &["bench", "stress", "--runs", "0"]).bad_input(&["--runs"]);
    shatter(dir.path(), &["bench", "stress", "--preconditioner", "ilu"])
        .bad_input(&["--preconditioner", "multigrid, block-jacobi"]);
    shatter(dir.path(), &["bench", "stress", "--tolerance", "2"]).bad_input(&["--tolerance"]);
}

#[test]
fn bench_runtime_reports_every_case_and_refuses_bad_counts() {
    let dir = tempfile::tempdir().unwrap();
    let json = shatter(dir.path(), &["bench", "runtime", "--runs", "1", "--json"])
        .ok()
        .json();
    assert_eq!(json["threads"], 1);
    assert_eq!(json["budget_ms"], 4.0);
    let rows = json["rows"].as_array().unwrap();
    let names: Vec<&str> = rows.iter().map(|r| r["case"].as_str().unwrap()).collect();
    assert_eq!(names, ["bird-50", "bird-20", "bird-100", "cube-50"]);
    for r in rows {
        // A cut makes several fragments, never more than it asked for.
        let fragments = r["fragments"].as_u64().unwrap();
        assert!(
            fragments > 3 && fragments <= r["pieces"].as_u64().unwrap(),
            "{r}"
        );
        assert!(r["cut_ms"]["max"].as_f64().unwrap() >= r["cut_ms"]["min"].as_f64().unwrap());
        let (world, apply) = (
            r["world_ms"]["mean"].as_f64().unwrap(),
            r["apply_ms"]["mean"].as_f64().unwrap(),
        );
        assert!(world > 0.0 && apply > 0.0 && apply < world, "{r}");
    }
    shatter(dir.path(), &["bench", "runtime", "--runs", "0"]).bad_input(&["--runs"]);
    shatter(dir.path(), &["bench", "runtime", "--threads", "0"]).bad_input(&["--threads"]);
}
