//! Tests of the fast paths against what they replace: ear-clipped caps against the
//! constrained Delaunay triangulation they must equal, Delaunay-neighbour cells against
//! cells cut by every other seed's bisector.

use glam::{DVec2, DVec3};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

use super::Piece;
use super::cap::ear_clip;
use crate::fracture::methods::voronoi::{delaunay_neighbours, voronoi_with};
use crate::shapes;

fn coord(p: DVec2) -> robust::Coord<f64> {
    robust::Coord { x: p.x, y: p.y }
}

fn orient(a: DVec2, b: DVec2, c: DVec2) -> f64 {
    robust::orient2d(coord(a), coord(b), coord(c))
}

/// A random simple polygon, counter-clockwise: a star around the origin, with some
/// points added on its edges (exactly collinear where the edge is axis-aligned) to
/// mimic the cut points cap loops carry.
fn star(rng: &mut ChaCha8Rng, n: usize) -> Vec<DVec2> {
    let mut angles: Vec<f64> = (0..n)
        .map(|_| rng.random::<f64>() * std::f64::consts::TAU)
        .collect();
    angles.sort_by(f64::total_cmp);
    angles.dedup();
    let mut pts: Vec<DVec2> = angles
        .iter()
        .map(|&a| DVec2::new(a.cos(), a.sin()) * (0.3 + rng.random::<f64>()))
        .collect();
    if rng.random::<bool>() {
        // An axis-aligned edge with exactly collinear points on it.
        pts.push(DVec2::new(1.5, -0.5));
        pts.insert(0, DVec2::new(1.5, 0.5));
        pts.insert(0, DVec2::new(1.5, 0.25));
        pts.insert(0, DVec2::new(1.5, 0.0));
        pts.rotate_left(3);
    }
    pts
}

#[test]
fn ear_clipped_caps_are_constrained_delaunay_triangulations() {
    let mut rng = ChaCha8Rng::seed_from_u64(5);
    let mut checked = 0;
    for case in 0..400 {
        let n = 3 + case % 60;
        let poly = star(&mut rng, n);
        // Keep only simple polygons (the star can fold where the added edge meets it).
        let m = poly.len();
        let simple = (0..m).all(|i| {
            (0..m).all(|j| {
                let (a, b) = (poly[i], poly[(i + 1) % m]);
                let (c, d) = (poly[j], poly[(j + 1) % m]);
                if i == j || (i + 1) % m == j || (j + 1) % m == i {
                    return true;
                }
                !(orient(a, b, c) * orient(a, b, d) < 0.0
                    && orient(c, d, a) * orient(c, d, b) < 0.0)
            })
        });
        let area2: f64 = (0..m).map(|i| poly[i].perp_dot(poly[(i + 1) % m])).sum();
        if !simple || area2 <= 0.0 {
            continue;
        }
        let pos: Vec<DVec3> = poly.iter().map(|p| p.extend(0.0)).collect();
        // The kept surface's boundary runs clockwise; the cap runs it backwards.
        let boundary: Vec<(u32, u32)> = (0..m).map(|i| (((i + 1) % m) as u32, i as u32)).collect();
        let to2 = |p: DVec3| p.truncate();
        let Some(tris) = ear_clip(&pos, &boundary, &to2) else {
            panic!("case {case}: a simple loop of {m} points was refused");
        };
        assert_eq!(tris.len(), m - 2, "case {case}");
        let p = |i: u32| poly[i as usize];
        let mut sum = 0.0;
        let mut directed = std::collections::HashMap::new();
        for t in &tris {
            let o = orient(p(t[0]), p(t[1]), p(t[2]));
            assert!(
                o > 0.0,
                "case {case}: triangle {t:?} not counter-clockwise ({o})"
            );
            sum += o;
            for k in 0..3 {
                let e = (t[k], t[(k + 1) % 3]);
                assert!(
                    directed.insert(e, t[(k + 2) % 3]).is_none(),
                    "case {case}: edge {e:?} twice"
                );
            }
        }
        assert!(
            (sum - area2).abs() <= 1e-12 * area2,
            "case {case}: area {sum} vs {area2}"
        );
        for &(a, b) in &boundary {
            // Each boundary edge is covered once, in the cap's direction.
            assert!(
                directed.contains_key(&(b, a)),
                "case {case}: boundary edge {b}->{a} missing"
            );
        }
        for (&(a, b), &c) in &directed {
            let Some(&d) = directed.get(&(b, a)) else {
                continue;
            };
            let inc = robust::incircle(coord(p(a)), coord(p(b)), coord(p(c)), coord(p(d)));
            assert!(
                inc <= 0.0,
                "case {case}: interior edge {a}-{b} not locally Delaunay"
            );
        }
        checked += 1;
    }
    assert!(checked > 200, "only {checked} simple polygons tried");
}

