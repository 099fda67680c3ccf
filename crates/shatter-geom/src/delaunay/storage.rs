//! Index-based tetrahedron storage shared by the construction steps.
//!
//! See the module docs of [`super`] for the layout. Vertex `0` is the infinite vertex;
//! the input points are internal vertices `1..=n`, numbered in insertion (BRIO) order
//! when they were copied in that order, or in input order when they are read in place
//! ([`Points`]).

use std::ops::Index;

use glam::DVec3;

use super::packed::{Store, Wide};
use super::types::FACES;

/// The infinite vertex.
pub(crate) const INF: u32 = 0;
/// Flag of a tetrahedron of the current cavity.
pub(crate) const MARK: u8 = 1;
/// Flag of a tetrahedron found *not* in conflict during the current cavity search (so it
/// is tested once, however many cavity faces it borders).
pub(crate) const SEEN: u8 = 2;
/// Both flags.
pub(crate) const FLAGS: u8 = MARK | SEEN;

/// One face of the cavity boundary, recorded while the cavity grows.
#[derive(Clone, Copy, Debug)]
pub(crate) struct BoundaryFace {
    /// Vertices of the new tetrahedron: the cavity tetrahedron's, with the new point at `apex`.
    pub verts: [u32; 4],
    /// Packed adjacency (`tet << 2 | face`) of the tetrahedron outside the cavity.
    pub outer: u32,
    /// Position of the new point in `verts` (the face opposite it is the boundary face).
    pub apex: u8,
}

/// Entry of the edge table that glues the new tetrahedra to each other.
#[derive(Clone, Copy, Default)]
pub(crate) struct EdgeSlot {
    pub u: u32,
    pub v: u32,
    pub stamp: u32,
    pub val: u32,
}

/// The points of a [`Mesh`] and the order they are inserted in: internal vertex `v`
/// (from 1; 0 is the infinite vertex) is `self[v]`.
///
/// Either the points copied in insertion order ([`Points::copied`]: vertex `v` is the
/// `v`-th inserted, so consecutive insertions read neighbouring memory), or the caller's
/// points read in place ([`Points::in_place`]: vertex `v` is input point `v - 1`, and
/// `order` says when it is inserted), which saves the copy's 24 bytes per point for
/// inputs large enough that the memory matters more than the cache.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Points<'p> {
    xyz: &'p [[f64; 3]],
    order: Option<&'p [u32]>,
}

impl<'p> Points<'p> {
    /// Points already in insertion order (from [`points_in_order`]).
    pub(crate) fn copied(xyz: &'p [[f64; 3]]) -> Self {
        Self { xyz, order: None }
    }

    /// The caller's `points`, inserted in `order` (a permutation of their indices).
    pub(crate) fn in_place(points: &'p [DVec3], order: &'p [u32]) -> Self {
        debug_assert_eq!(points.len(), order.len());
        Self {
            xyz: bytemuck::cast_slice(points),
            order: Some(order),
        }
    }

    /// Number of points (internal vertices `1..=len`).
    pub(crate) fn len(&self) -> usize {
        self.xyz.len()
    }

    /// The vertex inserted `k`-th (`1..=len`).
    #[inline(always)]
    pub(crate) fn inserted(&self, k: usize) -> u32 {
        match self.order {
            None => k as u32,
            Some(order) => order[k - 1] + 1,
        }
    }
}

impl Index<usize> for Points<'_> {
    type Output = [f64; 3];

    /// Vertex `v` (not the infinite one, which has no position).
    #[inline(always)]
    fn index(&self, v: usize) -> &[f64; 3] {
        &self.xyz[v - 1]
    }
}

/// The triangulation under construction plus the scratch buffers of one insertion.
pub(crate) struct Mesh<'p, S> {
    /// The points and their insertion order.
    pub pts: Points<'p>,
    /// Every tetrahedron: its vertices (internal indices; a free slot has the vertex
    /// marker first), the flags [`MARK`] and [`SEEN`], and its adjacency
    /// `adj(t, i) = n << 2 | j`: tetrahedron `n` is across the face opposite vertex `i` of
    /// `t`, and that face is opposite vertex `j` in `n`.
    pub tets: S,
    /// Most slots `tets` may grow to (its layout's limit, lower in tests).
    pub limit: usize,
    /// Free slots.
    pub free: Vec<u32>,
    /// A finite tetrahedron near the last inserted point: where the next walk starts.
    pub last: u32,
    /// Random state for the walk's face order.
    pub rng: u32,
    /// Scratch: cavity tetrahedra.
    pub cavity: Vec<u32>,
    /// Scratch: depth-first stack of the cavity search.
    pub stack: Vec<u32>,
    /// Scratch: tetrahedra flagged [`SEEN`] in the current cavity search.
    pub seen: Vec<u32>,
    /// Scratch: cavity boundary faces.
    pub boundary: Vec<BoundaryFace>,
    /// Scratch: the slot of each boundary face's new tetrahedron.
    pub slots: Vec<u32>,
    /// Scratch: the adjacency of each new tetrahedron, until its record is written.
    pub star: Vec<[u32; 4]>,
    /// Scratch: open-addressing edge table (power-of-two size), valid where `stamp` matches.
    pub edges: Vec<EdgeSlot>,
    /// Current stamp of `edges`.
    pub stamp: u32,
}

/// For a new tetrahedron with the new point at position `apex`, the face opposite `j`
/// (`j != apex`) contains the apex and the directed edge `EDGE[apex][j]` following it in
/// the face's outward winding. The tetrahedron across that face has the reversed edge.
pub(crate) const EDGE: [[(u8, u8); 4]; 4] = build_edge_table();

