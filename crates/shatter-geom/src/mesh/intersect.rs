//! Exact self-intersection detection: pairs of triangles, sharing no vertex, that touch
//! or cross. Broad phase: a sparse uniform grid; narrow phase: exact orientation
//! predicates (`robust::orient3d`, `orient2d`), so touching counts as intersecting and no
//! tolerance is involved.

use glam::DVec3;
use rayon::prelude::*;
use robust::{Coord, Coord3D, orient2d, orient3d};

use super::TriMesh;
use super::check::is_degenerate;

fn c3(p: DVec3) -> Coord3D<f64> {
    Coord3D {
        x: p.x,
        y: p.y,
        z: p.z,
    }
}

fn o3(a: DVec3, b: DVec3, c: DVec3, d: DVec3) -> f64 {
    orient3d(c3(a), c3(b), c3(c), c3(d))
}

/// Projection onto the coordinate plane that drops axis `drop`.
fn c2(p: DVec3, drop: usize) -> Coord<f64> {
    let (i, j) = match drop {
        0 => (1, 2),
        1 => (2, 0),
        _ => (0, 1),
    };
    Coord { x: p[i], y: p[j] }
}

/// Closed segments `ab` and `cd` in the plane intersect.
fn segments_meet_2d(a: Coord<f64>, b: Coord<f64>, c: Coord<f64>, d: Coord<f64>) -> bool {
    let (d1, d2) = (orient2d(a, b, c), orient2d(a, b, d));
    let (d3, d4) = (orient2d(c, d, a), orient2d(c, d, b));
    if d1 == 0.0 && d2 == 0.0 {
        // Collinear: overlap of the projections on the longer axis.
        let key = |p: Coord<f64>| {
            if (a.x - b.x).abs() >= (a.y - b.y).abs() {
                p.x
            } else {
                p.y
            }
        };
        let (lo1, hi1) = (key(a).min(key(b)), key(a).max(key(b)));
        let (lo2, hi2) = (key(c).min(key(d)), key(c).max(key(d)));
        return lo1 <= hi2 && lo2 <= hi1;
    }
    (d1 * d2 <= 0.0) && (d3 * d4 <= 0.0)
}

/// Point `p` in the closed triangle `abc` (non-degenerate) in the plane.
fn point_in_triangle_2d(p: Coord<f64>, a: Coord<f64>, b: Coord<f64>, c: Coord<f64>) -> bool {
    let s = orient2d(a, b, c).signum();
    [orient2d(a, b, p), orient2d(b, c, p), orient2d(c, a, p)]
        .iter()
        .all(|&o| o * s >= 0.0)
}

/// Two coplanar, non-degenerate triangles intersect (closed sets).
fn coplanar_meet(t: [DVec3; 3], u: [DVec3; 3]) -> bool {
    // Drop an axis along which the plane's projection stays non-degenerate.
    let Some(drop) = (0..3).find(|&k| orient2d(c2(t[0], k), c2(t[1], k), c2(t[2], k)) != 0.0)
    else {
        return false;
    };
    let t2 = t.map(|p| c2(p, drop));
    let u2 = u.map(|p| c2(p, drop));
    for i in 0..3 {
        for j in 0..3 {
            if segments_meet_2d(t2[i], t2[(i + 1) % 3], u2[j], u2[(j + 1) % 3]) {
                return true;
            }
        }
    }
    point_in_triangle_2d(u2[0], t2[0], t2[1], t2[2])
        || point_in_triangle_2d(t2[0], u2[0], u2[1], u2[2])
}

/// Whether a segment whose ends are at orientations `od` and `oe` from a triangle's
/// plane reaches the plane without lying in it.
fn reaches_plane(od: f64, oe: f64) -> bool {
    !((od > 0.0 && oe > 0.0) || (od < 0.0 && oe < 0.0) || (od == 0.0 && oe == 0.0))
}

/// Whether three orientations of a segment against a triangle's edges agree (none of
/// the opposite sign): the segment's line passes through the closed triangle.
fn one_sign(s: [f64; 3]) -> bool {
    s.iter().all(|&x| x >= 0.0) || s.iter().all(|&x| x <= 0.0)
}

