//! The working representation of a solid during fracture: an indexed, welded triangle
//! mesh whose triangles carry the tag of the cut that created them.

use glam::DVec3;

use super::Face;
use super::edges::for_each_edge;
use crate::TriMesh;
use crate::mesh::{is_degenerate, position_key};
use crate::util::{FastMap, UnionFind};

/// Bit set in the tag of a triangle on the original surface (not created by a cut); the
/// low 32 bits then name the input triangle it lies on ([`source_triangle`]).
const SURFACE_BIT: u64 = 1 << 63;
/// Low bits of a surface tag that name no input triangle.
const NO_SOURCE: u64 = u32::MAX as u64;

/// Tag of a surface triangle that lies on no input triangle (the box a Voronoi cell is
/// cut from, the convex decomposition's own cuts): `u64::MAX`.
pub(crate) const SURFACE: u64 = SURFACE_BIT | NO_SOURCE;

/// Tag of a surface triangle lying on input triangle `t` (`u32::MAX` names none: the
/// tag is then [`SURFACE`]).
pub(crate) fn surface_tag(t: u32) -> u64 {
    SURFACE_BIT | u64::from(t)
}

/// Whether a triangle's tag marks the original surface (rather than a cut's cap).
/// Code outside this module asks this, never compares with [`SURFACE`]: a surface tag
/// carries the source triangle ([`source_triangle`]).
pub(crate) fn is_surface(tag: u64) -> bool {
    tag & SURFACE_BIT != 0
}

/// The input triangle a surface triangle lies on; `None` for a cap (a cut's plane id)
/// and for a surface triangle of no input triangle ([`SURFACE`]).
pub(crate) fn source_triangle(tag: u64) -> Option<u32> {
    (is_surface(tag) && tag & NO_SOURCE != NO_SOURCE).then_some((tag & NO_SOURCE) as u32)
}

/// A closed solid being cut: welded positions, triangles and one tag per triangle, and
/// possibly caps not yet triangulated ([`Face`]s; see [`Piece::close_faces`]).
///
/// A tag is a surface tag for original surface triangles ([`surface_tag`]: the input
/// triangle it lies on; splitting a triangle keeps its tag), or the id of the plane whose
/// cap created the triangle (below 2⁶³; the methods give planes ids they can decode for
/// bonds).
#[derive(Debug, Clone, Default)]
pub(crate) struct Piece {
    pub pos: Vec<DVec3>,
    pub tris: Vec<[u32; 3]>,
    pub tags: Vec<u64>,
    pub faces: Vec<Face>,
}

/// Edges at most this fraction of a piece's size long are rounding: two copies of one
/// point (see [`Piece::collapse_rounding_edges`]). Far below the cuts' on-plane
/// tolerance (1e-10) and far above one unit in the last place (1e-16).
pub const ROUNDING_EDGE: f64 = 1e-13;

impl Piece {
    /// A piece from a mesh, welding vertices at exactly equal positions; all triangles
    /// are surface triangles, each tagged with its index in `mesh` ([`surface_tag`]).
    /// Triangles that repeat a vertex after the weld are dropped.
    pub fn from_mesh_welded(mesh: &TriMesh) -> Self {
        let mut map: FastMap<[u64; 3], u32> = FastMap::default();
        let mut pos = Vec::with_capacity(mesh.positions.len());
        let remap: Vec<u32> = mesh
            .positions
            .iter()
            .map(|p| {
                *map.entry(position_key(*p)).or_insert_with(|| {
                    pos.push(*p);
                    (pos.len() - 1) as u32
                })
            })
            .collect();
        let mut tris = Vec::with_capacity(mesh.triangles.len());
        let mut tags = Vec::with_capacity(mesh.triangles.len());
        for (index, t) in mesh.triangles.iter().enumerate() {
            let t = t.map(|i| remap[i as usize]);
            if t[0] != t[1] && t[1] != t[2] && t[0] != t[2] {
                tris.push(t);
                // (A mesh of 2³² triangles or more is refused long before this.)
                tags.push(u32::try_from(index).map_or(SURFACE, surface_tag));
            }
        }
        Self {
            pos,
            tris,
            tags,
            faces: Vec::new(),
        }
    }

