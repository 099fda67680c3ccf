//! Convex pieces for collision: a convex fragment is one piece; a concave one is cut
//! along its most violated face planes until the pieces are convex.
//!
//! (Cutting with the exact plane clipper rather than merging Delaunay tetrahedra keeps
//! the pieces an exact cover of the fragment and needs no hull computations.)

use glam::DVec3;

use super::clip::split_keeping_faces;
use super::edges::{Edge, for_each_edge};
use super::polytope::Polytope;
use super::{Piece, Plane, SURFACE, is_surface};
use crate::util::UnionFind;

/// Relative tolerance (of the fragment's size) for convexity tests.
const CONVEX_TOL: f64 = 1e-2;
/// Pieces smaller than this fraction of the fragment are dropped.
pub(crate) const MIN_PIECE_FRACTION: f64 = 1e-3;
/// At most this many convex pieces per fragment.
pub(crate) const MAX_PIECES: usize = 16;
/// At most this many convex pieces for a solid whose pieces are kept to be clipped later
/// ([`fine_pieces`]). The bird needs about 60 to be convex within the tolerance; at 16,
/// its pieces' hulls exceed it by a fifth.
const FINE_MAX_PIECES: usize = 64;

/// The most a concave fragment's own hull may hold, over its volume, to be its one
/// convex piece in a runtime cut ([`super::inherit`]: a dent of a few percent is not
/// worth the time there). A precomputed fracture decomposes such a fragment all the
/// same: on the bird resting on the ground, hulls of its concave cells made it rock
/// without end and wear its bonds out.
pub(crate) const ONE_PIECE: f64 = 1.05;

/// Convex pieces of a closed fragment (each with a non-degenerate volume). A fragment
/// with no edge concave beyond the tolerance is one piece: for a connected, embedded
/// closed surface, convex edges everywhere mean a convex solid. Any other is decomposed.
pub(crate) fn convex_pieces(piece: &Piece) -> Vec<Vec<DVec3>> {
    let total = piece.volume();
    let tol = CONVEX_TOL * super::mesh_scale(piece);
    let first = if total > 0.0 {
        worst_face(piece, tol)
    } else {
        (tol, None)
    };
    if first.1.is_none() {
        return vec![piece.pos.clone()];
    }
    let mut parts = Vec::new();
    decompose_into(piece, first, tol, MAX_PIECES, &mut parts);
    // Pieces under `MIN_PIECE_FRACTION` of the fragment are dropped (their volume is
    // negligible for collision).
    let pieces: Vec<Vec<DVec3>> = parts
        .into_iter()
        .filter(|p| p.volume() >= MIN_PIECE_FRACTION * total)
        .map(|p| p.pos)
        .collect();
    if pieces.is_empty() {
        vec![piece.pos.clone()]
    } else {
        pieces
    }
}

/// Convex pieces with their hulls: each piece's points, and the triangles of its hull over
/// them (as [`crate::fracture::Fragment::convex_pieces`] and `convex_hulls`).
pub(crate) type ConvexPieces = (Vec<Vec<DVec3>>, Vec<Vec<[u32; 3]>>);

/// Convex pieces of a closed solid that are kept to be clipped later (an intact body cut
/// at runtime, see [`super::inherit`]): [`decomposed_with_hulls`] into up to
/// `FINE_MAX_PIECES`.
pub(crate) fn fine_pieces(piece: &Piece) -> ConvexPieces {
    decomposed_with_hulls(piece, FINE_MAX_PIECES)
}

/// Convex pieces of a closed solid, each with its hull's triangles: decomposed as
/// [`convex_pieces`] does, into up to `max_pieces`, each piece's points reduced to the
/// corners of its hull ([`Polytope::hull`]; a piece whose hull cannot be found keeps its
/// points and has no triangles).
pub(crate) fn decomposed_with_hulls(piece: &Piece, max_pieces: usize) -> ConvexPieces {
    let total = piece.volume();
    let parts = if total > 0.0 {
        decomposition_parts_with(piece, CONVEX_TOL, max_pieces)
    } else {
        None
    };
    let mut points: Vec<Vec<DVec3>> = match parts {
        Some(parts) => parts
            .into_iter()
            .filter(|p| p.volume() >= MIN_PIECE_FRACTION * total)
            .map(|p| p.pos)
            .collect(),
        None => Vec::new(),
    };
    if points.is_empty() {
        points.push(piece.pos.clone());
    }
    points
        .into_iter()
        .map(|p| match Polytope::hull(&p) {
            Some(h) => h.to_mesh(),
            None => (p, Vec::new()),
        })
        .unzip()
}

