//! Triangulation of the cap closing a clipped solid: the region of the cutting plane
//! bounded by the clipped surface's boundary edges, possibly several polygons with holes.

use glam::{DVec2, DVec3};
use spade::{ConstrainedDelaunayTriangulation, Point2, Triangulation};

use super::clip::Plane;
use super::piece::FastMap;

/// An original face lying in the cutting plane and facing its positive side; the cap
/// triangles over it inherit its tag.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Covering {
    pub corners: [DVec3; 3],
    pub tag: u64,
}

/// An orthonormal frame `(u, v)` of the plane with `u × v` along `n`.
pub(crate) fn plane_frame(n: DVec3) -> (DVec3, DVec3) {
    let n = n.normalize();
    let u = n.any_orthonormal_vector();
    let v = n.cross(u);
    (u, v)
}

/// Triangulates the cap bounded by `boundary` (directed edges of the kept surface, all
/// on `plane`). Returns triangles wound so their normal points along `plane.n` (out of
/// the kept side), each with its tag.
///
/// Uses spade's constrained Delaunay triangulation in the plane's 2D frame; the inside
/// is found by parity of the constraint edges crossed from the outside. Spade is exact
/// (robust predicates), so loops that touch at a vertex and nested loops (holes, islands
/// in holes) come out right.
pub(crate) fn triangulate_cap(
    pos: &[DVec3],
    boundary: &[(u32, u32)],
    plane: &Plane,
    coverings: &[Covering],
) -> Vec<([u32; 3], u64)> {
    let (u, v) = plane_frame(plane.n);
    let origin = plane.n * (plane.d / plane.n.length_squared());
    let to2 = |p: DVec3| {
        let q = p - origin;
        DVec2::new(q.dot(u), q.dot(v))
    };

    if let Some(fan) = convex_fan(pos, boundary, &to2) {
        return fan
            .into_iter()
            .map(|ids| {
                let c = ids.iter().map(|&i| to2(pos[i as usize])).sum::<DVec2>() / 3.0;
                (ids, covering_tag(c, plane.tag, coverings, &to2))
            })
            .collect();
    }

    let mut cdt: ConstrainedDelaunayTriangulation<Point2<f64>> =
        ConstrainedDelaunayTriangulation::new();
    let mut handle_of: FastMap<u32, spade::handles::FixedVertexHandle> = FastMap::default();
    let mut id_of_handle: Vec<u32> = Vec::new();
    for &(a, b) in boundary {
        for id in [a, b] {
            if handle_of.contains_key(&id) {
                continue;
            }
            let p = to2(pos[id as usize]);
            let Ok(h) = cdt.insert(Point2::new(p.x, p.y)) else {
                continue;
            };
            if h.index() >= id_of_handle.len() {
                id_of_handle.resize(h.index() + 1, u32::MAX);
            }
            if id_of_handle[h.index()] == u32::MAX {
                id_of_handle[h.index()] = id;
            }
            handle_of.insert(id, h);
        }
    }
    for &(a, b) in boundary {
        if let (Some(&ha), Some(&hb)) = (handle_of.get(&a), handle_of.get(&b))
            && ha != hb
        {
            // A crossing constraint can only come from rounding in a degenerate cut;
            // skip it rather than panic.
            if !cdt.exists_constraint(ha, hb) && cdt.can_add_constraint(ha, hb) {
                cdt.add_constraint(ha, hb);
            }
        }
    }

    // Parity flood fill from the convex hull.
    let nf = cdt.num_all_faces();
    let mut inside: Vec<Option<bool>> = vec![None; nf];
    let mut stack: Vec<(
        spade::handles::FixedFaceHandle<spade::handles::InnerTag>,
        bool,
    )> = Vec::new();
    for e in cdt.convex_hull() {
        for f in [e.face(), e.rev().face()] {
            if let Some(inner) = f.as_inner() {
                stack.push((inner.fix(), e.is_constraint_edge()));
            }
        }
    }
    while let Some((f, state)) = stack.pop() {
        let slot = &mut inside[f.index()];
        if slot.is_some() {
            continue;
        }
        *slot = Some(state);
        let face = cdt.face(f);
        for e in face.adjacent_edges() {
            if let Some(other) = e.rev().face().as_inner()
                && inside[other.index()].is_none()
            {
                stack.push((other.fix(), state ^ e.is_constraint_edge()));
            }
        }
    }

    let mut out = Vec::new();
    for face in cdt.inner_faces() {
        if inside[face.index()] != Some(true) {
            continue;
        }
        let vs = face.vertices();
        let ids = vs.map(|h| id_of_handle.get(h.index()).copied().unwrap_or(u32::MAX));
        if ids.contains(&u32::MAX) {
            continue;
        }
        let c = vs
            .iter()
            .map(|h| DVec2::new(h.position().x, h.position().y))
            .sum::<DVec2>()
            / 3.0;
        let tag = covering_tag(c, plane.tag, coverings, &to2);
        // Spade's faces are counter-clockwise in (u, v), so their normal is along n.
        out.push((ids, tag));
    }
    out
}

