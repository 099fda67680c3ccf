//! Invariants of the Delaunay tetrahedralization on random and degenerate point sets.
#![allow(clippy::unwrap_used)]

use proptest::prelude::*;
use shatter_geom::DVec3;
use shatter_geom::delaunay::{DelaunayError, Tetrahedralization, orient, tetrahedralize};
use shatter_geom::sampling::{Distribution, sample};

/// Volume enclosed by the outward hull triangles (divergence theorem), computed
/// independently of the tetrahedra.
fn hull_volume(t: &Tetrahedralization, p: &[DVec3]) -> f64 {
    // Relative to a point near the set, so that large offsets do not cancel.
    let o = p[0];
    t.hull_faces()
        .iter()
        .map(|f| {
            let (a, b, c) = (
                p[f[0] as usize] - o,
                p[f[1] as usize] - o,
                p[f[2] as usize] - o,
            );
            a.dot(b.cross(c)) / 6.0
        })
        .sum()
}

/// Full check: the exact invariants, plus volumes adding up to the hull volume.
fn check(p: &[DVec3]) -> Tetrahedralization {
    let t = tetrahedralize(p).unwrap();
    t.validate(p).unwrap();
    let v = t.volume(p);
    let h = hull_volume(&t, p);
    assert!(v > 0.0);
    assert!((v - h).abs() <= 1e-9 * h.abs(), "volume {v} vs hull {h}");
    t
}

fn bbox_volume(p: &[DVec3]) -> f64 {
    let lo = p.iter().fold(DVec3::splat(f64::INFINITY), |a, b| a.min(*b));
    let hi = p
        .iter()
        .fold(DVec3::splat(f64::NEG_INFINITY), |a, b| a.max(*b));
    (hi - lo).element_product()
}

fn grid(k: usize) -> Vec<DVec3> {
    let mut p = Vec::new();
    for x in 0..k {
        for y in 0..k {
            for z in 0..k {
                p.push(DVec3::new(x as f64, y as f64, z as f64));
            }
        }
    }
    p
}

#[test]
fn random_distributions() {
    for d in Distribution::ALL {
        for seed in 0..3 {
            let p = sample(d, 2000, seed);
            let t = check(&p);
            assert_eq!(t.unique_points, 2000, "{d:?}");
        }
    }
}

#[test]
fn grid_10x10x10_fills_the_box() {
    let p = grid(10);
    let t = check(&p);
    assert_eq!(t.unique_points, 1000);
    assert!((t.volume(&p) - 729.0).abs() < 1e-9);
    assert!((bbox_volume(&p) - 729.0).abs() < 1e-9);
}

#[test]
fn points_on_a_sphere() {
    let p = sample(Distribution::Sphere, 3000, 11);
    let t = check(&p);
    // Every point is on the hull.
    let mut on_hull = vec![false; p.len()];
    for f in t.hull_faces() {
        for v in f {
            on_hull[v as usize] = true;
        }
    }
    assert!(on_hull.iter().all(|&b| b));
}

#[test]
fn exactly_cospherical_points() {
    // Integer points with x² + y² + z² = 25 or 0: cospherical in exact arithmetic.
    let mut p = Vec::new();
    for x in -5i32..=5 {
        for y in -5i32..=5 {
            for z in -5i32..=5 {
                if x * x + y * y + z * z == 25 {
                    p.push(DVec3::new(x as f64, y as f64, z as f64));
                }
            }
        }
    }
    p.push(DVec3::ZERO);
    check(&p);
}

#[test]
fn coplanar_layers() {
    let mut p = Vec::new();
    let pts = sample(Distribution::Uniform, 1500, 5);
    for (i, q) in pts.iter().enumerate() {
        p.push(DVec3::new(q.x, q.y, (i % 5) as f64));
    }
    let t = check(&p);
    assert_eq!(t.unique_points, 1500);
}

#[test]
fn many_duplicates() {
    let base = sample(Distribution::Ball, 300, 9);
    let mut p = Vec::new();
    for k in 0..5 {
        for (i, q) in base.iter().enumerate() {
            if (i + k) % 3 != 0 || k == 0 {
                p.push(*q);
            }
        }
    }
    let t = check(&p);
    assert_eq!(t.unique_points, 300);
    for (i, &r) in t.representative.iter().enumerate() {
        assert_eq!(p[i], p[r as usize]);
        assert!(r as usize <= i);
        assert_eq!(
            r as usize,
            p.iter().position(|q| *q == p[i]).unwrap(),
            "first occurrence"
        );
    }
    assert_eq!(t.duplicates.len(), p.len() - 300);
    for d in &t.duplicates {
        assert_eq!(t.representative[d[0] as usize], d[1]);
    }
}

