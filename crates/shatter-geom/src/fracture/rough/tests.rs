//! Edge cases of the roughness post-pass (the invariants on whole fractures are in
//! `tests/fracture_rough.rs`).

use super::*;
use crate::fracture::{FractureParams, Method, Pattern, fracture};
use crate::shapes;

fn voronoi(pieces: usize, seed: u64) -> FractureParams {
    FractureParams {
        method: Method::Voronoi {
            pieces,
            pattern: Pattern::Uniform,
            impact: None,
            seeds: None,
        },
        seed,
    }
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
