//! Voronoi fracture: each seed's cell (an intersection of bisector half-spaces) clipped
//! exactly against the mesh, one fragment per connected component.

use glam::DVec3;
use rayon::prelude::*;

use crate::fracture::Bond;
use crate::fracture::bonds::caps::cap_bonds;
use crate::fracture::kernel::clip::{clip, clip_keeping_faces};
use crate::fracture::kernel::{Piece, Plane, SURFACE, mesh_scale};
use crate::util::{bounds, box_corners};

/// [`voronoi_cells`] with the seeds' Delaunay neighbours, its pieces and bonds.
#[cfg(test)]
pub(crate) fn voronoi(
    mesh: &Piece,
    seeds: &[DVec3],
    metric: DVec3,
    eps: f64,
) -> (Vec<Piece>, Vec<Bond>) {
    voronoi_with(mesh, seeds, metric, eps, delaunay_neighbours(seeds, metric))
}

/// [`voronoi_cells`]' pieces and bonds.
#[cfg(test)]
pub(crate) fn voronoi_with(
    mesh: &Piece,
    seeds: &[DVec3],
    metric: DVec3,
    eps: f64,
    neighbours: Option<Neighbours>,
) -> (Vec<Piece>, Vec<Bond>) {
    let cells = voronoi_cells(mesh, seeds, metric, eps, neighbours);
    (cells.pieces, cells.bonds)
}

/// Each seed's Delaunay neighbours and each seed's first occurrence
/// ([`delaunay_neighbours`]).
pub(crate) type Neighbours = (Vec<Vec<u32>>, Vec<u32>);

/// A Voronoi cut with what made each piece: the pieces and their bonds, each piece's
/// seed, and each seed's cell planes.
pub(crate) struct Cells {
    /// The cells' pieces (cells in seed order, components in order).
    pub pieces: Vec<Piece>,
    /// Their bonds.
    pub bonds: Vec<Bond>,
    /// Per piece, the seed whose cell it is (part of).
    pub seed: Vec<u32>,
    /// Per seed, the planes its cell is cut by (the cell is the intersection of their
    /// negative sides; empty for a repeated seed or an empty cell).
    pub planes: Vec<Vec<Plane>>,
}

/// Clips `mesh` by the Voronoi cells of `seeds` under the diagonal metric `metric`
/// (`|x|² = Σ metricᵢ xᵢ²`; all ones for the Euclidean distance). Returns the fragments
/// (cells in seed order, components in order), their bonds, each one's seed and each
/// seed's planes ([`Cells`]).
///
/// A cell is cut only by the bisectors of its Delaunay neighbours (`neighbours`, see
/// [`delaunay_neighbours`]; `None`: every other seed is a candidate), each time by the
/// one that removes the most of what is left, so a cell costs about as many cuts as it
/// has faces. The cells are independent and are cut in parallel (rayon; one thread where
/// there are no threads, as in the browser); the result does not depend on the number
/// of threads. Duplicate seeds are ignored after their first occurrence.
pub(crate) fn voronoi_cells(
    mesh: &Piece,
    seeds: &[DVec3],
    metric: DVec3,
    eps: f64,
    neighbours: Option<Neighbours>,
) -> Cells {
    let k = seeds.len() as u64;
    let bisector = |i: usize, j: usize| {
        let (si, sj) = (seeds[i], seeds[j]);
        let n = (sj - si) * metric;
        let d = n.dot((si + sj) * 0.5);
        let tag = (i.min(j) as u64) * k + i.max(j) as u64;
        Plane { n, d, tag }
    };
    let bounding_box = box_piece(mesh);
    // One task per cell (not runs of cells): a thread descheduled by the host then
    // holds up one cell, not a run of them the other threads cannot steal.
    let per_seed: Vec<(Vec<Piece>, Vec<Plane>)> = (0..seeds.len())
        .into_par_iter()
        .with_max_len(1)
        .map(|i| {
            let Some(planes) = cell_planes(
                i,
                seeds,
                metric,
                neighbours.as_ref(),
                &bounding_box,
                &bisector,
                eps,
            ) else {
                return (Vec::new(), Vec::new());
            };
            (cut_cell(mesh, planes.clone(), eps), planes)
        })
        .collect();
    let mut cells: Vec<Piece> = Vec::new();
    let mut seed = Vec::new();
    let mut planes = Vec::with_capacity(per_seed.len());
    for (i, (pieces, p)) in per_seed.into_iter().enumerate() {
        seed.extend(std::iter::repeat_n(i as u32, pieces.len()));
        cells.extend(pieces);
        planes.push(p);
    }
    let plane_of = |tag: u64| {
        let (i, j) = ((tag / k) as usize, (tag % k) as usize);
        let p = bisector(i, j);
        let n = p.n.normalize();
        (n, p.n * (p.d / p.n.length_squared()))
    };
    let scale = mesh_scale(mesh);
    let bonds = cap_bonds(&cells, plane_of, 1e-12 * scale * scale);
    Cells {
        pieces: cells,
        bonds,
        seed,
        planes,
    }
}