#[test]
fn ear_clip_leaves_touching_loops_to_the_cdt() {
    // Two squares sharing the corner (1, 1): one vertex with two outgoing edges.
    let pts = [
        (0., 0.),
        (1., 0.),
        (1., 1.),
        (0., 1.),
        (2., 1.),
        (2., 2.),
        (1., 2.),
    ];
    let pos: Vec<DVec3> = pts.iter().map(|&(x, y)| DVec3::new(x, y, 0.0)).collect();
    let ccw = [
        (0, 1),
        (1, 2),
        (2, 3),
        (3, 0),
        (2, 4),
        (4, 5),
        (5, 6),
        (6, 2),
    ];
    let boundary: Vec<(u32, u32)> = ccw.iter().map(|&(a, b)| (b, a)).collect();
    assert!(ear_clip(&pos, &boundary, &|p: DVec3| p.truncate()).is_none());
}

/// Cells (volumes, in seed order) of `seeds` cut from `mesh` with and without the
/// Delaunay neighbour lists.
fn both_ways(mesh: &Piece, seeds: &[DVec3], metric: DVec3) -> (Vec<f64>, Vec<f64>, usize) {
    let eps = 1e-10;
    let neighbours = delaunay_neighbours(seeds, metric).expect("seeds in general position");
    let (fast, fast_bonds) = voronoi_with(mesh, seeds, metric, eps, Some(neighbours));
    let (slow, slow_bonds) = voronoi_with(mesh, seeds, metric, eps, None);
    assert_eq!(fast_bonds.len(), slow_bonds.len());
    (
        fast.iter().map(Piece::volume).collect(),
        slow.iter().map(Piece::volume).collect(),
        fast_bonds.len(),
    )
}

#[test]
fn delaunay_neighbour_cells_equal_cells_cut_by_every_bisector() {
    let bird = Piece::from_mesh_welded(&shapes::bird());
    let (lo, hi) = crate::util::bounds(&bird.pos);
    let mut rng = ChaCha8Rng::seed_from_u64(9);
    for metric in [DVec3::ONE, DVec3::new(1.0, 9.0, 9.0)] {
        let seeds: Vec<DVec3> = (0..60)
            .map(|_| lo + (hi - lo) * DVec3::new(rng.random(), rng.random(), rng.random()))
            .collect();
        let (fast, slow, bonds) = both_ways(&bird, &seeds, metric);
        assert_eq!(fast.len(), slow.len(), "metric {metric}");
        assert!(bonds > 60, "metric {metric}: {bonds} bonds");
        let total = bird.volume();
        for (k, (a, b)) in fast.iter().zip(&slow).enumerate() {
            assert!(
                (a - b).abs() <= 1e-9 * total,
                "metric {metric}, cell {k}: {a} vs {b}"
            );
        }
    }
}

#[test]
fn delaunay_neighbours_need_a_tetrahedralization() {
    // Coplanar seeds have none: the cells then fall back to every other seed.
    let flat: Vec<DVec3> = (0..10)
        .map(|i| {
            let x = i as f64 / 10.0 - 0.45;
            DVec3::new(x, x * x, 0.1)
        })
        .collect();
    assert!(delaunay_neighbours(&flat, DVec3::ONE).is_none());
    let cube = Piece::from_mesh_welded(&shapes::cube());
    let (cells, _) = crate::fracture::methods::voronoi::voronoi(&cube, &flat, DVec3::ONE, 1e-10);
    let sum: f64 = cells.iter().map(Piece::volume).sum();
    assert!((sum - cube.volume()).abs() < 1e-9 * cube.volume());
    assert_eq!(cells.len(), 10);
}

