//! Convex pieces a fragment inherits from the solid it was cut from: each of the solid's
//! convex pieces clipped by the fragment's cell and bounding box, rather than the
//! fragment decomposed again.
//!
//! A cell is convex and so is a piece, so each intersection is a convex polytope
//! ([`Polytope::clip_into`]); the fragment is the solid within the cell, so these polytopes
//! cover it as the solid's pieces covered the solid. Clipping them by the fragment's
//! bounding box as well keeps them near the fragment where a piece's hull reaches past
//! the solid (a piece convex within the decomposition's tolerance only).
//!
//! Of the two, the smaller (by bounding box) is clipped by the planes of the other's
//! faces: most of them miss it, and each cut goes through a small polytope. (A cell near
//! the impact is small where a piece can have a hundred faces; a cell far from it can
//! hold whole pieces.)

use glam::DVec3;

use super::convex::{ConvexPieces, MIN_PIECE_FRACTION, ONE_PIECE};
use super::polytope::{Outcome, Polytope, Scratch};
use super::{Piece, Plane};
use crate::util::bounds;

/// The most a fragment's inherited pieces may hold, over its own volume. A piece is a hull
/// of a piece of the solid (convex only within the decomposition's tolerance), so it can
/// reach past the solid; in a small fragment that excess can be a large part of it (the
/// bird cut twice: up to two thirds). Beyond this the fragment is decomposed instead, as
/// finely as a fragment cut from scratch (whose hulls hold under 1.09 of it on the bird).
const MAX_EXCESS: f64 = 1.1;

/// A convex piece of the solid being cut: the polytope, its faces' planes and its bounds.
#[derive(Debug, Clone)]
pub(crate) struct Part {
    poly: Polytope,
    planes: Vec<Plane>,
    lo: DVec3,
    hi: DVec3,
}

impl Part {
    /// The piece with the hull triangles `hull` over `points`, or the points' own hull
    /// when `hull` is `None` or does not bound a polytope; `None` when the points span
    /// no volume.
    pub fn new(points: &[DVec3], hull: Option<&[[u32; 3]]>) -> Option<Part> {
        let poly = hull
            .and_then(|tris| Polytope::from_triangles(points, tris))
            .filter(|p| p.volume() > 0.0)
            .or_else(|| Polytope::hull(points))?;
        let (lo, hi) = poly.bounds();
        Some(Part {
            planes: poly.face_planes(),
            poly,
            lo,
            hi,
        })
    }
}

