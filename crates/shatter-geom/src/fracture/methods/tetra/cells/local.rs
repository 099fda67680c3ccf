//! Clipping many small tetrahedra from a large mesh, each from only the part of the mesh
//! near it.
//!
//! Clipped from the whole mesh, every tetrahedron pays for every triangle: on a dense
//! surface, where every surface vertex is a corner and nearly every tetrahedron touches
//! the surface, that is quadratic (the 2-cylinder engine's 87,000 surface vertices did
//! not finish in an hour). Here the mesh is cut down a loose k-d tree of boxes first:
//! each node's piece is its parent's clipped by one plane (closed, its cut capped), and
//! a tetrahedron is clipped from the deepest node whose box holds it with room to
//! spare. A tetrahedron strictly inside a box meets the mesh only where the node's piece
//! is the mesh, so its cell is the same; the box's caps lie outside it and are cut away.
//!
//! The children overlap by a sixteenth of the parent on either side of the split, so a
//! tetrahedron small against its node always fits one of them.

use glam::DVec3;
use rayon::prelude::*;

use super::clip::{clip_cell, clip_exact, clip_greedily, clip_in_other_orders};
use crate::fracture::kernel::clip::clip_keeping_faces;
use crate::fracture::kernel::{Piece, Plane};

/// Tag of the boxes' caps: no tetrahedron face's (those are `4t + f`, far below) nor a
/// surface tag (bit 63).
const BOX_TAG: u64 = 1 << 62;
/// A node with at most this many triangles, or this many tetrahedra, clips them all.
const LEAF_TRIANGLES: usize = 4096;
const LEAF_TETRAHEDRA: usize = 8;
/// Each child reaches this fraction of its parent's extent past the split.
const OVERLAP: f64 = 1.0 / 16.0;
/// Deeper than this the boxes are far below any tetrahedron worth clipping.
const MAX_DEPTH: usize = 48;

/// One tetrahedron to clip: its corners' bounds and its four face planes.
pub(super) struct Job {
    pub lo: DVec3,
    pub hi: DVec3,
    pub planes: Vec<Plane>,
    /// The corners, face `f` ([`TET_FACES`](crate::fracture::kernel::convex::TET_FACES)
    /// `[f]`) on `planes[f]`: for the exact boolean ([`clip_exact`]).
    pub corners: [DVec3; 4],
}

/// Each job's cell: `mesh` clipped by its planes, as connected parts
/// ([`clip_cell`]), in the jobs' order (the same cells as clipping each from the whole
/// mesh, up to rounding and the order of the cuts). `eps` is the cuts' on-plane tolerance;
/// a tetrahedron is placed in a box only with `room` (well above `eps`) to each side.
pub(super) fn clip_cells(mesh: &Piece, jobs: Vec<Job>, eps: f64, room: f64) -> Vec<Vec<Piece>> {
    if mesh.tris.len() <= LEAF_TRIANGLES {
        // Small enough to clip each cell from it all.
        return jobs
            .into_par_iter()
            .with_max_len(1)
            .map(|j| clip_cell(mesh, j.planes, j.corners, eps))
            .collect();
    }
    down_the_tree(mesh, jobs, eps, room, &|piece, job| {
        clip_one(piece, job, eps, room)
    })
    .into_par_iter()
    .with_max_len(1)
    .map(|cell| cell.unwrap_or_else(|job| clip_cell(mesh, job.planes, job.corners, eps)))
    .collect()
}

/// Each job's cell by the exact boolean ([`clip_exact`]), from the node's piece down
/// the same tree as [`clip_cells`]; `None` where it fails.
pub(super) fn exact_cells(
    mesh: &Piece,
    jobs: Vec<Job>,
    eps: f64,
    room: f64,
) -> Vec<Option<Vec<Piece>>> {
    if mesh.tris.len() <= LEAF_TRIANGLES {
        return jobs
            .into_par_iter()
            .with_max_len(1)
            .map(|j| exact_parts(mesh, &j, eps, room))
            .collect();
    }
    down_the_tree(mesh, jobs, eps, room, &|piece, job| {
        exact_parts(piece, &job, eps, room).ok_or_else(|| Box::new(job))
    })
    .into_iter()
    .map(Result::ok)
    .collect()
}

