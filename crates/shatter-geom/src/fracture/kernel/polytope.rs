//! Convex polytopes clipped by planes: the collision pieces of a fragment cut from a
//! fragment that already has convex pieces.
//!
//! A Voronoi cell is convex and so is a convex piece, so where a cell meets a piece is a
//! convex polytope: the piece's faces clipped by the cell's planes, one plane after the
//! other. That needs no decomposition and leaves no hull to compute: the polytope's faces
//! are its hull.

use glam::DVec3;

use super::Plane;
use super::hull::{HullMesh, hull_mesh};
use crate::util::UnionFind;

/// A convex polytope: its corners and its faces, each face a convex polygon of corner
/// indices wound counter-clockwise seen from outside.
#[derive(Debug, Clone, Default, PartialEq)]
pub(crate) struct Polytope {
    pub pos: Vec<DVec3>,
    /// The faces' corners, face after face: face `f` is `corners[start[f]..start[f + 1]]`.
    corners: Vec<u32>,
    start: Vec<u32>,
}

/// Buffers a run of [`Polytope::clip_into`] reuses.
#[derive(Debug, Default)]
pub(crate) struct Scratch {
    s: Vec<f64>,
    side: Vec<i8>,
    remap: Vec<u32>,
    /// Per corner of the result, whether it lies on the plane.
    on: Vec<bool>,
    crossed: Vec<((u32, u32), u32)>,
    rim: Vec<(u32, u32)>,
    /// Polytopes done with, whose buffers the next results reuse.
    pool: Vec<Polytope>,
    /// Planes in the order a run of cuts takes them (see `inherit`).
    pub order: Vec<(f64, u32)>,
}

impl Scratch {
    /// An empty polytope, with the buffers of one given back if there is one.
    pub fn take(&mut self) -> Polytope {
        self.pool.pop().unwrap_or_default()
    }

    /// Gives `p`'s buffers back for [`Scratch::take`].
    pub fn give(&mut self, p: Polytope) {
        self.pool.push(p);
    }
}

/// What [`Polytope::clip_into`] did.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Outcome {
    /// The polytope lies on the kept side: nothing written.
    Unchanged,
    /// Nothing lies strictly on the kept side: nothing written.
    Empty,
    /// The part on the kept side is in `out`.
    Cut,
}

/// What a plane does to a polytope ([`Polytope::clip`]).
#[cfg(test)]
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum Clipped {
    /// The polytope lies on the kept side (within the tolerance): it stays as it is.
    Unchanged,
    /// Nothing lies strictly on the kept side.
    Empty,
    /// The part on the kept side.
    Cut(Polytope),
}

/// Where a corner lies: strictly on the kept side (negative), on the plane, or beyond.
const IN: i8 = -1;
const ON: i8 = 0;
const OUT: i8 = 1;

impl Polytope {
    /// The polytope bounded by `tris` (outward triangles over `pos`, a closed convex
    /// surface), as [`Polytope::to_mesh`] writes one: each run of triangles fanned from
    /// one corner in one plane is one face (cut as one polygon, a face gains no corners
    /// along the cut where its inner edges cross it). Corners no face uses are dropped.
    /// `None` when an index is out of range or there are fewer than four triangles.
    pub fn from_triangles(pos: &[DVec3], tris: &[[u32; 3]]) -> Option<Polytope> {
        if tris.len() < 4 || tris.iter().flatten().any(|&i| i as usize >= pos.len()) {
            return None;
        }
        let (corners, start) = fanned_faces(pos, tris);
        Some(Polytope::from_faces(pos, corners, start))
    }

    /// The convex hull of `points` ([`hull_mesh`]), neighbouring triangles in one plane
    /// joined into one face (a hull's flat regions come as many triangles);
    /// `None` when the points span no volume.
    pub fn hull(points: &[DVec3]) -> Option<Polytope> {
        let mesh = hull_mesh(points)?;
        let (corners, start) = merged_faces(points, &mesh);
        Some(Polytope::from_faces(points, corners, start))
    }

    /// The polytope of `corners` and `start` over `pos`, unused corners dropped.
    fn from_faces(pos: &[DVec3], corners: Vec<u32>, start: Vec<u32>) -> Polytope {
        let mut p = Polytope {
            pos: pos.to_vec(),
            corners,
            start,
        };
        p.compact();
        p
    }

