//! Clipping a closed solid by a plane, keeping the part on the plane's negative side as
//! a closed solid (the cut is capped; see [`super::cap`]).

use glam::DVec3;

use super::{Face, Piece, Plane};
use crate::util::{FastMap, FastSet};

/// Clips `piece` by `plane`, keeping the closed part on the negative side.
///
/// Vertices within `eps · |n|` of the plane count as lying on it. Triangles with a
/// vertex on each side are split at the edges' intersections, computed once per edge
/// from its lower-indexed end so that both triangles of an edge share the new vertex.
/// An original face lying in the plane is kept when it faces the positive side (it then
/// bounds the kept part) and dropped otherwise. The boundary edges of what is kept all
/// lie on the plane; they bound the cap, the part of the plane with the solid on both
/// sides, which is triangulated and tagged `plane.tag`. Returns `None` when the plane
/// misses the piece (everything is kept), so callers can skip the copy.
pub(crate) fn clip(piece: &Piece, plane: &Plane, eps: f64) -> Option<Piece> {
    let [neg, _] = cut(piece, plane, eps, false, false);
    neg
}

/// [`clip`], leaving the cap as a [`Face`] (a polygon) instead of triangles; the faces
/// of `piece` are cut as polygons. [`Piece::close_faces`] triangulates them at the end,
/// so a sequence of cuts triangulates each cap once, with only its own corners.
pub(crate) fn clip_keeping_faces(piece: &Piece, plane: &Plane, eps: f64) -> Option<Piece> {
    let [neg, _] = cut(piece, plane, eps, false, true);
    neg
}

/// Both sides of `piece` cut by `plane`: `[clip(piece, plane), clip(piece, flipped)]`
/// (the same pieces), made in one pass with the cut points computed once.
///
/// Both sides' caps are the part of the plane with the solid on both sides, so one is
/// the other reversed: the sides share their cut points, and faces lying in the plane
/// are kept by one side only. (Only the tests use it closed; the decomposition and
/// slicing keep the caps as faces, [`split_keeping_faces`].)
#[cfg(test)]
pub(crate) fn split(piece: &Piece, plane: &Plane, eps: f64) -> [Option<Piece>; 2] {
    cut(piece, plane, eps, true, false)
}

/// Both sides of `piece` cut by `plane` (the tests' `split`), leaving both caps as
/// [`Face`]s; the faces of `piece` are cut as polygons.
pub(crate) fn split_keeping_faces(piece: &Piece, plane: &Plane, eps: f64) -> [Option<Piece>; 2] {
    cut(piece, plane, eps, true, true)
}

/// The two sides of a cut being built: the positions (the piece's and the cut points),
/// which of them lie on the plane, the cut point of each crossed edge, and the kept
/// triangles and faces of each side (`out[0]` negative, `out[1]` positive).
struct Cutter<'a> {
    piece: &'a Piece,
    /// Per vertex of the piece: its signed distance, 0 within the tolerance.
    s: Vec<f64>,
    pos: Vec<DVec3>,
    on_plane: Vec<bool>,
    cuts: FastMap<(u32, u32), u32>,
    out: [Piece; 2],
    /// Per side, the edges of what is kept that run between two cut points: when no
    /// vertex of the piece lies on the plane, exactly its boundary.
    rims: [Vec<(u32, u32)>; 2],
    both: bool,
}