/// The jobs sent down the tree, each done by `clip` on the piece of the deepest node
/// that holds it; in the jobs' order.
fn down_the_tree(mesh: &Piece, jobs: Vec<Job>, eps: f64, room: f64, clip: &Clip<'_>) -> Vec<Cell> {
    let n = jobs.len();
    let (lo, hi) = crate::util::bounds(&mesh.pos);
    let node = Node {
        lo: lo - DVec3::splat(room),
        hi: hi + DVec3::splat(room),
    };
    let mut done: Vec<(usize, Cell)> = Vec::with_capacity(n);
    let indexed: Vec<(usize, Job)> = jobs.into_iter().enumerate().collect();
    descend(mesh, node, indexed, eps, room, clip, 0, &mut done);
    done.sort_unstable_by_key(|(k, _)| *k);
    done.into_iter().map(|(_, cell)| cell).collect()
}

/// What is done with a job on a node's piece.
type Clip<'a> = dyn Fn(&Piece, Job) -> Cell + Sync + 'a;

/// A cell clipped from a node's piece, or its job back, to clip it from the whole mesh
/// ([`clip_one`]).
type Cell = Result<Vec<Piece>, Box<Job>>;

/// A node's box.
#[derive(Clone, Copy)]
struct Node {
    lo: DVec3,
    hi: DVec3,
}

/// The jobs of one node: those that fit a child go down with it, the others are
/// clipped from `piece` here.
#[allow(clippy::too_many_arguments)]
fn descend(
    piece: &Piece,
    node: Node,
    jobs: Vec<(usize, Job)>,
    eps: f64,
    room: f64,
    clip: &Clip<'_>,
    depth: usize,
    done: &mut Vec<(usize, Cell)>,
) {
    if jobs.is_empty() {
        return;
    }
    let here = |jobs: Vec<(usize, Job)>, done: &mut Vec<(usize, Cell)>| {
        let cells: Vec<(usize, Cell)> = jobs
            .into_par_iter()
            .with_max_len(1)
            .map(|(k, job)| (k, clip(piece, job)))
            .collect();
        done.extend(cells);
    };
    if piece.is_empty() {
        // The box holds no part of the mesh: every tetrahedron in it has no cell.
        done.extend(jobs.into_iter().map(|(k, _)| (k, Ok(Vec::new()))));
        return;
    }
    if depth >= MAX_DEPTH
        || jobs.len() <= LEAF_TETRAHEDRA
        || piece.tris.len() + piece.faces.len() <= LEAF_TRIANGLES
    {
        here(jobs, done);
        return;
    }
    let extent = node.hi - node.lo;
    let axis = if extent.x >= extent.y && extent.x >= extent.z {
        0
    } else if extent.y >= extent.z {
        1
    } else {
        2
    };
    let mid = (node.lo[axis] + node.hi[axis]) / 2.0;
    let reach = OVERLAP * extent[axis];
    // Child 0 is the box below `mid + reach`, child 1 the box above `mid - reach`.
    let (top0, bottom1) = (mid + reach, mid - reach);
    let mut kids: [Vec<(usize, Job)>; 2] = [Vec::new(), Vec::new()];
    let mut stay: Vec<(usize, Job)> = Vec::new();
    for (k, job) in jobs {
        let fits0 = job.hi[axis] + room < top0;
        let fits1 = job.lo[axis] - room > bottom1;
        match (fits0, fits1) {
            (true, true) => {
                let side = usize::from(job.lo[axis] + job.hi[axis] > 2.0 * mid);
                kids[side].push((k, job));
            }
            (true, false) => kids[0].push((k, job)),
            (false, true) => kids[1].push((k, job)),
            (false, false) => stay.push((k, job)),
        }
    }
    // Each child's piece is its parent's clipped by the plane at its side of the split.
    let child = |side: usize| -> (Piece, Node) {
        let (sign, at) = if side == 0 {
            (1.0, top0)
        } else {
            (-1.0, bottom1)
        };
        let plane = box_plane(axis, sign, at);
        let mut bounds = node;
        if side == 0 {
            bounds.hi[axis] = at;
        } else {
            bounds.lo[axis] = at;
        }
        let mut p = clip_keeping_faces(piece, &plane, eps).unwrap_or_else(|| piece.clone());
        p.compact();
        (p, bounds)
    };
    let [jobs0, jobs1] = kids;
    let mut done0 = Vec::new();
    let mut done1 = Vec::new();
    let mut done_here = Vec::new();
    rayon::join(
        || here(stay, &mut done_here),
        || {
            rayon::join(
                || {
                    if !jobs0.is_empty() {
                        let (p, b) = child(0);
                        descend(&p, b, jobs0, eps, room, clip, depth + 1, &mut done0);
                    }
                },
                || {
                    if !jobs1.is_empty() {
                        let (p, b) = child(1);
                        descend(&p, b, jobs1, eps, room, clip, depth + 1, &mut done1);
                    }
                },
            )
        },
    );
    done.extend(done_here);
    done.extend(done0);
    done.extend(done1);
}

