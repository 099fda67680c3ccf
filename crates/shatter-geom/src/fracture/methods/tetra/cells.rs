//! The tetrahedra as convex cells clipped exactly to the mesh: the pieces of the tetra
//! method before merging.
//!
//! A tetrahedron the surface does not enter is either wholly inside the mesh or wholly
//! outside; one inside whose four neighbours are inside too is kept as it is (the fast
//! path: on a convex mesh holding every point, all of them). Every other tetrahedron is
//! clipped from the mesh by its four face planes with the exact clipper of the Voronoi
//! cells, and each connected part of what is left is a piece: surface triangles keep
//! their source-triangle tags, cut faces are caps tagged with the tetrahedron face.

use glam::DVec3;
use rayon::prelude::*;

use crate::delaunay::{NO_NEIGHBOR, Tetrahedralization};
use crate::fracture::kernel::clip::clip_keeping_faces;
use crate::fracture::kernel::convex::{TET_FACES, tet_volume};
use crate::fracture::kernel::{Piece, Plane, SURFACE, is_surface, mesh_scale};
use crate::fracture::seeds::inside::InsideTester;
use crate::util::{FastMap, UnionFind, bounds};

/// Distance (relative to the mesh's size) the surface must keep from a tetrahedron's
/// faces for it to count as not entering the tetrahedron; nearer, it is clipped.
const CROSS_MARGIN: f64 = 1e-12;
/// Tetrahedra of at most this fraction of the mesh's volume are flat: left out, their
/// faces made one plane (as fragments they would have back-to-back faces).
pub(super) const FLAT_FRACTION: f64 = 1e-16;
/// A tetrahedron on the points' hull at most this thin (relative to the mesh's size) is
/// flat too: four surface points coplanar up to the input's own precision (a float32
/// file's quads are planar only to about 1e-7 of its size). Kept, it would be a sliver
/// on the surface whose inner faces, merged into one neighbour, leave the other
/// neighbour a cut face a hair under the outer surface, labelled interior.
pub(super) const HULL_FLAT_THICKNESS: f64 = 1e-7;
/// A mesh convex up to [`HULL_FLAT_THICKNESS`] whose points' hull is within this
/// fraction of its volume is taken as that hull (its tetrahedra kept whole).
const HULL_VOLUME_GAP: f64 = 1e-6;
/// Clipped pieces of at most this fraction of the mesh's volume are dropped (what is
/// left where a cut grazes the surface: zero volume up to rounding).
const PIECE_FLAT_FRACTION: f64 = 1e-16;

/// The pieces of a tetrahedralization clipped to a mesh.
pub(super) struct Cells {
    pub pieces: Vec<Piece>,
    /// Per piece: its tetrahedron.
    pub tet: Vec<usize>,
    /// Per piece: whether it is its whole tetrahedron, not clipped (four triangles,
    /// the tetrahedron's own corners).
    pub whole: Vec<bool>,
}

/// Where a tetrahedron lies relative to the mesh.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Side {
    /// The surface does not enter it and its centroid is inside.
    Inside,
    /// The surface does not enter it and its centroid is outside.
    Outside,
    /// The surface comes into it (or within the margin of its faces).
    Crossed,
}

