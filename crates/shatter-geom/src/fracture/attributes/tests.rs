use glam::DVec3;
use proptest::prelude::*;

use super::nearest::{NearestTriangle, closest_point};
use super::planar::{Basis, SAME_PLANE_SINE, cap_bases};
use super::{barycentric, mix};
use crate::fracture::entry::fragment;
use crate::fracture::kernel::{Piece, SURFACE};
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

/// A tetrahedron at `at` whose face 0 lies in the plane of normal `n` and carries
/// `tag`; the other three faces are the surface.
fn tet_with_cap(at: DVec3, n: DVec3, tag: u64) -> Piece {
    let n = n.normalize();
    let e1 = n.any_orthonormal_vector();
    let e2 = n.cross(e1);
    Piece {
        pos: vec![at, at + e1, at + e2, at - n],
        tris: vec![[0, 2, 1], [0, 1, 3], [1, 2, 3], [2, 0, 3]],
        tags: vec![tag, SURFACE, SURFACE, SURFACE],
        faces: Vec::new(),
    }
}

/// Two caps facing each other across a crack in nearly one plane (normals a few 1e-7
/// apart, as the faces on either side of a sliver leave them), at 45° between the x and
/// y axes, where the canonical basis of each normal alone takes different axes: they get
/// one basis. So do two caps 5e-4 rad apart (whose own bases would differ by that much,
/// a UV step of about 5e-4 across the crack), and a cap of the same plane elsewhere; a
/// cap 1e-2 rad off keeps its own.
#[test]
fn caps_in_nearly_one_plane_share_a_basis_where_the_axis_ties() {
    let n1 = DVec3::new(1.0 - 1.5e-6, 1.0, 0.0).normalize();
    let n2 = -DVec3::new(1.0 - 0.5e-6, 1.0, 0.0).normalize();
    assert!(n1.cross(n2).length() < SAME_PLANE_SINE);
    assert_ne!(
        Basis::canonical(n1),
        Basis::canonical(n2),
        "the two normals alone must pick different axes for the test to bite"
    );
    let z = DVec3::new(0.2, 0.1, 1.0).normalize();
    let tilted = |angle: f64| glam::DQuat::from_axis_angle(z.any_orthonormal_vector(), angle) * z;
    let pieces = [
        tet_with_cap(DVec3::ZERO, n1, 7),
        tet_with_cap(DVec3::new(0.1, 0.0, 0.0), n2, 9),
        tet_with_cap(DVec3::new(3.0, 0.0, 0.0), z, 11),
        tet_with_cap(DVec3::new(3.0, 0.1, 0.0), -tilted(5e-4), 13),
        tet_with_cap(DVec3::new(6.0, 0.0, 0.0), tilted(1e-2), 15),
        tet_with_cap(DVec3::new(9.0, 0.0, 0.0), -z, 17),
    ];
    let fragments: Vec<_> = pieces.iter().map(fragment).collect();
    let tags: Vec<Vec<u64>> = pieces.iter().map(|p| p.tags.clone()).collect();
    let bases = cap_bases(&fragments, &tags);
    assert_eq!(
        bases.len(),
        6,
        "one basis per cap tag, none for the surface"
    );
    assert_eq!(bases[&7], bases[&9]);
    assert!(bases[&7].n.cross(n1).length() < SAME_PLANE_SINE);
    assert_ne!(
        Basis::canonical(z),
        Basis::canonical(tilted(5e-4)),
        "alone, the two would differ"
    );
    assert_eq!(bases[&11], bases[&13]);
    assert_eq!(bases[&11], bases[&17], "an equal plane elsewhere");
    assert!(bases[&11].n.cross(z).length() < SAME_PLANE_SINE);
    let (own, alone) = (bases[&15], Basis::canonical(tilted(1e-2)));
    assert!(own.u.distance(alone.u) < 1e-12 && own.v.distance(alone.v) < 1e-12);
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