/// One tetrahedron's cell from a node's piece; its job back for [`clip_cells`] to clip
/// it from the whole mesh instead ([`clip_cell`]).
///
/// The greedy order is tried first. When its cell is not closed, the other orders are
/// tried on the node's piece, but a cell of theirs is taken only if its volume is the
/// greedy one's: on a mesh with features far below the cut tolerance an order can leave
/// nothing where the whole mesh leaves a part (seen on `regr01.obj`), and the volumes
/// would no longer add up. When no order closes it, the cell is the exact boolean of the
/// node's piece and the tetrahedron ([`clip_exact`]). A box's cap left by the cuts
/// also sends the cell to the whole mesh (it cannot be when the tetrahedron lies inside
/// the box, but rounding is not proved away).
fn clip_one(piece: &Piece, job: Job, eps: f64, room: f64) -> Cell {
    let cell = match clip_greedily(piece, job.planes.clone(), eps) {
        Ok(parts) => no_box(&parts).then_some(parts),
        Err(None) => None,
        Err(Some(volume)) => {
            let tol = 1e-9 * piece.volume().abs();
            clip_in_other_orders(piece, &job.planes, eps, |parts| {
                let v: f64 = parts.iter().map(Piece::volume).sum();
                no_box(parts) && (v - volume).abs() <= tol
            })
            .or_else(|| exact_parts(piece, &job, eps, room))
        }
    };
    cell.ok_or_else(|| Box::new(job))
}

/// The plane `sign · x[axis] = sign · at` (keeping `sign · x[axis] ≤ sign · at`),
/// tagged as a box's cap.
fn box_plane(axis: usize, sign: f64, at: f64) -> Plane {
    let mut n = DVec3::ZERO;
    n[axis] = sign;
    Plane {
        n,
        d: sign * at,
        tag: BOX_TAG,
    }
}

/// Whether no part has a face of a box's cap.
fn no_box(parts: &[Piece]) -> bool {
    parts.iter().all(|p| !p.tags.contains(&BOX_TAG))
}