/// The cells of `del` (over `pts`) clipped to `mesh` (volume `mesh_volume`); `eps` is
/// the clipper's on-plane tolerance.
pub(super) fn cells(
    mesh: &Piece,
    mesh_volume: f64,
    del: &Tetrahedralization,
    pts: &[DVec3],
    eps: f64,
    exact: bool,
) -> Cells {
    let nt = del.len();
    let corners = |t: usize| del.tetrahedron(t).map(|i| pts[i as usize]);
    let hull_volume: f64 = (0..nt).map(|t| tet_volume(corners(t))).sum();
    // Every tetrahedron is inside when the points' hull is the mesh (a convex mesh
    // holding every point): the thesis's case, no test needed. A mesh read from a
    // 32-bit file is convex only up to its rounding (its quads bent by ~1e-8): then too,
    // and the tetrahedra are kept whole rather than clipped by a hair, which would leave
    // edges far below what a 32-bit writer or viewer can hold.
    let gap = (hull_volume - mesh_volume).abs();
    let all_inside = gap <= 1e-9 * mesh_volume
        || (gap <= HULL_VOLUME_GAP * mesh_volume
            && convex_within(mesh, HULL_FLAT_THICKNESS * mesh_scale(mesh)));
    let side: Vec<Side> = if all_inside {
        vec![Side::Inside; nt]
    } else {
        let tester = InsideTester::new(mesh);
        let grid = TriangleGrid::new(mesh);
        let margin = CROSS_MARGIN * mesh_scale(mesh);
        (0..nt)
            .into_par_iter()
            .map(|t| {
                let c = corners(t);
                if exact && grid.enters(mesh, c, margin) {
                    Side::Crossed
                } else if tester.contains((c[0] + c[1] + c[2] + c[3]) / 4.0) {
                    Side::Inside
                } else {
                    Side::Outside
                }
            })
            .collect()
    };
    let min_volume = FLAT_FRACTION * mesh_volume;
    // A flat tetrahedron (four coplanar points, as on a torus's cross-section) is left
    // out, and its faces are made one plane: the caps its neighbours have on either side
    // then bond through their overlaps.
    let thin = HULL_FLAT_THICKNESS * mesh_scale(mesh);
    let flat: Vec<bool> = (0..nt)
        .map(|t| {
            let c = corners(t);
            let volume = tet_volume(c);
            volume <= min_volume
                || (del.neighbors(t).contains(&NO_NEIGHBOR) && thickness(c, volume) <= thin)
        })
        .collect();
    // A flat tetrahedron on the points' hull (coplanar points on a flat part of it)
    // makes its neighbours' faces there outer surface.
    let mut same_plane = UnionFind::new(4 * nt);
    let mut hull_faces: Vec<usize> = Vec::new();
    for t in (0..nt).filter(|&t| flat[t]) {
        let first = face_plane(del, pts, t, 0).tag as usize;
        for f in 0..4 {
            let tag = face_plane(del, pts, t, f).tag as usize;
            same_plane.union(first, tag);
            if del.neighbors(t)[f] == NO_NEIGHBOR {
                hull_faces.push(tag);
            }
        }
    }
    let mut on_hull = vec![false; 4 * nt];
    for tag in hull_faces {
        let r = same_plane.find(tag);
        on_hull[r] = true;
    }
    // Kept as it is: inside, and so is every neighbour, none of them flat (a flat one
    // can lie on the surface, which then bounds this one).
    let fast = |t: usize| {
        side[t] == Side::Inside
            && (all_inside
                || !exact
                || del.neighbors(t).iter().all(|&n| {
                    n != NO_NEIGHBOR && side[n as usize] == Side::Inside && !flat[n as usize]
                }))
    };
    let per_tet: Vec<Vec<(Piece, bool)>> = (0..nt)
        .into_par_iter()
        .with_max_len(1)
        .map(|t| {
            if side[t] == Side::Outside || flat[t] {
                return Vec::new();
            }
            if fast(t) {
                return vec![(whole_piece(del, pts, t), true)];
            }
            let planes: Vec<Plane> = (0..4).map(|f| face_plane(del, pts, t, f)).collect();
            clip_cell(mesh, planes, eps)
                .into_iter()
                .map(|mut p| {
                    // A cap on a face of the points' hull has no neighbour: it is the
                    // fragments' outer surface (inside the mesh when corners are skipped).
                    for tag in &mut p.tags {
                        if !is_surface(*tag) && is_hull_face(del, *tag) {
                            *tag = SURFACE;
                        }
                    }
                    (p, false)
                })
                .collect()
        })
        .collect();
    let mut out = Cells {
        pieces: Vec::new(),
        tet: Vec::new(),
        whole: Vec::new(),
    };
    let any_flat = flat.iter().any(|&f| f);
    for (t, list) in per_tet.into_iter().enumerate() {
        for (mut p, whole) in list {
            if p.volume() <= PIECE_FLAT_FRACTION * mesh_volume {
                continue;
            }
            if any_flat {
                for tag in p.tags.iter_mut().filter(|t| !is_surface(**t)) {
                    let r = same_plane.find(*tag as usize);
                    *tag = if on_hull[r] { SURFACE } else { r as u64 };
                }
            }
            out.pieces.push(p);
            out.tet.push(t);
            out.whole.push(whole);
        }
    }
    out
}

