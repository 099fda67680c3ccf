//! The tetrahedra as convex cells clipped exactly to the mesh: the pieces of the tetra
//! method before merging.
//!
//! A tetrahedron the surface does not enter is either wholly inside the mesh or wholly
//! outside; one inside whose four neighbours are inside too is kept as it is (the fast
//! path: on a convex mesh holding every point, all of them). Every other tetrahedron is
//! clipped from the mesh by its four face planes with the exact clipper of the Voronoi
//! cells, and each connected part of what is left is a piece: surface triangles keep
//! their source-triangle tags, cut faces are caps tagged with the tetrahedron face.

mod clip;
mod exact;
mod grid;
mod local;

use glam::DVec3;
use rayon::prelude::*;

use crate::delaunay::{NO_NEIGHBOR, Tetrahedralization};
use crate::fracture::kernel::convex::{TET_FACES, tet_volume};
use crate::fracture::kernel::{Piece, Plane, SURFACE, is_surface, mesh_scale};
use crate::fracture::seeds::inside::InsideTester;
use crate::util::{FastMap, UnionFind, bounds};
use grid::TriangleGrid;
use local::{Job, clip_cells, exact_cells};

/// Distance (relative to the mesh's size) the surface must keep from a tetrahedron's
/// faces for it to count as not entering the tetrahedron; nearer, it is clipped.
const CROSS_MARGIN: f64 = 1e-12;
/// Tetrahedra of at most this fraction of the mesh's volume are flat: left out (as
/// fragments they would have back-to-back faces), their faces made one plane where they
/// are one ([`COPLANAR_SINE`]).
pub(super) const FLAT_FRACTION: f64 = 1e-16;
/// A flat tetrahedron's faces are made one plane when their normals are parallel up to
/// this sine (the same bound as the UV bases' planes, [`crate::fracture::attributes`]).
const COPLANAR_SINE: f64 = crate::fracture::attributes::SAME_PLANE_SINE;
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
    let hull_thin = |t: usize, c: [DVec3; 4], volume: f64| {
        del.neighbors(t).contains(&NO_NEIGHBOR) && thickness(c, volume) <= thin
    };
    let flat: Vec<bool> = (0..nt)
        .map(|t| {
            let c = corners(t);
            let volume = tet_volume(c);
            volume <= min_volume || hull_thin(t, c, volume)
        })
        .collect();
    // A flat tetrahedron on the points' hull (coplanar points on a flat part of it)
    // makes its neighbours' faces there outer surface. One that is merely tiny (a few
    // points a rounding error apart, as a CAD model's welded cracks leave them) is left
    // out too, but its faces are not one plane: made one, their caps would share one
    // UV basis averaged over planes far apart, and match no facing cap's.
    let mut same_plane = UnionFind::new(4 * nt);
    let mut hull_faces: Vec<usize> = Vec::new();
    for t in (0..nt).filter(|&t| flat[t]) {
        let c = corners(t);
        if !hull_thin(t, c, tet_volume(c)) && !faces_coplanar(c) {
            continue;
        }
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
    // The tetrahedra to clip, each from the part of the mesh near it ([`local`]).
    let to_clip: Vec<usize> = (0..nt)
        .filter(|&t| side[t] != Side::Outside && !flat[t] && !fast(t))
        .collect();
    let job = |t: usize| {
        let c = corners(t);
        let (lo, hi) = bounds(&c);
        Job {
            lo,
            hi,
            planes: (0..4).map(|f| face_plane(del, pts, t, f)).collect(),
            corners: c,
        }
    };
    let room = (1e3 * eps).max(1e-9 * mesh_scale(mesh));
    let jobs: Vec<Job> = to_clip.iter().map(|&t| job(t)).collect();
    // The rest are kept whole (inside, with every neighbour inside) or have no cell.
    let mut per_tet: Vec<Vec<(Piece, bool)>> = (0..nt)
        .map(|t| {
            if fast(t) && !flat[t] {
                vec![(whole_piece(del, pts, t), true)]
            } else {
                Vec::new()
            }
        })
        .collect();
    for (&t, parts) in to_clip.iter().zip(clip_cells(mesh, jobs, eps, room)) {
        per_tet[t] = parts.into_iter().map(|p| (p, false)).collect();
    }
    // A cell the clipper closed can still be wrong where rounding decides (a CAD
    // model's faces in a tetrahedron's face plane): the two cells of a face must meet
    // in equal caps. Those that do not are made again by the exact boolean.
    let redo = disagreeing(del, pts, &per_tet, &to_clip, &flat, eps);
    let exact = exact_cells(mesh, redo.iter().map(|&t| job(t)).collect(), eps, room);
    for (&t, parts) in redo.iter().zip(exact) {
        if let Some(parts) = parts {
            per_tet[t] = parts.into_iter().map(|p| (p, false)).collect();
        }
    }
    for &t in &to_clip {
        for (p, _) in &mut per_tet[t] {
            // A cap on a face of the points' hull has no neighbour: it is the
            // fragments' outer surface (inside the mesh when corners are skipped).
            for tag in &mut p.tags {
                if !is_surface(*tag) && is_hull_face(del, *tag) {
                    *tag = SURFACE;
                }
            }
        }
    }
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

/// How far the caps of a face's two cells may differ: this fraction of the face's area,
/// plus the strip of the cuts' on-plane tolerance along its edges, [`CAP_EDGE_STRIP`]
/// times the tolerance wide (where a cut vertex may be moved onto the plane).
const CAP_AREA_MISMATCH: f64 = 1e-6;
const CAP_EDGE_STRIP: f64 = 10.0;

/// The clipped tetrahedra (in `to_clip`, whose cells `per_tet` holds) whose cell does
/// not meet a neighbour's in equal caps on their shared face: the cap's area vector
/// (the sum over the cell's triangles tagged with the face) must be minus the
/// neighbour's when that is clipped too, the whole face when the neighbour is kept
/// whole, and zero when the neighbour has no cell (the surface there is the mesh's own).
/// Faces of the points' hull and of flat tetrahedra are not checked. Both tetrahedra of
/// a face that disagrees are returned, in increasing order.
fn disagreeing(
    del: &Tetrahedralization,
    pts: &[DVec3],
    per_tet: &[Vec<(Piece, bool)>],
    to_clip: &[usize],
    flat: &[bool],
    eps: f64,
) -> Vec<usize> {
    let caps = |t: usize| -> [DVec3; 4] {
        let tags: [u64; 4] = std::array::from_fn(|f| face_plane(del, pts, t, f).tag);
        let mut area = [DVec3::ZERO; 4];
        for (p, _) in &per_tet[t] {
            for (tri, tag) in p.tris.iter().zip(&p.tags) {
                if let Some(f) = tags.iter().position(|x| x == tag) {
                    let [a, b, c] = tri.map(|i| p.pos[i as usize]);
                    area[f] += 0.5 * (b - a).cross(c - a);
                }
            }
        }
        area
    };
    // Per tetrahedron, its cell's caps when it is clipped.
    let mut areas: Vec<Option<[DVec3; 4]>> = vec![None; del.len()];
    let computed: Vec<[DVec3; 4]> = to_clip.par_iter().map(|&t| caps(t)).collect();
    for (&t, a) in to_clip.iter().zip(computed) {
        areas[t] = Some(a);
    }
    let areas = &areas;
    let mut bad: Vec<usize> = to_clip
        .par_iter()
        .filter_map(|&t| areas[t].map(|mine| (t, mine)))
        .flat_map_iter(|(t, mine)| {
            let c = del.tetrahedron(t).map(|i| pts[i as usize]);
            (0..4).filter_map(move |f| {
                let u = del.neighbors(t)[f];
                if u == NO_NEIGHBOR || flat[u as usize] {
                    return None;
                }
                let u = u as usize;
                let [a, b, cc] = TET_FACES[f].map(|i| c[i]);
                let face = 0.5 * (b - a).cross(cc - a);
                let expected = match &areas[u] {
                    Some(theirs) => {
                        let g = (0..4).find(|&g| del.neighbors(u)[g] as usize == t)?;
                        -theirs[g]
                    }
                    None if per_tet[u].is_empty() => DVec3::ZERO,
                    None => face,
                };
                let perimeter = (b - a).length() + (cc - b).length() + (a - cc).length();
                let tol = CAP_AREA_MISMATCH * face.length() + CAP_EDGE_STRIP * eps * perimeter;
                ((mine[f] - expected).length() > tol).then_some([t, u])
            })
        })
        .flatten()
        .filter(|&t| areas[t].is_some())
        .collect();
    bad.sort_unstable();
    bad.dedup();
    bad
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

/// Whether the four faces of the tetrahedron `c` lie in one plane up to
/// [`COPLANAR_SINE`]: each face's unit normal parallel to the first's, up to sign (faces
/// of no area, collinear corners, agree with any).
fn faces_coplanar(c: [DVec3; 4]) -> bool {
    let normals: Vec<DVec3> = TET_FACES
        .iter()
        .filter_map(|f| (c[f[1]] - c[f[0]]).cross(c[f[2]] - c[f[0]]).try_normalize())
        .collect();
    normals
        .iter()
        .all(|n| n.cross(normals[0]).length() <= COPLANAR_SINE)
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
    let c = del.tetrahedron(t).map(|i| pts[i as usize]);
    corner_plane(c, f, (4 * t + f) as u64)
}

/// The plane of face `f` ([`TET_FACES`]`[f]`) of the tetrahedron with corners `c`,
/// outward when `c` is positively oriented, tagged `tag`.
fn corner_plane(c: [DVec3; 4], f: usize, tag: u64) -> Plane {
    let [a, b, cc] = TET_FACES[f].map(|i| c[i]);
    let n = (b - a).cross(cc - a);
    Plane {
        n,
        d: n.dot(a),
        tag,
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

#[cfg(test)]
mod tests {
    use glam::DVec3;

    use super::{COPLANAR_SINE, disagreeing, face_plane, faces_coplanar};
    use crate::delaunay::tetrahedralize;
    use crate::fracture::kernel::{Piece, Plane};
    use crate::shapes;

    /// A few tetrahedra about the origin, all cut by the unit cube: their cells meet in
    /// equal caps, and none is found. A cell clipped from a smaller cube (a cell that
    /// lost part of its volume) no longer matches its neighbours' caps: it is found, with
    /// them.
    #[test]
    fn a_cell_that_lost_volume_is_found_by_its_neighbours_cap() {
        // A triangle in z = 0 with one apex above and one below.
        let pts = vec![
            DVec3::new(-0.9, -0.8, 0.0),
            DVec3::new(0.9, -0.7, 0.0),
            DVec3::new(0.1, 0.9, 0.0),
            DVec3::new(0.05, 0.0, 0.8),
            DVec3::new(-0.05, 0.05, -0.8),
        ];
        let del = tetrahedralize(&pts).unwrap();
        let n = del.len();
        assert!(n >= 2);
        let cell = |mesh: &Piece, t: usize| -> Vec<(Piece, bool)> {
            let planes: Vec<Plane> = (0..4).map(|f| face_plane(&del, &pts, t, f)).collect();
            let corners = del.tetrahedron(t).map(|i| pts[i as usize]);
            super::clip::clip_cell(mesh, planes, corners, 1e-10)
                .into_iter()
                .map(|p| (p, false))
                .collect()
        };
        let cube = Piece::from_mesh_welded(&shapes::cube());
        let mut per_tet: Vec<Vec<(Piece, bool)>> = (0..n).map(|t| cell(&cube, t)).collect();
        assert!(per_tet.iter().all(|c| !c.is_empty()));
        let flat = vec![false; n];
        let all: Vec<usize> = (0..n).collect();
        assert!(disagreeing(&del, &pts, &per_tet, &all, &flat, 1e-10).is_empty());
        let mut smaller = shapes::cube();
        for p in &mut smaller.positions {
            p.x *= 0.8;
        }
        per_tet[0] = cell(&Piece::from_mesh_welded(&smaller), 0);
        let found = disagreeing(&del, &pts, &per_tet, &all, &flat, 1e-10);
        let neighbours = del.neighbors(0);
        assert!(found.len() >= 2 && found[0] == 0, "{found:?}");
        assert!(found[1..].iter().all(|&t| neighbours.contains(&(t as u32))));
    }

    /// Four points a rounding error off one plane make a tetrahedron whose faces are one
    /// plane; a tiny regular tetrahedron (of any volume) does not, nor does one whose
    /// fourth point stands off the plane by more than the bound allows.
    #[test]
    fn only_a_tetrahedron_of_coplanar_faces_is_made_one_plane() {
        let base = [DVec3::ZERO, DVec3::X, DVec3::Y];
        let flat = [base[0], base[1], base[2], DVec3::new(0.4, 0.4, 1e-12)];
        assert!(faces_coplanar(flat));
        let off = [
            base[0],
            base[1],
            base[2],
            DVec3::new(0.4, 0.4, 10.0 * COPLANAR_SINE),
        ];
        assert!(!faces_coplanar(off));
        let tiny = [
            DVec3::ZERO,
            DVec3::new(1e-7, 0.0, 0.0),
            DVec3::new(0.0, 1e-7, 0.0),
            DVec3::new(0.0, 0.0, 1e-7),
        ];
        assert!(!faces_coplanar(tiny), "tiny is not flat");
        let collinear = [DVec3::ZERO, DVec3::X, 2.0 * DVec3::X, 3.0 * DVec3::X];
        assert!(faces_coplanar(collinear), "no face has an area");
    }
}