/// The job's cell by the exact boolean, as closed parts without a box's cap; `None`
/// when the boolean fails or the parts are not so. The piece is first cut down to the
/// tetrahedron's box with `room` to spare (six cuts of the clipper, far from the
/// tetrahedron): the boolean's cost grows with the whole piece it is given (on
/// `regr01.obj`, 827 cells took 44 s from their nodes' pieces).
fn exact_parts(piece: &Piece, job: &Job, eps: f64, room: f64) -> Option<Vec<Piece>> {
    let mut near: Option<Piece> = None;
    for axis in 0..3 {
        for (sign, at) in [(1.0, job.hi[axis] + room), (-1.0, job.lo[axis] - room)] {
            let plane = box_plane(axis, sign, at);
            let current = near.as_ref().unwrap_or(piece);
            if let Some(mut cut) = clip_keeping_faces(current, &plane, eps) {
                if cut.is_empty() {
                    return Some(Vec::new());
                }
                cut.compact();
                near = Some(cut);
            }
        }
    }
    let exact = |from: &Piece| clip_exact(from, &job.planes, job.corners).filter(|p| no_box(p));
    // The cuts to the box can fail where the cell's own cuts did (the boolean then
    // refuses the open piece): then the whole piece.
    match &near {
        Some(near) => exact(near).or_else(|| exact(piece)),
        None => exact(piece),
    }
}

#[cfg(test)]
mod tests {
    use glam::DVec3;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    use super::super::corner_plane;
    use super::{Job, LEAF_TETRAHEDRA, LEAF_TRIANGLES, clip_cell, clip_cells};
    use crate::fracture::kernel::convex::tet_volume;
    use crate::fracture::kernel::{Piece, Plane};
    use crate::shapes;

    /// Small tetrahedra about the surface of a dense torus, each clipped down the tree
    /// and from the whole mesh: the same parts, closed, of the same volumes.
    #[test]
    fn cells_clipped_down_the_tree_are_the_cells_clipped_from_the_whole_mesh() {
        let mesh = Piece::from_mesh_welded(&shapes::torus(0.5, 0.2, 96, 48));
        assert!(mesh.tris.len() > LEAF_TRIANGLES, "the tree must be used");
        let mut rng = ChaCha8Rng::seed_from_u64(7);
        let mut jobs = Vec::new();
        let mut planes_of = Vec::new();
        for t in 0..120 {
            let centre = mesh.pos[rng.random_range(0..mesh.pos.len())];
            let mut c: [DVec3; 4] = std::array::from_fn(|_| {
                centre
                    + DVec3::new(
                        rng.random_range(-0.04..0.04),
                        rng.random_range(-0.04..0.04),
                        rng.random_range(-0.04..0.04),
                    )
            });
            if tet_volume(c) < 0.0 {
                c.swap(0, 1);
            }
            let planes: Vec<Plane> = (0..4)
                .map(|f| corner_plane(c, f, (4 * t + f) as u64))
                .collect();
            // Outward: the opposite corner is on the kept side of each face.
            for (f, p) in planes.iter().enumerate() {
                assert!(p.eval(c[f]) < 0.0);
            }
            planes_of.push((planes.clone(), c));
            jobs.push(Job {
                lo: c[0].min(c[1]).min(c[2]).min(c[3]),
                hi: c[0].max(c[1]).max(c[2]).max(c[3]),
                planes,
                corners: c,
            });
        }
        assert!(jobs.len() > LEAF_TETRAHEDRA);
        let eps = 1e-10;
        let local = clip_cells(&mesh, jobs, eps, 1e-7);
        let scale = mesh.volume();
        let mut cut = 0;
        for (parts, (planes, c)) in local.iter().zip(planes_of) {
            let whole = clip_cell(&mesh, planes, c, eps);
            assert_eq!(parts.len(), whole.len());
            let v = |ps: &[Piece]| ps.iter().map(Piece::volume).sum::<f64>();
            assert!((v(parts) - v(&whole)).abs() <= 1e-9 * scale);
            assert!(parts.iter().all(Piece::is_closed));
            assert!(
                parts
                    .iter()
                    .all(|p| p.tags.iter().all(|t| t != &super::BOX_TAG))
            );
            if parts.iter().any(|p| p.tags.iter().any(|&t| t < 1 << 62)) {
                cut += 1;
            }
        }
        // Most of them straddle the surface: their cells have caps.
        assert!(cut > 60, "{cut} cells cut");
    }
}
