//! ARCHITECTURE.md's crate table against `cargo metadata`: every workspace crate has a row
//! and every row a crate, each row's "Depends on" names exactly the workspace crates it
//! depends on, and every other name there is a real dependency. (It lives in the lab, the
//! lightest crate that already has serde_json.)

#![allow(clippy::unwrap_used)]

use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

fn root() -> &'static Path {
    Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."))
}

/// Per workspace crate (by its folder, `crates/NAME`): its package name and the names of
/// its normal (not dev, not build) dependencies.
fn metadata() -> BTreeMap<String, (String, BTreeSet<String>)> {
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
    let out = std::process::Command::new(cargo)
        .args([
            "metadata",
            "--format-version",
            "1",
            "--no-deps",
            "--offline",
        ])
        .current_dir(root())
        .output()
        .expect("run cargo metadata");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let root = std::fs::canonicalize(root()).unwrap();
    let mut crates = BTreeMap::new();
    for p in json["packages"].as_array().unwrap() {
        let manifest = Path::new(p["manifest_path"].as_str().unwrap());
        let dir = manifest.parent().unwrap().strip_prefix(&root).unwrap();
        let deps = p["dependencies"]
            .as_array()
            .unwrap()
            .iter()
            .filter(|d| d["kind"].is_null())
            .map(|d| d["name"].as_str().unwrap().replace('_', "-"))
            .collect();
        crates.insert(
            dir.to_string_lossy().into_owned(),
            (p["name"].as_str().unwrap().replace('_', "-"), deps),
        );
    }
    crates
}

/// The table's rows: crate folder → the names in its "Depends on" column (parenthetical
/// remarks dropped).
fn table() -> BTreeMap<String, BTreeSet<String>> {
    let text = std::fs::read_to_string(root().join("ARCHITECTURE.md")).unwrap();
    let mut rows = BTreeMap::new();
    for line in text.lines().filter(|l| l.starts_with("| `crates/")) {
        let cells: Vec<&str> = line.trim_matches('|').split('|').map(str::trim).collect();
        let dir = cells[0].trim_matches('`').to_string();
        let deps = cells.last().unwrap();
        // Drop "(...)" remarks, which may hold commas.
        let mut plain = String::new();
        let mut depth = 0;
        for c in deps.chars() {
            match c {
                '(' => depth += 1,
                ')' => depth -= 1,
                _ if depth == 0 => plain.push(c),
                _ => {}
            }
        }
        let names = plain
            .split(',')
            .map(|s| s.trim().trim_matches('`').replace('_', "-"))
            .filter(|s| !s.is_empty() && s != "—" && s != "-")
            .collect();
        rows.insert(dir, names);
    }
    rows
}

#[test]
fn architecture_lists_every_crate_and_its_workspace_dependencies() {
    let crates = metadata();
    let rows = table();
    let in_table: BTreeSet<&String> = rows.keys().collect();
    let in_cargo: BTreeSet<&String> = crates.keys().collect();
    assert_eq!(
        in_table, in_cargo,
        "ARCHITECTURE.md's crate table against the workspace"
    );
    let workspace: BTreeSet<&String> = crates.values().map(|(name, _)| name).collect();
    for (dir, (name, deps)) in &crates {
        let listed = &rows[dir];
        let internal_real: BTreeSet<&String> =
            deps.iter().filter(|d| workspace.contains(d)).collect();
        let internal_listed: BTreeSet<&String> =
            listed.iter().filter(|d| workspace.contains(d)).collect();
        assert_eq!(
            internal_listed, internal_real,
            "{name}: the workspace crates its row names against its Cargo.toml"
        );
        for d in listed {
            assert!(
                deps.contains(d),
                "{name}: ARCHITECTURE.md names `{d}`, which is not one of its dependencies"
            );
        }
    }
}
