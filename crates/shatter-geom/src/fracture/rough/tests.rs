//! Edge cases of the roughness post-pass (the invariants on whole fractures are in
//! `tests/fracture_rough.rs`).

use super::*;
use crate::fracture::{FractureParams, Method, fracture};
use crate::shapes;

fn voronoi(pieces: usize, seed: u64) -> FractureParams {
    FractureParams::voronoi(pieces, seed)
}

#[test]
fn bad_values_are_refused_by_name() {
    let cases = [
        (
            Roughness {
                amplitude: -1.0,
                ..Roughness::STONE
            },
            "amplitude",
        ),
        (
            Roughness {
                amplitude: f64::NAN,
                ..Roughness::STONE
            },
            "amplitude",
        ),
        (
            Roughness {
                frequency: 0.0,
                ..Roughness::STONE
            },
            "frequency",
        ),
        (
            Roughness {
                frequency: f64::INFINITY,
                ..Roughness::STONE
            },
            "frequency",
        ),
        (
            Roughness {
                octaves: 0,
                ..Roughness::STONE
            },
            "octaves",
        ),
        (
            Roughness {
                octaves: 9,
                ..Roughness::STONE
            },
            "octaves",
        ),
    ];
    let mut fr = fracture(&shapes::cube(), &voronoi(4, 1)).unwrap();
    for (r, name) in cases {
        match roughen(&mut fr, &r) {
            Err(FractureError::BadRoughness { field, .. }) => assert_eq!(field, name),
            other => panic!("{r:?}: {other:?}"),
        }
    }
}

#[test]
fn off_leaves_the_fracture_as_it_was() {
    let fr = fracture(&shapes::cube(), &voronoi(6, 2)).unwrap();
    let mut same = fr.clone();
    assert_eq!(
        roughen(&mut same, &Roughness::GLASS).unwrap(),
        RoughReport::default()
    );
    assert_eq!(same, fr);
}

#[test]
fn a_slice_in_two_gets_one_rough_cap_shared_by_both_halves() {
    let params = FractureParams {
        method: Method::Slice {
            pieces: 0,
            planes: Some(vec![(glam::DVec3::ZERO, glam::DVec3::X)]),
        },
        seed: 0,
    };
    let mut fr = fracture(&shapes::cube(), &params).unwrap();
    let r = Roughness {
        amplitude: 0.05,
        frequency: 4.0,
        octaves: 3,
        seed: 9,
    };
    let report = roughen(&mut fr, &r).unwrap();
    assert_eq!(report.caps, 1, "{report:?}");
    assert!(report.max_displacement > 0.01, "{report:?}");
    assert!((fr.total_volume() - 1.0).abs() < 1e-12);
    // The interior vertices off the plane x = 0 are the same points on both sides.
    let off = |f: &Fragment| {
        let mut v: Vec<[u64; 3]> = f
            .mesh
            .positions
            .iter()
            .filter(|p| p.x.abs() > 1e-6 && p.x.abs() < 0.2)
            .map(|p| crate::mesh::position_key(*p))
            .collect();
        v.sort_unstable();
        v
    };
    assert!(!off(&fr.fragments[0]).is_empty());
    assert_eq!(off(&fr.fragments[0]), off(&fr.fragments[1]));
    fr.validate(Some(1.0)).unwrap();
}

#[test]
fn a_malformed_fragment_is_refused_not_a_panic() {
    let good = fracture(&shapes::cube(), &voronoi(4, 1)).unwrap();
    type Breakage = (&'static str, fn(&mut Fragment));
    let breakages: [Breakage; 4] = [
        ("index", |f| f.mesh.triangles[0][0] = 1 << 30),
        ("flags", |f| {
            f.interior.pop();
        }),
        ("nan", |f| f.mesh.positions[0].x = f64::NAN),
        ("uv", |f| f.corners.uv = Some(vec![[[0.0; 2]; 3]])),
    ];
    for (what, broken) in breakages {
        let mut fr = good.clone();
        broken(&mut fr.fragments[1]);
        let err = roughen(&mut fr, &Roughness::STONE).unwrap_err();
        assert!(
            matches!(err, FractureError::BadFragment { fragment: 1, .. }),
            "{what}: {err}"
        );
    }
}

#[test]
fn the_result_does_not_depend_on_the_threads() {
    let fr = fracture(&shapes::bird(), &voronoi(20, 4)).unwrap();
    let r = Roughness {
        amplitude: 0.05,
        frequency: 2.0,
        ..Roughness::STONE
    };
    let run = || {
        let mut out = fr.clone();
        let report = roughen(&mut out, &r).unwrap();
        (out, report)
    };
    let one = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap()
        .install(run);
    let many = rayon::ThreadPoolBuilder::new()
        .num_threads(4)
        .build()
        .unwrap()
        .install(run);
    assert!(one.1.caps > 0);
    assert_eq!(one, many);
}

#[test]
fn roughness_reads_from_json_with_defaults_and_refuses_unknown_fields() {
    let r: Roughness = serde_json::from_str(r#"{"amplitude": 0.01, "seed": 3}"#).unwrap();
    assert_eq!(
        r,
        Roughness {
            amplitude: 0.01,
            seed: 3,
            ..Roughness::OFF
        }
    );
    assert!(serde_json::from_str::<Roughness>(r#"{"amplitud": 0.01}"#).is_err());
    let back: Roughness =
        serde_json::from_str(&serde_json::to_string(&Roughness::STONE).unwrap()).unwrap();
    assert_eq!(back, Roughness::STONE);
}
