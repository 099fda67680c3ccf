//! Voronoi fracture: each seed's cell (an intersection of bisector half-spaces) clipped
//! exactly against the mesh, one fragment per connected component.

use glam::DVec3;

use super::bonds::cap_bonds;
use super::clip::{Plane, clip};
use super::piece::Piece;
use super::types::Bond;

/// Clips `mesh` by the Voronoi cells of `seeds` under the diagonal metric `metric`
/// (`|x|² = Σ metricᵢ xᵢ²`; all ones for the Euclidean distance). Returns the fragments
/// (cells in seed order, components in order) and their bonds.
///
/// A cell is cut only by the bisectors that can reach it: the other seeds are visited
/// by increasing distance and the loop stops once a seed is more than twice the cell's
/// current radius away (no point of the cell can be closer to it), so a cell costs
/// about as many cuts as it has faces. Duplicate seeds are ignored after their first
/// occurrence.
pub(crate) fn voronoi(
    mesh: &Piece,
    seeds: &[DVec3],
    metric: DVec3,
    eps: f64,
) -> (Vec<Piece>, Vec<Bond>) {
    let k = seeds.len() as u64;
    let dist2 = |a: DVec3, b: DVec3| ((a - b) * (a - b)).dot(metric);
    let bisector = |i: usize, j: usize| {
        let (si, sj) = (seeds[i], seeds[j]);
        let n = (sj - si) * metric;
        let d = n.dot((si + sj) * 0.5);
        let tag = (i.min(j) as u64) * k + i.max(j) as u64;
        Plane { n, d, tag }
    };
    let bounding_box = box_piece(mesh);
    let mut cells = Vec::new();
    let mut order: Vec<(f64, usize)> = Vec::with_capacity(seeds.len());
    'seeds: for i in 0..seeds.len() {
        let si = seeds[i];
        order.clear();
        for (j, &sj) in seeds.iter().enumerate() {
            if j == i {
                continue;
            }
            let d2 = dist2(si, sj);
            if d2 == 0.0 {
                if j < i {
                    // A duplicate of an earlier seed: that seed's cell is this one.
                    continue 'seeds;
                }
                continue;
            }
            order.push((d2, j));
        }
        order.sort_unstable_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
        let radius2 = |p: &Piece| p.pos.iter().map(|&x| dist2(x, si)).fold(0.0, f64::max);
        // First the convex cell itself, clipped from the mesh's bounding box (a dozen
        // triangles, so cheap): only the bisectors that end up as its faces need to
        // cut the mesh, which saves the cuts a later plane would make redundant.
        let mut poly = bounding_box.clone();
        let mut r2 = radius2(&poly);
        for &(d2, j) in &order {
            if d2 > 4.0 * r2 {
                break;
            }
            if let Some(next) = clip(&poly, &bisector(i, j), eps) {
                if next.is_empty() {
                    continue 'seeds;
                }
                r2 = radius2(&next);
                poly = next;
            }
        }
        let mut faces: Vec<u64> = poly.tags.clone();
        faces.sort_unstable();
        faces.dedup();
        let mut cell: Option<Piece> = None;
        for &(_, j) in &order {
            let plane = bisector(i, j);
            if faces.binary_search(&plane.tag).is_err() {
                continue;
            }
            let current = cell.as_ref().unwrap_or(mesh);
            if let Some(next) = clip(current, &plane, eps) {
                if next.is_empty() {
                    continue 'seeds;
                }
                cell = Some(next);
            }
        }
        let piece = cell.unwrap_or_else(|| mesh.clone());
        cells.extend(piece.components());
    }
    let plane_of = |tag: u64| {
        let (i, j) = ((tag / k) as usize, (tag % k) as usize);
        let p = bisector(i, j);
        let n = p.n.normalize();
        (n, p.n * (p.d / p.n.length_squared()))
    };
    let scale = mesh_scale(mesh);
    let bonds = cap_bonds(&cells, plane_of, 1e-12 * scale * scale);
    (cells, bonds)
}

/// Length of the bounding-box diagonal of a piece (1 for an empty one).
pub(crate) fn mesh_scale(p: &Piece) -> f64 {
    if p.pos.is_empty() {
        return 1.0;
    }
    let (lo, hi) = super::seeds::bounds(&p.pos);
    (hi - lo).length().max(f64::MIN_POSITIVE)
}

/// A closed box around `mesh` (its bounds grown by a tenth), all faces tagged surface.
fn box_piece(mesh: &Piece) -> Piece {
    let (lo, hi) = super::seeds::bounds(&mesh.pos);
    let pad = (hi - lo) * 0.1 + DVec3::splat(1e-9);
    let (lo, hi) = (lo - pad, hi + pad);
    let pos: Vec<DVec3> = (0..8)
        .map(|i| {
            DVec3::new(
                if i & 1 == 0 { lo.x } else { hi.x },
                if i & 2 == 0 { lo.y } else { hi.y },
                if i & 4 == 0 { lo.z } else { hi.z },
            )
        })
        .collect();
    let quads = [
        [0, 2, 3, 1],
        [4, 5, 7, 6],
        [0, 1, 5, 4],
        [2, 6, 7, 3],
        [0, 4, 6, 2],
        [1, 3, 7, 5],
    ];
    let mut tris = Vec::with_capacity(12);
    for q in quads {
        tris.push([q[0], q[1], q[2]]);
        tris.push([q[0], q[2], q[3]]);
    }
    Piece {
        pos,
        tags: vec![super::piece::SURFACE; 12],
        tris,
    }
}
