//! Caps kept as polygons until a cell is done.

use glam::DVec3;

use super::cap::{loops, triangulate_cap};
use super::plane::Plane;

/// A cap kept as a polygon: the region of `plane` bounded by `edges`, directed
/// counter-clockwise seen from the side `plane.n` points to (outside the solid), so the
/// region lies to the left of each edge. Its triangles will carry `plane.tag`.
///
/// A cell of a Voronoi fracture is cut by one plane after another; each cut crosses the
/// caps of the earlier ones. Triangulated caps would gain a vertex wherever the cut
/// crosses one of their diagonals, so caps grew to several times their corners and
/// every later cut and cap paid for them. A polygon is cut by splitting its edges and
/// closing each side along the cut line, and is triangulated once, at the end.
#[derive(Debug, Clone)]
pub(crate) struct Face {
    pub plane: Plane,
    pub edges: Vec<(u32, u32)>,
}

impl Face {
    /// The face's triangles ([`triangulate_cap`]), wound like the face, as indices into
    /// `pos`.
    pub fn triangles(&self, pos: &[DVec3]) -> Vec<[u32; 3]> {
        // The cap's triangulation takes the edges as the solid's side sees them.
        let rim: Vec<(u32, u32)> = self.edges.iter().map(|&(a, b)| (b, a)).collect();
        triangulate_cap(pos, &rim, &self.plane)
    }

    /// The face as one face per region, when that is plain from its loops: one loop, or
    /// loops all counter-clockwise (no holes, so each bounds a region of its own).
    /// `None` when a loop runs clockwise (a hole, which belongs to some other loop's
    /// region) or the loops touch.
    pub(super) fn regions(&self, pos: &[DVec3]) -> Option<Vec<Face>> {
        let loops = loops(&self.edges)?;
        let counter_clockwise = |lp: &[u32]| {
            let o = pos[lp[0] as usize];
            let area: DVec3 = (0..lp.len())
                .map(|k| (pos[lp[k] as usize] - o).cross(pos[lp[(k + 1) % lp.len()] as usize] - o))
                .sum();
            area.dot(self.plane.n) > 0.0
        };
        if loops.len() > 1 && !loops.iter().all(|lp| counter_clockwise(lp)) {
            return None;
        }
        let plane = self.plane;
        let edges = |lp: Vec<u32>| {
            (0..lp.len())
                .map(|k| (lp[k], lp[(k + 1) % lp.len()]))
                .collect()
        };
        Some(
            loops
                .into_iter()
                .map(|lp| Face {
                    plane,
                    edges: edges(lp),
                })
                .collect(),
        )
    }
}
