use glam::DVec3;
use proptest::prelude::*;

use super::nearest::{NearestTriangle, closest_point};
use super::planar::Basis;
use super::{barycentric, mix};
use crate::shapes;

fn v3() -> impl Strategy<Value = DVec3> {
    (-10.0..10.0f64, -10.0..10.0f64, -10.0..10.0f64).prop_map(|(x, y, z)| DVec3::new(x, y, z))
}

#[test]
fn the_canonical_basis_is_orthonormal_and_the_same_for_both_sides() {
    for n in [
        DVec3::X,
        -DVec3::Y,
        DVec3::new(1.0, 1.0, 0.0),
        DVec3::new(-1.0, -1.0, -1.0),
        DVec3::new(0.3, -2.0, 1e-17),
    ] {
        let (b, c) = (Basis::canonical(n), Basis::canonical(-n));
        assert_eq!(b, c, "{n}");
        assert!((b.u.length() - 1.0).abs() < 1e-12 && (b.v.length() - 1.0).abs() < 1e-12);
        assert!(b.u.dot(b.v).abs() < 1e-12 && b.u.dot(b.n).abs() < 1e-12);
        assert!((b.n.dot(n.normalize()).abs() - 1.0).abs() < 1e-12);
    }
}

#[test]
fn a_triangle_basis_ignores_the_winding() {
    let p = [
        DVec3::new(0.1, 0.2, 0.3),
        DVec3::new(1.0, -0.5, 0.2),
        DVec3::new(0.4, 0.9, -1.0),
    ];
    let b = Basis::of_triangle(p);
    assert_eq!(b, Basis::of_triangle([p[0], p[2], p[1]]));
    assert_eq!(b, Basis::of_triangle([p[2], p[1], p[0]]));
    assert_eq!(b, Basis::of_triangle([p[1], p[2], p[0]]));
}

proptest! {
    #[test]
    fn barycentric_coordinates_rebuild_the_point(a in v3(), b in v3(), c in v3(),
                                                 s in 0.0..1.0f64, t in 0.0..1.0f64) {
        let area = (b - a).cross(c - a).length();
        prop_assume!(area > 1e-3);
        let (s, t) = if s + t > 1.0 { (1.0 - s, 1.0 - t) } else { (s, t) };
        let p = a + (b - a) * s + (c - a) * t;
        let w = barycentric([a, b, c], p, true);
        let q = a * w[0] + b * w[1] + c * w[2];
        prop_assert!((q - p).length() < 1e-9 * (1.0 + p.length()), "{q} vs {p}");
        // And a linear attribute is reproduced.
        let vals = [[1.0f32, 2.0], [3.0, -1.0], [0.5, 0.25]];
        let m = mix(&vals, w);
        let want = [1.0 + 2.0 * s + -0.5 * t, 2.0 - 3.0 * s - 1.75 * t];
        prop_assert!((m[0] - want[0]).abs() < 1e-9 && (m[1] - want[1]).abs() < 1e-9);
    }

    #[test]
    fn the_grid_finds_the_nearest_triangle(p in v3()) {
        let bird = shapes::bird();
        let grid = NearestTriangle::new(&bird.positions, &bird.triangles);
        let tri = |t: usize| bird.triangles[t].map(|i| bird.positions[i as usize]);
        let d = |t: usize| (closest_point(tri(t), p) - p).length();
        let best = (0..bird.triangles.len()).map(d).fold(f64::INFINITY, f64::min);
        let got = grid.nearest(p).unwrap();
        prop_assert!((d(got) - best).abs() <= 1e-12 * (1.0 + best), "{} vs {best}", d(got));
    }
}

#[test]
fn a_point_beyond_a_corner_snaps_to_it() {
    let t = [DVec3::ZERO, DVec3::X, DVec3::Y];
    assert_eq!(closest_point(t, DVec3::new(-1.0, -1.0, 3.0)), DVec3::ZERO);
    assert_eq!(
        closest_point(t, DVec3::new(0.25, 0.25, 3.0)),
        DVec3::new(0.25, 0.25, 0.0)
    );
    assert_eq!(
        closest_point(t, DVec3::new(0.5, -2.0, 0.0)),
        DVec3::new(0.5, 0.0, 0.0)
    );
}
