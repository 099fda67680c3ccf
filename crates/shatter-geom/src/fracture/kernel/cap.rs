//! Triangulation of the cap closing a clipped solid: the region of the cutting plane
//! bounded by the clipped surface's boundary edges, possibly several polygons with holes.

use glam::{DVec2, DVec3};
use spade::{ConstrainedDelaunayTriangulation, Point2, Triangulation};

use super::Plane;
use crate::mesh::position_key;
use crate::util::{FastMap, FastSet};

/// An orthonormal frame `(u, v)` of the plane with `u × v` along `n`.
pub(crate) fn plane_frame(n: DVec3) -> (DVec3, DVec3) {
    let n = n.normalize();
    let u = n.any_orthonormal_vector();
    let v = n.cross(u);
    (u, v)
}

/// Triangulates the cap bounded by `boundary` (directed edges of the kept surface, all
/// on `plane`). Returns triangles wound so their normal points along `plane.n` (out of
/// the kept side).
///
/// Both paths give the constrained Delaunay triangulation of the cap in the plane's 2D
/// frame, with exact predicates. The common cap, one or more simple loops without holes,
/// is cut into ears and flipped to Delaunay (see [`ear_clip`]); that is several times
/// faster than building a CDT with spade, which a cap of tens of vertices needs about
/// 20 µs for. Anything else
/// goes to spade's CDT, the inside found by parity of the constraint edges crossed from
/// the outside, so loops that touch at a vertex and nested loops (holes, islands in
/// holes) come out right.
pub(crate) fn triangulate_cap(
    pos: &[DVec3],
    boundary: &[(u32, u32)],
    plane: &Plane,
) -> Vec<[u32; 3]> {
    let (u, v) = plane_frame(plane.n);
    let origin = plane.n * (plane.d / plane.n.length_squared());
    let to2 = |p: DVec3| {
        let q = p - origin;
        DVec2::new(q.dot(u), q.dot(v))
    };

    if let Some(ears) = ear_clip(pos, boundary, &to2) {
        return ears;
    }

    let mut points: Vec<(u32, DVec2)> = Vec::with_capacity(boundary.len());
    let mut seen: FastSet<u32> = FastSet::default();
    for &(a, b) in boundary {
        for id in [a, b] {
            if seen.insert(id) {
                points.push((id, to2(pos[id as usize])));
            }
        }
    }
    constrained_triangulation(&points, boundary)
}

/// The constrained Delaunay triangulation (spade, exact predicates) of the region
/// bounded by the directed edges `boundary`, over `points` (an id and its 2D position;
/// ids not on the boundary are interior points, Steiner points of the caller). Returns
/// the inside triangles as ids, counter-clockwise in 2D. The inside is found by the
/// parity of the constraint edges crossed from the outside, so loops that touch at a
/// vertex and nested loops (holes, islands in holes) come out right. Points at an
/// existing point's position are merged into it (the first id is kept), and crossing
/// constraints (only from rounding in a degenerate input) are skipped, not a panic.
pub(crate) fn constrained_triangulation(
    points: &[(u32, DVec2)],
    boundary: &[(u32, u32)],
) -> Vec<[u32; 3]> {
    let mut cdt: ConstrainedDelaunayTriangulation<Point2<f64>> =
        ConstrainedDelaunayTriangulation::new();
    let mut handle_of: FastMap<u32, spade::handles::FixedVertexHandle> = FastMap::default();
    let mut id_of_handle: Vec<u32> = Vec::new();
    for &(id, p) in points {
        if handle_of.contains_key(&id) {
            continue;
        }
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
        // Spade's faces are counter-clockwise in (u, v), so their normal is along n.
        out.push(ids);
    }
    out
}