/// Whether no edge of the closed `mesh` is reflex by more than `delta`: the far corner of
/// each triangle across an edge lies at most `delta` above the other's plane. A closed
/// surface convex at every edge is convex.
fn convex_within(mesh: &Piece, delta: f64) -> bool {
    let mut across: FastMap<(u32, u32), u32> = FastMap::default();
    across.reserve(3 * mesh.tris.len());
    for t in &mesh.tris {
        for k in 0..3 {
            across.insert((t[k], t[(k + 1) % 3]), t[(k + 2) % 3]);
        }
    }
    mesh.tris.iter().all(|t| {
        let [a, b, c] = t.map(|i| mesh.pos[i as usize]);
        let n = (b - a).cross(c - a).normalize_or_zero();
        (0..3).all(|k| match across.get(&(t[(k + 1) % 3], t[k])) {
            Some(&d) => n.dot(mesh.pos[d as usize] - a) <= delta,
            None => false,
        })
    })
}

/// The height of a tetrahedron of volume `volume` over its largest face: how thin it is.
fn thickness(c: [DVec3; 4], volume: f64) -> f64 {
    let largest = TET_FACES
        .iter()
        .map(|f| (c[f[1]] - c[f[0]]).cross(c[f[2]] - c[f[0]]).length() / 2.0)
        .fold(0.0, f64::max);
    if largest == 0.0 {
        0.0
    } else {
        3.0 * volume / largest
    }
}

/// The plane of face `f` of tetrahedron `t`, outward from `t`, tagged with the face:
/// both tetrahedra of a face use the lower-numbered one's plane and tag (one of them
/// flipped, which is exact), so they classify every vertex alike and their caps match.
pub(super) fn face_plane(del: &Tetrahedralization, pts: &[DVec3], t: usize, f: usize) -> Plane {
    let nb = del.neighbors(t)[f];
    if nb != NO_NEIGHBOR && (nb as usize) < t {
        let n = nb as usize;
        if let Some(g) = (0..4).find(|&g| del.neighbors(n)[g] as usize == t) {
            return own_plane(del, pts, n, g).flipped();
        }
    }
    own_plane(del, pts, t, f)
}

/// The plane of face `f` of `t` from its own corners, outward, tagged `4t + f`.
pub(super) fn own_plane(del: &Tetrahedralization, pts: &[DVec3], t: usize, f: usize) -> Plane {
    let c = del.tetrahedron(t);
    let [a, b, cc] = TET_FACES[f].map(|i| pts[c[i] as usize]);
    let n = (b - a).cross(cc - a);
    Plane {
        n,
        d: n.dot(a),
        tag: (4 * t + f) as u64,
    }
}

/// Whether a cap tag names a face of the points' hull (no tetrahedron beyond it).
fn is_hull_face(del: &Tetrahedralization, tag: u64) -> bool {
    let (t, f) = ((tag / 4) as usize, (tag % 4) as usize);
    t < del.len() && del.neighbors(t)[f] == NO_NEIGHBOR
}

/// Tetrahedron `t` as a piece: its corners and four faces, each tagged with its face
/// plane, or [`SURFACE`] on the points' hull.
fn whole_piece(del: &Tetrahedralization, pts: &[DVec3], t: usize) -> Piece {
    let c = del.tetrahedron(t);
    let tags = (0..4)
        .map(|f| {
            if del.neighbors(t)[f] == NO_NEIGHBOR {
                SURFACE
            } else {
                face_plane(del, pts, t, f).tag
            }
        })
        .collect();
    Piece {
        pos: c.iter().map(|&i| pts[i as usize]).collect(),
        tris: TET_FACES.iter().map(|f| f.map(|i| i as u32)).collect(),
        tags,
        faces: Vec::new(),
    }
}

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
        cell.components()
            .into_iter()
            .flat_map(split_at_pinched_edges)
            .collect()
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

