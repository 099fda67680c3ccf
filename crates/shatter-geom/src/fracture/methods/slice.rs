//! Slice fracture: planes cutting every current piece in two.

use glam::DVec3;
use rand::Rng;
use rand_chacha::ChaCha8Rng;

use crate::fracture::Bond;
use crate::fracture::bonds::caps::cap_bonds;
use crate::fracture::kernel::clip::split_keeping_faces;
use crate::fracture::kernel::{Piece, Plane, mesh_scale};
use crate::fracture::seeds::patterns::unit_vector;
use crate::util::bounds;

/// `k` random planes through the mesh: a random direction through a random point of
/// the middle half of the bounds (so that most planes cut it).
pub(crate) fn random_planes(mesh: &Piece, k: usize, rng: &mut ChaCha8Rng) -> Vec<(DVec3, DVec3)> {
    let (lo, hi) = bounds(&mesh.pos);
    (0..k)
        .map(|_| {
            let t = DVec3::new(
                rng.random_range(0.25..0.75),
                rng.random_range(0.25..0.75),
                rng.random_range(0.25..0.75),
            );
            (lo + (hi - lo) * t, unit_vector(rng))
        })
        .collect()
}

/// Cuts `mesh` by every plane `(point, normal)` in turn, each plane cutting all current
/// pieces; returns the fragments (connected components) and their bonds. The caps are
/// kept as faces (polygons) until the last plane.
pub(crate) fn slice(mesh: &Piece, planes: &[(DVec3, DVec3)], eps: f64) -> (Vec<Piece>, Vec<Bond>) {
    let mut pieces = vec![mesh.clone()];
    let unit: Vec<(DVec3, DVec3)> = planes.iter().map(|&(p, n)| (p, n.normalize())).collect();
    for (idx, &(p, n)) in unit.iter().enumerate() {
        let plane = Plane {
            n,
            d: n.dot(p),
            tag: idx as u64,
        };
        let mut next = Vec::with_capacity(pieces.len() * 2);
        for piece in pieces {
            match split_keeping_faces(&piece, &plane, eps) {
                // Entirely on one side.
                [None, _] | [_, None] => next.push(piece),
                [Some(neg), Some(pos)] => {
                    for side in [neg, pos] {
                        if !side.is_empty() {
                            next.extend(side.solids());
                        }
                    }
                }
            }
        }
        pieces = next;
    }
    // The caps stayed polygons through the later planes; one triangulation each.
    for piece in &mut pieces {
        piece.close_faces();
    }
    let scale = mesh_scale(mesh);
    let plane_of = |tag: u64| {
        let (p, n) = unit[tag as usize];
        (n, p)
    };
    let bonds = cap_bonds(&pieces, plane_of, 1e-12 * scale * scale);
    (pieces, bonds)
}
