//! `shatter fracture --out X.glb` writes a pre-fractured asset (the `SHATTER_fracture`
//! extension) that reads back with the counts and bonds the JSON report printed, that
//! the `gltf` crate still opens, and that `shatter inspect` describes.
#![allow(clippy::unwrap_used)]

mod common;

use common::shatter;
use shatter_geom::io;

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-9 * a.abs().max(b.abs())
}

#[test]
fn the_glb_reads_back_with_the_bonds_the_json_printed() {
    let dir = tempfile::tempdir().unwrap();
    let json = shatter(
        dir.path(),
        &[
            "fracture",
            "--shape",
            "bird",
            "--pieces",
            "30",
            "--seed",
            "3",
            "--out",
            "bird.glb",
            "--json",
            "--json-bonds",
            "--material",
            "stone",
            "--anchor",
            "lowest",
        ],
    )
    .ok()
    .json();
    let path = dir.path().join("bird.glb");
    let (fracture, meta) = io::read_fracture(&path).unwrap();
    assert_eq!(
        fracture.fragments.len() as u64,
        json["fragments"].as_u64().unwrap()
    );
    assert_eq!(fracture.bonds.len() as u64, json["bonds"].as_u64().unwrap());
    let list = json["bond_list"].as_array().unwrap();
    assert_eq!(list.len(), fracture.bonds.len());
    for (printed, read) in list.iter().zip(&fracture.bonds) {
        assert_eq!(printed["a"].as_u64(), Some(u64::from(read.a)));
        assert_eq!(printed["b"].as_u64(), Some(u64::from(read.b)));
        assert!(
            close(printed["area"].as_f64().unwrap(), read.area),
            "{printed}"
        );
        for k in 0..3 {
            let c = printed["centroid"][k].as_f64().unwrap();
            assert!(
                (c - read.centroid[k]).abs() <= 1e-9 * c.abs().max(1.0),
                "{printed}"
            );
        }
    }
    let volume: f64 = fracture.fragments.iter().map(|f| f.volume).sum();
    assert!(close(volume, json["fragments_volume"].as_f64().unwrap()));
    // The collision shapes travel with the asset (an OBJ has none, and gets none made).
    for (i, f) in fracture.fragments.iter().enumerate() {
        assert!(!f.convex_pieces.is_empty(), "fragment {i}: no convex piece");
    }
    // The material preset and its thresholds, and the lowest fragments as anchors.
    assert_eq!(meta.material.as_deref(), Some("stone"));
    let t = meta.thresholds.unwrap();
    assert_eq!((t.strength, t.tension, t.wear), (20_000.0, 6e6, 0.2));
    assert!(!meta.anchors.is_empty() && meta.anchors.len() < fracture.fragments.len());
    assert_eq!(meta.anchors, fracture.lowest_fragments());
    // Still an ordinary glTF: one node per fragment, the extension only "used".
    let doc = gltf::Gltf::open(&path).unwrap();
    assert_eq!(doc.nodes().count(), fracture.fragments.len());
    assert_eq!(doc.extensions_required().count(), 0);
    assert!(doc.extensions_used().any(|e| e == "SHATTER_fracture"));
    // And a mesh file shatter itself reads (and could fracture again).
    shatter(dir.path(), &["fracture", "bird.glb", "--pieces", "4"]).ok();
}

#[test]
fn the_obj_the_glb_and_no_file_report_the_same_fracture() {
    // Only the GLB gets convex pieces made; the fragments are the same without.
    let dir = tempfile::tempdir().unwrap();
    let run = |out: Option<&str>| {
        let mut args = vec![
            "fracture", "--shape", "bird", "--pieces", "25", "--seed", "8",
        ];
        if let Some(out) = out {
            args.extend(["--out", out]);
        }
        args.extend(["--json", "--json-bonds"]);
        let mut json = shatter(dir.path(), &args).ok().json();
        let map = json.as_object_mut().unwrap();
        for key in ["millis", "peak_rss_bytes", "estimate"] {
            map.remove(key);
        }
        json
    };
    let glb = run(Some("bird.glb"));
    assert!(glb["fragments"].as_u64().unwrap() > 10, "{glb}");
    assert_eq!(run(Some("bird.obj")), glb);
    assert_eq!(run(None), glb);
}

#[test]
fn without_options_the_glb_has_no_anchors_and_no_material() {
    let dir = tempfile::tempdir().unwrap();
    shatter(
        dir.path(),
        &["fracture", "--shape", "cube", "--out", "cube.glb"],
    )
    .ok();
    let (fracture, meta) = io::read_fracture(dir.path().join("cube.glb")).unwrap();
    assert!(fracture.fragments.len() > 1);
    assert_eq!(meta, io::FractureAssetMeta::default());
}

#[test]
fn inspect_reports_the_extension() {
    let dir = tempfile::tempdir().unwrap();
    let json = shatter(
        dir.path(),
        &[
            "fracture",
            "--shape",
            "cube",
            "--pieces",
            "6",
            "--out",
            "c.glb",
            "--json",
            "--material",
            "glass",
        ],
    )
    .ok()
    .json();
    let (fragments, bonds) = (
        json["fragments"].as_u64().unwrap(),
        json["bonds"].as_u64().unwrap(),
    );
    let text = shatter(dir.path(), &["inspect", "c.glb"]).ok().stdout;
    let line = format!(
        "SHATTER_fracture: {fragments} fragments, {bonds} bonds, 0 anchored, material glass"
    );
    assert!(text.contains(&line), "{text}");
    let report = shatter(dir.path(), &["inspect", "c.glb", "--json"])
        .ok()
        .json();
    assert_eq!(
        report["shatter_fracture"]["fragments"].as_u64(),
        Some(fragments)
    );
    assert_eq!(report["shatter_fracture"]["bonds"].as_u64(), Some(bonds));
    // A plain mesh file has no such line.
    shatter(dir.path(), &["shape", "cube", "--out", "plain.glb"]).ok();
    let text = shatter(dir.path(), &["inspect", "plain.glb"]).ok().stdout;
    assert!(!text.contains("SHATTER_fracture"), "{text}");
    // A malformed extension is described, not a failure of inspect.
    let mut bytes = std::fs::read(dir.path().join("c.glb")).unwrap();
    let at = bytes
        .windows(11)
        .position(|w| w == b"\"version\":1")
        .unwrap();
    bytes[at + 10] = b'7';
    std::fs::write(dir.path().join("bad.glb"), bytes).unwrap();
    let text = shatter(dir.path(), &["inspect", "bad.glb"]).ok().stdout;
    assert!(
        text.contains("SHATTER_fracture: unreadable") && text.contains("version 7"),
        "{text}"
    );
}

#[test]
fn asset_options_are_refused_where_they_cannot_apply() {
    let dir = tempfile::tempdir().unwrap();
    let base = ["fracture", "--shape", "cube"];
    let run = |extra: &[&str]| {
        let args: Vec<&str> = base.iter().chain(extra).copied().collect();
        shatter(dir.path(), &args)
    };
    run(&["--out", "c.glb", "--material", "cheese"]).bad_input(&["--material cheese", "stone"]);
    run(&["--out", "c.obj", "--material", "stone"]).bad_input(&["--out FILE.glb"]);
    run(&["--anchor", "lowest"]).bad_input(&["--out FILE.glb"]);
    run(&["--out", "c.glb", "--anchor", "highest"]).bad_input(&["highest"]);
    assert!(!dir.path().join("c.glb").exists() && !dir.path().join("c.obj").exists());
}
