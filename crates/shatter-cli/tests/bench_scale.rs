//! `shatter bench scale`, end to end (small worlds for a tenth of a second: these tests
//! check the report and the plots, not the speed).
#![allow(clippy::unwrap_used)]

mod common;

use common::shatter;

#[test]
fn bench_scale_reports_a_row_per_case_model_and_size_and_writes_the_plots() {
    let dir = tempfile::tempdir().unwrap();
    let json = shatter(
        dir.path(),
        &[
            "bench",
            "scale",
            "--sizes",
            "100,200",
            "--seconds",
            "0.1",
            "--out",
            "plots",
            "--json",
        ],
    )
    .ok()
    .json();
    assert_eq!(json["steps"], 6);
    let rows = json["rows"].as_array().unwrap();
    assert_eq!(rows.len(), 4 * 2 * 2);
    assert_eq!(rows[0]["case"], "shots");
    assert_eq!(rows[0]["model"], "joints");
    assert_eq!(rows[11]["case"], "landing");
    assert_eq!(rows[11]["model"], "clusters");
    assert_eq!(rows[15]["case"], "blast");
    assert_eq!(rows[15]["model"], "clusters");
    assert_eq!(json["enclosed_colliders"], false);
    assert_eq!(json["contact_speed_cap"], true);
    for row in rows {
        let fastest = row["fastest"].as_f64().unwrap();
        assert!(fastest.is_finite() && fastest >= 0.0, "{row}");
        assert!(row["speeds_capped"].is_u64(), "{row}");
        let fragments = row["fragments"].as_u64().unwrap();
        let grid: u64 = row["grid"]
            .as_array()
            .unwrap()
            .iter()
            .map(|c| c.as_u64().unwrap())
            .product();
        assert_eq!(fragments, grid, "{row}");
        let (mean, max) = (
            row["mean_ms"].as_f64().unwrap(),
            row["max_ms"].as_f64().unwrap(),
        );
        assert!(mean > 0.0 && mean <= max, "{row}");
        assert!(
            row["still_fragments"].as_u64().unwrap() <= fragments,
            "{row}"
        );
        assert_eq!(row["diverged"], 0, "{row}");
    }
    for stem in ["scale_mean_ms", "scale_max_ms", "scale_cpu_ms"] {
        for ext in ["png", "svg"] {
            let path = dir.path().join("plots").join(format!("{stem}.{ext}"));
            assert!(
                std::fs::metadata(&path).unwrap().len() > 0,
                "{}",
                path.display()
            );
        }
    }
}

/// `shatter bench scale` in `dir` on 100 bricks of the clusters model for 0.05 s, for
/// `cases`, with the options `extra`.
fn small_clusters_run(dir: &std::path::Path, cases: &str, extra: &[&str]) -> common::Run {
    let mut args = vec![
        "bench",
        "scale",
        "--sizes",
        "100",
        "--models",
        "clusters",
        "--cases",
        cases,
        "--seconds",
        "0.05",
    ];
    args.extend_from_slice(extra);
    shatter(dir, &args)
}

#[test]
fn bench_scale_table_has_a_row_per_run() {
    let dir = tempfile::tempdir().unwrap();
    let run = small_clusters_run(dir.path(), "landing,shots", &[]).ok();
    let lines: Vec<&str> = run.stdout.lines().collect();
    assert!(lines[2].starts_with("landing   clusters"), "{}", run.stdout);
    assert!(lines[3].starts_with("shots     clusters"), "{}", run.stdout);
    assert!(dir.path().join("bench-scale/scale_mean_ms.png").exists());
}

#[test]
fn bench_scale_can_turn_the_contact_speed_cap_off() {
    let dir = tempfile::tempdir().unwrap();
    let json = small_clusters_run(dir.path(), "landing", &["--no-contact-speed-cap", "--json"])
        .ok()
        .json();
    assert_eq!(json["contact_speed_cap"], false);
    let rows = json["rows"].as_array().unwrap();
    assert_eq!(rows.len(), 1);
    assert_eq!(rows[0]["speeds_capped"], 0);
}

#[test]
fn bench_scale_bad_options_are_input_errors() {
    let dir = tempfile::tempdir().unwrap();
    let bad = |args: &[&str], needles: &[&str]| {
        let mut all = vec!["bench", "scale"];
        all.extend_from_slice(args);
        shatter(dir.path(), &all).bad_input(needles);
    };
    bad(&["--sizes", "100,0"], &["at least 1"]);
    bad(&["--sizes", "100,100"], &["--sizes: 100 is repeated"]);
    bad(
        &["--models", "glue"],
        &["--models: unknown bond model 'glue'"],
    );
    bad(&["--cases", "rain"], &["--cases: unknown case 'rain'"]);
    bad(&["--seconds", "0"], &["--seconds must be positive"]);
    bad(
        &["--seconds", "100000"],
        &["--models clusters leaves it out", "--no-limits"],
    );
    assert!(!dir.path().join("bench-scale").exists());
}