/// Volume of the tetrahedron `[a, b, c, d]` (signed).
pub(crate) fn tet_volume(p: [DVec3; 4]) -> f64 {
    (p[1] - p[0]).dot((p[2] - p[0]).cross(p[3] - p[0])) / 6.0
}

/// Outward faces of a positively oriented tetrahedron, indexed by the opposite vertex.
pub(crate) const TET_FACES: [[usize; 3]; 4] = [[1, 2, 3], [0, 3, 2], [0, 1, 3], [0, 2, 1]];

/// The parts of a concave solid (none dropped, their caps left as faces: closed, their
/// volumes adding up to the solid's); `None` when it is convex within the tolerance.
///
/// It is split along the plane of its most violated face (the face with a vertex
/// farthest in front of it), again and again, worst part first, until every part is
/// convex within the tolerance or `MAX_PIECES` is reached. The clipping is exact, so
/// the parts cover the solid without gaps.
#[cfg(test)]
pub(crate) fn decomposition_parts(piece: &Piece) -> Option<Vec<Piece>> {
    decomposition_parts_with(piece, CONVEX_TOL, MAX_PIECES)
}

/// The convex parts of `piece` (the tests' `decomposition_parts`) with its tolerance
/// (relative to the solid's size) and the most parts it makes.
fn decomposition_parts_with(piece: &Piece, rel_tol: f64, max_pieces: usize) -> Option<Vec<Piece>> {
    let tol = rel_tol * super::mesh_scale(piece);
    let first = worst_face(piece, tol);
    first.1?;
    let mut parts = Vec::new();
    decompose_into(piece, first, tol, max_pieces, &mut parts);
    Some(parts)
}

/// The loop of [`decomposition_parts_with`]: the parts of `piece`, split worst first, into
/// `out`.
fn decompose_into(
    piece: &Piece,
    first: (f64, Option<Plane>),
    tol: f64,
    max_pieces: usize,
    out: &mut Vec<Piece>,
) {
    let eps = 1e-10 * tol.max(f64::MIN_POSITIVE) / CONVEX_TOL;
    // (violation, face plane, piece)
    let mut work: Vec<(f64, Option<Plane>, Piece)> = vec![(first.0, first.1, piece.clone())];
    loop {
        if work.len() >= max_pieces {
            break;
        }
        let Some(k) = (0..work.len())
            .filter(|&k| work[k].1.is_some())
            .max_by(|&a, &b| work[a].0.total_cmp(&work[b].0).then(b.cmp(&a)))
        else {
            break;
        };
        let (_, plane, p) = work.swap_remove(k);
        let Some(plane) = plane else { break };
        let mut parts = Vec::new();
        let mut sides = 0;
        for side in split_keeping_faces(&p, &plane, eps) {
            if let Some(q) = side.filter(|q| !q.is_empty()) {
                sides += 1;
                parts.extend(components_with_worst_face(q, tol));
            }
        }
        if sides < 2 {
            // No progress (rounding): keep the piece as it is.
            work.push((0.0, None, p));
            continue;
        }
        work.extend(parts);
    }
    out.extend(work.into_iter().map(|(_, _, p)| p));
}

/// The edge-connected components of `p`, each with its [`worst_face`]: pairing each
/// directed edge with its reverse serves both (it joins the two triangles and gives the
/// vertex across the edge).
fn components_with_worst_face(mut p: Piece, tol: f64) -> Vec<(f64, Option<Plane>, Piece)> {
    // A face of several loops may be several regions.
    p.faces_into_regions();
    let n = p.tris.len();
    let (nbr, mut uf) = neighbours(&p);
    // The triangles violating convexity beyond `tol` (few: most edges are convex), with
    // their violation and plane, in triangle order.
    let concave: Vec<(usize, f64, Plane)> = (0..n)
        .filter_map(|t| concavity(&p, t, &nbr, tol).map(|(v, plane)| (t, v, plane)))
        .collect();
    let (parts, group) = p.into_groups(&mut uf);
    let mut out: Vec<(f64, Option<Plane>, Piece)> =
        parts.into_iter().map(|q| (tol, None, q)).collect();
    for (t, violation, plane) in concave {
        // The first triangle with the largest violation, as worst_face picks it.
        let g = group[t];
        if violation > out[g].0 {
            out[g].0 = violation;
            out[g].1 = Some(plane);
        }
    }
    out
}

