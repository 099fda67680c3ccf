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
    let [neg, _] = cut(piece, plane, eps, false);
    neg
}

/// Both sides of `piece` cut by `plane`: `[clip(piece, plane), clip(piece, flipped)]`
/// (the same pieces), made in one pass with the cut points and the cap computed once.
///
/// Both sides' caps are the part of the plane with the solid on both sides, so one is
/// the other reversed: the sides share their cut points, and faces lying in the plane
/// are kept by one side only. The positive side checks that its boundary is the
/// negative one's reversed before taking its cap, and triangulates its own otherwise.
pub(crate) fn split(piece: &Piece, plane: &Plane, eps: f64) -> [Option<Piece>; 2] {
    cut(piece, plane, eps, true)
}

/// The negative side of `piece` cut by `plane` and, with `both`, the positive side (as
/// `clip` by the flipped plane would give it); `None` for a side the plane misses.
fn cut(piece: &Piece, plane: &Plane, eps: f64, both: bool) -> [Option<Piece>; 2] {
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
    };
    let (mut neg_side, mut pos_side) = (side(), if both { side() } else { Piece::default() });
    // Per vertex of `pos`: does it lie on the plane?
    let mut on_plane: Vec<bool> = s.iter().map(|&v| v == 0.0).collect();
    let mut cuts: FastMap<(u32, u32), u32> = FastMap::default();
    cuts.reserve(64);

    for (t, tri) in piece.tris.iter().enumerate() {
        let sv = tri.map(|i| s[i as usize]);
        let neg = sv.iter().filter(|&&v| v < 0.0).count();
        let posc = sv.iter().filter(|&&v| v > 0.0).count();
        let tag = piece.tags[t];
        if posc == 0 && neg == 0 {
            // A face lying in the plane bounds the side below it (the one it faces away
            // from); a flat one bounds neither.
            let [a, b, c] = tri.map(|i| piece.pos[i as usize]);
            let facing = (b - a).cross(c - a).dot(plane.n);
            if facing > 0.0 {
                neg_side.tris.push(*tri);
                neg_side.tags.push(tag);
            } else if facing < 0.0 && both {
                pos_side.tris.push(*tri);
                pos_side.tags.push(tag);
            }
            continue;
        }
        if posc == 0 {
            neg_side.tris.push(*tri);
            neg_side.tags.push(tag);
            continue;
        }
        if neg == 0 {
            if both {
                pos_side.tris.push(*tri);
                pos_side.tags.push(tag);
            }
            continue;
        }
        // A straddling triangle: each side's part is at most a quadrilateral, the
        // corners in the triangle's order, fanned from the first.
        let mut polys: [[u32; 4]; 2] = [[0; 4]; 2];
        let mut m = [0usize; 2];
        for k in 0..3 {
            let (i, j) = (tri[k], tri[(k + 1) % 3]);
            let (si, sj) = (s[i as usize], s[j as usize]);
            if si <= 0.0 {
                polys[0][m[0]] = i;
                m[0] += 1;
            }
            if si >= 0.0 {
                polys[1][m[1]] = i;
                m[1] += 1;
            }
            if (si < 0.0 && sj > 0.0) || (si > 0.0 && sj < 0.0) {
                let key = (i.min(j), i.max(j));
                let v = *cuts.entry(key).or_insert_with(|| {
                    let (a, b) = key;
                    let (pa, pb) = (piece.pos[a as usize], piece.pos[b as usize]);
                    let (sa, sb) = (s[a as usize], s[b as usize]);
                    let tt = sa / (sa - sb);
                    pos.push(pa + (pb - pa) * tt);
                    on_plane.push(true);
                    (pos.len() - 1) as u32
                });
                for h in 0..2 {
                    polys[h][m[h]] = v;
                    m[h] += 1;
                }
            }
        }
        let sides = if both { 2 } else { 1 };
        for (h, out) in [&mut neg_side, &mut pos_side]
            .into_iter()
            .enumerate()
            .take(sides)
        {
            for k in 1..m[h] - 1 {
                out.tris.push([polys[h][0], polys[h][k], polys[h][k + 1]]);
                out.tags.push(tag);
            }
        }
    }

    let neg_boundary = boundary_edges(&neg_side.tris, &on_plane, cuts.len());
    let cap_of = |boundary: &[(u32, u32)], plane: &Plane| {
        if boundary.is_empty() {
            Vec::new()
        } else {
            triangulate_cap(&pos, boundary, plane)
        }
    };
    let neg_cap = cap_of(&neg_boundary, plane);
    let mut pos_piece = None;
    if both {
        let pos_boundary = boundary_edges(&pos_side.tris, &on_plane, cuts.len());
        // The same loops reversed (as sets; each vertex starts one boundary edge)?
        let mut reversed: Vec<(u32, u32)> = neg_boundary.iter().map(|&(a, b)| (b, a)).collect();
        let mut mine = pos_boundary.clone();
        reversed.sort_unstable();
        mine.sort_unstable();
        let cap: Vec<[u32; 3]> = if reversed == mine {
            neg_cap.iter().map(|t| [t[0], t[2], t[1]]).collect()
        } else {
            cap_of(&pos_boundary, &plane.flipped())
        };
        pos_side.tris.extend_from_slice(&cap);
        pos_side
            .tags
            .extend(std::iter::repeat_n(plane.tag, cap.len()));
        pos_side.pos.clone_from(&pos);
        pos_side.compact();
        pos_piece = Some(pos_side);
    }
    neg_side.tris.extend_from_slice(&neg_cap);
    neg_side
        .tags
        .extend(std::iter::repeat_n(plane.tag, neg_cap.len()));
    neg_side.pos = pos;
    neg_side.compact();
    [Some(neg_side), pos_piece]
}

/// Boundary edges of a kept surface: directed edges whose reverse is missing. Both ends
/// of a boundary edge lie on the plane, so only such edges are collected. `cuts` sizes
/// the set.
fn boundary_edges(tris: &[[u32; 3]], on_plane: &[bool], cuts: usize) -> Vec<(u32, u32)> {
    let mut directed: FastSet<(u32, u32)> = FastSet::default();
    directed.reserve(2 * cuts + 16);
    for t in tris {
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            if on_plane[a as usize] && on_plane[b as usize] {
                directed.insert((a, b));
            }
        }
    }
    let mut boundary = Vec::new();
    for t in tris {
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            if on_plane[a as usize] && on_plane[b as usize] && !directed.contains(&(b, a)) {
                boundary.push((a, b));
            }
        }
    }
    boundary
}