/// The convex pieces of fragment `p` (of volume `volume`), cut from the solid whose
/// convex pieces are `parts` by the cells `cells` (each the negative side of all its
/// planes; a fragment merged from several cells has them all).
///
/// A fragment whose own hull holds at most `ONE_PIECE` of it (most small ones: a cell of
/// a solid is convex where the solid is, near enough) is that hull, one piece. Any other
/// takes each cell within the fragment's bounding box, clipped by each part; pieces under
/// `MIN_PIECE_FRACTION` of the fragment are left out, and pieces holding more than
/// `MAX_EXCESS` times the fragment are cut back to its hull (or replaced by the hull when
/// it holds less). Returns the pieces' points and their hulls' triangles, or `None` when
/// no piece is left (the caller then decomposes the fragment).
pub(crate) fn inherited_pieces(
    p: &Piece,
    volume: f64,
    parts: &[Part],
    cells: &[&[Plane]],
    eps: f64,
) -> Option<ConvexPieces> {
    if p.pos.is_empty() || volume.is_nan() || volume <= 0.0 {
        return None;
    }
    let own = Polytope::hull(&p.pos)?;
    let own_volume = own.volume();
    if own_volume <= ONE_PIECE * volume {
        let (pos, tris) = own.to_mesh();
        return Some((vec![pos], vec![tris]));
    }
    let (lo, hi) = bounds(&p.pos);
    let min_volume = MIN_PIECE_FRACTION * volume;
    let mut pieces: Vec<(Polytope, f64)> = Vec::new();
    let mut scratch = Scratch::default();
    for planes in cells {
        let Some(cell) = clip_all(&Polytope::cuboid(lo, hi), planes, eps, &mut scratch) else {
            continue;
        };
        let (clo, chi) = cell.bounds();
        let cell_volume = (chi - clo).element_product();
        let mut cell_planes: Option<Vec<Plane>> = None;
        for part in parts {
            if part.lo.cmpgt(chi).any() || part.hi.cmplt(clo).any() {
                continue;
            }
            let piece = if (part.hi - part.lo).element_product() < cell_volume {
                let planes = cell_planes.get_or_insert_with(|| cell.face_planes());
                clip_all(&part.poly, planes, eps, &mut scratch)
            } else {
                clip_all(&cell, &part.planes, eps, &mut scratch)
            };
            let Some(piece) = piece else {
                continue;
            };
            let v = piece.volume();
            if v >= min_volume {
                pieces.push((piece, v));
            } else {
                scratch.give(piece);
            }
        }
        scratch.give(cell);
    }
    let held: f64 = pieces.iter().map(|(_, v)| v).sum();
    if held > MAX_EXCESS * volume {
        // Too much outside the fragment: cut it back to the fragment's own hull, or take
        // that hull alone when it holds less.
        let planes = own.face_planes();
        let mut kept = Vec::with_capacity(pieces.len());
        for (piece, _) in pieces {
            if let Some(q) = clip_all(&piece, &planes, eps, &mut scratch) {
                let v = q.volume();
                if v >= min_volume {
                    kept.push((q, v));
                }
            }
        }
        pieces = kept;
        let held: f64 = pieces.iter().map(|(_, v)| v).sum();
        if own_volume <= held {
            pieces = vec![(own, own_volume)];
        }
    }
    if pieces.is_empty() {
        return None;
    }
    Some(pieces.iter().map(|(p, _)| p.to_mesh()).unzip())
}

/// `poly` clipped by every plane; `None` once nothing is left. A plane that misses the
/// box around what is left keeps all of it or none, untested (the box shrinks with each
/// cut); the others cut in order of how far beyond them the first box's centre lies, so
/// the planes that cut most away come first and later ones have less to cut, or miss.
fn clip_all(
    poly: &Polytope,
    planes: &[Plane],
    eps: f64,
    scratch: &mut Scratch,
) -> Option<Polytope> {
    let (lo, hi) = poly.bounds();
    let (mut centre, mut half) = ((lo + hi) * 0.5, (hi - lo) * 0.5);
    // How the box's centre lies against `plane`, over how far the box reaches from it.
    let against =
        |plane: &Plane, centre: DVec3, half: DVec3| (plane.eval(centre), plane.n.abs().dot(half));
    let order = &mut scratch.order;
    order.clear();
    for (k, plane) in planes.iter().enumerate() {
        let (at, reach) = against(plane, centre, half);
        if at > reach {
            return None;
        }
        if at >= -reach {
            order.push((at / plane.n.length(), k as u32));
        }
    }
    order.sort_unstable_by(|a, b| b.0.total_cmp(&a.0));
    let order = std::mem::take(order);
    let mut current: Option<Polytope> = None;
    let mut next = scratch.take();
    for &(_, k) in &order {
        let plane = &planes[k as usize];
        let (at, reach) = against(plane, centre, half);
        if at < -reach {
            continue;
        }
        let from = current.as_ref().unwrap_or(poly);
        let outcome = if at > reach {
            Outcome::Empty
        } else {
            from.clip_into(plane, eps, scratch, &mut next)
        };
        match outcome {
            Outcome::Unchanged => {}
            Outcome::Empty => {
                scratch.give(next);
                if let Some(c) = current {
                    scratch.give(c);
                }
                scratch.order = order;
                return None;
            }
            Outcome::Cut => {
                let (lo, hi) = next.bounds();
                (centre, half) = ((lo + hi) * 0.5, (hi - lo) * 0.5);
                match current.as_mut() {
                    Some(c) => std::mem::swap(c, &mut next),
                    None => current = Some(std::mem::replace(&mut next, scratch.take())),
                }
            }
        }
    }
    scratch.give(next);
    scratch.order = order;
    Some(current.unwrap_or_else(|| {
        let mut p = scratch.take();
        p.clone_from(poly);
        p
    }))
}