/// Fast path for the common caps: boundary loops that are each simple, none inside
/// another (all counter-clockwise once reversed, so there are no holes), and without
/// repeated points, each cut into ears. `None` when the boundary is anything else
/// (holes, loops touching at a point) or when no ear is left (a degenerate loop): the
/// caller then falls back to the CDT.
///
/// An ear is a strictly convex corner (exact `orient2d`) whose triangle has no other
/// loop vertex inside or on it; only reflex and straight corners can lie there, so only
/// they are tested, and a convex loop costs one orientation test per corner. Corners
/// turning by less than ~1e-9 rad (straight up to the rounding of the 2D projection)
/// are taken as ears only when no clearly convex one is left, so flat triangles are
/// avoided where the loop allows it. The loops here have tens of vertices, for which
/// this O(n²) worst case is faster than building a CDT.
pub(crate) fn ear_clip(
    pos: &[DVec3],
    boundary: &[(u32, u32)],
    to2: &impl Fn(DVec3) -> DVec2,
) -> Option<Vec<[u32; 3]>> {
    let n = boundary.len();
    if n < 3 {
        return None;
    }
    let loops = loops(boundary)?;
    // Two loop vertices at one point (cuts meeting on an edge, loops touching): leave
    // it to the CDT, which merges them.
    let mut keys: Vec<[u64; 3]> = boundary
        .iter()
        .map(|&(a, _)| position_key(pos[a as usize]))
        .collect();
    keys.sort_unstable();
    if keys.windows(2).any(|w| w[0] == w[1]) {
        return None;
    }
    let mut out = Vec::with_capacity(n);
    for lp in loops {
        out.extend(ear_clip_loop(pos, lp, to2)?);
    }
    Some(out)
}

/// The loops of a set of directed edges, each as its vertices in edge order; `None`
/// unless every vertex starts exactly one edge and the edges close up into cycles (they
/// are grouped by first vertex by sorting, with no hashing).
pub(crate) fn loops(edges: &[(u32, u32)]) -> Option<Vec<Vec<u32>>> {
    let mut edges = edges.to_vec();
    edges.sort_unstable();
    if edges.windows(2).any(|w| w[0].0 == w[1].0) {
        return None;
    }
    let slot = |v: u32| edges.binary_search_by(|e| e.0.cmp(&v)).ok();
    let mut used = vec![false; edges.len()];
    let mut out = Vec::new();
    for first in 0..edges.len() {
        if used[first] {
            continue;
        }
        let start = edges[first].0;
        let mut lp = Vec::with_capacity(edges.len() - first);
        let mut k = first;
        loop {
            if used[k] {
                return None;
            }
            used[k] = true;
            lp.push(edges[k].0);
            let v = edges[k].1;
            if v == start {
                break;
            }
            k = slot(v)?;
        }
        out.push(lp);
    }
    Some(out)
}

