//! Every model of the corpus (`tests/corpus/`: real public models, see its `SOURCES.md`)
//! is repaired and fractured by every method (tetra, voronoi, slice, grid), and the
//! fragments are checked here, by code independent of the fracture's own validation:
//! - each is a closed 2-manifold (on welded positions every directed edge occurs once
//!   and so does its reverse);
//! - they do not overlap, and leave no gap: sampled points inside the repaired solid are
//!   inside exactly one fragment, points outside in none (generalized winding numbers
//!   computed in this test);
//! - their volumes add up to the repaired solid's (relative 1e-6);
//! - every fragment has UVs, one per corner, finite;
//! - interior UVs agree across every bond where the two sides' caps face each other.
//!
//! A file is found by walking the corpus folder, so a model added there is tested too;
//! files refused on loading or holding no solid must be the ones listed (with their
//! messages) in `support/corpus.rs`.
#![allow(clippy::unwrap_used)]

mod support;

use shatter_geom::fracture::{self, FractureParams, Method, Placement, Seeds};
use shatter_geom::io;
use shatter_geom::mesh::repair::{RepairError, RepairOptions, repair};
use support::corpus::{NO_SOLID, REFUSED, corpus, mesh_files};

/// Slow cases, left out unless `CORPUS_SLOW=1` is set, with what they cost. The tetra
/// method clips every tetrahedron the surface enters, and a dense surface makes nearly
/// all of them such: its time grows with the surface's vertices well beyond the other
/// methods'.
const SLOW: &[(&str, &str, &str)] = &[
    (
        "gltf/engine/2CylinderEngine.glb",
        "tetra",
        "tetra on the engine's 87,000 surface vertices: about 5 minutes in release, 11 \
         with this test's checks (8,037 fragments, 20,531 bonds); passes every check",
    ),
    (
        "obj/regr01.obj",
        "tetra",
        "60 s in release with this test's checks",
    ),
    (
        "stl/bunny.bin.stl",
        "tetra",
        "tetra on 34,834 surface vertices: 25 s in release with this test's checks",
    ),
];

/// Whether the case is left out of this run.
fn left_out(file: &str, method: &str) -> bool {
    std::env::var("CORPUS_SLOW").is_err() && SLOW.iter().any(|(f, m, _)| *f == file && *m == method)
}

/// The methods, sized for a test: 12 Voronoi cells, 6 slices, a 3×3×3 grid, and tetra on
/// the surface's vertices plus 20 inside (every surface vertex: with some skipped, tetra
/// fills only the points' hull, by design, and the volumes would not add up).
fn methods() -> Vec<(&'static str, Method)> {
    vec![
        (
            "voronoi",
            Method::Voronoi {
                seeds: Seeds::count(12),
            },
        ),
        (
            "slice",
            Method::Slice {
                pieces: 6,
                planes: None,
            },
        ),
        (
            "grid",
            Method::Grid {
                cells: [3, 3, 3],
                voids: Vec::new(),
            },
        ),
        (
            "tetra",
            Method::Tetra {
                random_vertices: 20,
                skip: 0,
                center: false,
                placement: Placement::Interior,
            },
        ),
    ]
}

#[test]
fn every_corpus_model_fractures_by_every_method_into_checked_fragments() {
    let files = mesh_files();
    assert!(
        files.len() >= 15,
        "the corpus has {} mesh files",
        files.len()
    );
    let mut fractured = 0;
    // `CORPUS_FILE=part-of-a-path cargo test …` runs the files whose path contains it.
    let only = std::env::var("CORPUS_FILE").ok();
    for file in &files {
        if only.as_ref().is_some_and(|o| !file.contains(o.as_str())) {
            continue;
        }
        let loaded = match io::load_model(corpus(file)) {
            Ok(loaded) => loaded,
            Err(err) => {
                let (_, want) = REFUSED
                    .iter()
                    .find(|(f, _)| f == file)
                    .unwrap_or_else(|| panic!("{file}: refused unexpectedly: {err}"));
                assert!(err.to_string().contains(want), "{file}: {err}");
                continue;
            }
        };
        let (model, report) = match repair(&loaded.model, &RepairOptions::default()) {
            Ok(done) => done,
            Err(RepairError::NoSolid { found }) => {
                let (_, want) = NO_SOLID
                    .iter()
                    .find(|(f, _)| f == file)
                    .unwrap_or_else(|| panic!("{file}: no solid unexpectedly: {found}"));
                assert!(found.contains(want), "{file}: {found}");
                continue;
            }
            Err(err) => panic!("{file}: repair failed: {err}"),
        };
        assert!(
            !NO_SOLID.iter().any(|(f, _)| f == file),
            "{file}: listed as holding no solid, but repaired into one"
        );
        let solid = model.mesh.volume();
        assert!(
            (solid - report.volume).abs() <= 1e-9 * solid,
            "{file}: the report's volume {} is not the result's {solid}",
            report.volume
        );
        for (name, method) in methods() {
            if left_out(file, name) {
                continue;
            }
            let started = std::time::Instant::now();
            let what = format!("{file} by {name}");
            let params = FractureParams { method, seed: 1 };
            let fr = fracture::fracture_model(&model, &params)
                .unwrap_or_else(|err| panic!("{what}: {err}"));
            assert!(fr.fragments.len() >= 2, "{what}: one fragment");
            let total: f64 = fr.fragments.iter().map(|f| f.mesh.volume()).sum();
            assert!(
                (total - solid).abs() <= 1e-6 * solid,
                "{what}: fragments {total}, solid {solid}"
            );
            for (i, f) in fr.fragments.iter().enumerate() {
                if let Some(defect) = support::closed_defect(&f.mesh) {
                    panic!("{what}: fragment {i} is not closed: {defect}");
                }
                let uv = f
                    .corners
                    .uv
                    .as_ref()
                    .unwrap_or_else(|| panic!("{what}: fragment {i} has no UVs"));
                assert_eq!(uv.len(), f.mesh.triangles.len(), "{what}: fragment {i}");
                assert!(
                    uv.iter().flatten().flatten().all(|x| x.is_finite()),
                    "{what}: fragment {i} has a non-finite UV"
                );
            }
            let (lo, hi) = model.mesh.bounds().unwrap();
            let eps = 1e-9 * (hi - lo).length();
            let (compared, bonds) = support::interior_uvs_agree(&fr, eps, 1e-4, &what);
            assert!(
                fr.bonds.is_empty() || compared > 0,
                "{what}: no cap compared across {} bonds",
                fr.bonds.len()
            );
            let inside = support::no_overlap_no_gap(&model.mesh, &fr, 100, &what);
            eprintln!(
                "{what}: {} fragments, {} bonds ({bonds} with caps compared), {inside} \
                 sampled points inside ({:.1?})",
                fr.fragments.len(),
                fr.bonds.len(),
                started.elapsed()
            );
        }
        fractured += 1;
    }
    if only.is_none() {
        assert!(fractured >= 12, "only {fractured} corpus models fractured");
    }
}
