//! Clipping a closed solid by a plane, keeping the part on the plane's negative side as
//! a closed solid (the cut is capped; see [`super::cap`]).

use glam::DVec3;

use super::cap::triangulate_cap;
use super::piece::{FastMap, FastSet, Piece};

/// An oriented plane `n · x = d`; its negative side `n · x < d` is kept by [`clip`].
/// `tag` is written on the cap triangles the plane creates.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Plane {
    pub n: DVec3,
    pub d: f64,
    pub tag: u64,
}

impl Plane {
    /// The same plane with the other side kept (negation is exact in floating point, so
    /// both sides classify every vertex identically and share their cut vertices).
    pub fn flipped(self) -> Self {
        Self {
            n: -self.n,
            d: -self.d,
            tag: self.tag,
        }
    }

    /// Signed distance times `|n|`.
    #[inline]
    pub fn eval(&self, p: DVec3) -> f64 {
        self.n.dot(p) - self.d
    }
}

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
    clip_with(piece, plane, eps, None).map(|c| c.piece)
}

/// Both sides of `piece` cut by `plane`: `[clip(piece, plane), clip(piece, flipped)]`,
/// with the cap triangulated once when it can be shared.
///
/// Both sides' caps are the part of the plane with the solid on both sides, so one is
/// the other reversed: the two clips meet the same straddling edges in the same order
/// and number the cut points alike (negating the plane is exact), and faces lying in the
/// plane are kept by one side only. The second side checks that its boundary is the
/// first one's reversed before taking its cap, and triangulates its own otherwise.
pub(crate) fn split(piece: &Piece, plane: &Plane, eps: f64) -> [Option<Piece>; 2] {
    let flipped = plane.flipped();
    match clip_with(piece, plane, eps, None) {
        Some(Clipped {
            piece: neg,
            cap: Some(cap),
        }) => {
            let pos = clip_with(piece, &flipped, eps, Some(&cap)).map(|c| c.piece);
            [Some(neg), pos]
        }
        neg => [neg.map(|c| c.piece), clip(piece, &flipped, eps)],
    }
}

/// A cap as numbered before compaction: its sorted boundary edges and its triangles.
struct Cap {
    boundary: Vec<(u32, u32)>,
    tris: Vec<[u32; 3]>,
}

/// What [`clip_with`] returns: the kept part and, when it has one, its cap.
struct Clipped {
    piece: Piece,
    cap: Option<Cap>,
}

/// [`clip`], returning the cap too; with `other` (the cap of the other side), its
/// triangles reversed are taken as the cap when the boundaries match.
fn clip_with(piece: &Piece, plane: &Plane, eps: f64, other: Option<&Cap>) -> Option<Clipped> {
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
    if !any_pos {
        return None;
    }
    if !s.iter().any(|&v| v < 0.0) {
        return Some(Clipped {
            piece: Piece::default(),
            cap: None,
        });
    }

    // Room for the cut points and the cap, so that neither grows by reallocation.
    let extra = 64 + piece.tris.len() / 4;
    let mut pos = Vec::with_capacity(piece.pos.len() + extra);
    pos.extend_from_slice(&piece.pos);
    let mut out = Piece {
        pos,
        tris: Vec::with_capacity(piece.tris.len() + 2 * extra),
        tags: Vec::with_capacity(piece.tris.len() + 2 * extra),
    };
    // Per vertex of `out`: does it lie on the plane?
    let mut on_plane: Vec<bool> = s.iter().map(|&v| v == 0.0).collect();
    let mut cut: FastMap<(u32, u32), u32> = FastMap::default();
    cut.reserve(64);

    for (t, tri) in piece.tris.iter().enumerate() {
        let sv = tri.map(|i| s[i as usize]);
        let neg = sv.iter().filter(|&&v| v < 0.0).count();
        let pos = sv.iter().filter(|&&v| v > 0.0).count();
        let tag = piece.tags[t];
        if pos == 0 && neg == 0 {
            // A face lying in the plane bounds the kept part if it faces the positive
            // side (the solid is below it). The flipped plane negates the test exactly,
            // so such a face is kept by exactly one side (or, if flat, by neither).
            let [a, b, c] = tri.map(|i| piece.pos[i as usize]);
            if (b - a).cross(c - a).dot(plane.n) > 0.0 {
                out.tris.push(*tri);
                out.tags.push(tag);
            }
            continue;
        }
        if pos == 0 {
            out.tris.push(*tri);
            out.tags.push(tag);
            continue;
        }
        if neg == 0 {
            continue;
        }
        // Negative part of a straddling triangle: at most a quadrilateral.
        let mut poly: [u32; 4] = [0; 4];
        let mut m = 0;
        for k in 0..3 {
            let (i, j) = (tri[k], tri[(k + 1) % 3]);
            let (si, sj) = (s[i as usize], s[j as usize]);
            if si <= 0.0 {
                poly[m] = i;
                m += 1;
            }
            if (si < 0.0 && sj > 0.0) || (si > 0.0 && sj < 0.0) {
                let key = (i.min(j), i.max(j));
                let v = *cut.entry(key).or_insert_with(|| {
                    let (a, b) = key;
                    let (pa, pb) = (piece.pos[a as usize], piece.pos[b as usize]);
                    let (sa, sb) = (s[a as usize], s[b as usize]);
                    let tt = sa / (sa - sb);
                    out.pos.push(pa + (pb - pa) * tt);
                    on_plane.push(true);
                    (out.pos.len() - 1) as u32
                });
                poly[m] = v;
                m += 1;
            }
        }
        for k in 1..m - 1 {
            out.tris.push([poly[0], poly[k], poly[k + 1]]);
            out.tags.push(tag);
        }
    }

    // Boundary edges of the kept surface: directed edges whose reverse is missing. Both
    // ends of a boundary edge lie on the plane, so only such edges are collected.
    let mut directed: FastSet<(u32, u32)> = FastSet::default();
    directed.reserve(2 * cut.len() + 16);
    for t in &out.tris {
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            if on_plane[a as usize] && on_plane[b as usize] {
                directed.insert((a, b));
            }
        }
    }
    let mut boundary: Vec<(u32, u32)> = Vec::new();
    for t in &out.tris {
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            if on_plane[a as usize] && on_plane[b as usize] && !directed.contains(&(b, a)) {
                boundary.push((a, b));
            }
        }
    }
    let mut cap = None;
    if !boundary.is_empty() {
        let mut sorted = boundary.clone();
        sorted.sort_unstable();
        let shared = other.filter(|o| {
            o.boundary.len() == sorted.len()
                && o.boundary
                    .iter()
                    .all(|&(a, b)| sorted.binary_search(&(b, a)).is_ok())
        });
        let tris: Vec<[u32; 3]> = match shared {
            Some(o) => o.tris.iter().map(|t| [t[0], t[2], t[1]]).collect(),
            None => triangulate_cap(&out.pos, &boundary, plane),
        };
        out.tris.extend_from_slice(&tris);
        out.tags.extend(std::iter::repeat_n(plane.tag, tris.len()));
        cap = Some(Cap {
            boundary: sorted,
            tris,
        });
    }
    out.compact();
    Some(Clipped { piece: out, cap })
}