const fn build_edge_table() -> [[(u8, u8); 4]; 4] {
    let mut t = [[(0u8, 0u8); 4]; 4];
    let mut apex = 0;
    while apex < 4 {
        let mut j = 0;
        while j < 4 {
            if j != apex {
                let f = FACES[j];
                let mut k = 0;
                while f[k] != apex {
                    k += 1;
                }
                t[apex][j] = (f[(k + 1) % 3] as u8, f[(k + 2) % 3] as u8);
            }
            j += 1;
        }
        apex += 1;
    }
    t
}

/// Records to reserve for the tetrahedra of `points` points: ~6.77 finite tetrahedra per
/// point for uniform points, plus the hull's infinite ones. Reserving a little more
/// avoids a reallocation (which may copy) near the end; pages never written are never
/// resident.
pub(crate) fn reserve_for(points: usize) -> usize {
    points * 7 + 1024
}

/// The points `order` lists, in that order: what [`Points::copied`] reads.
pub(crate) fn points_in_order(points: &[DVec3], order: &[u32]) -> Vec<[f64; 3]> {
    order
        .iter()
        .map(|&i| points[i as usize].to_array())
        .collect()
}

impl<'p, S: Store> Mesh<'p, S> {
    /// Empty triangulation of `pts` over the empty storage `tets`, growing to at most
    /// `limit` records.
    pub(crate) fn new(pts: Points<'p>, tets: S, limit: usize) -> Self {
        Self {
            limit: limit.min(tets.max_len()),
            tets,
            pts,
            free: Vec::new(),
            last: 0,
            rng: 0x9E37_79B9,
            cavity: Vec::with_capacity(64),
            stack: Vec::with_capacity(64),
            boundary: Vec::with_capacity(128),
            slots: Vec::with_capacity(128),
            star: Vec::with_capacity(128),
            seen: Vec::with_capacity(64),
            edges: vec![EdgeSlot::default(); 512],
            stamp: 0,
        }
    }

    /// Whether tetrahedron `t` has the infinite vertex.
    #[inline(always)]
    pub(crate) fn is_infinite(&self, t: u32) -> bool {
        self.tets.verts(t).contains(&INF)
    }

    /// Frees slot `t`.
    #[inline]
    pub(crate) fn kill(&mut self, t: u32) {
        let dead = self.tets.vertex_marker();
        self.tets.set_verts(t, [dead; 4]);
        self.free.push(t);
    }

    /// Whether `extra` more slots than the cavity's own fit within [`Self::limit`].
    #[inline]
    pub(crate) fn has_room(&self, extra: usize) -> bool {
        extra <= self.free.len() + (self.limit - self.tets.len())
    }

    /// A slot for a new tetrahedron (not the cavity's own); [`Self::has_room`] must have
    /// said there is one.
    #[inline]
    pub(crate) fn alloc(&mut self) -> u32 {
        match self.free.pop() {
            Some(t) => t,
            None => self.tets.push(),
        }
    }

    /// Builds the first tetrahedron `(a, b, c, d)` (positively oriented) and the four
    /// infinite tetrahedra on its faces.
    pub(crate) fn init(&mut self, a: u32, b: u32, c: u32, d: u32) {
        let t0 = [a, b, c, d];
        let mut all = vec![t0];
        for i in 0..4 {
            // The face opposite i, seen from the other side, plus the infinite vertex:
            // replacing vertex i by INF and swapping two others keeps a positive orientation.
            let mut t = t0;
            t[i] = INF;
            let (j, k) = match i {
                0 => (1, 2),
                1 => (0, 2),
                2 => (0, 1),
                _ => (0, 1),
            };
            t.swap(j, k);
            all.push(t);
        }
        for (s, v) in all.iter().enumerate() {
            let t = self.tets.push();
            debug_assert_eq!(t as usize, s);
            self.tets.set_verts(t, *v);
        }
        // Glue by matching faces (25 pairs, once).
        let face = |v: &[u32; 4], i: usize| {
            let mut f: Vec<u32> = (0..4).filter(|&k| k != i).map(|k| v[k]).collect();
            f.sort_unstable();
            f
        };
        for (s, v) in all.iter().enumerate() {
            for i in 0..4 {
                let f = face(v, i);
                for (u, w) in all.iter().enumerate() {
                    for j in 0..4 {
                        if u != s && face(w, j) == f {
                            self.tets.set_adj(s as u32, i, (u as u32) << 2 | j as u32);
                        }
                    }
                }
            }
        }
        self.last = 0;
    }

    /// The same triangulation in the wide layout, for when a packed one is full.
    pub(crate) fn into_wide(self) -> Mesh<'p, Wide> {
        let tets = Wide::from_store(&self.tets, self.tets.len());
        Mesh {
            limit: tets.max_len(),
            tets,
            pts: self.pts,
            free: self.free,
            last: self.last,
            rng: self.rng,
            cavity: self.cavity,
            stack: self.stack,
            seen: self.seen,
            boundary: self.boundary,
            slots: self.slots,
            star: self.star,
            edges: self.edges,
            stamp: self.stamp,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn edge_table_pairs_faces_with_reversed_edges() {
        // For every face j containing the apex, the apex followed by EDGE[apex][j] is a
        // rotation of the outward winding FACES[j].
        for (apex, row) in EDGE.iter().enumerate() {
            for (j, &(u, v)) in row.iter().enumerate() {
                if j == apex {
                    continue;
                }
                let f = FACES[j];
                let k = f.iter().position(|&x| x == apex).expect("apex on face");
                assert_eq!((f[(k + 1) % 3], f[(k + 2) % 3]), (u as usize, v as usize));
                assert!(u as usize != j && v as usize != j);
            }
        }
    }
}
