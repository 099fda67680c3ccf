//! A tetrahedron's cell clipped from the mesh by its face planes, the cut order checked
//! by volume, and split into its connected parts.

use crate::fracture::kernel::clip::clip_keeping_faces;
use crate::fracture::kernel::{Piece, Plane, with_cavities};
use crate::util::{FastMap, UnionFind};

/// `mesh` clipped by every plane (the convex cell they bound), as its connected parts.
/// As for a Voronoi cell, each time the plane with the most vertices beyond it cuts.
///
/// Each cut must keep a volume between zero and what it cut (up to rounding); a cut that
/// does not (a cap the kernel triangulated wrongly, seen on a torus's saddle) makes the
/// cuts be tried again in the other orders, the first order whose every cut passes kept.
pub(super) fn clip_cell(mesh: &Piece, planes: Vec<Plane>, eps: f64) -> Vec<Piece> {
    let finish = |cell: Piece| -> Vec<Piece> {
        let mut cell = cell;
        cell.close_faces();
        with_cavities(
            cell.components()
                .into_iter()
                .flat_map(split_at_pinched_edges)
                .collect(),
        )
    };
    let good = |parts: &Vec<Piece>| parts.iter().all(Piece::is_closed);
    let greedy = clip_in_order(mesh, planes.clone(), eps, None).map(finish);
    if let Some(parts) = greedy.filter(good) {
        return parts;
    }
    for order in permutations(planes.len()) {
        let parts = clip_in_order(mesh, planes.clone(), eps, Some(&order)).map(finish);
        if let Some(parts) = parts.filter(good) {
            return parts;
        }
    }
    clip_unchecked(mesh, planes, eps)
        .map(finish)
        .unwrap_or_default()
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