    /// The box `[lo, hi]`.
    pub fn cuboid(lo: DVec3, hi: DVec3) -> Polytope {
        let quads: [u32; 24] = [
            0, 2, 3, 1, 4, 5, 7, 6, 0, 1, 5, 4, 2, 6, 7, 3, 0, 4, 6, 2, 1, 3, 7, 5,
        ];
        Polytope {
            pos: crate::util::box_corners(lo, hi),
            corners: quads.to_vec(),
            start: (0..=6).map(|f| 4 * f).collect(),
        }
    }

    /// The plane of each face (through its first corner, normal from its corners by
    /// Newell's method, unit length, outward): the polytope is the negative side of
    /// them all. A face flat within rounding (its area under `1e-12` of its longest
    /// edge squared) bounds nothing and has no plane.
    pub fn face_planes(&self) -> Vec<Plane> {
        self.faces()
            .filter_map(|f| {
                let mut n = DVec3::ZERO;
                let mut longest: f64 = 0.0;
                for (k, &a) in f.iter().enumerate() {
                    let (p, q) = (
                        self.pos[a as usize],
                        self.pos[f[(k + 1) % f.len()] as usize],
                    );
                    n += p.cross(q);
                    longest = longest.max(p.distance_squared(q));
                }
                let area2 = n.length();
                if area2.is_nan() || area2 <= 2e-12 * longest {
                    return None;
                }
                let n = n.normalize();
                Some(Plane {
                    n,
                    d: n.dot(self.pos[f[0] as usize]),
                    tag: 0,
                })
            })
            .collect()
    }