#[test]
fn unity_cube_24_vertices() {
    // Unity's cube mesh: 8 corners, each repeated once per adjacent face.
    let mut p = Vec::new();
    for face in 0..6 {
        let axis = face / 2;
        let side = if face % 2 == 0 { -0.5 } else { 0.5 };
        for (u, v) in [(-0.5, -0.5), (0.5, -0.5), (0.5, 0.5), (-0.5, 0.5)] {
            let mut c = [0.0; 3];
            c[axis] = side;
            c[(axis + 1) % 3] = u;
            c[(axis + 2) % 3] = v;
            p.push(DVec3::from_array(c));
        }
    }
    let t = check(&p);
    assert_eq!(t.unique_points, 8);
    assert_eq!(t.duplicates.len(), 16);
    assert!((t.volume(&p) - 1.0).abs() < 1e-12);
}

#[test]
fn offset_by_1e6_and_scaled_by_1e_minus_9() {
    let g = grid(6);
    let offset: Vec<DVec3> = g.iter().map(|q| *q * 0.1 + DVec3::splat(1e6)).collect();
    let t = check(&offset);
    assert_eq!(t.unique_points, 216);
    let scaled: Vec<DVec3> = sample(Distribution::Uniform, 2000, 2)
        .iter()
        .map(|q| *q * 1e-9)
        .collect();
    check(&scaled);
    let both: Vec<DVec3> = sample(Distribution::Sphere, 1000, 2)
        .iter()
        .map(|q| *q * 1e-3 + DVec3::new(1e6, -1e6, 1e6))
        .collect();
    check(&both);
}

/// Points on two skew lines have only one tetrahedralization, with `(m - 1)²` tetrahedra
/// for `m` points per line: far more than the storage first reserves (about 7 per point).
#[test]
fn two_skew_lines_need_quadratic_tetrahedra() {
    let m = 60;
    let mut p = Vec::new();
    for i in 0..m {
        p.push(DVec3::new(i as f64, 0.0, 0.0));
        p.push(DVec3::new(0.0, i as f64 * 0.5, 7.0));
    }
    let t = check(&p);
    assert_eq!(t.len(), (m - 1) * (m - 1));
    assert!(t.len() > 7 * p.len() + 1024);
}

/// The result is compact: 24 bytes per tetrahedron (vertices and adjacency) plus 4 per
/// point, so about 166 bytes per uniform point once shrunk — the bulk of the 200 bytes per
/// point the construction may use at its peak.
#[test]
fn the_result_takes_24_bytes_per_tetrahedron() {
    let n = 50_000;
    let p = sample(Distribution::Uniform, n, 9);
    let mut t = tetrahedralize(&p).unwrap();
    t.shrink_to_fit();
    let exact = t.len() * 24 + n * 4;
    assert!(
        (exact..exact + exact / 100).contains(&t.heap_bytes()),
        "{} bytes for {} tetrahedra",
        t.heap_bytes(),
        t.len()
    );
    let per_point = t.heap_bytes() as f64 / n as f64;
    assert!(per_point < 170.0, "{per_point} bytes per point");
}

#[test]
fn single_tetrahedron_and_orientation() {
    let p = [DVec3::ZERO, DVec3::X, DVec3::Z, DVec3::Y];
    let t = check(&p);
    assert_eq!(t.len(), 1);
    let v = t.tetrahedron(0).map(|i| p[i as usize].to_array());
    assert!(orient(&v[0], &v[1], &v[2], &v[3]) > 0.0);
    assert_eq!(t.hull_faces().len(), 4);
}

