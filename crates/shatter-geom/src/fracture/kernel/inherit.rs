//! Convex pieces a fragment inherits from the solid it was cut from: each of the solid's
//! convex pieces clipped by the fragment's cell and bounding box, rather than the
//! fragment decomposed again.
//!
//! A cell is convex and so is a piece, so each intersection is a convex polytope
//! ([`Polytope::clip`]); the fragment is the solid within the cell, so these polytopes
//! cover it as the solid's pieces covered the solid. Clipping them by the fragment's
//! bounding box as well keeps them near the fragment where a piece's hull reaches past
//! the solid (a piece convex within the decomposition's tolerance only).
//!
//! Of the two, the smaller (by bounding box) is clipped by the planes of the other's
//! faces: most of them miss it, and each cut goes through a small polytope. (A cell near
//! the impact is small where a piece can have a hundred faces; a cell far from it can
//! hold whole pieces.)

use glam::DVec3;

use super::convex::{ConvexPieces, MIN_PIECE_FRACTION};
use super::polytope::{Outcome, Polytope, Scratch};
use super::{Piece, Plane};
use crate::util::bounds;

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
/// planes; a fragment merged from several cells has them all): each cell within the
/// fragment's bounding box, clipped by each part. Pieces under `MIN_PIECE_FRACTION` of
/// the fragment are left out. Returns the pieces' points and their hulls' triangles, or
/// `None` when no piece is left (the caller then decomposes the fragment).
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
    let (lo, hi) = bounds(&p.pos);
    let min_volume = MIN_PIECE_FRACTION * volume;
    let (mut points, mut hulls) = (Vec::new(), Vec::new());
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
            if piece.volume() >= min_volume {
                let (pos, tris) = piece.to_mesh();
                points.push(pos);
                hulls.push(tris);
            }
            scratch.give(piece);
        }
        scratch.give(cell);
    }
    (!points.is_empty()).then_some((points, hulls))
}

/// `poly` clipped by every plane in turn; `None` once nothing is left.
fn clip_all(
    poly: &Polytope,
    planes: &[Plane],
    eps: f64,
    scratch: &mut Scratch,
) -> Option<Polytope> {
    let mut current: Option<Polytope> = None;
    let mut next = scratch.take();
    for plane in planes {
        let from = current.as_ref().unwrap_or(poly);
        match from.clip_into(plane, eps, scratch, &mut next) {
            Outcome::Unchanged => {}
            Outcome::Empty => {
                scratch.give(next);
                if let Some(c) = current {
                    scratch.give(c);
                }
                return None;
            }
            Outcome::Cut => match current.as_mut() {
                Some(c) => std::mem::swap(c, &mut next),
                None => current = Some(std::mem::replace(&mut next, scratch.take())),
            },
        }
    }
    scratch.give(next);
    Some(current.unwrap_or_else(|| {
        let mut p = scratch.take();
        p.clone_from(poly);
        p
    }))
}