    /// The faces, each a slice of corner indices.
    pub fn faces(&self) -> impl Iterator<Item = &[u32]> + '_ {
        self.start
            .windows(2)
            .map(|w| &self.corners[w[0] as usize..w[1] as usize])
    }

    /// The corners and the faces as triangles (outward): each face fanned from its first
    /// corner, or, when a fan triangle would be nearly flat (corners in a line along
    /// the face's edge), from a new corner at the face's centre, so no triangle is
    /// (nearly) flat unless an edge is.
    pub fn to_mesh(&self) -> (Vec<DVec3>, Vec<[u32; 3]>) {
        let mut pos = self.pos.clone();
        let mut tris = Vec::with_capacity(self.corners.len());
        for f in self.faces() {
            let at = |i: u32| self.pos[i as usize];
            let flat = |a: DVec3, b: DVec3, c: DVec3| {
                let (u, v) = (b - a, c - a);
                u.cross(v).length_squared() <= 1e-12 * u.length_squared() * v.length_squared()
            };
            let fan_is_flat =
                (1..f.len().saturating_sub(1)).any(|k| flat(at(f[0]), at(f[k]), at(f[k + 1])));
            if !fan_is_flat || f.len() < 4 {
                for k in 1..f.len().saturating_sub(1) {
                    tris.push([f[0], f[k], f[k + 1]]);
                }
                continue;
            }
            let centre = f.iter().map(|&i| at(i)).sum::<DVec3>() / f.len() as f64;
            let c = pos.len() as u32;
            pos.push(centre);
            for (k, &a) in f.iter().enumerate() {
                tris.push([c, a, f[(k + 1) % f.len()]]);
            }
        }
        (pos, tris)
    }

    /// The volume enclosed by the faces.
    pub fn volume(&self) -> f64 {
        let Some(&o) = self.pos.first() else {
            return 0.0;
        };
        let at = |i: u32| self.pos[i as usize] - o;
        let mut six = 0.0;
        for f in self.faces() {
            let a = at(f[0]);
            for k in 1..f.len().saturating_sub(1) {
                six += a.dot(at(f[k]).cross(at(f[k + 1])));
            }
        }
        six / 6.0
    }

    /// The least and greatest coordinates of the corners.
    pub fn bounds(&self) -> (DVec3, DVec3) {
        crate::util::bounds(&self.pos)
    }

    /// The part of the polytope on the negative side of `plane` (`n · x < d`); corners
    /// within `eps · |n|` of the plane count as lying on it. See [`Polytope::clip_into`].
    #[cfg(test)]
    pub fn clip(&self, plane: &Plane, eps: f64) -> Clipped {
        let mut out = Polytope::default();
        match self.clip_into(plane, eps, &mut Scratch::default(), &mut out) {
            Outcome::Unchanged => Clipped::Unchanged,
            Outcome::Empty => Clipped::Empty,
            Outcome::Cut => Clipped::Cut(out),
        }
    }

    /// The part of the polytope on the negative side of `plane` (the tests' `clip`),
    /// written to `out` (when it is [`Outcome::Cut`]), with `scratch`'s buffers: a loop
    /// of cuts allocates nothing once they have grown.
    ///
    /// Each face keeps its corners on the kept side or on the plane, and gains the point
    /// where each of its edges crosses the plane (computed once per edge, from its
    /// lower-indexed end, so both faces of the edge share it). The new face, the cap,
    /// is bounded by the kept faces' edges that lie in the plane and are not shared by
    /// two kept faces: chained, reversed, they give its polygon. (Should rounding keep
    /// them from making one loop, the cap is instead every corner in the plane sorted by
    /// angle around their centroid: they all lie on the boundary of the convex cap.)
    /// Faces lying in the plane are left out: the cap replaces them. Corners of the
    /// polytope are numbered in order of first use by the faces.
    pub fn clip_into(
        &self,
        plane: &Plane,
        eps: f64,
        scratch: &mut Scratch,
        out: &mut Polytope,
    ) -> Outcome {
        let tol = eps * plane.n.length();
        let Scratch {
            s,
            side,
            remap,
            on,
            crossed,
            rim,
            ..
        } = scratch;
        // Most planes miss: tell that before anything else (the distances are kept for
        // when it cuts).
        let (mut any_in, mut any_out) = (false, false);
        s.clear();
        for &p in &self.pos {
            let v = plane.eval(p);
            any_in |= v < -tol;
            any_out |= v > tol;
            s.push(v);
        }
        if !any_out {
            return Outcome::Unchanged;
        }
        if !any_in {
            return Outcome::Empty;
        }
        side.clear();
        for v in s.iter_mut() {
            let (w, k) = if v.abs() <= tol {
                (0.0, ON)
            } else if *v < 0.0 {
                (*v, IN)
            } else {
                (*v, OUT)
            };
            *v = w;
            side.push(k);
        }
        remap.clear();
        remap.resize(self.pos.len(), u32::MAX);
        crossed.clear();
        rim.clear();
        on.clear();
        out.pos.clear();
        out.corners.clear();
        out.start.clear();
        out.start.push(0);
        out.corners.reserve(self.corners.len() + 64);
        for f in self.faces() {
            let (mut outside, mut onto) = (0, 0);
            for &a in f {
                match side[a as usize] {
                    OUT => outside += 1,
                    ON => onto += 1,
                    _ => {}
                }
            }
            if outside == f.len() || onto == f.len() {
                // Beyond the plane, or in it (the cap replaces it).
                continue;
            }
            let first = out.corners.len();
            #[inline(always)]
            fn renumber(
                a: u32,
                remap: &mut [u32],
                side: &[i8],
                from: &[DVec3],
                pos: &mut Vec<DVec3>,
                on: &mut Vec<bool>,
            ) -> u32 {
                let r = &mut remap[a as usize];
                if *r == u32::MAX {
                    *r = pos.len() as u32;
                    pos.push(from[a as usize]);
                    on.push(side[a as usize] == ON);
                }
                *r
            }
            if outside == 0 {
                // Untouched: its corners as they are.
                for &a in f {
                    let r = renumber(a, remap, side, &self.pos, &mut out.pos, on);
                    out.corners.push(r);
                }
            } else {
                let mut a = f[f.len() - 1];
                for &b in f {
                    // Edge a → b: b is kept, and the crossing comes first.
                    let (ka, kb) = (side[a as usize], side[b as usize]);
                    if ka * kb == -1 {
                        let key = (a.min(b), a.max(b));
                        let x = match crossed.iter().find(|(e, _)| *e == key) {
                            Some(&(_, x)) => x,
                            None => {
                                let (i, j) = (key.0 as usize, key.1 as usize);
                                let t = s[i] / (s[i] - s[j]);
                                out.pos.push(self.pos[i] + (self.pos[j] - self.pos[i]) * t);
                                on.push(true);
                                let x = (out.pos.len() - 1) as u32;
                                crossed.push((key, x));
                                x
                            }
                        };
                        out.corners.push(x);
                    }
                    if kb != OUT {
                        let r = renumber(b, remap, side, &self.pos, &mut out.pos, on);
                        out.corners.push(r);
                    }
                    a = b;
                }
            }
            let kept = &out.corners[first..];
            if kept.len() < 3 {
                out.corners.truncate(first);
                continue;
            }
            if outside > 0 || onto >= 2 {
                let mut u = kept[kept.len() - 1];
                for &v in kept {
                    if on[u as usize] && on[v as usize] {
                        rim.push((u, v));
                    }
                    u = v;
                }
            }
            out.start.push(out.corners.len() as u32);
        }
        // The cap's boundary: the rim edges without their reverse, each walked back.
        let mut k = 0;
        while k < rim.len() {
            let (u, v) = rim[k];
            if let Some(m) = rim.iter().position(|&e| e == (v, u)) {
                rim.swap_remove(m.max(k));
                rim.swap_remove(m.min(k));
            } else {
                k += 1;
            }
        }
        let first = out.corners.len();
        if let Some(&(u0, v0)) = rim.first() {
            // Walk v → u for each edge (u, v): from v0 to u0, then on from u0.
            out.corners.push(v0);
            let mut at = u0;
            while at != v0 && out.corners.len() - first < rim.len() {
                out.corners.push(at);
                match rim.iter().find(|&&(_, v)| v == at) {
                    Some(&(u, _)) => at = u,
                    None => break,
                }
            }
            if at != v0 || out.corners.len() - first != rim.len() {
                out.corners.truncate(first);
                sorted_cap(&out.pos, on, plane, &mut out.corners);
            }
        }
        if out.corners.len() - first >= 3 {
            out.start.push(out.corners.len() as u32);
        } else {
            out.corners.truncate(first);
        }
        if out.start.len() < 5 {
            // Fewer than four faces: flat, within the tolerance.
            return Outcome::Empty;
        }
        Outcome::Cut
    }

    /// Drops the corners no face uses, keeping the others' order.
    fn compact(&mut self) {
        let mut remap = vec![u32::MAX; self.pos.len()];
        for &c in &self.corners {
            remap[c as usize] = 0;
        }
        let mut next = 0u32;
        let mut pos = Vec::with_capacity(self.pos.len());
        for (i, r) in remap.iter_mut().enumerate() {
            if *r == 0 {
                *r = next;
                next += 1;
                pos.push(self.pos[i]);
            }
        }
        if pos.len() == self.pos.len() {
            return;
        }
        for c in &mut self.corners {
            *c = remap[*c as usize];
        }
        self.pos = pos;
    }
}