/// Two non-degenerate triangles intersect (closed sets), decided exactly.
pub(crate) fn triangles_meet(t: [DVec3; 3], u: [DVec3; 3]) -> bool {
    // Early exact rejection: one triangle strictly on one side of the other's plane.
    let strictly_one_side = |s: [f64; 3]| s.iter().all(|&x| x > 0.0) || s.iter().all(|&x| x < 0.0);
    let u_vs_t = u.map(|p| o3(t[0], t[1], t[2], p));
    if strictly_one_side(u_vs_t) {
        return false;
    }
    if u_vs_t.iter().all(|&x| x == 0.0) {
        return coplanar_meet(t, u);
    }
    let t_vs_u = t.map(|p| o3(u[0], u[1], u[2], p));
    if strictly_one_side(t_vs_u) {
        return false;
    }
    // Non-coplanar: if they meet, an edge of one meets the other. An edge reaching the
    // other's plane (its ends' sides are the orientations above) meets the closed
    // triangle when its orientations against the triangle's three edges agree. The
    // orientation of t's edge i against u's edge j, `orient3d(tᵢ, tᵢ₊₁, uⱼ, uⱼ₊₁)`, has
    // the sign of u's edge against t's (an even permutation of the four points), so
    // each of the nine is computed once, when first needed.
    let mut edges = [[None::<f64>; 3]; 3];
    let mut edge = |i: usize, j: usize| {
        *edges[i][j].get_or_insert_with(|| o3(t[i], t[(i + 1) % 3], u[j], u[(j + 1) % 3]))
    };
    for i in 0..3 {
        if reaches_plane(t_vs_u[i], t_vs_u[(i + 1) % 3])
            && one_sign([edge(i, 0), edge(i, 1), edge(i, 2)])
        {
            return true;
        }
    }
    for j in 0..3 {
        if reaches_plane(u_vs_t[j], u_vs_t[(j + 1) % 3])
            && one_sign([edge(0, j), edge(1, j), edge(2, j)])
        {
            return true;
        }
    }
    false
}

/// How far triangle `t` pokes through triangle `u`: the part of `t` over `u` (clipped to
/// the prism `u` spans along its normal) lies on both sides of `u`'s plane; this is the
/// lesser of the two sides' greatest distances from the plane (0 when `t` only touches
/// `u`, or lies on one side of it). Floating point, for telling rounding from a real
/// crossing; `u` must not be degenerate.
fn poke_depth(t: [DVec3; 3], u: [DVec3; 3]) -> f64 {
    let Some(n) = (u[1] - u[0]).cross(u[2] - u[0]).try_normalize() else {
        return 0.0;
    };
    // Keeps the part of `poly` where `m·x ≥ d`.
    let clip = |poly: Vec<DVec3>, m: DVec3, d: f64| -> Vec<DVec3> {
        let mut out = Vec::with_capacity(poly.len() + 2);
        for (i, &a) in poly.iter().enumerate() {
            let b = poly[(i + 1) % poly.len()];
            let (da, db) = (m.dot(a) - d, m.dot(b) - d);
            if da >= 0.0 {
                out.push(a);
            }
            if (da >= 0.0) != (db >= 0.0) {
                out.push(a + (b - a) * (da / (da - db)));
            }
        }
        out
    };
    let mut over = t.to_vec();
    for i in 0..3 {
        let (a, b) = (u[i], u[(i + 1) % 3]);
        let Some(m) = n.cross(b - a).try_normalize() else {
            return 0.0;
        };
        over = clip(over, m, m.dot(a));
        if over.is_empty() {
            return 0.0;
        }
    }
    let level = n.dot(u[0]);
    let side = |s: f64| {
        clip(over.clone(), n * s, level * s)
            .iter()
            .map(|p| (n.dot(*p) - level).abs())
            .fold(0.0, f64::max)
    };
    side(1.0).min(side(-1.0))
}

/// How deep two meeting triangles cross: the lesser of each poking through the other
/// ([`poke_depth`]); 0 for triangles that only touch.
pub(crate) fn crossing_depth(t: [DVec3; 3], u: [DVec3; 3]) -> f64 {
    poke_depth(t, u).min(poke_depth(u, t))
}

