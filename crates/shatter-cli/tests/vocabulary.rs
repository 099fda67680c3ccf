//! The CLI's value lists are the library's vocabulary types: `--help` lists exactly their
//! `ALL` words, in order, and a bad word is refused (exit code 2) with the valid ones.

mod common;

use common::shatter;
use shatter_geom::fracture::{MethodKind, Pattern, Placement};
use shatter_geom::shapes::Shape;
use shatter_sim::BondModel;

/// The words clap lists under "Possible values" for `flag` in `help`.
fn possible_values(help: &str, flag: &str) -> Vec<String> {
    let mut lines = help
        .lines()
        .skip_while(|l| !l.trim_start().starts_with(flag))
        .skip(1);
    let mut words = Vec::new();
    for line in lines.by_ref() {
        let t = line.trim();
        if t.starts_with("--") || (t.starts_with('[') && !words.is_empty()) {
            break;
        }
        if let Some(rest) = t.strip_prefix("- ") {
            words.push(rest.split(':').next().unwrap_or("").trim().to_string());
        }
    }
    words
}

fn help(args: &[&str]) -> String {
    let dir = tempfile::tempdir().expect("temp dir");
    let run = shatter(dir.path(), args).ok();
    run.stdout
}

#[test]
fn fracture_help_lists_exactly_the_vocabulary() {
    let h = help(&["fracture", "--help"]);
    assert_eq!(possible_values(&h, "--method"), MethodKind::NAMES, "{h}");
    assert_eq!(possible_values(&h, "--pattern"), Pattern::NAMES, "{h}");
    assert_eq!(possible_values(&h, "--placement"), Placement::NAMES, "{h}");
    assert_eq!(possible_values(&h, "--shape"), Shape::NAMES, "{h}");
}

#[test]
fn simulate_help_lists_the_bond_models() {
    let h = help(&["simulate", "--help"]);
    assert_eq!(possible_values(&h, "--bonds"), BondModel::NAMES, "{h}");
}

#[test]
fn a_bad_method_is_refused_with_the_valid_words() {
    let dir = tempfile::tempdir().expect("temp dir");
    let run = shatter(
        dir.path(),
        &["fracture", "--shape", "cube", "--method", "shred"],
    );
    assert_eq!(run.code, 2, "{}", run.stderr);
    for word in MethodKind::NAMES {
        assert!(run.stderr.contains(word), "{word} missing: {}", run.stderr);
    }
}

#[test]
fn grid_cuts_the_scaled_cube_into_its_cells() {
    let dir = tempfile::tempdir().expect("temp dir");
    let run = shatter(
        dir.path(),
        &[
            "fracture", "--shape", "cube", "--scale", "2,1,0.5", "--method", "grid", "--grid",
            "4,2,1", "--json",
        ],
    )
    .ok();
    let j = run.json();
    assert_eq!(j["fragments"], 8);
    // 3·2 faces across x, 4·1 across y.
    assert_eq!(j["bonds"], 10);
    let v = j["fragments_volume"].as_f64().expect("a number");
    assert!((v - 1.0).abs() < 1e-9, "volume {v}");
}

#[test]
fn grid_cuts_any_mesh_into_cells_and_its_flag_needs_the_method() {
    let dir = tempfile::tempdir().expect("temp dir");
    let run = shatter(
        dir.path(),
        &[
            "fracture", "--shape", "sphere", "--method", "grid", "--grid", "3,3,3", "--json",
        ],
    );
    let j = run.json();
    // The sphere's box in 27 cells, its corners cut away: fewer fragments than cells.
    let n = j["fragments"].as_u64().expect("a count");
    assert!((8..=27).contains(&n), "{n} fragments");
    let (a, b) = (
        j["mesh_volume"].as_f64().expect("a number"),
        j["fragments_volume"].as_f64().expect("a number"),
    );
    assert!((a - b).abs() < 1e-9 * a, "volumes {a} and {b}");
    shatter(
        dir.path(),
        &["fracture", "--shape", "cube", "--grid", "2,2,2"],
    )
    .bad_input(&["--grid applies to --method grid"]);
    shatter(
        dir.path(),
        &[
            "fracture", "--shape", "cube", "--method", "grid", "--grid", "0,2,2",
        ],
    )
    .bad_input(&["--grid"]);
}