    /// Merges vertices at exactly equal positions and drops the triangles that then
    /// repeat a vertex (slivers of rounding, e.g. cuts through a nearly flat triangle
    /// meeting at one point). Each dropped triangle takes an edge and its reverse with
    /// it, so a closed piece stays closed. Then collapses the edges of rounding length
    /// ([`Piece::collapse_rounding_edges`]).
    pub fn weld(&mut self) {
        self.weld_equal();
        self.collapse_rounding_edges();
    }

    /// Collapses every edge at most [`ROUNDING_EDGE`] of the piece's size long into its
    /// first vertex, and drops the triangles that then repeat a vertex, when the piece
    /// stays closed (else it is left as it was).
    ///
    /// Such an edge joins two computed copies of one point: a cut vertex interpolated
    /// onto a corner that another plane's cut made (a tetrahedron's corner, which is a
    /// mesh vertex), a few units in the last place away. Kept, the pair is two vertices
    /// in `f64` but one in any `f32` writer or viewer, where its two triangles vanish.
    pub fn collapse_rounding_edges(&mut self) {
        if self.tris.is_empty() {
            return;
        }
        let size = mesh_scale(self);
        let tol2 = (ROUNDING_EDGE * size).powi(2);
        let mut sets: Option<UnionFind> = None;
        for t in &self.tris {
            for k in 0..3 {
                let (a, b) = (t[k] as usize, t[(k + 1) % 3] as usize);
                if self.pos[a].distance_squared(self.pos[b]) <= tol2 {
                    sets.get_or_insert_with(|| UnionFind::new(self.pos.len()))
                        .union(a, b);
                }
            }
        }
        let Some(mut sets) = sets else {
            return;
        };
        let (tris, tags) = self.remapped_triangles(|i| sets.find(i as usize) as u32);
        if !tris.is_empty() && closed(&tris) {
            self.tris = tris;
            self.tags = tags;
            self.compact();
        }
    }

    /// Removes each triangle whose corners are exactly collinear (a corner lying on the
    /// opposite edge, which rounding in a cut can leave) by splitting the neighbour
    /// across that edge at the corner: the flat triangle's two short edges then meet
    /// the split neighbour's halves, so a closed piece stays closed. Left as it was
    /// when that does not give a closed piece.
    pub fn split_flat_triangles(&mut self) {
        for _ in 0..4 {
            let flat = self.flat_triangles();
            if flat.is_empty() {
                return;
            }
            let mut across: FastMap<(u32, u32), usize> = FastMap::default();
            for (t, tri) in self.tris.iter().enumerate() {
                for k in 0..3 {
                    across.insert((tri[k], tri[(k + 1) % 3]), t);
                }
            }
            let mut gone = vec![false; self.tris.len()];
            let mut added: Vec<([u32; 3], u64)> = Vec::new();
            for t in flat {
                if gone[t] {
                    continue;
                }
                let tri = self.tris[t];
                let p = tri.map(|i| self.pos[i as usize]);
                // The long edge a -> b, with the middle corner m on it.
                let k = (0..3)
                    .max_by(|&i, &j| {
                        let l = |k: usize| p[k].distance_squared(p[(k + 1) % 3]);
                        l(i).total_cmp(&l(j))
                    })
                    .unwrap_or(0);
                let (a, b, m) = (tri[k], tri[(k + 1) % 3], tri[(k + 2) % 3]);
                if [a, b]
                    .iter()
                    .any(|&v| self.pos[v as usize] == self.pos[m as usize])
                {
                    continue;
                }
                let Some(&u) = across.get(&(b, a)) else {
                    continue;
                };
                if gone[u] || u == t {
                    continue;
                }
                let nt = self.tris[u];
                let r = (0..3)
                    .find(|&r| nt[r] == b && nt[(r + 1) % 3] == a)
                    .unwrap_or(0);
                let d = nt[(r + 2) % 3];
                gone[t] = true;
                gone[u] = true;
                let tag = self.tags[u];
                added.push(([b, m, d], tag));
                added.push(([m, a, d], tag));
            }
            if added.is_empty() {
                return;
            }
            let mut tris: Vec<[u32; 3]> = Vec::with_capacity(self.tris.len());
            let mut tags: Vec<u64> = Vec::with_capacity(self.tris.len());
            for (t, (&tri, &tag)) in self.tris.iter().zip(&self.tags).enumerate() {
                if !gone[t] {
                    tris.push(tri);
                    tags.push(tag);
                }
            }
            for (tri, tag) in added {
                tris.push(tri);
                tags.push(tag);
            }
            if !closed(&tris) {
                return;
            }
            self.tris = tris;
            self.tags = tags;
        }
    }