/// Point in (closed) triangle test in 2D, for either winding.
pub(crate) fn point_in_triangle(p: DVec2, a: DVec2, b: DVec2, c: DVec2) -> bool {
    let d1 = (b - a).perp_dot(p - a);
    let d2 = (c - b).perp_dot(p - b);
    let d3 = (a - c).perp_dot(p - c);
    let has_neg = d1 < 0.0 || d2 < 0.0 || d3 < 0.0;
    let has_pos = d1 > 0.0 || d2 > 0.0 || d3 > 0.0;
    !(has_neg && has_pos)
}

/// The tag of a cap triangle with 2D centroid `c`: that of the covering original face it
/// lies in, or `tag`.
fn covering_tag(c: DVec2, tag: u64, coverings: &[Covering], to2: &impl Fn(DVec3) -> DVec2) -> u64 {
    for cov in coverings {
        let [a, b, cc] = cov.corners.map(to2);
        if point_in_triangle(c, a, b, cc) {
            return cov.tag;
        }
    }
    tag
}

/// Fast path for the common cap: a single boundary loop whose reverse is a convex
/// polygon (decided exactly with `orient2d`), triangulated as a fan. `None` when the
/// boundary is anything else (several loops, holes, shared vertices, a concave loop).
fn convex_fan(
    pos: &[DVec3],
    boundary: &[(u32, u32)],
    to2: &impl Fn(DVec3) -> DVec2,
) -> Option<Vec<[u32; 3]>> {
    let n = boundary.len();
    if n < 3 {
        return None;
    }
    let mut next: FastMap<u32, u32> = FastMap::default();
    for &(a, b) in boundary {
        if next.insert(a, b).is_some() {
            return None;
        }
    }
    // Walk the loop from the first edge; it must use every edge.
    let start = boundary[0].0;
    let mut lp = Vec::with_capacity(n);
    let mut v = start;
    loop {
        lp.push(v);
        v = *next.get(&v)?;
        if v == start {
            break;
        }
        if lp.len() > n {
            return None;
        }
    }
    if lp.len() != n {
        return None;
    }
    // Two loop vertices at one point (cuts meeting on an edge): leave it to the CDT,
    // which merges them.
    let mut seen: FastMap<[u64; 3], ()> = FastMap::default();
    for &i in &lp {
        let q = pos[i as usize];
        if seen.insert([q.x, q.y, q.z].map(f64::to_bits), ()).is_some() {
            return None;
        }
    }
    // The cap runs the loop backwards, counter-clockwise in the plane's frame.
    lp.reverse();
    let p: Vec<DVec2> = lp.iter().map(|&i| to2(pos[i as usize])).collect();
    let orient = |a: DVec2, b: DVec2, c: DVec2| {
        robust::orient2d(
            robust::Coord { x: a.x, y: a.y },
            robust::Coord { x: b.x, y: b.y },
            robust::Coord { x: c.x, y: c.y },
        )
    };
    let mut area2 = 0.0;
    for i in 0..n {
        let (a, b, c) = (p[i], p[(i + 1) % n], p[(i + 2) % n]);

        if orient(a, b, c) < 0.0 {
            return None;
        }
        area2 += a.perp_dot(b);
    }
    if area2 <= 0.0 {
        return None;
    }
    // Fan from a vertex where the polygon and both its neighbours turn strictly: then
    // no fan triangle is flat (collinear vertices lie only on sides away from the apex).
    // "Strictly" with a margin: a turn of less than ~1e-9 rad counts as straight, as
    // the 2D projection of collinear 3D points is only collinear up to rounding.
    let strict: Vec<bool> = (0..n)
        .map(|i| {
            let (a, b, c) = (p[(i + n - 1) % n], p[i], p[(i + 1) % n]);
            orient(a, b, c) > 1e-9 * (b - a).length() * (c - b).length()
        })
        .collect();
    let apex = (0..n).find(|&i| strict[(i + n - 1) % n] && strict[i] && strict[(i + 1) % n])?;
    Some(
        (1..n - 1)
            .map(|k| [lp[apex], lp[(apex + k) % n], lp[(apex + k + 1) % n]])
            .collect(),
    )
}
