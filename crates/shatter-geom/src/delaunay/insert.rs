//! One Bowyer–Watson insertion: walk to a conflicting tetrahedron, grow the cavity of
//! tetrahedra whose (perturbed) circumsphere contains the point, and fill it with the star
//! of new tetrahedra joining the point to the cavity boundary.

use super::packed::Store;
use super::predicates::{insphere_perturbed, orient};
use super::storage::{BoundaryFace, EDGE, EdgeSlot, FLAGS, INF, MARK, Mesh, SEEN};

/// Where a point landed.
pub(crate) enum Location {
    /// A tetrahedron in conflict with the point.
    Conflict(u32),
    /// The point coincides with this existing vertex.
    Duplicate(u32),
}

/// Whether an insertion happened.
#[derive(Debug, PartialEq, Eq)]
pub(crate) enum Inserted {
    /// The point is in the triangulation.
    Done,
    /// The new tetrahedra would not fit the storage's limit; nothing changed.
    Full,
}

impl<S: Store> Mesh<'_, S> {
    /// Orientation of tetrahedron `v` with vertex `i` replaced by `p`: positive when `p`
    /// is on the same side of the face opposite `i` as vertex `i` (all of `v` finite
    /// except possibly position `i`).
    #[inline(always)]
    fn orient_replaced(&self, v: &[u32; 4], i: usize, p: &[f64; 3]) -> f64 {
        let q = |k: usize| if k == i { p } else { &self.pts[v[k] as usize] };
        orient(q(0), q(1), q(2), q(3))
    }

    /// Visibility walk from `self.last` towards `p`.
    pub(crate) fn locate(&mut self, p: &[f64; 3]) -> Location {
        let mut t = self.last;
        let mut from = 4usize;
        'walk: loop {
            let v = self.tets.verts(t);
            // xorshift32 for the face order.
            let mut r = self.rng;
            r ^= r << 13;
            r ^= r >> 17;
            r ^= r << 5;
            self.rng = r;
            let start = (r >> 7) as usize;
            for k in 0..4 {
                let i = (start + k) & 3;
                if i == from {
                    continue;
                }
                if self.orient_replaced(&v, i, p) < 0.0 {
                    let packed = self.tets.adj(t, i);
                    let n = packed >> 2;
                    from = (packed & 3) as usize;
                    if self.is_infinite(n) {
                        // p is strictly outside this hull face: the infinite tetrahedron
                        // beyond it is in conflict.
                        return Location::Conflict(n);
                    }
                    t = n;
                    continue 'walk;
                }
            }
            // p is in the closed tetrahedron t; if it is a vertex of the triangulation it is
            // a vertex of t.
            for &w in &v {
                if self.pts[w as usize] == *p {
                    return Location::Duplicate(w);
                }
            }
            return Location::Conflict(t);
        }
    }

    /// Whether (unmarked) tetrahedron `t` is in conflict with `p`.
    #[inline]
    fn in_conflict(&self, t: u32, p: &[f64; 3]) -> bool {
        let v = self.tets.verts(t);
        let inf = if v[0] == INF {
            0
        } else if v[1] == INF {
            1
        } else if v[2] == INF {
            2
        } else if v[3] == INF {
            3
        } else {
            let q = |k: usize| &self.pts[v[k] as usize];
            return insphere_perturbed(q(0), q(1), q(2), q(3), p);
        };
        // Infinite tetrahedron: in conflict when p is strictly beyond its hull face, or on
        // the face's plane and in conflict with the finite tetrahedron behind the face.
        let o = self.orient_replaced(&v, inf, p);
        if o != 0.0 {
            return o > 0.0;
        }
        let n = self.tets.adj(t, inf) >> 2;
        let w = self.tets.verts(n);
        let q = |k: usize| &self.pts[w[k] as usize];
        insphere_perturbed(q(0), q(1), q(2), q(3), p)
    }

    /// Inserts internal vertex `pi`, starting from the conflicting tetrahedron `t0`.
    pub(crate) fn insert(&mut self, pi: u32, t0: u32) -> Inserted {
        let p = self.pts[pi as usize];
        // 1. Cavity: depth-first search over tetrahedra in conflict.
        self.cavity.clear();
        self.boundary.clear();
        self.stack.clear();
        self.tets.add_flags(t0, MARK);
        self.cavity.push(t0);
        self.stack.push(t0);
        while let Some(t) = self.stack.pop() {
            let tv = self.tets.verts(t);
            let ta = self.tets.adjs(t);
            for (i, &outer) in ta.iter().enumerate() {
                let n = outer >> 2;
                let flags = self.tets.flags(n) & FLAGS;
                if flags == MARK {
                    continue;
                }
                if flags == 0 && self.in_conflict(n, &p) {
                    self.tets.add_flags(n, MARK);
                    self.cavity.push(n);
                    self.stack.push(n);
                } else {
                    if flags == 0 {
                        self.tets.add_flags(n, SEEN);
                        self.seen.push(n);
                    }
                    let mut verts = tv;
                    verts[i] = pi;
                    self.boundary.push(BoundaryFace {
                        verts,
                        outer,
                        apex: i as u8,
                    });
                }
            }
        }
        for &n in &self.seen {
            self.tets.clear_flags(n, SEEN);
        }
        self.seen.clear();
        // 2. Star: one new tetrahedron per boundary face, glued through the edge table.
        let nb = self.boundary.len();
        if !self.has_room(nb.saturating_sub(self.cavity.len())) {
            for &t in &self.cavity {
                self.tets.clear_flags(t, MARK);
            }
            return Inserted::Full;
        }
        let need = (nb * 6).next_power_of_two().max(64);
        if self.edges.len() < need {
            self.edges = vec![EdgeSlot::default(); need];
            self.stamp = 0;
        }
        self.stamp = self.stamp.wrapping_add(1);
        if self.stamp == 0 {
            self.edges.fill(EdgeSlot::default());
            self.stamp = 1;
        }
        let mask = self.edges.len() - 1;
        let shift = 64 - self.edges.len().trailing_zeros();
        // Slots first (the cavity's own, then new ones), so that every new tetrahedron's
        // record is written once, whole, after its faces are glued in `star`.
        self.slots.clear();
        for k in 0..nb {
            let s = if k < self.cavity.len() {
                self.cavity[k]
            } else {
                self.alloc()
            };
            self.slots.push(s);
        }
        self.star.clear();
        self.star.resize(nb, [0; 4]);
        let mut last_finite = u32::MAX;
        for k in 0..nb {
            let bf = self.boundary[k];
            let s = self.slots[k];
            let apex = bf.apex as usize;
            self.star[k][apex] = bf.outer;
            self.tets
                .set_adj(bf.outer >> 2, (bf.outer & 3) as usize, s << 2 | apex as u32);
            if bf.verts.iter().all(|&x| x != INF) {
                last_finite = s;
            }
            for (j, &(a, b)) in EDGE[apex].iter().enumerate() {
                if j == apex {
                    continue;
                }
                let u = bf.verts[a as usize];
                let v = bf.verts[b as usize];
                // Look for the partner's edge (v, u); otherwise register (u, v). Values are
                // `k << 2 | face` with `k` the index in the star.
                let mut h = (hash(v, u) >> shift) as usize;
                let mut found = false;
                loop {
                    let e = self.edges[h];
                    if e.stamp != self.stamp {
                        break;
                    }
                    if e.u == v && e.v == u {
                        let (k2, j2) = ((e.val >> 2) as usize, (e.val & 3) as usize);
                        self.star[k][j] = self.slots[k2] << 2 | j2 as u32;
                        self.star[k2][j2] = s << 2 | j as u32;
                        found = true;
                        break;
                    }
                    h = (h + 1) & mask;
                }
                if !found {
                    let mut h = (hash(u, v) >> shift) as usize;
                    while self.edges[h].stamp == self.stamp {
                        h = (h + 1) & mask;
                    }
                    self.edges[h] = EdgeSlot {
                        u,
                        v,
                        stamp: self.stamp,
                        val: (k as u32) << 2 | j as u32,
                    };
                }
            }
        }
        for k in 0..nb {
            self.tets
                .write(self.slots[k], self.boundary[k].verts, self.star[k]);
        }
        // Cavity slots left over (the cavity had more tetrahedra than the star) are freed.
        for k in nb..self.cavity.len() {
            let t = self.cavity[k];
            self.kill(t);
        }
        if last_finite != u32::MAX {
            self.last = last_finite;
        }
        Inserted::Done
    }
}

#[inline(always)]
fn hash(u: u32, v: u32) -> u64 {
    (u as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15) ^ (v as u64).wrapping_mul(0xC2B2_AE3D_27D4_EB4F)
}
