//! `shatter fracture --json --json-bonds`: the bond list in the JSON report (the Blender
//! add-on builds its rigid-body constraints from it).
#![allow(clippy::unwrap_used)]

mod common;

use common::shatter;

#[test]
fn two_seeds_in_the_cube_give_one_bond_across_the_bisector() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("seeds.xyz"), "-0.25 0 0\n0.25 0 0\n").unwrap();
    let json = shatter(
        dir.path(),
        &[
            "fracture",
            "--shape",
            "cube",
            "--seeds-file",
            "seeds.xyz",
            "--json",
            "--json-bonds",
        ],
    )
    .ok()
    .json();
    assert_eq!(json["fragments"], 2);
    let list = json["bond_list"].as_array().unwrap();
    assert_eq!(list.len(), 1, "{list:?}");
    let bond = &list[0];
    assert_eq!((bond["a"].as_u64(), bond["b"].as_u64()), (Some(0), Some(1)));
    // The unit cube's cross-section at x = 0: area 1, centred on the origin.
    assert!(
        (bond["area"].as_f64().unwrap() - 1.0).abs() < 1e-9,
        "{bond}"
    );
    let v = |key: &str| -> Vec<f64> {
        bond[key]
            .as_array()
            .unwrap()
            .iter()
            .map(|c| c.as_f64().unwrap())
            .collect()
    };
    let centroid = v("centroid");
    assert!(centroid.iter().all(|c| c.abs() < 1e-9), "{centroid:?}");
    // From fragment 0 (the seed at -x) to fragment 1 (+x), if the fragments keep the
    // seeds' order; either way the normal is ±x.
    let normal = v("normal");
    assert!(
        (normal[0].abs() - 1.0).abs() < 1e-9 && normal[1].abs() < 1e-9 && normal[2].abs() < 1e-9
    );
}

#[test]
fn bond_list_matches_the_bond_count_and_names_valid_fragments() {
    let dir = tempfile::tempdir().unwrap();
    let json = shatter(
        dir.path(),
        &[
            "fracture",
            "--shape",
            "bird",
            "--pieces",
            "25",
            "--json",
            "--json-bonds",
        ],
    )
    .ok()
    .json();
    let fragments = json["fragments"].as_u64().unwrap();
    let list = json["bond_list"].as_array().unwrap();
    assert_eq!(list.len() as u64, json["bonds"].as_u64().unwrap());
    for bond in list {
        let (a, b) = (bond["a"].as_u64().unwrap(), bond["b"].as_u64().unwrap());
        assert!(a < b && b < fragments, "{bond}");
        assert!(bond["area"].as_f64().unwrap() > 0.0, "{bond}");
        let n: f64 = bond["normal"]
            .as_array()
            .unwrap()
            .iter()
            .map(|c| c.as_f64().unwrap().powi(2))
            .sum();
        assert!((n - 1.0).abs() < 1e-9, "{bond}");
    }
}

#[test]
fn bond_list_only_with_the_flag_and_only_with_json() {
    let dir = tempfile::tempdir().unwrap();
    let json = shatter(dir.path(), &["fracture", "--shape", "cube", "--json"])
        .ok()
        .json();
    assert!(json.get("bond_list").is_none(), "{json}");
    shatter(dir.path(), &["fracture", "--shape", "cube", "--json-bonds"])
        .bad_input(&["--json-bonds", "--json"]);
}