/// Ears of one simple loop (kept-surface direction, so reversed here); `None` if it runs
/// clockwise (a hole) or no ear is left.
fn ear_clip_loop(
    pos: &[DVec3],
    mut lp: Vec<u32>,
    to2: &impl Fn(DVec3) -> DVec2,
) -> Option<Vec<[u32; 3]>> {
    let n = lp.len();
    if n < 3 {
        return None;
    }
    // The cap runs the loop backwards, counter-clockwise in the plane's frame.
    lp.reverse();
    let p: Vec<DVec2> = lp.iter().map(|&i| to2(pos[i as usize])).collect();
    let orient = |a: usize, b: usize, c: usize| {
        let (a, b, c) = (p[a], p[b], p[c]);
        robust::orient2d(
            robust::Coord { x: a.x, y: a.y },
            robust::Coord { x: b.x, y: b.y },
            robust::Coord { x: c.x, y: c.y },
        )
    };
    let mut area2 = 0.0;
    for i in 0..n {
        area2 += p[i].perp_dot(p[(i + 1) % n]);
    }
    if area2 <= 0.0 {
        return None;
    }
    let mut prev: Vec<usize> = (0..n).map(|i| (i + n - 1) % n).collect();
    let mut nxt: Vec<usize> = (0..n).map(|i| (i + 1) % n).collect();
    // Turn at each live corner (exact sign; the magnitude only ranks flat corners).
    let turn = |i: usize, prev: &[usize], nxt: &[usize]| orient(prev[i], i, nxt[i]);
    let mut reflex: Vec<usize> = (0..n).filter(|&i| turn(i, &prev, &nxt) <= 0.0).collect();
    // 0: not an ear, 1: an ear turning by less than the margin, 2: a clear ear.
    let class = |i: usize, prev: &[usize], nxt: &[usize], reflex: &[usize]| -> u8 {
        let (a, c) = (prev[i], nxt[i]);
        let t = turn(i, prev, nxt);
        if t <= 0.0 {
            return 0;
        }
        let (lo, hi) = (p[a].min(p[i]).min(p[c]), p[a].max(p[i]).max(p[c]));
        if reflex.iter().any(|&r| {
            let q = p[r];
            q.x >= lo.x
                && q.y >= lo.y
                && q.x <= hi.x
                && q.y <= hi.y
                && r != a
                && r != i
                && r != c
                && orient(a, i, r) >= 0.0
                && orient(i, c, r) >= 0.0
                && orient(c, a, r) >= 0.0
        }) {
            return 0;
        }
        if t > 1e-9 * (p[i] - p[a]).length() * (p[c] - p[i]).length() {
            2
        } else {
            1
        }
    };
    let mut cls: Vec<u8> = (0..n).map(|i| class(i, &prev, &nxt, &reflex)).collect();
    let mut alive = vec![true; n];
    let mut out = Vec::with_capacity(n - 2);
    let mut left = n;
    let mut cur = 0;
    // The first clear ear going round from `cur`, else the first flat one.
    let pick = |cur: usize, left: usize, cls: &[u8], nxt: &[usize]| {
        let mut flat = None;
        let mut i = cur;
        for _ in 0..left {
            match cls[i] {
                2 => return Some(i),
                1 if flat.is_none() => flat = Some(i),
                _ => {}
            }
            i = nxt[i];
        }
        flat
    };
    while left > 3 {
        // Removing an ear changes only its neighbours' classes, except that a reflex
        // neighbour turning convex stops blocking others: a class can be stale only as
        // "not an ear", so when no ear is left, all are recomputed once.
        let found = pick(cur, left, &cls, &nxt).or_else(|| {
            let mut i = cur;
            for _ in 0..left {
                cls[i] = class(i, &prev, &nxt, &reflex);
                i = nxt[i];
            }
            pick(cur, left, &cls, &nxt)
        });
        let i = found?;
        let (a, c) = (prev[i], nxt[i]);
        out.push([a, i, c]);
        alive[i] = false;
        nxt[a] = c;
        prev[c] = a;
        left -= 1;
        // The neighbours' turns changed; a reflex corner may have become convex.
        reflex.retain(|&r| alive[r] && (r != a && r != c || turn(r, &prev, &nxt) <= 0.0));
        cls[a] = class(a, &prev, &nxt, &reflex);
        cls[c] = class(c, &prev, &nxt, &reflex);
        // Go on past the new corner rather than at it: consecutive ears then go round
        // the loop instead of fanning from one vertex, a better start for the flips.
        cur = nxt[c];
    }
    let a = cur;
    let (b, c) = (nxt[a], nxt[nxt[a]]);
    if orient(a, b, c) <= 0.0 {
        return None;
    }
    out.push([a, b, c]);
    delaunay_flips(&p, &mut out);
    Some(out.into_iter().map(|t| t.map(|k| lp[k])).collect())
}