/// `mesh` within the cell that is the negative side of all `planes`, one piece per
/// connected component, caps triangulated: cut each time by the plane that cuts away
/// the most of what is left (counted in vertices), so the pieces shrink fast and later
/// cuts have less to go through; a plane with no vertex beyond it cannot cut.
fn cut_cell(mesh: &Piece, mut planes: Vec<Plane>, eps: f64) -> Vec<Piece> {
    let mut cell: Option<Piece> = None;
    // Planes found to have no vertex beyond them, counted on all the vertices: they
    // never cut (every later piece lies within this one), so they are not counted again.
    let mut spent = vec![false; planes.len()];
    while !planes.is_empty() {
        let current = cell.as_ref().unwrap_or(mesh);
        // Counted on at most ~128 of the vertices (the choice is only an order;
        // every plane still cuts), and on all of them before concluding that
        // no plane has a vertex beyond it.
        let stride = (current.pos.len() / 128).max(1);
        let beyond = |plane: &Plane, stride: usize| {
            current
                .pos
                .iter()
                .step_by(stride)
                .filter(|&&p| plane.eval(p) > 0.0)
                .count()
        };
        let mut best_of = |stride: usize| {
            let mut best = (0, 0);
            for (k, plane) in planes.iter().enumerate() {
                if spent[k] {
                    continue;
                }
                let count = beyond(plane, stride);
                if count > best.1 {
                    best = (k, count);
                }
                spent[k] = stride == 1 && count == 0;
            }
            best
        };
        let mut best_count = best_of(stride);
        if best_count.1 == 0 && stride > 1 {
            best_count = best_of(1);
        }
        let (best, count) = best_count;
        if count == 0 {
            break;
        }
        let plane = planes.swap_remove(best);
        spent.swap_remove(best);
        if let Some(next) = clip_keeping_faces(current, &plane, eps) {
            if next.is_empty() {
                return Vec::new();
            }
            cell = Some(next);
        }
    }
    let mut cell = cell.unwrap_or_else(|| mesh.clone());
    cell.close_faces();
    cell.solids()
}

/// The planes that bound seed `i`'s cell, nearest first (the order in which equally good
/// cuts are taken); `None` when the seed repeats an earlier one (whose cell it shares)
/// or its cell is empty.
fn cell_planes(
    i: usize,
    seeds: &[DVec3],
    metric: DVec3,
    neighbours: Option<&Neighbours>,
    bounding_box: &Piece,
    bisector: &impl Fn(usize, usize) -> Plane,
    eps: f64,
) -> Option<Vec<Plane>> {
    let si = seeds[i];
    let dist2 = |a: DVec3, b: DVec3| ((a - b) * (a - b)).dot(metric);
    let by_distance = |order: &mut Vec<(f64, usize)>| {
        order.sort_unstable_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
    };
    let mut order: Vec<(f64, usize)>;
    if let Some((adjacent, representative)) = neighbours {
        if representative[i] as usize != i {
            return None;
        }
        order = adjacent[i]
            .iter()
            .map(|&j| (dist2(si, seeds[j as usize]), j as usize))
            .collect();
        by_distance(&mut order);
        return Some(order.iter().map(|&(_, j)| bisector(i, j)).collect());
    }
    // No tetrahedralization: every other seed is a candidate, and the convex cell,
    // clipped from the mesh's bounding box (a dozen triangles, so cheap), tells which
    // bisectors are its faces.
    order = Vec::with_capacity(seeds.len());
    for (j, &sj) in seeds.iter().enumerate() {
        if j == i {
            continue;
        }
        let d2 = dist2(si, sj);
        if d2 == 0.0 {
            if j < i {
                return None;
            }
            continue;
        }
        order.push((d2, j));
    }
    by_distance(&mut order);
    let radius2 = |p: &Piece| p.pos.iter().map(|&x| dist2(x, si)).fold(0.0, f64::max);
    let mut faces = cell_faces(bounding_box, &order, bisector, i, &radius2, eps)?;
    faces.sort_unstable();
    faces.dedup();
    Some(
        order
            .iter()
            .map(|&(_, j)| bisector(i, j))
            .filter(|plane| faces.binary_search(&plane.tag).is_ok())
            .collect(),
    )
}