impl Cutter<'_> {
    /// The cut point of the crossed edge `i j` (one per undirected edge, computed from
    /// its lower-indexed end, so every triangle and face of the edge shares it).
    fn cut_point(&mut self, i: u32, j: u32) -> u32 {
        let key = (i.min(j), i.max(j));
        let (pos, on_plane, piece, s) = (&mut self.pos, &mut self.on_plane, self.piece, &self.s);
        *self.cuts.entry(key).or_insert_with(|| {
            let (a, b) = key;
            let (pa, pb) = (piece.pos[a as usize], piece.pos[b as usize]);
            let (sa, sb) = (s[a as usize], s[b as usize]);
            let tt = sa / (sa - sb);
            pos.push(pa + (pb - pa) * tt);
            on_plane.push(true);
            (pos.len() - 1) as u32
        })
    }

    fn keep(&mut self, side: usize, tri: [u32; 3], tag: u64) {
        if side == 0 || self.both {
            self.out[side].tris.push(tri);
            self.out[side].tags.push(tag);
        }
    }

    /// One triangle of the piece: kept by the side it lies on, or split between them.
    fn triangle(&mut self, tri: [u32; 3], tag: u64, plane: &Plane) {
        let sv = tri.map(|i| self.s[i as usize]);
        let neg = sv.iter().filter(|&&v| v < 0.0).count();
        let posc = sv.iter().filter(|&&v| v > 0.0).count();
        if posc == 0 && neg == 0 {
            // A face lying in the plane bounds the side below it (the one it faces away
            // from); a flat one bounds neither.
            let [a, b, c] = tri.map(|i| self.piece.pos[i as usize]);
            let facing = (b - a).cross(c - a).dot(plane.n);
            if facing > 0.0 {
                self.keep(0, tri, tag);
            } else if facing < 0.0 {
                self.keep(1, tri, tag);
            }
            return;
        }
        if posc == 0 {
            self.keep(0, tri, tag);
            return;
        }
        if neg == 0 {
            self.keep(1, tri, tag);
            return;
        }
        // A straddling triangle: each side's part is at most a quadrilateral, the
        // corners in the triangle's order, fanned from the first.
        let mut polys: [[u32; 4]; 2] = [[0; 4]; 2];
        let mut m = [0usize; 2];
        // Where the cut points went in each side's part.
        let mut at = [[0usize; 2]; 2];
        let mut cuts = [0usize; 2];
        for k in 0..3 {
            let (i, j) = (tri[k], tri[(k + 1) % 3]);
            let (si, sj) = (sv[k], sv[(k + 1) % 3]);
            if si <= 0.0 {
                polys[0][m[0]] = i;
                m[0] += 1;
            }
            if si >= 0.0 {
                polys[1][m[1]] = i;
                m[1] += 1;
            }
            if (si < 0.0 && sj > 0.0) || (si > 0.0 && sj < 0.0) {
                let v = self.cut_point(i, j);
                for h in 0..2 {
                    at[h][cuts[h] & 1] = m[h];
                    cuts[h] += 1;
                    polys[h][m[h]] = v;
                    m[h] += 1;
                }
            }
        }
        for h in 0..2 {
            if cuts[h] == 2 && (h == 0 || self.both) {
                // The two cut points follow each other round the part.
                let [p, q] = at[h];
                let (a, b) = if q == p + 1 { (p, q) } else { (q, p) };
                self.rims[h].push((polys[h][a], polys[h][b]));
            }
            for k in 1..m[h] - 1 {
                self.keep(h, [polys[h][0], polys[h][k], polys[h][k + 1]], tag);
            }
        }
    }

    /// One face of the piece, as a polygon: kept whole by the side it lies on, or its
    /// edges split and each side's part closed along the cut line. A face with a corner
    /// on the plane, or nearly parallel to it, is triangulated and its triangles cut
    /// instead (the polygon rule below assumes every crossing is a cut point).
    fn face(&mut self, face: &Face, plane: &Plane) {
        let (mut neg, mut posc, mut zero) = (0, 0, 0);
        for &(a, _) in &face.edges {
            match self.s[a as usize] {
                v if v < 0.0 => neg += 1,
                v if v > 0.0 => posc += 1,
                _ => zero += 1,
            }
        }
        if zero == 0 && posc == 0 {
            self.out[0].faces.push(face.clone());
            return;
        }
        if zero == 0 && neg == 0 {
            if self.both {
                self.out[1].faces.push(face.clone());
            }
            return;
        }
        let m = face.plane.n;
        // Along the cut line, the negative side's closing edges run along m × n (the
        // part kept lies to their left, on the negative side).
        let along = m.cross(plane.n);
        let parallel =
            along.length_squared() <= 1e-12 * m.length_squared() * plane.n.length_squared();
        if zero > 0 || parallel || !self.face_as_polygon(face, along) {
            self.face_as_triangles(face, plane);
        }
    }

    /// The polygon cut of [`Cutter::face`]; `false` (nothing kept) when the crossings
    /// along the cut line do not alternate as a polygon's must (rounding in a nearly
    /// degenerate cut), for the caller to fall back on triangles.
    fn face_as_polygon(&mut self, face: &Face, along: DVec3) -> bool {
        let sides = if self.both { 2 } else { 1 };
        // (Sized up front: a side keeps at most every edge and two per crossing.)
        let room = face.edges.len() + 4;
        let mut kept: [Vec<(u32, u32)>; 2] = [
            Vec::with_capacity(room),
            Vec::with_capacity(if self.both { room } else { 0 }),
        ];
        // Per side: (position along the line, cut point, whether the side's boundary
        // leaves the face's edges there (true) or comes back to them).
        let mut crossings: [Vec<(f64, u32, bool)>; 2] =
            [Vec::with_capacity(4), Vec::with_capacity(4)];
        for &(a, b) in &face.edges {
            let (sa, sb) = (self.s[a as usize], self.s[b as usize]);
            if sa < 0.0 && sb < 0.0 {
                kept[0].push((a, b));
            } else if sa > 0.0 && sb > 0.0 {
                kept[1].push((a, b));
            } else {
                let x = self.cut_point(a, b);
                let t = along.dot(self.pos[x as usize]);
                let (from, to) = if sa < 0.0 { (0, 1) } else { (1, 0) };
                kept[from].push((a, x));
                kept[to].push((x, b));
                // The positive side runs along the line the other way.
                let signed = |h: usize| if h == 0 { t } else { -t };
                crossings[from].push((signed(from), x, true));
                crossings[to].push((signed(to), x, false));
            }
        }
        let mut closing: [Vec<(u32, u32)>; 2] = [Vec::new(), Vec::new()];
        for h in 0..sides {
            let list = &mut crossings[h];
            list.sort_unstable_by(|p, q| p.0.total_cmp(&q.0));
            // Along the line: where the boundary leaves the edges, then where it comes
            // back, the face's inside between them, and so on.
            for (k, pair) in list.chunks(2).enumerate() {
                let [(t0, exit, true), (t1, entry, false)] = *pair else {
                    return false;
                };
                if t1 <= t0 || list.get(2 * k + 2).is_some_and(|next| next.0 <= t1) {
                    return false;
                }
                closing[h].push((exit, entry));
            }
        }
        for h in 0..sides {
            self.rims[h].extend_from_slice(&closing[h]);
            let mut edges = std::mem::take(&mut kept[h]);
            edges.append(&mut closing[h]);
            let plane = face.plane;
            self.out[h].faces.push(Face { plane, edges });
        }
        true
    }

    fn face_as_triangles(&mut self, face: &Face, plane: &Plane) {
        for tri in face.triangles(&self.piece.pos) {
            self.triangle(tri, face.plane.tag, plane);
        }
    }
}