    /// Whether a triangle's corners are exactly collinear (see
    /// [`Piece::split_flat_triangles`]); the fragment check refuses those.
    pub fn has_flat_triangle(&self) -> bool {
        !self.flat_triangles().is_empty()
    }

    /// The triangles whose corners are exactly collinear, in order.
    fn flat_triangles(&self) -> Vec<usize> {
        (0..self.tris.len())
            .filter(|&t| {
                let [a, b, c] = self.tris[t].map(|i| self.pos[i as usize]);
                is_degenerate(a, b, c)
            })
            .collect()
    }

    /// Every directed edge once, with its reverse once: closed, and a 2-manifold by
    /// edges.
    pub fn is_closed(&self) -> bool {
        closed(&self.tris)
    }

    /// The triangles with their vertices mapped by `remap`, less those that then repeat
    /// a vertex, and their tags.
    fn remapped_triangles(&self, mut remap: impl FnMut(u32) -> u32) -> (Vec<[u32; 3]>, Vec<u64>) {
        let mut tris = Vec::with_capacity(self.tris.len());
        let mut tags = Vec::with_capacity(self.tags.len());
        for (t, &tag) in self.tris.iter().zip(&self.tags) {
            let t = t.map(&mut remap);
            if t[0] != t[1] && t[1] != t[2] && t[0] != t[2] {
                tris.push(t);
                tags.push(tag);
            }
        }
        (tris, tags)
    }

    /// Merges vertices at exactly equal positions (see [`Piece::weld`]).
    fn weld_equal(&mut self) {
        debug_assert!(self.faces.is_empty(), "weld a closed piece");
        let mut map: FastMap<[u64; 3], u32> = FastMap::default();
        map.reserve(self.pos.len());
        let mut pos = Vec::with_capacity(self.pos.len());
        let remap: Vec<u32> = self
            .pos
            .iter()
            .map(|p| {
                *map.entry(position_key(*p)).or_insert_with(|| {
                    pos.push(*p);
                    (pos.len() - 1) as u32
                })
            })
            .collect();
        if pos.len() == self.pos.len() {
            return;
        }
        self.pos = pos;
        (self.tris, self.tags) = self.remapped_triangles(|i| remap[i as usize]);
        self.compact();
    }

    /// `true` when the piece has no triangles and no faces.
    pub fn is_empty(&self) -> bool {
        self.tris.is_empty() && self.faces.is_empty()
    }

    /// Triangulates the [`Face`]s (see [`triangulate_cap`](super::cap::triangulate_cap)),
    /// each triangle tagged with its face's plane; afterwards the piece is triangles only.
    pub fn close_faces(&mut self) {
        for face in std::mem::take(&mut self.faces) {
            self.triangulate(&face);
        }
    }

    /// Makes each face one region: a face of several loops can be several regions (a
    /// cut across both arms of a U), which as one face would join the piece's parts in
    /// [`Piece::components`]. Loops without holes become a face each; a face with holes
    /// or touching loops is triangulated (its triangles tell which loop goes with which).
    pub fn faces_into_regions(&mut self) {
        for face in std::mem::take(&mut self.faces) {
            match face.regions(&self.pos) {
                Some(regions) => self.faces.extend(regions),
                None => self.triangulate(&face),
            }
        }
    }

