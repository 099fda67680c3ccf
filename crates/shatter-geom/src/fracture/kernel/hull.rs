//! The convex hull of a point set (quickhull, with a tolerance far above rounding). A
//! convex piece of the decomposition is convex only within its tolerance; its hull is
//! what the collider is, and what a runtime cut clips ([`super::polytope::Polytope`]).

use glam::DVec3;

use crate::delaunay::FACES;
use crate::util::FastMap;

/// How far in front of the hull (relative to the points' extent) a point must lie to be
/// added; nearer ones are left out. Far above rounding, so that every new triangle is far
/// from flat and its plane is known to about 1e-9 of the extent; far below anything a
/// collider feels.
const HULL_TOLERANCE: f64 = 1e-7;

/// A hull: its outward triangles (indices into the points) and, per triangle, the
/// triangle across each edge (`nbr[t][k]` across `tris[t][k] → tris[t][k + 1]`).
#[derive(Debug, Clone, Default, PartialEq)]
pub(crate) struct HullMesh {
    pub tris: Vec<[u32; 3]>,
    pub nbr: Vec<[u32; 3]>,
}

/// The convex hull of `points`, or `None` when the points span no volume.
///
/// Quickhull: every point not yet on the hull waits on a face it lies in front of (the
/// one it lies farthest in front of, among the faces it was offered). The farthest
/// point waiting on a face is added: the faces it lies more than [`HULL_TOLERANCE`] in
/// front of, the connected region around that face, give way to a fan from the point to
/// the region's boundary, and their waiting points move to the new face they lie
/// farthest in front of (a point in front of none is inside the hull). A point inside
/// the hull, on it or nearer to it than the tolerance is left out (the hull may miss it
/// by that much). Faces keep their neighbours as they go, so no edge is ever looked up.
/// Should rounding still leave the result other than a closed surface convex at every
/// edge (within twice the tolerance), the exact hull of the points' Delaunay
/// tetrahedralization is taken instead.
pub(crate) fn hull_mesh(points: &[DVec3]) -> Option<HullMesh> {
    if points.len() < 4 {
        return None;
    }
    let (lo, hi) = crate::util::bounds(points);
    let tol = HULL_TOLERANCE * (hi - lo).length();
    let Some(first) = first_tetrahedron(points, tol) else {
        return exact_hull(points);
    };
    // Room for the faces of a hull of a few dozen corners, made and removed.
    let room = 8 * points.len().min(256);
    let mut h = Hull {
        pts: points,
        faces: Vec::with_capacity(room),
        nbr: Vec::with_capacity(room),
        planes: Vec::with_capacity(room),
        alive: Vec::with_capacity(room),
        waiting: Vec::with_capacity(room),
        spare: Vec::new(),
        tol,
    };
    for face in FACES {
        h.add(face.map(|k| first[k]), [u32::MAX; 3]);
    }
    // The first four faces' neighbours: the face holding each edge the other way.
    for f in 0..4 {
        for k in 0..3 {
            let (a, b) = (h.faces[f][k], h.faces[f][(k + 1) % 3]);
            h.nbr[f][k] = (0..4)
                .find(|&g| (0..3).any(|j| h.faces[g][j] == b && h.faces[g][(j + 1) % 3] == a))
                .map_or(u32::MAX, |g| g as u32);
        }
    }
    let all: Vec<u32> = (0..points.len() as u32)
        .filter(|p| !first.contains(p))
        .collect();
    h.assign(&all, 0);
    let mut seen = Vec::new();
    let mut stack = Vec::new();
    // The seen region's boundary: (from, to, the unseen face across it).
    let mut horizon: Vec<(u32, u32, u32)> = Vec::new();
    let mut cycle: Vec<(u32, u32, u32)> = Vec::new();
    let mut orphans = Vec::new();
    // Per face, the round that last checked it and what it found (seen or not): no
    // clearing between rounds.
    let mut state: Vec<(u32, bool)> = Vec::new();
    let mut round = 0u32;
    let mut f = 0;
    while f < h.faces.len() {
        if !h.alive[f] || h.waiting[f].is_empty() {
            f += 1;
            continue;
        }
        // The point waiting on `f` farthest in front of it: a corner of the hull.
        let (k, p) = h.waiting[f]
            .iter()
            .enumerate()
            .map(|(k, &p)| (k, p, h.height(f, p)))
            .max_by(|a, b| a.2.total_cmp(&b.2))
            .map(|(k, p, _)| (k, p))
            .unwrap_or((0, 0));
        h.waiting[f].swap_remove(k);
        // The faces `p` sees, flooded from `f`.
        round += 1;
        state.resize(h.faces.len(), (0, false));
        seen.clear();
        horizon.clear();
        orphans.clear();
        state[f] = (round, true);
        stack.push(f);
        while let Some(g) = stack.pop() {
            seen.push(g);
            for k in 0..3 {
                let n = h.nbr[g][k] as usize;
                let Some(&(checked, seen_n)) = state.get(n) else {
                    return exact_hull(points);
                };
                let seen_n = if checked == round {
                    seen_n
                } else {
                    let s = h.height(n, p) > h.tol;
                    state[n] = (round, s);
                    if s {
                        stack.push(n);
                    }
                    s
                };
                if !seen_n {
                    let tri = h.faces[g];
                    horizon.push((tri[k], tri[(k + 1) % 3], n as u32));
                }
            }
        }
        // The boundary as one loop (it is one when the seen region is a disc).
        cycle.clear();
        if let Some(&start) = horizon.first() {
            cycle.push(start);
            while cycle.len() < horizon.len() {
                let to = cycle[cycle.len() - 1].1;
                match horizon.iter().find(|e| e.0 == to) {
                    Some(&e) if e != start => cycle.push(e),
                    _ => break,
                }
            }
        }
        if cycle.len() != horizon.len() || cycle.len() < 3 || cycle[cycle.len() - 1].1 != cycle[0].0
        {
            return exact_hull(points);
        }
        for &g in &seen {
            orphans.append(&mut h.waiting[g]);
            // Its list, empty now, keeps its room for a new face (no regrowing).
            let list = std::mem::take(&mut h.waiting[g]);
            h.spare.push(list);
            h.alive[g] = false;
        }
        // The fan: face i is (a, b, p) for boundary edge i, between faces i - 1 and i + 1.
        let first_new = h.faces.len() as u32;
        let m = cycle.len() as u32;
        for (i, &(a, b, outer)) in cycle.iter().enumerate() {
            let i = i as u32;
            let f = first_new + i;
            h.add(
                [a, b, p],
                [outer, first_new + (i + 1) % m, first_new + (i + m - 1) % m],
            );
            let o = &mut h.nbr[outer as usize];
            let of = h.faces[outer as usize];
            for j in 0..3 {
                if of[j] == b && of[(j + 1) % 3] == a {
                    o[j] = f;
                }
            }
        }
        h.assign(&orphans, first_new as usize);
        // Faces before `f` may have waiting points only if new; new ones come after.
        f = f.min(first_new as usize);
    }
    // The live faces, renumbered.
    let mut index = vec![u32::MAX; h.faces.len()];
    let mut mesh = HullMesh::default();
    for g in (0..h.faces.len()).filter(|&g| h.alive[g]) {
        index[g] = mesh.tris.len() as u32;
        mesh.tris.push(h.faces[g]);
    }
    for g in (0..h.faces.len()).filter(|&g| h.alive[g]) {
        let nbr = h.nbr[g].map(|n| index.get(n as usize).copied().unwrap_or(u32::MAX));
        if nbr.contains(&u32::MAX) {
            return exact_hull(points);
        }
        mesh.nbr.push(nbr);
    }
    // Convex at every edge: the far corner of the face across each edge lies behind (a
    // closed surface convex at every edge bounds a convex solid).
    let convex = (0..h.faces.len()).filter(|&g| h.alive[g]).all(|g| {
        (0..3).all(|k| {
            let (a, b) = (h.faces[g][k], h.faces[g][(k + 1) % 3]);
            h.faces[h.nbr[g][k] as usize]
                .iter()
                .all(|&v| v == a || v == b || h.height(g, v) <= 2.0 * tol)
        })
    });
    if !convex {
        return exact_hull(points);
    }
    Some(mesh)
}

