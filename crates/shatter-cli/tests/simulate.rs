//! `shatter simulate` and `shatter bench step`, end to end through the real binary.
#![allow(clippy::unwrap_used)]

mod common;

use std::path::PathBuf;

use common::shatter;

fn scene(name: &str) -> String {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../assets/scenes");
    root.join(name).to_string_lossy().into_owned()
}

#[test]
fn explosion_scene_breaks_bonds_and_repeats_its_digest() {
    let dir = tempfile::tempdir().unwrap();
    let path = scene("explosion.toml");
    let args = ["simulate", path.as_str(), "--seconds", "1.5", "--json"];
    let first = shatter(dir.path(), &args).ok().json();
    let second = shatter(dir.path(), &args).ok().json();
    assert_eq!(first["steps"], 90);
    assert!(first["bonds_total"].as_u64().unwrap() > 0);
    // The explosion at t = 1 s blows the corner off the block.
    assert!(
        first["bonds_broken"].as_u64().unwrap() > 0,
        "no bond broke: {first}"
    );
    assert!(first["bodies"].as_u64().unwrap() > 1, "{first}");
    assert_eq!(first["digest"], second["digest"], "same scene, same digest");
}

#[test]
fn the_bridge_reports_the_bonds_its_stress_broke() {
    let dir = tempfile::tempdir().unwrap();
    let path = scene("bridge.toml");
    let json = shatter(
        dir.path(),
        &["simulate", path.as_str(), "--seconds", "2", "--json"],
    )
    .ok()
    .json();
    let n = |k: &str| {
        json[k]
            .as_u64()
            .unwrap_or_else(|| panic!("{k} missing: {json}"))
    };
    assert!(n("bonds_broken_by_stress") > 0, "{json}");
    assert!(
        n("bonds_broken_by_impact") > 0,
        "the blast breaks bonds: {json}"
    );
    assert_eq!(
        n("bonds_broken"),
        n("bonds_broken_by_impact") + n("bonds_broken_by_stress") + n("bonds_broken_by_damage")
    );
}

#[test]
fn the_runtime_scene_reports_its_cuts_and_their_depth() {
    let dir = tempfile::tempdir().unwrap();
    let path = scene("runtime.toml");
    let json = shatter(
        dir.path(),
        &["simulate", path.as_str(), "--seconds", "2.5", "--json"],
    )
    .ok()
    .json();
    // The bird and the pane are each cut once by their ball; the bird's loose pieces may
    // be cut again (depth 2), never deeper.
    assert!(json["runtime_fractures"].as_u64().unwrap() >= 2, "{json}");
    let depth = json["max_depth"].as_u64().unwrap();
    assert!((1..=2).contains(&depth), "{json}");
    let health = json["min_bond_health"].as_f64().unwrap();
    assert!((0.0..=1.0).contains(&health), "{json}");
    assert!(json["bonds_damaged"].as_u64().is_some(), "{json}");
}

/// bench scale's 2,000-brick landing as a scene: a block of 13 × 13 × 12 weakly bonded
/// bricks dropped from 4 m, with the `[world]` line `extra`.
fn landing_scene(dir: &std::path::Path, extra: &str) -> String {
    let path = dir.join(format!("landing{}.toml", extra.len()));
    std::fs::write(
        &path,
        format!(
            "[world]\nbond_model = \"clusters\"\n{extra}\n\n[[objects]]\nshape = \"cube\"\n\
             method = \"grid\"\ngrid = [13, 13, 12]\nbreak_force = 2000.0\n\
             position = [0.0, 4.6, 0.0]\nscale = [1.3, 1.3, 1.2]\n"
        ),
    )
    .unwrap();
    path.to_string_lossy().into_owned()
}

#[test]
fn the_landing_reports_the_bodies_the_speed_cap_slowed() {
    let dir = tempfile::tempdir().unwrap();
    let capped = |extra: &str| {
        let path = landing_scene(dir.path(), extra);
        let json = shatter(
            dir.path(),
            &["simulate", path.as_str(), "--seconds", "2", "--json"],
        )
        .ok()
        .json();
        assert!(json["bonds_broken"].as_u64().unwrap() > 1_000, "{json}");
        json["speeds_capped"]
            .as_u64()
            .unwrap_or_else(|| panic!("speeds_capped missing: {json}"))
    };
    // On by default: bricks squeezed under the landing block are slowed.
    assert!(capped("") > 0);
    assert_eq!(capped("contact_speed_cap = false"), 0);
}

#[test]
fn before_the_explosion_nothing_breaks() {
    let dir = tempfile::tempdir().unwrap();
    let path = scene("explosion.toml");
    let json = shatter(
        dir.path(),
        &["simulate", path.as_str(), "--seconds", "0.5", "--json"],
    )
    .ok()
    .json();
    assert_eq!(json["bonds_broken"], 0, "{json}");
}

#[test]
fn bad_scenes_exit_2_naming_the_problem() {
    let dir = tempfile::tempdir().unwrap();
    shatter(dir.path(), &["simulate", "missing.toml"]).bad_input(&["missing.toml"]);

    std::fs::write(
        dir.path().join("cheese.toml"),
        "[[objects]]\nshape = \"cube\"\nmaterial = \"cheese\"\n",
    )
    .unwrap();
    shatter(dir.path(), &["simulate", "cheese.toml"]).bad_input(&["material", "cheese"]);

    std::fs::write(dir.path().join("typo.toml"), "[world]\ngravty = -9.81\n").unwrap();
    shatter(dir.path(), &["simulate", "typo.toml"]).bad_input(&["gravty", "line 2"]);
}
