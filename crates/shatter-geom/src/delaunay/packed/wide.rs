//! The wide layout: two arrays of `[u32; 4]`, for anything the packed ones cannot hold.

use super::Store;

/// Bit of `v3` marking a [`Wide`] record as in the current cavity; the next one down marks
/// it as tested (the flags `1` and `2` of [`Store`]).
const WIDE_FLAG_SHIFT: u32 = 30;
const WIDE_FLAGS: u32 = 3 << WIDE_FLAG_SHIFT;

/// Two arrays of `[u32; 4]`: vertices (flags in the top two bits of `v3`) and adjacency.
#[derive(Clone, Debug, Default)]
pub(crate) struct Wide {
    tv: Vec<[u32; 4]>,
    adj: Vec<[u32; 4]>,
}

impl Wide {
    /// Most tetrahedra (`t << 2 | face` fits a `u32` below the marker).
    pub(crate) const MAX_TETS: usize = (1 << 30) - 1;

    /// The same records, one by one, in the wide layout (markers stay markers), with room
    /// for `spare` more.
    pub(crate) fn from_store(n: &impl Store, spare: usize) -> Self {
        let mut w = Self::with_capacity(n.len() + spare);
        let (vm, am) = (n.vertex_marker(), n.adjacency_marker());
        for t in 0..n.len() as u32 {
            w.push();
            let v = n
                .verts(t)
                .map(|x| if x == vm { w.vertex_marker() } else { x });
            w.set_verts(t, v);
            w.add_flags(t, n.flags(t));
            for i in 0..4 {
                let a = n.adj(t, i);
                w.set_adj(t, i, if a == am { w.adjacency_marker() } else { a });
            }
        }
        w
    }

    /// Empty records with room reserved for `capacity`.
    pub(crate) fn with_capacity(capacity: usize) -> Self {
        let capacity = capacity.min(Self::MAX_TETS);
        Self {
            tv: Vec::with_capacity(capacity),
            adj: Vec::with_capacity(capacity),
        }
    }
}

impl Store for Wide {
    #[inline(always)]
    fn len(&self) -> usize {
        self.tv.len()
    }

    #[inline(always)]
    fn max_len(&self) -> usize {
        Self::MAX_TETS
    }

    #[inline(always)]
    fn vertex_marker(&self) -> u32 {
        !WIDE_FLAGS
    }

    #[inline(always)]
    fn adjacency_marker(&self) -> u32 {
        u32::MAX
    }

    #[inline(always)]
    fn verts(&self, t: u32) -> [u32; 4] {
        let mut v = self.tv[t as usize];
        v[3] &= !WIDE_FLAGS;
        v
    }

    #[inline(always)]
    fn set_verts(&mut self, t: u32, v: [u32; 4]) {
        debug_assert!(v.iter().all(|&x| x <= self.vertex_marker()));
        self.tv[t as usize] = v;
    }

    #[inline(always)]
    fn flags(&self, t: u32) -> u8 {
        (self.tv[t as usize][3] >> WIDE_FLAG_SHIFT) as u8
    }

    #[inline(always)]
    fn add_flags(&mut self, t: u32, f: u8) {
        self.tv[t as usize][3] |= (f as u32) << WIDE_FLAG_SHIFT;
    }

    #[inline(always)]
    fn clear_flags(&mut self, t: u32, f: u8) {
        self.tv[t as usize][3] &= !((f as u32) << WIDE_FLAG_SHIFT);
    }

    #[inline(always)]
    fn adj(&self, t: u32, i: usize) -> u32 {
        self.adj[t as usize][i]
    }

    #[inline(always)]
    fn adjs(&self, t: u32) -> [u32; 4] {
        self.adj[t as usize]
    }

    #[inline(always)]
    fn set_adj(&mut self, t: u32, i: usize, a: u32) {
        self.adj[t as usize][i] = a;
    }

    #[inline(always)]
    fn write(&mut self, t: u32, v: [u32; 4], a: [u32; 4]) {
        self.tv[t as usize] = v;
        self.adj[t as usize] = a;
    }

    #[inline]
    fn push(&mut self) -> u32 {
        self.tv.push([0; 4]);
        self.adj.push([0; 4]);
        (self.tv.len() - 1) as u32
    }

    fn truncate(&mut self, len: usize) {
        self.tv.truncate(len);
        self.adj.truncate(len);
    }

    fn shrink_to_fit(&mut self) {
        self.tv.shrink_to_fit();
        self.adj.shrink_to_fit();
    }

    fn heap_bytes(&self) -> usize {
        (self.tv.capacity() + self.adj.capacity()) * 16
    }
}
