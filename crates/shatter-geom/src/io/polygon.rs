//! Triangulating a polygon face of a file (OBJ's `f` with more than three corners).
//!
//! A fan from the first corner is wrong for a concave polygon (its triangles leave the
//! polygon and overlap), so the polygon is projected onto the plane of its Newell normal
//! and ear-clipped there by the `earcut` crate (a port of mapbox's earcut, well kept and
//! robust on the degenerate rings real files hold). Each triangle is wound like the
//! polygon.

use glam::{DVec2, DVec3};

/// A polygon triangulator that reuses `earcut`'s buffers across calls.
pub(crate) struct Triangulator {
    earcut: earcut::Earcut<f64>,
    flat: Vec<[f64; 2]>,
    out: Vec<u32>,
}

impl Triangulator {
    pub fn new() -> Triangulator {
        Triangulator {
            earcut: earcut::Earcut::new(),
            flat: Vec::new(),
            out: Vec::new(),
        }
    }

    /// Triangulates the polygon whose corners are `corners` (positions, in order);
    /// returns triangles as indices into `corners`, wound like the polygon, or `None`
    /// when the polygon has no area or earcut could not cover it (the caller decides).
    pub fn triangulate(&mut self, corners: &[DVec3]) -> Option<Vec<[usize; 3]>> {
        let n = corners.len();
        if n < 3 {
            return None;
        }
        if n == 3 {
            return Some(vec![[0, 1, 2]]);
        }
        let normal = newell_normal(corners);
        if normal.length_squared() <= 0.0 || !normal.is_finite() {
            return None;
        }
        // Drop the normal's largest axis; keep the projection's orientation positive.
        let axis = normal.abs().max_position();
        let project = |p: DVec3| -> DVec2 {
            match axis {
                0 => DVec2::new(p.y, p.z),
                1 => DVec2::new(p.z, p.x),
                _ => DVec2::new(p.x, p.y),
            }
        };
        let sign = normal[axis].signum();
        self.flat.clear();
        self.flat.extend(corners.iter().map(|&p| {
            let q = project(p);
            [q.x, q.y * sign]
        }));
        let flat = std::mem::take(&mut self.flat);
        self.earcut
            .earcut(flat.iter().copied(), &[] as &[u32], &mut self.out);
        self.flat = flat;
        if self.out.len() != 3 * (n - 2) {
            return None;
        }
        let area = |t: &[usize; 3]| {
            let [a, b, c] = t.map(|i| DVec2::from(self.flat[i]));
            (b - a).perp_dot(c - a)
        };
        Some(
            self.out
                .chunks_exact(3)
                .map(|t| {
                    let tri = [t[0] as usize, t[1] as usize, t[2] as usize];
                    // The projection keeps the polygon counter-clockwise: wind each
                    // triangle the same way.
                    if area(&tri) < 0.0 {
                        [tri[0], tri[2], tri[1]]
                    } else {
                        tri
                    }
                })
                .collect(),
        )
    }
}

/// The polygon's Newell normal: its area vector (twice the area, along the normal of
/// its counter-clockwise side).
fn newell_normal(corners: &[DVec3]) -> DVec3 {
    let o = corners[0];
    let mut n = DVec3::ZERO;
    for w in 1..corners.len() - 1 {
        n += (corners[w] - o).cross(corners[w + 1] - o);
    }
    n
}

#[cfg(test)]
mod tests {
    use super::*;

    fn area_vector(p: &[DVec3], tris: &[[usize; 3]]) -> DVec3 {
        tris.iter()
            .map(|t| (p[t[1]] - p[t[0]]).cross(p[t[2]] - p[t[0]]))
            .sum()
    }

    #[test]
    fn a_concave_polygon_is_covered_without_overlap_and_keeps_its_winding() {
        // An L-shaped hexagon in the plane x + y + z = 0 seen through a rotation: its
        // fan from corner 0 would cover area outside it.
        let l = [
            (0.0, 0.0),
            (2.0, 0.0),
            (2.0, 1.0),
            (1.0, 1.0),
            (1.0, 2.0),
            (0.0, 2.0),
        ];
        let (u, v) = (
            DVec3::new(1.0, -1.0, 0.0).normalize(),
            DVec3::new(1.0, 1.0, -2.0).normalize(),
        );
        let p: Vec<DVec3> = l.iter().map(|&(a, b)| a * u + b * v).collect();
        let tris = Triangulator::new().triangulate(&p).unwrap();
        assert_eq!(tris.len(), 4);
        // Each triangle has positive area along the polygon's normal, and they add up
        // to the polygon's area (3): no overlap, no gap.
        let n = u.cross(v);
        for t in &tris {
            assert!(area_vector(&p, &[*t]).dot(n) > 0.0, "{t:?}");
        }
        assert!((area_vector(&p, &tris).dot(n) / 2.0 - 3.0).abs() < 1e-12);
        // Reversed, every triangle is reversed too.
        let rev: Vec<DVec3> = p.iter().rev().copied().collect();
        let tris = Triangulator::new().triangulate(&rev).unwrap();
        assert!((area_vector(&rev, &tris).dot(n) / 2.0 + 3.0).abs() < 1e-12);
    }

    #[test]
    fn a_polygon_without_area_is_not_triangulated() {
        let line = [DVec3::ZERO, DVec3::X, DVec3::X * 2.0, DVec3::X * 3.0];
        assert!(Triangulator::new().triangulate(&line).is_none());
    }
}