    fn triangulate(&mut self, face: &Face) {
        let tris = face.triangles(&self.pos);
        self.tags
            .extend(std::iter::repeat_n(face.plane.tag, tris.len()));
        self.tris.extend(tris);
    }

    /// Every directed edge: `(owner, slot, from, to)` for edge `slot` (`tri[slot] →
    /// tri[slot + 1]`) of triangle `owner`, then for the faces' edges, whose owner is
    /// `tris.len() + f` for face `f` and whose slot is 3 (naming no triangle edge).
    pub fn edges(&self) -> impl Iterator<Item = (usize, u8, u32, u32)> + Clone + '_ {
        let n = self.tris.len();
        let tri_edges = self.tris.iter().enumerate().flat_map(|(t, tri)| {
            (0..3u8).map(move |k| (t, k, tri[k as usize], tri[(k as usize + 1) % 3]))
        });
        let face_edges = self
            .faces
            .iter()
            .enumerate()
            .flat_map(move |(f, face)| face.edges.iter().map(move |&(a, b)| (n + f, 3, a, b)));
        tri_edges.chain(face_edges)
    }

    /// Signed volume (positive for a closed outward solid), faces included: each face
    /// edge makes a triangle with the face's first vertex, and these triangles add up
    /// to the face's polygon (holes and several loops included).
    pub fn volume(&self) -> f64 {
        let Some(&o) = self.pos.first() else {
            return 0.0;
        };
        let tet = |a: u32, b: u32, c: u32| {
            let [a, b, c] = [a, b, c].map(|i| self.pos[i as usize] - o);
            a.dot(b.cross(c))
        };
        let tris: f64 = self.tris.iter().map(|t| tet(t[0], t[1], t[2])).sum();
        let faces: f64 = self
            .faces
            .iter()
            .filter_map(|f| {
                let &(apex, _) = f.edges.first()?;
                Some(f.edges.iter().map(|&(a, b)| tet(apex, a, b)).sum::<f64>())
            })
            .sum();
        (tris + faces) / 6.0
    }

    /// Drops vertices no triangle or face uses and renumbers the rest (in order of first
    /// use).
    pub fn compact(&mut self) {
        let mut remap = vec![u32::MAX; self.pos.len()];
        let mut pos = Vec::with_capacity(self.pos.len());
        let old = &self.pos;
        let mut renumber = |i: &mut u32| {
            let r = &mut remap[*i as usize];
            if *r == u32::MAX {
                *r = pos.len() as u32;
                pos.push(old[*i as usize]);
            }
            *i = *r;
        };
        for t in &mut self.tris {
            t.iter_mut().for_each(&mut renumber);
        }
        for f in &mut self.faces {
            for (a, b) in &mut f.edges {
                renumber(a);
                renumber(b);
            }
        }
        self.pos = pos;
    }

    /// Splits the piece into its edge-connected components (triangles and faces), in
    /// order of their first triangle, then face. Each component is compacted. Faces of
    /// several loops are made one face per region first
    /// ([`Piece::faces_into_regions`]).
    pub fn components(mut self) -> Vec<Piece> {
        self.faces_into_regions();
        let n = self.tris.len();
        let mut uf = UnionFind::new(n + self.faces.len());
        // Each element (triangle, face `n + f`) is joined to the first along each of
        // its undirected edges.
        for_each_edge(&self, |first: &mut Option<u32>, e| match *first {
            Some(f) => uf.union(f as usize, e.elem as usize),
            None => *first = Some(e.elem),
        });
        self.into_groups(&mut uf).0
    }

    /// Splits the piece into the groups of triangles and faces that `uf` joins (over the
    /// triangles, then the faces: face `f` is element `tris.len() + f`), in order of
    /// their first element, each compacted; also returns each triangle's group.
    pub fn into_groups(self, uf: &mut UnionFind) -> (Vec<Piece>, Vec<usize>) {
        let n = self.tris.len();
        let mut group_of_root = vec![usize::MAX; n + self.faces.len()];
        let mut group = vec![0; n];
        let mut out: Vec<Piece> = Vec::new();
        let mut group_of = |x: usize, out: &mut Vec<Piece>| {
            let r = uf.find(x);
            if group_of_root[r] == usize::MAX {
                group_of_root[r] = out.len();
                // The first group is most often the only one: room for every triangle.
                let room = if out.is_empty() { n } else { 0 };
                out.push(Piece {
                    tris: Vec::with_capacity(room),
                    tags: Vec::with_capacity(room),
                    ..Piece::default()
                });
            }
            group_of_root[r]
        };
        for t in 0..n {
            group[t] = group_of(t, &mut out);
            out[group[t]].tris.push(self.tris[t]);
            out[group[t]].tags.push(self.tags[t]);
        }
        for (f, face) in self.faces.into_iter().enumerate() {
            let g = group_of(n + f, &mut out);
            out[g].faces.push(face);
        }
        if let [only] = out.as_mut_slice() {
            // One group: the positions move instead of being copied.
            only.pos = self.pos;
            only.compact();
            return (out, group);
        }
        for p in &mut out {
            p.pos.clone_from(&self.pos);
            p.compact();
        }
        (out, group)
    }
}