impl TriMesh {
    /// Pairs of triangles `(s, t)`, `s < t`, that share no vertex (after welding) yet
    /// touch or cross, decided exactly. Triangles sharing a vertex or an edge are not
    /// tested against each other (a fold between neighbours is not reported; a mesh that
    /// passes [`check`](TriMesh::check) has none that matter for inside/outside), and
    /// zero-area triangles are skipped. At most `limit` pairs are returned. Out-of-range
    /// indices are skipped.
    ///
    /// ```
    /// use shatter_geom::{DVec3, TriMesh, shapes};
    /// assert!(shapes::bird().self_intersections(10).is_empty());
    /// // Two overlapping cubes cross each other.
    /// let a = shapes::cube();
    /// let b = a.transformed(DVec3::ONE, DVec3::splat(0.5));
    /// assert!(!TriMesh::merge(&[a, b]).self_intersections(10).is_empty());
    /// ```
    pub fn self_intersections(&self, limit: usize) -> Vec<(u32, u32)> {
        let mesh = self.welded();
        let n = mesh.positions.len();
        let mut boxes: Vec<(DVec3, DVec3, u32)> = Vec::with_capacity(mesh.triangles.len());
        for (t, tri) in mesh.triangles.iter().enumerate() {
            if tri.iter().any(|&i| i as usize >= n) {
                continue;
            }
            let [a, b, c] = mesh.triangle(t);
            let finite = a.is_finite() && b.is_finite() && c.is_finite();
            if !finite
                || tri[0] == tri[1]
                || tri[1] == tri[2]
                || tri[0] == tri[2]
                || is_degenerate(a, b, c)
            {
                continue;
            }
            boxes.push((a.min(b).min(c), a.max(b).max(c), t as u32));
        }
        let grid = Grid::new(&boxes);
        // Each box's lowest cell: the cell of two boxes' overlap corner (their lows'
        // maximum) is the maximum of theirs, the floor being monotonic.
        let low_cells: Vec<[i64; 3]> = boxes.iter().map(|b| grid.cell_of(b.0)).collect();
        // The cells are independent: tested in parallel, the pairs then sorted.
        let per_cell: Vec<Vec<(u32, u32)>> = grid
            .cells
            .par_iter()
            .map(|(cell, members)| {
                let mut found = Vec::new();
                for (k, &i) in members.iter().enumerate() {
                    let (lo, hi, s) = boxes[i as usize];
                    let low = low_cells[i as usize];
                    for &j in &members[k + 1..] {
                        let (lo2, hi2, t) = boxes[j as usize];
                        if lo2.cmpgt(hi).any() || lo.cmpgt(hi2).any() {
                            continue;
                        }
                        // Test each pair once: in the cell holding its boxes' overlap corner.
                        let low2 = low_cells[j as usize];
                        if std::array::from_fn(|a| low[a].max(low2[a])) != *cell {
                            continue;
                        }
                        let (ts, tt) = (mesh.triangles[s as usize], mesh.triangles[t as usize]);
                        if ts.iter().any(|v| tt.contains(v)) {
                            continue;
                        }
                        if triangles_meet(mesh.triangle(s as usize), mesh.triangle(t as usize)) {
                            found.push((s.min(t), s.max(t)));
                        }
                    }
                }
                found
            })
            .collect();
        let mut found: Vec<(u32, u32)> = per_cell.into_iter().flatten().collect();
        found.sort_unstable();
        found.truncate(limit);
        found
    }
}

/// Broad phase: a sparse uniform grid of triangle boxes, cells about the size of a
/// typical triangle, so each pair test is local (linear in practice; a sweep along one
/// axis was quadratic on large closed meshes).
struct Grid {
    origin: DVec3,
    cell: f64,
    cells: Vec<([i64; 3], Vec<u32>)>,
}

impl Grid {
    fn new(boxes: &[(DVec3, DVec3, u32)]) -> Self {
        let origin = boxes
            .iter()
            .fold(DVec3::splat(f64::INFINITY), |acc, b| acc.min(b.0));
        let mean_extent = boxes
            .iter()
            .map(|(lo, hi, _)| (*hi - *lo).max_element())
            .sum::<f64>()
            / boxes.len().max(1) as f64;
        let cell = if mean_extent > 0.0 && mean_extent.is_finite() {
            1.5 * mean_extent
        } else {
            1.0
        };
        let mut grid = Grid {
            origin,
            cell,
            cells: Vec::new(),
        };
        // Coarsen until the boxes cover a bounded number of cells in all (a few huge
        // triangles among small ones would otherwise fill millions).
        let budget = 16 * boxes.len() as u64 + 1024;
        loop {
            let covered = boxes.iter().fold(0u64, |sum, (lo, hi, _)| {
                let (a, b) = (grid.cell_of(*lo), grid.cell_of(*hi));
                let span = |k: usize| (b[k].saturating_sub(a[k]) as u64).saturating_add(1);
                sum.saturating_add(span(0).saturating_mul(span(1)).saturating_mul(span(2)))
            });
            if covered <= budget || !grid.cell.is_finite() {
                break;
            }
            grid.cell *= 2.0;
        }
        let mut map: crate::util::FastMap<[i64; 3], Vec<u32>> = crate::util::FastMap::default();
        for (i, (lo, hi, _)) in boxes.iter().enumerate() {
            let (a, b) = (grid.cell_of(*lo), grid.cell_of(*hi));
            for x in a[0]..=b[0] {
                for y in a[1]..=b[1] {
                    for z in a[2]..=b[2] {
                        map.entry([x, y, z]).or_default().push(i as u32);
                    }
                }
            }
        }
        // Sorted cells: a deterministic order, so a `limit` cuts the same pairs each run.
        grid.cells = map.into_iter().collect();
        grid.cells.sort_unstable_by_key(|(k, _)| *k);
        grid
    }