/// The negative side of `piece` cut by `plane` and, with `both`, the positive side (as
/// `clip` by the flipped plane would give it); `None` for a side the plane misses. With
/// `keep_faces` the caps are left as [`Face`]s, else every face is triangulated.
fn cut(piece: &Piece, plane: &Plane, eps: f64, both: bool, keep_faces: bool) -> [Option<Piece>; 2] {
    let tol = eps * plane.n.length();
    let s: Vec<f64> = piece
        .pos
        .iter()
        .map(|&p| {
            let v = plane.eval(p);
            if v.abs() <= tol { 0.0 } else { v }
        })
        .collect();
    let any_pos = s.iter().any(|&v| v > 0.0);
    let any_neg = s.iter().any(|&v| v < 0.0);
    if !any_pos || !any_neg {
        // Nothing to cut: the side the piece lies on keeps it whole, the other is empty.
        let whole = |kept: bool| if kept { None } else { Some(Piece::default()) };
        return [whole(!any_pos), if both { whole(!any_neg) } else { None }];
    }

    // Room for the cut points and the cap, so that nothing grows by reallocation.
    let extra = 64 + piece.tris.len() / 4;
    let mut pos = Vec::with_capacity(piece.pos.len() + extra);
    pos.extend_from_slice(&piece.pos);
    let side = || Piece {
        pos: Vec::new(),
        tris: Vec::with_capacity(piece.tris.len() + 2 * extra),
        tags: Vec::with_capacity(piece.tris.len() + 2 * extra),
        faces: Vec::with_capacity(piece.faces.len() + 1),
    };
    let on_plane: Vec<bool> = s.iter().map(|&v| v == 0.0).collect();
    // With a vertex on the plane, kept edges can lie in it: the boundary is then found
    // by pairing edges; otherwise it is the edges between cut points.
    let any_on_plane = on_plane.contains(&true);
    let mut cuts: FastMap<(u32, u32), u32> = FastMap::default();
    cuts.reserve(64);
    let mut c = Cutter {
        piece,
        s,
        pos,
        on_plane,
        cuts,
        out: [side(), if both { side() } else { Piece::default() }],
        rims: [
            Vec::with_capacity(extra),
            Vec::with_capacity(if both { extra } else { 0 }),
        ],
        both,
    };
    for (tri, &tag) in piece.tris.iter().zip(&piece.tags) {
        // Most triangles lie wholly on one side: kept or dropped as they are.
        let [a, b, d] = tri.map(|i| c.s[i as usize]);
        if a < 0.0 && b < 0.0 && d < 0.0 {
            c.out[0].tris.push(*tri);
            c.out[0].tags.push(tag);
        } else if a > 0.0 && b > 0.0 && d > 0.0 {
            c.keep(1, *tri, tag);
        } else {
            c.triangle(*tri, tag, plane);
        }
    }
    for face in &piece.faces {
        c.face(face, plane);
    }
    let Cutter {
        pos,
        on_plane,
        cuts,
        out: [neg_side, pos_side],
        rims: [neg_rim, pos_rim],
        ..
    } = c;
    let boundary = |side: &Piece, rim: Vec<(u32, u32)>| {
        if any_on_plane {
            boundary_edges(side, &on_plane, cuts.len())
        } else {
            // (Checked in every test run against the pairing it replaces.)
            debug_assert!({
                let mut paired = boundary_edges(side, &on_plane, cuts.len());
                let mut mine = rim.clone();
                paired.sort_unstable();
                mine.sort_unstable();
                paired == mine
            });
            rim
        }
    };

    // Each side's cap is the face its boundary bounds; the two are one region of the
    // plane, seen from either side.
    let cap = |boundary: Vec<(u32, u32)>, plane: Plane| Face {
        plane,
        edges: boundary.into_iter().map(|(a, b)| (b, a)).collect(),
    };
    let finish = |mut side: Piece, rim: Vec<(u32, u32)>, plane: Plane, pos: Vec<DVec3>| {
        let boundary = boundary(&side, rim);
        if !boundary.is_empty() {
            side.faces.push(cap(boundary, plane));
        }
        side.pos = pos;
        side.compact();
        if !keep_faces {
            side.close_faces();
        }
        side
    };
    let pos_piece = both.then(|| finish(pos_side, pos_rim, plane.flipped(), pos.clone()));
    [Some(finish(neg_side, neg_rim, *plane, pos)), pos_piece]
}

/// Boundary edges of a kept surface (triangles and faces): directed edges whose reverse
/// is missing. Both ends of a boundary edge lie on the plane, so only such edges are
/// collected. `cuts` sizes the set.
fn boundary_edges(side: &Piece, on_plane: &[bool], cuts: usize) -> Vec<(u32, u32)> {
    let on = |&(a, b): &(u32, u32)| on_plane[a as usize] && on_plane[b as usize];
    let edges = || side.edges().map(|(_, _, a, b)| (a, b)).filter(on);
    let mut directed: FastSet<(u32, u32)> = FastSet::default();
    directed.reserve(2 * cuts + 16);
    directed.extend(edges());
    edges()
        .filter(|&(a, b)| !directed.contains(&(b, a)))
        .collect()
}