/// Marker in [`neighbours`] for an edge without a reverse.
const NO_NEIGHBOUR: u32 = u32::MAX;

/// Per triangle of `p`, the triangle across each edge `k` (`tri[k] → tri[k + 1]`), found
/// by pairing each directed edge with an unpaired reverse before it (in
/// [`Piece::edges`] order, per undirected edge: [`for_each_edge`], no map), and the
/// union of the triangles and faces so joined (face `f` is element `tris.len() + f`).
/// An edge shared with a face has no neighbour triangle: a face is a cut, which makes no
/// concave edge.
fn neighbours(p: &Piece) -> (Vec<[u32; 3]>, UnionFind) {
    let n = p.tris.len();
    let mut nbr = vec![[NO_NEIGHBOUR; 3]; n];
    let mut uf = UnionFind::new(n + p.faces.len());
    // Per undirected edge, its unpaired directed edge in each direction (from the lower
    // vertex, from the upper); a later one of the same direction replaces it. A face's
    // edges carry slot 3, which names no triangle edge.
    for_each_edge(p, |open: &mut [Option<Edge>; 2], e| {
        let dir = usize::from(e.a > e.b);
        if let Some(u) = open[1 - dir].take() {
            if e.slot < 3 && u.slot < 3 {
                nbr[e.elem as usize][e.slot as usize] = u.elem;
                nbr[u.elem as usize][u.slot as usize] = e.elem;
            }
            uf.union(e.elem as usize, u.elem as usize);
        } else {
            open[dir] = Some(e);
        }
    });
    (nbr, uf)
}

/// How far the vertices across the edges of triangle `t` of `p` lie in front of its
/// plane, when the farthest lies beyond `tol`: that distance and the plane. `nbr` are
/// the triangles' neighbours ([`neighbours`]); the vertex across edge `k` is the one
/// opposite it in the neighbour there. The normal stays unnormalised until a violation
/// shows up, so the common convex edges need no square root.
fn concavity(p: &Piece, t: usize, nbr: &[[u32; 3]], tol: f64) -> Option<(f64, Plane)> {
    // A cap lies on a plane the whole solid is behind (a cell face, a slicing plane), so
    // no vertex lies in front of it, and its edges with the surface are convex: only
    // edges between two surface triangles can be concave. (The decomposition's own
    // cuts are tagged as surface of no input triangle, [`SURFACE`], so they are tested
    // like it.)
    if !is_surface(p.tags[t]) {
        return None;
    }
    let tri = p.tris[t];
    let [a, b, c] = tri.map(|i| p.pos[i as usize]);
    let normal = (b - a).cross(c - a);
    let len2 = normal.length_squared();
    let mut raw = 0.0f64;
    for k in 0..3 {
        let u = nbr[t][k];
        let (ea, eb) = (tri[k], tri[(k + 1) % 3]);
        if u != NO_NEIGHBOUR
            && is_surface(p.tags[u as usize])
            && len2 > 0.0
            && let Some(o) = p.tris[u as usize].into_iter().find(|&v| v != ea && v != eb)
        {
            raw = raw.max(normal.dot(p.pos[o as usize] - a));
        }
    }
    if raw > 0.0 && raw * raw > tol * tol * len2 {
        let len = len2.sqrt();
        let n = normal / len;
        Some((
            raw / len,
            Plane {
                n,
                d: n.dot(a),
                tag: SURFACE,
            },
        ))
    } else {
        None
    }
}

/// The face with the most concave edge of `p` (the vertex across the edge farthest in
/// front of the face's plane), as a plane; `None` when no edge is concave beyond `tol`.
fn worst_face(p: &Piece, tol: f64) -> (f64, Option<Plane>) {
    let (nbr, _) = neighbours(p);
    let mut best: (f64, Option<Plane>) = (tol, None);
    for t in 0..p.tris.len() {
        if let Some((v, plane)) = concavity(p, t, &nbr, best.0) {
            best = (v, Some(plane));
        }
    }
    best
}