/// The corners of `pos` marked `on` the plane, by angle around their centroid seen from
/// the plane's positive side, appended to `corners` (the cap's polygon when the rim does
/// not chain).
fn sorted_cap(pos: &[DVec3], on: &[bool], plane: &Plane, corners: &mut Vec<u32>) {
    let cap: Vec<u32> = (0..pos.len() as u32).filter(|&i| on[i as usize]).collect();
    if cap.len() < 3 {
        return;
    }
    let centre = cap.iter().map(|&i| pos[i as usize]).sum::<DVec3>() / cap.len() as f64;
    let n = plane.n.normalize();
    let u = n.any_orthonormal_vector();
    let v = n.cross(u);
    let mut keyed: Vec<(f64, u32)> = cap
        .iter()
        .map(|&i| {
            let d = pos[i as usize] - centre;
            (d.dot(v).atan2(d.dot(u)), i)
        })
        .collect();
    keyed.sort_unstable_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
    corners.extend(keyed.into_iter().map(|(_, i)| i));
}

/// Neighbouring triangles whose normals differ by under this (`1 − cos`, about 1.4e-6
/// radians) are one face.
const COPLANAR: f64 = 1e-12;

/// The faces of the closed surface `tris` over `pos` written as fans: each run of
/// consecutive triangles `[a, b, c]`, `[a, c, d]`, … in one plane (within [`COPLANAR`])
/// is the polygon `a b c d …`, or, when the run closes on itself round `a` (a fan from a
/// centre corner), the polygon round `a`. Returns the faces' corners and starts, as in
/// [`Polytope`].
fn fanned_faces(pos: &[DVec3], tris: &[[u32; 3]]) -> (Vec<u32>, Vec<u32>) {
    let normal = |t: &[u32; 3]| {
        let [a, b, c] = t.map(|i| pos[i as usize]);
        (b - a).cross(c - a)
    };
    let same_plane = |m: DVec3, n: DVec3| {
        m.dot(n) >= (1.0 - COPLANAR) * (m.length_squared() * n.length_squared()).sqrt()
    };
    let (mut corners, mut start) = (Vec::with_capacity(3 * tris.len()), vec![0u32]);
    let mut i = 0;
    while i < tris.len() {
        let t = tris[i];
        let first = corners.len();
        corners.extend_from_slice(&t);
        let n = normal(&t);
        let mut j = i + 1;
        while let Some(u) = tris.get(j) {
            let last = corners[corners.len() - 1];
            if u[0] != t[0] || u[1] != last || !same_plane(n, normal(u)) {
                break;
            }
            corners.push(u[2]);
            j += 1;
        }
        let fan = &corners[first..];
        if fan.len() > 4 && fan[fan.len() - 1] == fan[1] {
            // Round a centre corner: the polygon is the rim.
            let rim: Vec<u32> = fan[1..fan.len() - 1].to_vec();
            corners.truncate(first);
            corners.extend(rim);
        }
        start.push(corners.len() as u32);
        i = j;
    }
    (corners, start)
}