    fn cell_of(&self, p: DVec3) -> [i64; 3] {
        ((p - self.origin) / self.cell)
            .floor()
            .as_i64vec3()
            .to_array()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const T: [DVec3; 3] = [DVec3::ZERO, DVec3::X, DVec3::Y];

    #[test]
    fn crossing_touching_and_separate_triangles() {
        let pierce = [
            DVec3::new(0.2, 0.2, -1.0),
            DVec3::new(0.2, 0.2, 1.0),
            DVec3::new(0.3, 0.25, 1.0),
        ];
        assert!(triangles_meet(T, pierce));
        // Touching the interior with a vertex.
        let touch = [
            DVec3::new(0.2, 0.2, 0.0),
            DVec3::new(0.2, 0.2, 1.0),
            DVec3::new(0.3, 0.25, 1.0),
        ];
        assert!(triangles_meet(T, touch));
        let above = touch.map(|p| p + DVec3::Z * 1e-12);
        assert!(!triangles_meet(T, above));
    }

    #[test]
    fn crossing_depth_is_how_far_one_triangle_pokes_through_the_other() {
        // Pierces T at (0.2, 0.2) from z = −1 to z = 1: it reaches 1 on each side.
        let pierce = [
            DVec3::new(0.2, 0.2, -1.0),
            DVec3::new(0.2, 0.2, 1.0),
            DVec3::new(0.3, 0.25, 1.0),
        ];
        assert!((poke_depth(pierce, T) - 1.0).abs() < 1e-12);
        // T, for its part, lies on both sides of the piercing plane, as far as the part
        // of T over the piercing triangle reaches: less than 1, more than 0.1.
        let d = crossing_depth(T, pierce);
        assert!(d > 0.1 && d < 1.0, "{d}");
        // Pokes 1e-3 below T, a long way above: at most 1e-3.
        let poke = pierce.map(|p| DVec3::new(p.x, p.y, p.z.max(-1e-3)));
        assert!((poke_depth(poke, T) - 1e-3).abs() < 1e-12);
        let d = crossing_depth(T, poke);
        assert!(d > 0.0 && d <= 1e-3 + 1e-15, "{d}");
        // Touching only: depth 0.
        let touch = [
            DVec3::new(0.2, 0.2, 0.0),
            DVec3::new(0.2, 0.2, 1.0),
            DVec3::new(0.3, 0.25, 1.0),
        ];
        assert_eq!(crossing_depth(T, touch), 0.0);
        // Beside T (not over it): nothing pokes through.
        let beside = pierce.map(|p| p + DVec3::new(2.0, 0.0, 0.0));
        assert_eq!(crossing_depth(T, beside), 0.0);
    }

    /// The narrow phase as first written: each edge of one against the other triangle,
    /// every orientation computed afresh.
    fn meet_by_segments(t: [DVec3; 3], u: [DVec3; 3]) -> bool {
        let segment = |d: DVec3, e: DVec3, [a, b, c]: [DVec3; 3]| {
            let (od, oe) = (o3(a, b, c, d), o3(a, b, c, e));
            if (od > 0.0 && oe > 0.0) || (od < 0.0 && oe < 0.0) || (od == 0.0 && oe == 0.0) {
                return false;
            }
            let s = [o3(d, e, a, b), o3(d, e, b, c), o3(d, e, c, a)];
            s.iter().all(|&x| x >= 0.0) || s.iter().all(|&x| x <= 0.0)
        };
        let side = |s: [f64; 3]| s.iter().all(|&x| x > 0.0) || s.iter().all(|&x| x < 0.0);
        let u_vs_t = u.map(|p| o3(t[0], t[1], t[2], p));
        if side(u_vs_t) {
            return false;
        }
        if u_vs_t.iter().all(|&x| x == 0.0) {
            return coplanar_meet(t, u);
        }
        if side(t.map(|p| o3(u[0], u[1], u[2], p))) {
            return false;
        }
        (0..3).any(|i| segment(t[i], t[(i + 1) % 3], u))
            || (0..3).any(|i| segment(u[i], u[(i + 1) % 3], t))
    }

    #[test]
    fn the_shared_edge_orientations_decide_as_each_segment_alone_does() {
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(9);
        // Corners on a coarse lattice: many touching, collinear and coplanar cases.
        let corner = |rng: &mut rand_chacha::ChaCha8Rng| {
            DVec3::new(
                f64::from(rng.random_range(0..4u8)),
                f64::from(rng.random_range(0..4u8)),
                f64::from(rng.random_range(0..4u8)),
            ) * 0.25
        };
        let (mut meet, mut apart, mut coplanar) = (0, 0, 0);
        for _ in 0..40_000 {
            let t = [corner(&mut rng), corner(&mut rng), corner(&mut rng)];
            let u = [corner(&mut rng), corner(&mut rng), corner(&mut rng)];
            if is_degenerate(t[0], t[1], t[2]) || is_degenerate(u[0], u[1], u[2]) {
                continue;
            }
            let expected = meet_by_segments(t, u);
            assert_eq!(triangles_meet(t, u), expected, "{t:?} {u:?}");
            assert_eq!(triangles_meet(u, t), expected, "{u:?} {t:?}");
            if u.iter().all(|&p| o3(t[0], t[1], t[2], p) == 0.0) {
                coplanar += 1;
            } else if expected {
                meet += 1;
            } else {
                apart += 1;
            }
        }
        assert!(
            meet > 1000 && apart > 1000 && coplanar > 100,
            "{meet} {apart} {coplanar}"
        );
    }

    #[test]
    fn coplanar_overlap_and_gap() {
        let shifted = T.map(|p| p + DVec3::new(0.4, 0.4, 0.0));
        assert!(triangles_meet(T, shifted));
        let apart = T.map(|p| p + DVec3::new(0.6, 0.6, 0.0));
        assert!(!triangles_meet(T, apart));
        let inner = T.map(|p| p * 0.1 + DVec3::new(0.1, 0.1, 0.0));
        assert!(triangles_meet(T, inner));
    }

    #[test]
    fn the_grid_finds_every_meeting_pair_once_as_all_pairs_do() {
        use rand::{Rng, SeedableRng};
        // Soups of small triangles of mixed sizes, some sharing vertices, some on a grid
        // of exactly coplanar points, crossing each other's boxes and the grid's cells.
        for seed in 0..6 {
            let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
            let mut positions = Vec::new();
            let mut triangles = Vec::new();
            for k in 0..300u32 {
                let size = if k % 7 == 0 { 0.5 } else { 0.08 };
                let c = DVec3::new(rng.random(), rng.random(), rng.random());
                let mut corner = || {
                    let d = DVec3::new(rng.random(), rng.random(), rng.random()) - 0.5;
                    let p = c + d * size;
                    if seed % 2 == 0 {
                        // On the plane z = 0.5, at multiples of 1/64.
                        DVec3::new(
                            (p.x * 64.0).round() / 64.0,
                            (p.y * 64.0).round() / 64.0,
                            0.5,
                        )
                    } else {
                        p
                    }
                };
                let at = positions.len() as u32;
                positions.extend([corner(), corner(), corner()]);
                // Every fifth triangle shares a vertex with the one before.
                let first = if k % 5 == 4 { at - 1 } else { at };
                triangles.push([first, at + 1, at + 2]);
            }
            let mesh = TriMesh::new(positions, triangles);
            let welded = mesh.welded();
            let mut expected = Vec::new();
            for s in 0..welded.triangles.len() {
                for t in s + 1..welded.triangles.len() {
                    let (ts, tt) = (welded.triangles[s], welded.triangles[t]);
                    let (a, b) = (welded.triangle(s), welded.triangle(t));
                    let flat = |x: [u32; 3], p: [DVec3; 3]| {
                        x[0] == x[1]
                            || x[1] == x[2]
                            || x[0] == x[2]
                            || is_degenerate(p[0], p[1], p[2])
                    };
                    if flat(ts, a) || flat(tt, b) || ts.iter().any(|v| tt.contains(v)) {
                        continue;
                    }
                    if triangles_meet(a, b) {
                        expected.push((s as u32, t as u32));
                    }
                }
            }
            assert!(expected.len() > 20, "seed {seed}: {}", expected.len());
            assert_eq!(mesh.self_intersections(usize::MAX), expected, "seed {seed}");
        }
    }
}