/// Lawson's flips: turns a triangulation of a polygon into its constrained Delaunay
/// triangulation by flipping every interior edge whose opposite vertex lies inside the
/// circumcircle (exact `incircle`), until none does. Boundary edges are never flipped.
/// Triangles are counter-clockwise, as indices into `p`.
///
/// The ears alone are long fans; later cuts would cross many of them and multiply the
/// cap's vertices, which the well-shaped Delaunay triangles avoid.
fn delaunay_flips(p: &[DVec2], tris: &mut [[usize; 3]]) {
    const NONE: usize = usize::MAX;
    let coord = |i: usize| robust::Coord {
        x: p[i].x,
        y: p[i].y,
    };
    // nbr[t][k]: the triangle across edge k (tri[k] -> tri[k + 1]) of triangle t, found
    // through the edges grouped by first vertex (the vertices are 0..n, n - 2 triangles).
    let nv = tris.len() + 2;
    let mut nbr = vec![[NONE; 3]; tris.len()];
    {
        let mut start = vec![0usize; nv + 1];
        for tri in tris.iter() {
            for &v in tri {
                start[v + 1] += 1;
            }
        }
        for v in 0..nv {
            start[v + 1] += start[v];
        }
        let mut fill = start.clone();
        // (second vertex, triangle, edge slot)
        let mut out_edges = vec![(0usize, 0usize, 0usize); 3 * tris.len()];
        for (t, tri) in tris.iter().enumerate() {
            for k in 0..3 {
                out_edges[fill[tri[k]]] = (tri[(k + 1) % 3], t, k);
                fill[tri[k]] += 1;
            }
        }
        for (t, tri) in tris.iter().enumerate() {
            for k in 0..3 {
                let (a, b) = (tri[k], tri[(k + 1) % 3]);
                if let Some(&(_, u, _)) =
                    out_edges[start[b]..start[b + 1]].iter().find(|e| e.0 == a)
                {
                    nbr[t][k] = u;
                }
            }
        }
    }
    let mut stack: Vec<(usize, usize)> = Vec::with_capacity(tris.len() * 3);
    for (t, nb) in nbr.iter().enumerate() {
        for (k, &u) in nb.iter().enumerate() {
            if u != NONE && t < u {
                stack.push((t, k));
            }
        }
    }
    // Each flip strictly increases the triangulation's angle vector; the bound only
    // guards against the unexpected (incircle is exact, so it is never reached).
    let mut budget = 16 * tris.len() * tris.len() + 64;
    while let Some((t1, k1)) = stack.pop() {
        let t2 = nbr[t1][k1];
        if t2 == NONE {
            continue;
        }
        // t1 = a b c with edge a -> b at k1; t2 has b -> a at k2, third vertex d.
        let (a, b, c) = (tris[t1][k1], tris[t1][(k1 + 1) % 3], tris[t1][(k1 + 2) % 3]);
        let Some(k2) = (0..3).find(|&k| tris[t2][k] == b && tris[t2][(k + 1) % 3] == a) else {
            continue;
        };
        let d = tris[t2][(k2 + 2) % 3];
        if robust::incircle(coord(a), coord(b), coord(c), coord(d)) <= 0.0 {
            continue;
        }
        if budget == 0 {
            break;
        }
        budget -= 1;
        // Outer neighbours: across b -> c and c -> a in t1, a -> d and d -> b in t2.
        let n_bc = nbr[t1][(k1 + 1) % 3];
        let n_ca = nbr[t1][(k1 + 2) % 3];
        let n_ad = nbr[t2][(k2 + 1) % 3];
        let n_db = nbr[t2][(k2 + 2) % 3];
        // New t1 = a d c (edges a->d, d->c, c->a), new t2 = d b c (d->b, b->c, c->d).
        tris[t1] = [a, d, c];
        tris[t2] = [d, b, c];
        nbr[t1] = [n_ad, t2, n_ca];
        nbr[t2] = [n_db, n_bc, t1];
        let mut relink = |u: usize, old: usize, new: usize| {
            if u != NONE {
                for slot in &mut nbr[u] {
                    if *slot == old {
                        *slot = new;
                    }
                }
            }
        };
        relink(n_ad, t2, t1);
        relink(n_bc, t1, t2);
        stack.extend([(t1, 0), (t1, 2), (t2, 0), (t2, 1)]);
    }
}
