//! A tetrahedron's cell clipped from the mesh by its face planes, the cut order checked
//! by volume, and split into its connected parts.

use glam::DVec3;

use super::exact::clip_exactly;
use crate::fracture::kernel::clip::clip_keeping_faces;
use crate::fracture::kernel::{Piece, Plane, with_cavities};
use crate::util::{FastMap, UnionFind};

/// `mesh` clipped by every plane (the convex cell they bound), as its connected parts.
/// As for a Voronoi cell, each time the plane with the most vertices beyond it cuts.
///
/// Each cut must keep a volume between zero and what it cut (up to rounding); a cut that
/// does not (a cap the kernel triangulated wrongly, seen on a torus's saddle) makes the
/// cuts be tried again in the other orders, the first order whose every cut passes kept.
/// When none closes the cell, it is the exact boolean of the mesh and the tetrahedron
/// `corners` ([`clip_exactly`]); when that fails too, the greedy cut unchecked.
pub(super) fn clip_cell(
    mesh: &Piece,
    planes: Vec<Plane>,
    corners: [DVec3; 4],
    eps: f64,
) -> Vec<Piece> {
    if let Ok(parts) = clip_greedily(mesh, planes.clone(), eps) {
        return parts;
    }
    if let Some(parts) = clip_in_other_orders(mesh, &planes, eps, |_| true) {
        return parts;
    }
    if let Some(parts) = clip_exact(mesh, &planes, corners) {
        return parts;
    }
    clip_unchecked(mesh, planes, eps)
        .map(finish)
        .unwrap_or_default()
}

/// The cell as the exact boolean of `mesh` and the tetrahedron `corners` (its faces on
/// `planes`; [`clip_exactly`]), as closed parts; `None` when the boolean fails or a part
/// is not closed (which also refuses an edge of more than two triangles).
pub(super) fn clip_exact(
    mesh: &Piece,
    planes: &[Plane],
    corners: [DVec3; 4],
) -> Option<Vec<Piece>> {
    clip_exactly(mesh, planes, corners)
        .map(finish)
        .filter(|p| good(p))
}

/// The cell of [`clip_cell`] cut in the greedy order only. Fails when a cut fails the
/// volume check (`Err(None)`) or a part is not closed (`Err(Some(volume))`, the
/// volume of the cell as cut).
pub(super) fn clip_greedily(
    mesh: &Piece,
    planes: Vec<Plane>,
    eps: f64,
) -> Result<Vec<Piece>, Option<f64>> {
    let cell = clip_in_order(mesh, planes, eps, None).ok_or(None)?;
    let volume = cell.volume();
    let parts = finish(cell);
    if good(&parts) {
        Ok(parts)
    } else {
        Err(Some(volume))
    }
}

/// The cell cut in each order in turn: the first whose cuts pass the volume check,
/// whose parts are closed and which `accept` takes.
pub(super) fn clip_in_other_orders(
    mesh: &Piece,
    planes: &[Plane],
    eps: f64,
    accept: impl Fn(&[Piece]) -> bool,
) -> Option<Vec<Piece>> {
    permutations(planes.len()).into_iter().find_map(|order| {
        clip_in_order(mesh, planes.to_vec(), eps, Some(&order))
            .map(finish)
            .filter(|p| good(p) && accept(p))
    })
}

/// A cut cell closed, as its connected parts (cavities with the part around them),
/// without flat triangles ([`Piece::split_flat_triangles`]).
fn finish(mut cell: Piece) -> Vec<Piece> {
    cell.close_faces();
    let mut parts = with_cavities(
        cell.components()
            .into_iter()
            .flat_map(split_at_pinched_edges)
            .collect(),
    );
    for p in &mut parts {
        p.split_flat_triangles();
    }
    parts
}

/// Whether every part of a cell is closed.
fn good(parts: &[Piece]) -> bool {
    parts.iter().all(Piece::is_closed)
}

/// The cell cut greedily (`order` `None`) or in the given order; `None` when a cut
/// fails the volume check. An empty piece when nothing is left.
fn clip_in_order(
    mesh: &Piece,
    mut planes: Vec<Plane>,
    eps: f64,
    order: Option<&[usize]>,
) -> Option<Piece> {
    let mut cell: Option<Piece> = None;
    let mut volume = mesh.volume();
    let tol = 1e-9 * volume.abs();
    let fixed: Vec<Plane> = order
        .map(|o| o.iter().map(|&k| planes[k]).collect())
        .unwrap_or_default();
    let mut step = 0;
    loop {
        let current = cell.as_ref().unwrap_or(mesh);
        let plane = if order.is_some() {
            if step == fixed.len() {
                break;
            }
            step += 1;
            fixed[step - 1]
        } else {
            if planes.is_empty() {
                break;
            }
            let beyond =
                |plane: &Plane| current.pos.iter().filter(|&&p| plane.eval(p) > 0.0).count();
            let (best, count) = planes
                .iter()
                .enumerate()
                .map(|(k, plane)| (k, beyond(plane)))
                .fold((0, 0), |acc, x| if x.1 > acc.1 { x } else { acc });
            if count == 0 {
                break;
            }
            planes.swap_remove(best)
        };
        if let Some(next) = clip_keeping_faces(current, &plane, eps) {
            if next.is_empty() {
                return Some(Piece::default());
            }
            let v = next.volume();
            if v < -tol || v > volume + tol {
                return None;
            }
            volume = v;
            cell = Some(next);
        }
    }
    Some(cell.unwrap_or_else(|| mesh.clone()))
}

/// The greedy cell without the volume check (no order passed it); `None` when empty.
fn clip_unchecked(mesh: &Piece, planes: Vec<Plane>, eps: f64) -> Option<Piece> {
    let mut cell = mesh.clone();
    for plane in planes {
        if let Some(next) = clip_keeping_faces(&cell, &plane, eps) {
            if next.is_empty() {
                return None;
            }
            cell = next;
        }
    }
    Some(cell)
}

/// Every order of `0..n` (n at most 4 here), in lexicographic order.
fn permutations(n: usize) -> Vec<Vec<usize>> {
    if n == 0 {
        return vec![Vec::new()];
    }
    let mut out = Vec::new();
    for first in 0..n {
        for rest in permutations(n - 1) {
            let mut p = vec![first];
            p.extend(rest.into_iter().map(|k| if k >= first { k + 1 } else { k }));
            out.push(p);
        }
    }
    out
}

/// A clipped piece that touches itself along an edge (the tetrahedron spans a concave
/// edge of the mesh on both sides: an edge of four triangles) split into the parts that
/// meet there, each joined to the rest only through edges of two triangles. Kept as it
/// is unless every part is closed.
fn split_at_pinched_edges(p: Piece) -> Vec<Piece> {
    let key = |a: u32, b: u32| (a.min(b), a.max(b));
    let mut uses: FastMap<(u32, u32), Vec<usize>> = FastMap::default();
    for (t, tri) in p.tris.iter().enumerate() {
        for k in 0..3 {
            uses.entry(key(tri[k], tri[(k + 1) % 3]))
                .or_default()
                .push(t);
        }
    }
    if uses.values().all(|ts| ts.len() == 2) {
        return vec![p];
    }
    let mut uf = UnionFind::new(p.tris.len());
    for ts in uses.values() {
        if let [a, b] = ts[..] {
            uf.union(a, b);
        }
    }
    let (parts, _) = p.clone().into_groups(&mut uf);
    if parts.len() > 1 && parts.iter().all(Piece::is_closed) {
        parts
    } else {
        vec![p]
    }
}