/// [`hull_mesh`]'s triangles.
#[cfg(test)]
pub(crate) fn hull_triangles(points: &[DVec3]) -> Option<Vec<[u32; 3]>> {
    hull_mesh(points).map(|m| m.tris)
}

/// The exact hull: the faces of the points' Delaunay tetrahedralization that have no
/// neighbour (slower: the exact predicates are slow on the many points of a piece that
/// lie in one plane).
fn exact_hull(points: &[DVec3]) -> Option<HullMesh> {
    let t = crate::delaunay::tetrahedralize(points).ok()?;
    let tris = t.hull_faces();
    let mut across: FastMap<(u32, u32), u32> = FastMap::default();
    for (f, tri) in tris.iter().enumerate() {
        for k in 0..3 {
            across.insert((tri[k], tri[(k + 1) % 3]), f as u32);
        }
    }
    let nbr = tris
        .iter()
        .map(|tri| {
            let mut n = [u32::MAX; 3];
            for k in 0..3 {
                n[k] = *across.get(&(tri[(k + 1) % 3], tri[k]))?;
            }
            Some(n)
        })
        .collect::<Option<Vec<_>>>()?;
    Some(HullMesh { tris, nbr })
}

/// The hull being built: its triangles (removed ones kept, not alive), their
/// neighbours and planes, and the points waiting on each.
struct Hull<'a> {
    pts: &'a [DVec3],
    faces: Vec<[u32; 3]>,
    nbr: Vec<[u32; 3]>,
    /// Per face, its unit outward normal and offset.
    planes: Vec<(DVec3, f64)>,
    alive: Vec<bool>,
    /// Per face, the points waiting on it (lying in front of it).
    waiting: Vec<Vec<u32>>,
    /// Empty lists of removed faces, kept with their room for new faces.
    spare: Vec<Vec<u32>>,
    /// How far in front of a face a point must lie to see it.
    tol: f64,
}