/// For every seed, the seeds whose Voronoi cells can share a face with its cell (its
/// neighbours in the Delaunay tetrahedralization of the seeds under `metric`), and every
/// seed's first occurrence. `None` when the seeds have no tetrahedralization (fewer than
/// four distinct seeds, or all coplanar): then every other seed is a candidate.
///
/// A Voronoi face of positive area lies on the bisector of a Delaunay edge in any
/// Delaunay tetrahedralization (a point inside the face is the centre of an empty sphere
/// through exactly its two seeds), so no face is missed; a cospherical configuration may
/// add a neighbour whose face has no area, whose cut then removes nothing.
pub(crate) fn delaunay_neighbours(seeds: &[DVec3], metric: DVec3) -> Option<Neighbours> {
    let scale = DVec3::new(metric.x.sqrt(), metric.y.sqrt(), metric.z.sqrt());
    let scaled: Vec<DVec3> = seeds.iter().map(|&s| s * scale).collect();
    let t = crate::delaunay::tetrahedralize(&scaled).ok()?;
    let mut adjacent: Vec<Vec<u32>> = vec![Vec::new(); seeds.len()];
    for tet in t.tetrahedra() {
        for a in 0..4 {
            for b in 0..4 {
                if a != b {
                    adjacent[tet[a] as usize].push(tet[b]);
                }
            }
        }
    }
    for list in &mut adjacent {
        list.sort_unstable();
        list.dedup();
    }
    Some((adjacent, t.representative))
}

/// The tags of the faces of seed `i`'s convex cell, found by clipping the mesh's
/// bounding box by the bisectors in `order` (by increasing distance; the loop stops once
/// a seed is more than twice the cell's current radius away, as no point of the cell
/// can be closer to it). `None` when the cell is empty.
fn cell_faces(
    bounding_box: &Piece,
    order: &[(f64, usize)],
    bisector: &impl Fn(usize, usize) -> Plane,
    i: usize,
    radius2: &impl Fn(&Piece) -> f64,
    eps: f64,
) -> Option<Vec<u64>> {
    let mut poly = bounding_box.clone();
    let mut r2 = radius2(&poly);
    for &(d2, j) in order {
        if d2 > 4.0 * r2 {
            break;
        }
        if let Some(next) = clip(&poly, &bisector(i, j), eps) {
            if next.is_empty() {
                return None;
            }
            r2 = radius2(&next);
            poly = next;
        }
    }
    Some(poly.tags)
}

/// A closed box around `mesh` (its bounds grown by a tenth), all faces tagged surface of
/// no input triangle ([`SURFACE`]: the box is not the input; only its cells' cap tags are
/// used).
fn box_piece(mesh: &Piece) -> Piece {
    let (lo, hi) = bounds(&mesh.pos);
    let pad = (hi - lo) * 0.1 + DVec3::splat(1e-9);
    let (lo, hi) = (lo - pad, hi + pad);
    let pos = box_corners(lo, hi);
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
        tags: vec![SURFACE; 12],
        faces: Vec::new(),
        tris,
    }
}