/// Every directed edge has its reverse exactly once (a closed, consistently wound
/// surface), and no triangle repeats a vertex.
pub(super) fn closed(p: &Piece) -> bool {
    let mut count = std::collections::HashMap::new();
    for t in &p.tris {
        if t[0] == t[1] || t[1] == t[2] || t[0] == t[2] {
            return false;
        }
        for k in 0..3 {
            *count.entry((t[k], t[(k + 1) % 3])).or_insert(0i32) += 1;
        }
    }
    count
        .iter()
        .all(|(&(a, b), &n)| n == 1 && count.get(&(b, a)) == Some(&1))
}

#[test]
fn split_shares_one_cap_and_matches_two_clips() {
    use super::Plane;
    use super::clip::{clip, split};
    let bird = Piece::from_mesh_welded(&shapes::bird());
    let total = bird.volume();
    let mut rng = ChaCha8Rng::seed_from_u64(3);
    let (lo, hi) = crate::util::bounds(&bird.pos);
    // Random planes, and the planes of mesh faces (a face then lies in the plane, as
    // in convex decomposition).
    let mut planes = Vec::new();
    for _ in 0..20 {
        let n = crate::fracture::seeds::patterns::unit_vector(&mut rng);
        let p = lo + (hi - lo) * DVec3::new(rng.random(), rng.random(), rng.random());
        planes.push(Plane {
            n,
            d: n.dot(p),
            tag: 7,
        });
    }
    for t in bird.tris.iter().step_by(97) {
        let [a, b, c] = t.map(|i| bird.pos[i as usize]);
        let n = (b - a).cross(c - a).normalize();
        planes.push(Plane {
            n,
            d: n.dot(a),
            tag: 7,
        });
    }
    let mut cut = 0;
    for plane in &planes {
        let [neg, pos] = split(&bird, plane, 1e-10);
        let (Some(neg), Some(pos)) = (neg, pos) else {
            continue;
        };
        cut += 1;
        let (a, b) = (
            clip(&bird, plane, 1e-10).expect("the plane cuts"),
            clip(&bird, &plane.flipped(), 1e-10).expect("the plane cuts"),
        );
        for (side, alone) in [(&neg, &a), (&pos, &b)] {
            assert!(closed(side), "plane {plane:?}: a side is not closed");
            // The same vertices, to the bit, and the same triangles off the cap as the
            // clip by that side's plane (the positive cap may be triangulated apart).
            assert!(
                side.pos == alone.pos,
                "plane {plane:?}: the vertices differ"
            );
            let off_cap = |p: &Piece| -> Vec<([u32; 3], u64)> {
                p.tris
                    .iter()
                    .copied()
                    .zip(p.tags.iter().copied())
                    .filter(|t| t.1 != 7)
                    .collect()
            };
            assert!(
                off_cap(side) == off_cap(alone),
                "plane {plane:?}: the triangles differ"
            );
            assert!((side.volume() - alone.volume()).abs() <= 1e-12 * total);
        }
        assert!((neg.volume() + pos.volume() - total).abs() <= 1e-12 * total);
        // The two caps are one region: equal areas.
        let cap_area = |p: &Piece| -> f64 {
            p.tris
                .iter()
                .zip(&p.tags)
                .filter(|(_, tag)| **tag == 7)
                .map(|(t, _)| {
                    let [a, b, c] = t.map(|i| p.pos[i as usize]);
                    (b - a).cross(c - a).length() / 2.0
                })
                .sum()
        };
        let (ca, cb) = (cap_area(&neg), cap_area(&pos));
        assert!(
            ca > 0.0 && (ca - cb).abs() <= 1e-12 * ca.max(1.0),
            "caps {ca} vs {cb}"
        );
    }
    assert!(cut >= 20, "only {cut} planes cut the bird");
}