#[test]
fn errors_name_the_problem() {
    let mut p = sample(Distribution::Uniform, 10, 1);
    p[7].y = f64::NAN;
    assert_eq!(
        tetrahedralize(&p).unwrap_err(),
        DelaunayError::NonFinite { index: 7 }
    );
    p[7].y = f64::INFINITY;
    assert_eq!(
        tetrahedralize(&p).unwrap_err(),
        DelaunayError::NonFinite { index: 7 }
    );
    p[7].y = 1e200;
    assert!(matches!(
        tetrahedralize(&p).unwrap_err(),
        DelaunayError::OutOfRange { index: 7, .. }
    ));
    p[7].y = 1e-300;
    assert!(matches!(
        tetrahedralize(&p).unwrap_err(),
        DelaunayError::OutOfRange { index: 7, .. }
    ));

    let three = [DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::X, DVec3::ZERO];
    assert_eq!(
        tetrahedralize(&three).unwrap_err(),
        DelaunayError::TooFewPoints { distinct: 3 }
    );
    assert_eq!(
        tetrahedralize(&[]).unwrap_err(),
        DelaunayError::TooFewPoints { distinct: 0 }
    );

    let flat: Vec<DVec3> = sample(Distribution::Uniform, 50, 1)
        .iter()
        .map(|q| DVec3::new(q.x, q.y, 0.5 * q.x - q.y))
        .collect();
    assert_eq!(
        tetrahedralize(&flat).unwrap_err(),
        DelaunayError::AllCoplanar { distinct: 50 }
    );
    let line: Vec<DVec3> = (0..20).map(|i| DVec3::splat(i as f64)).collect();
    assert_eq!(
        tetrahedralize(&line).unwrap_err(),
        DelaunayError::AllCoplanar { distinct: 20 }
    );
    let msg = DelaunayError::NonFinite { index: 7 }.to_string();
    assert!(msg.contains('7'));
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn random_sets_are_delaunay(
        pts in prop::collection::vec((-8i32..8, -8i32..8, -8i32..8), 5..200),
        scale in prop::sample::select(vec![1.0, 0.25, 1e-7, 3e5]),
    ) {
        // Small integer coordinates: many duplicates, coplanar and cospherical subsets.
        let p: Vec<DVec3> = pts.iter().map(|&(x, y, z)| DVec3::new(x as f64, y as f64, z as f64) * scale).collect();
        match tetrahedralize(&p) {
            Ok(t) => {
                t.validate(&p).unwrap();
                let h = hull_volume(&t, &p);
                prop_assert!((t.volume(&p) - h).abs() <= 1e-9 * h);
            }
            Err(DelaunayError::TooFewPoints { .. } | DelaunayError::AllCoplanar { .. }) => {}
            Err(e) => prop_assert!(false, "unexpected error {e}"),
        }
    }

    #[test]
    fn random_float_sets_are_delaunay(
        pts in prop::collection::vec((-1.0f64..1.0, -1.0f64..1.0, -1.0f64..1.0), 4..300),
    ) {
        let p: Vec<DVec3> = pts.iter().map(|&(x, y, z)| DVec3::new(x, y, z)).collect();
        let t = tetrahedralize(&p).unwrap();
        t.validate(&p).unwrap();
        let h = hull_volume(&t, &p);
        prop_assert!((t.volume(&p) - h).abs() <= 1e-9 * h);
    }
}

#[test]
fn validate_rejects_broken_results() {
    use shatter_geom::delaunay::NO_NEIGHBOR;
    let p = sample(Distribution::Uniform, 200, 4);
    let good = tetrahedralize(&p).unwrap();
    good.validate(&p).unwrap();

    // A flipped tetrahedron.
    let mut bad = good.clone();
    let mut v = bad.tetrahedron(3);
    v.swap(0, 1);
    bad.set_tetrahedron(3, v);
    assert!(bad.validate(&p).is_err());

    // A broken adjacency.
    let mut bad = good.clone();
    let t = (0..bad.len())
        .find(|&t| bad.neighbors(t)[0] != NO_NEIGHBOR)
        .unwrap();
    bad.set_neighbor(t, 0, NO_NEIGHBOR);
    assert!(bad.validate(&p).is_err());

    // A non-Delaunay configuration: move the far vertex of a neighbour to the centroid of
    // the first tetrahedron (deep inside its circumsphere), keeping the connectivity.
    let mut q = p.clone();
    let (t, n) = (0..good.len())
        .find_map(|t| {
            let n = good.neighbors(t)[0];
            (n != NO_NEIGHBOR).then_some((t, n as usize))
        })
        .unwrap();
    let far = good
        .tetrahedron(n)
        .into_iter()
        .find(|v| !good.tetrahedron(t).contains(v))
        .unwrap();
    let c: DVec3 = good
        .tetrahedron(t)
        .iter()
        .map(|&v| p[v as usize])
        .sum::<DVec3>()
        / 4.0;
    q[far as usize] = c;
    assert!(good.validate(&q).is_err());
}