/// The mesh's triangles bucketed on a 3D grid by their bounds.
struct TriangleGrid {
    lo: DVec3,
    cell: DVec3,
    n: usize,
    buckets: Vec<Vec<u32>>,
}

impl TriangleGrid {
    fn new(mesh: &Piece) -> Self {
        let (lo, hi) = bounds(&mesh.pos);
        let n = ((mesh.tris.len() as f64 / 4.0).cbrt().ceil() as usize).clamp(1, 48);
        let cell = ((hi - lo) / n as f64).max(DVec3::splat(f64::MIN_POSITIVE));
        let mut grid = Self {
            lo,
            cell,
            n,
            buckets: vec![Vec::new(); n * n * n],
        };
        for (t, tri) in mesh.tris.iter().enumerate() {
            let [a, b, c] = tri.map(|i| mesh.pos[i as usize]);
            let (i0, i1) = (grid.index(a.min(b).min(c)), grid.index(a.max(b).max(c)));
            for x in i0[0]..=i1[0] {
                for y in i0[1]..=i1[1] {
                    for z in i0[2]..=i1[2] {
                        grid.buckets[(z * n + y) * n + x].push(t as u32);
                    }
                }
            }
        }
        grid
    }

    fn index(&self, p: DVec3) -> [usize; 3] {
        let q = (p - self.lo) / self.cell;
        let k = |v: f64| (v.max(0.0) as usize).min(self.n - 1);
        [k(q.x), k(q.y), k(q.z)]
    }

    /// Whether a triangle of `mesh` comes into tetrahedron `c` (positively oriented)
    /// shrunk by `margin`: then the surface may cut it.
    fn enters(&self, mesh: &Piece, c: [DVec3; 4], margin: f64) -> bool {
        let mut planes = [(DVec3::ZERO, 0.0); 4];
        for (f, face) in TET_FACES.iter().enumerate() {
            let [a, b, cc] = face.map(|i| c[i]);
            let n = (b - a).cross(cc - a).normalize_or_zero();
            if n == DVec3::ZERO {
                return false;
            }
            planes[f] = (n, n.dot(a) - margin);
        }
        let (lo, hi) = (
            c[0].min(c[1]).min(c[2]).min(c[3]),
            c[0].max(c[1]).max(c[2]).max(c[3]),
        );
        let (i0, i1) = (self.index(lo), self.index(hi));
        let n = self.n;
        let mut seen: Vec<u32> = Vec::new();
        for x in i0[0]..=i1[0] {
            for y in i0[1]..=i1[1] {
                for z in i0[2]..=i1[2] {
                    seen.extend(&self.buckets[(z * n + y) * n + x]);
                }
            }
        }
        seen.sort_unstable();
        seen.dedup();
        seen.iter().any(|&t| {
            let tri = mesh.tris[t as usize].map(|i| mesh.pos[i as usize]);
            triangle_enters(tri, &planes)
        })
    }
}

/// Whether some point of triangle `tri` lies on the negative side of all `planes`
/// (`n · x <= d`): the triangle clipped by each in turn (Sutherland–Hodgman) keeps
/// something.
fn triangle_enters(tri: [DVec3; 3], planes: &[(DVec3, f64); 4]) -> bool {
    let mut poly: Vec<DVec3> = tri.to_vec();
    for &(n, d) in planes {
        let s: Vec<f64> = poly.iter().map(|&p| n.dot(p) - d).collect();
        if s.iter().all(|&v| v > 0.0) {
            return false;
        }
        if s.iter().all(|&v| v <= 0.0) {
            continue;
        }
        let mut next = Vec::with_capacity(poly.len() + 1);
        for i in 0..poly.len() {
            let j = (i + 1) % poly.len();
            if s[i] <= 0.0 {
                next.push(poly[i]);
            }
            if (s[i] <= 0.0) != (s[j] <= 0.0) {
                let t = s[i] / (s[i] - s[j]);
                next.push(poly[i] + (poly[j] - poly[i]) * t);
            }
        }
        poly = next;
        if poly.is_empty() {
            return false;
        }
    }
    !poly.is_empty()
}