/// The faces of the hull `mesh` over `pos`: each group of neighbouring triangles in one
/// plane (within [`COPLANAR`]) as one polygon, its boundary walked in the triangles'
/// order; a group whose boundary is not one simple loop stays triangles. Returns the
/// faces' corners and starts, as in [`Polytope`].
fn merged_faces(pos: &[DVec3], mesh: &HullMesh) -> (Vec<u32>, Vec<u32>) {
    let tris = &mesh.tris;
    let normal: Vec<DVec3> = tris
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|i| pos[i as usize]);
            (b - a).cross(c - a).normalize_or_zero()
        })
        .collect();
    let mut groups = UnionFind::new(tris.len());
    for (t, nbr) in mesh.nbr.iter().enumerate() {
        for &u in nbr {
            if normal[t].dot(normal[u as usize]) >= 1.0 - COPLANAR {
                groups.union(t, u as usize);
            }
        }
    }
    let root: Vec<usize> = (0..tris.len()).map(|t| groups.find(t)).collect();
    // The triangles, group after group.
    let mut order: Vec<u32> = (0..tris.len() as u32).collect();
    order.sort_unstable_by_key(|&t| (root[t as usize], t));
    let (mut corners, mut start) = (Vec::with_capacity(3 * tris.len()), vec![0u32]);
    let mut next: Vec<(u32, u32)> = Vec::new();
    for group in order.chunk_by(|&a, &b| root[a as usize] == root[b as usize]) {
        let first = corners.len();
        let mut simple = group.len() > 1;
        if simple {
            next.clear();
            for &t in group {
                let tri = tris[t as usize];
                for k in 0..3 {
                    let u = mesh.nbr[t as usize][k] as usize;
                    if root[u] != root[t as usize] {
                        let a = tri[k];
                        simple &= !next.iter().any(|e| e.0 == a);
                        next.push((a, tri[(k + 1) % 3]));
                    }
                }
            }
            // Walk the boundary; it must come back after using every edge once.
            let v0 = next.first().map_or(0, |e| e.0);
            let mut v = v0;
            while simple {
                corners.push(v);
                match next.iter().find(|e| e.0 == v) {
                    Some(&(_, w)) if w == v0 => break,
                    Some(&(_, w)) if corners.len() - first < next.len() => v = w,
                    _ => simple = false,
                }
            }
            simple &= corners.len() - first == next.len();
        }
        if simple {
            start.push(corners.len() as u32);
        } else {
            corners.truncate(first);
            for &t in group {
                corners.extend_from_slice(&tris[t as usize]);
                start.push(corners.len() as u32);
            }
        }
    }
    (corners, start)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::util::box_corners;

    /// The unit cube `[0, 1]³` as a polytope.
    fn cube() -> Polytope {
        let pos = box_corners(DVec3::ZERO, DVec3::ONE);
        Polytope::hull(&pos).unwrap()
    }

    fn plane(n: DVec3, d: f64) -> Plane {
        Plane { n, d, tag: 0 }
    }

    /// Every directed edge of the faces once, with its reverse once.
    fn closed(p: &Polytope) -> bool {
        let mut edges = std::collections::HashMap::new();
        for f in p.faces() {
            for k in 0..f.len() {
                *edges.entry((f[k], f[(k + 1) % f.len()])).or_insert(0) += 1;
            }
        }
        edges
            .iter()
            .all(|(&(a, b), &n)| n == 1 && edges.get(&(b, a)) == Some(&1))
    }

    /// Every corner behind (or on) every face's plane: convex.
    fn convex(p: &Polytope, tol: f64) -> bool {
        p.faces().all(|f| {
            let [a, b, c] = [f[0], f[1], f[2]].map(|i| p.pos[i as usize]);
            let n = (b - a).cross(c - a).normalize();
            p.pos.iter().all(|&q| n.dot(q - a) <= tol)
        })
    }

    #[test]
    fn a_hull_drops_inner_points_and_has_the_volume() {
        let mut pts = box_corners(DVec3::ZERO, DVec3::ONE);
        pts.push(DVec3::splat(0.5));
        let p = Polytope::hull(&pts).unwrap();
        assert_eq!(p.pos.len(), 8);
        assert!((p.volume() - 1.0).abs() < 1e-12);
        assert!(closed(&p) && convex(&p, 1e-12));
        assert!(Polytope::hull(&[DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::X + DVec3::Y]).is_none());
    }

    #[test]
    fn a_plane_through_the_cube_halves_it_into_a_closed_convex_polytope() {
        let c = cube();
        let Clipped::Cut(half) = c.clip(&plane(DVec3::new(1.0, 1.0, 1.0), 1.5), 1e-12) else {
            panic!("the plane crosses the cube");
        };
        assert!((half.volume() - 0.5).abs() < 1e-12, "{}", half.volume());
        assert!(closed(&half) && convex(&half, 1e-12));
        // The cap is a regular hexagon.
        assert!(half.faces().any(|f| f.len() == 6));
        assert_eq!(c.clip(&plane(DVec3::X, 2.0), 1e-12), Clipped::Unchanged);
        assert_eq!(c.clip(&plane(DVec3::X, -1.0), 1e-12), Clipped::Empty);
        // Touching a face from outside keeps everything, from inside nothing.
        assert_eq!(c.clip(&plane(DVec3::X, 1.0), 1e-12), Clipped::Unchanged);
        assert_eq!(c.clip(&plane(-DVec3::X, -1.0), 1e-12), Clipped::Empty);
    }

    #[test]
    fn a_plane_through_corners_shares_them_with_the_cap() {
        // x + y <= 1 runs through two vertical edges: a triangular prism.
        let Clipped::Cut(prism) = cube().clip(&plane(DVec3::new(1.0, 1.0, 0.0), 1.0), 1e-12) else {
            panic!("the plane crosses the cube");
        };
        assert_eq!(prism.pos.len(), 6);
        assert!((prism.volume() - 0.5).abs() < 1e-12);
        assert!(closed(&prism) && convex(&prism, 1e-12));
    }

    #[test]
    fn many_cuts_keep_the_polytope_closed_convex_and_of_the_exact_volume() {
        // The cube cut by the planes of an octahedron |x−½| + |y−½| + |z−½| <= r: for
        // r = 1 the corners are cut off as tetrahedra of volume (½)³/6 each.
        let mut p = cube();
        for sx in [-1.0, 1.0] {
            for sy in [-1.0, 1.0] {
                for sz in [-1.0, 1.0] {
                    let n = DVec3::new(sx, sy, sz);
                    let d = 1.0 + n.dot(DVec3::splat(0.5));
                    if let Clipped::Cut(q) = p.clip(&plane(n, d), 1e-12) {
                        p = q;
                    }
                }
            }
        }
        let expected = 1.0 - 8.0 * 0.125 / 6.0;
        assert!((p.volume() - expected).abs() < 1e-12, "{}", p.volume());
        assert!(closed(&p) && convex(&p, 1e-12));
        assert_eq!(p.faces().count(), 14);
        let (pos, tris) = p.to_mesh();
        assert_eq!((pos.len(), tris.len()), (12, 6 * 2 + 8));
    }
}