impl Hull<'_> {
    /// How far point `p` lies in front of face `f`.
    fn height(&self, f: usize, p: u32) -> f64 {
        let (n, d) = self.planes[f];
        n.dot(self.pts[p as usize]) - d
    }

    fn add(&mut self, tri: [u32; 3], nbr: [u32; 3]) {
        let [a, b, c] = tri.map(|i| self.pts[i as usize]);
        let n = (b - a).cross(c - a).normalize_or_zero();
        self.planes.push((n, n.dot(a)));
        self.faces.push(tri);
        self.nbr.push(nbr);
        self.alive.push(true);
        self.waiting.push(self.spare.pop().unwrap_or_default());
    }

    /// Each of `points` waits on the face from `first` on it lies farthest in front of,
    /// if it lies more than the tolerance in front of one.
    fn assign(&mut self, points: &[u32], first: usize) {
        for &p in points {
            let best = (first..self.faces.len())
                .filter(|&f| self.alive[f])
                .map(|f| (self.height(f, p), f))
                .filter(|&(d, _)| d > self.tol)
                .max_by(|a, b| a.0.total_cmp(&b.0));
            if let Some((_, f)) = best {
                self.waiting[f].push(p);
            }
        }
    }
}

/// Four points spanning a tetrahedron whose faces in [`FACES`] order are outward: two
/// far apart, the one farthest from their line, the one farthest from their plane;
/// `None` when that one lies within `tol` of the plane (the points are flat, as far as
/// this hull can tell).
fn first_tetrahedron(pts: &[DVec3], tol: f64) -> Option<[u32; 4]> {
    let farthest = |score: &dyn Fn(usize) -> f64| {
        (0..pts.len()).max_by(|&i, &j| score(i).total_cmp(&score(j)).then(j.cmp(&i)))
    };
    let a = farthest(&|i| -pts[i].x)?;
    let b = farthest(&|i| pts[i].distance_squared(pts[a]))?;
    let ab = pts[b] - pts[a];
    let c = farthest(&|i| ab.cross(pts[i] - pts[a]).length_squared())?;
    let n = ab.cross(pts[c] - pts[a]).try_normalize()?;
    let d = farthest(&|i| n.dot(pts[i] - pts[a]).abs())?;
    let height = n.dot(pts[d] - pts[a]);
    if height.abs() <= tol {
        return None;
    }
    let [a, b, c, d] = [a, b, c, d].map(|i| i as u32);
    // `d` in front of `a b c` (counter-clockwise seen from `d`) is the positive order.
    Some(if height > 0.0 {
        [a, b, c, d]
    } else {
        [b, a, c, d]
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::util::box_corners;

    fn volume(points: &[DVec3], tris: &[[u32; 3]]) -> f64 {
        tris.iter()
            .map(|t| {
                let [a, b, c] = t.map(|i| points[i as usize]);
                a.dot(b.cross(c)) / 6.0
            })
            .sum()
    }

    #[test]
    fn the_hull_of_a_cube_with_points_inside_and_on_its_faces_is_the_cube() {
        let mut pts = box_corners(DVec3::ZERO, DVec3::ONE);
        // Inside, on a face's centre, on an edge's middle.
        pts.extend([
            DVec3::splat(0.5),
            DVec3::new(0.5, 0.5, 1.0),
            DVec3::new(0.5, 0.0, 0.0),
        ]);
        let tris = hull_triangles(&pts).unwrap();
        assert!((volume(&pts, &tris) - 1.0).abs() < 1e-12);
        let mut used: Vec<u32> = tris.iter().flatten().copied().collect();
        used.sort_unstable();
        used.dedup();
        // The corners come first: the points on the faces and inside add nothing.
        assert_eq!(used, (0..8).collect::<Vec<u32>>(), "{tris:?}");
        // Added first, points on the boundary may stay corners; the inner one never.
        pts.rotate_right(3);
        let tris = hull_triangles(&pts).unwrap();
        assert!((volume(&pts, &tris) - 1.0).abs() < 1e-12);
        assert!(tris.iter().flatten().all(|&i| i != 0), "{tris:?}");
        // Closed: every directed edge once, with its reverse.
        let mut edges: Vec<(u32, u32)> = tris
            .iter()
            .flat_map(|t| [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])])
            .collect();
        edges.sort_unstable();
        assert!(edges.windows(2).all(|w| w[0] != w[1]));
        assert!(
            edges
                .iter()
                .all(|&(a, b)| edges.binary_search(&(b, a)).is_ok())
        );
    }

    #[test]
    fn points_in_a_plane_have_no_hull() {
        let pts = [
            DVec3::ZERO,
            DVec3::X,
            DVec3::Y,
            DVec3::X + DVec3::Y,
            DVec3::X * 2.0,
        ];
        assert!(hull_triangles(&pts).is_none());
        assert!(hull_triangles(&pts[..3]).is_none());
    }

    #[test]
    fn the_hull_of_points_on_a_sphere_has_them_all_as_corners() {
        // A Fibonacci sphere: every point is extreme.
        let n = 200;
        let pts: Vec<DVec3> = (0..n)
            .map(|i| {
                let z = 1.0 - 2.0 * (i as f64 + 0.5) / n as f64;
                let r = (1.0 - z * z).sqrt();
                let phi = i as f64 * 2.399_963_229_728_653;
                DVec3::new(r * phi.cos(), r * phi.sin(), z)
            })
            .collect();
        let tris = hull_triangles(&pts).unwrap();
        assert_eq!(tris.len(), 2 * n - 4);
        let v = volume(&pts, &tris);
        assert!(v > 4.0 && v < 4.0 / 3.0 * std::f64::consts::PI, "{v}");
    }
}