/// Length of the bounding-box diagonal of a piece (1 for an empty one).
/// Whether every directed edge of `tris` is used once, and its reverse once.
fn closed(tris: &[[u32; 3]]) -> bool {
    let mut count: FastMap<(u32, u32), u32> = FastMap::default();
    count.reserve(3 * tris.len());
    for tri in tris {
        for k in 0..3 {
            *count.entry((tri[k], tri[(k + 1) % 3])).or_default() += 1;
        }
    }
    count
        .iter()
        .all(|(&(a, b), &n)| n == 1 && count.get(&(b, a)) == Some(&1))
}

pub(crate) fn mesh_scale(p: &Piece) -> f64 {
    if p.pos.is_empty() {
        return 1.0;
    }
    let (lo, hi) = crate::util::bounds(&p.pos);
    (hi - lo).length().max(f64::MIN_POSITIVE)
}

#[cfg(test)]
mod flat_tests {
    use glam::DVec3;

    use super::Piece;
    use crate::mesh::is_degenerate;

    /// A tetrahedron whose face a-b-c is split at the midpoint m of a-b, the face
    /// a-d-b across that edge left whole, and the gap closed by the flat triangle
    /// a-b-m: closed, but with a triangle of no area. Splitting it away leaves a closed
    /// piece of the same volume, with no flat triangle.
    #[test]
    fn a_flat_triangle_is_split_away_and_the_piece_stays_closed() {
        let (a, b, c, d) = (DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z);
        let m = (a + b) / 2.0;
        let mut p = Piece {
            pos: vec![a, b, c, d, m],
            // Outward: a-c-b (below), a-b-d (front), a-d-c (side), b-c-d (slant).
            tris: vec![
                [0, 2, 4],
                [4, 2, 1],
                [0, 1, 3],
                [0, 3, 2],
                [1, 2, 3],
                [0, 4, 1],
            ],
            tags: vec![1, 1, 2, 3, 4, 5],
            faces: Vec::new(),
        };
        assert!(p.is_closed());
        let flat = |p: &Piece| {
            p.tris
                .iter()
                .filter(|t| {
                    let [x, y, z] = t.map(|i| p.pos[i as usize]);
                    is_degenerate(x, y, z)
                })
                .count()
        };
        assert_eq!(flat(&p), 1);
        let volume = p.volume();
        p.split_flat_triangles();
        assert!(p.is_closed());
        assert_eq!(flat(&p), 0);
        assert!((p.volume() - volume).abs() < 1e-15);
        assert!((volume - 1.0 / 6.0).abs() < 1e-15);
        // The front face a-b-d, split at m, keeps its tag.
        assert_eq!(p.tags.iter().filter(|&&t| t == 2).count(), 2);
        assert_eq!(p.tris.len(), 6);
    }
}
