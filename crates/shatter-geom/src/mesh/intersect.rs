//! Exact self-intersection detection: pairs of triangles, sharing no vertex, that touch
//! or cross. Broad phase: sweep and prune along `x`; narrow phase: exact orientation
//! predicates (`robust::orient3d`, `orient2d`), so touching counts as intersecting and no
//! tolerance is involved.

use glam::DVec3;
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

/// Closed segment `de` meets the closed triangle `abc`, whose plane the segment does not
/// lie in.
fn segment_meets_triangle(d: DVec3, e: DVec3, [a, b, c]: [DVec3; 3]) -> bool {
    let (od, oe) = (o3(a, b, c, d), o3(a, b, c, e));
    if (od > 0.0 && oe > 0.0) || (od < 0.0 && oe < 0.0) || (od == 0.0 && oe == 0.0) {
        return false;
    }
    let s = [o3(d, e, a, b), o3(d, e, b, c), o3(d, e, c, a)];
    s.iter().all(|&x| x >= 0.0) || s.iter().all(|&x| x <= 0.0)
}

/// Two non-degenerate triangles intersect (closed sets), decided exactly.
pub(crate) fn triangles_meet(t: [DVec3; 3], u: [DVec3; 3]) -> bool {
    let coplanar = u.iter().all(|&p| o3(t[0], t[1], t[2], p) == 0.0);
    if coplanar {
        return coplanar_meet(t, u);
    }
    // Non-coplanar: if they meet, an edge of one meets the other.
    (0..3).any(|i| segment_meets_triangle(t[i], t[(i + 1) % 3], u))
        || (0..3).any(|i| segment_meets_triangle(u[i], u[(i + 1) % 3], t))
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
            if tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2] || is_degenerate(a, b, c) {
                continue;
            }
            boxes.push((a.min(b).min(c), a.max(b).max(c), t as u32));
        }
        boxes.sort_unstable_by(|p, q| p.0.x.total_cmp(&q.0.x));
        let mut found = Vec::new();
        for (k, &(lo, hi, s)) in boxes.iter().enumerate() {
            for &(lo2, hi2, t) in &boxes[k + 1..] {
                if lo2.x > hi.x {
                    break;
                }
                if lo2.y > hi.y || lo.y > hi2.y || lo2.z > hi.z || lo.z > hi2.z {
                    continue;
                }
                let (ts, tt) = (mesh.triangles[s as usize], mesh.triangles[t as usize]);
                if ts.iter().any(|v| tt.contains(v)) {
                    continue;
                }
                if triangles_meet(mesh.triangle(s as usize), mesh.triangle(t as usize)) {
                    found.push((s.min(t), s.max(t)));
                    if found.len() >= limit {
                        return found;
                    }
                }
            }
        }
        found.sort_unstable();
        found
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
    fn coplanar_overlap_and_gap() {
        let shifted = T.map(|p| p + DVec3::new(0.4, 0.4, 0.0));
        assert!(triangles_meet(T, shifted));
        let apart = T.map(|p| p + DVec3::new(0.6, 0.6, 0.0));
        assert!(!triangles_meet(T, apart));
        let inner = T.map(|p| p * 0.1 + DVec3::new(0.1, 0.1, 0.0));
        assert!(triangles_meet(T, inner));
    }
}
