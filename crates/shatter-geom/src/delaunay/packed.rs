//! Tetrahedron storage: the construction's working records and the result's.
//!
//! Two layouts behind one trait, [`Store`]:
//!
//! - [`Narrow`]: one 24-byte record per tetrahedron, with fields at fixed bit positions,
//!   for up to [`Narrow::MAX_POINTS`] points and [`Narrow::MAX_TETS`] tetrahedra:
//!   ```text
//!    bit 0    2     23    44    65    86      112     138     164     190
//!    +-----+-----+-----+-----+-----+-------+-------+-------+-------+--+
//!    |flags| v0  | v1  | v2  | v3  |  a0   |  a1   |  a2   |  a3   |  |
//!    +-----+-----+-----+-----+-----+-------+-------+-------+-------+--+
//!           21 bits per vertex      26 bits per adjacency (24-bit tetrahedron, 2-bit face)
//!   ```
//!   Each field is read with one 8-byte load at an offset fixed per field (the last two
//!   adjacency fields share the record's last eight bytes), a shift and a mask, so access
//!   costs about what an array of `u32` costs, in three quarters of the memory of the
//!   wide layout.
//! - [`Wide`]: two arrays of `[u32; 4]` (vertices with the flags in the top bits of `v3`,
//!   and adjacency), 32 bytes per tetrahedron, for anything larger.
//!
//! A construction starts narrow when the points allow it and moves to the wide layout if
//! the tetrahedra outgrow it ([`Wide::from_narrow`]).

/// The operations the construction and the result need from a tetrahedron storage.
///
/// Vertex fields hold ids up to [`Store::vertex_marker`] (exclusive: the marker itself
/// marks a free slot); adjacency fields hold `t << 2 | face` during the construction, or a
/// tetrahedron (or [`Store::adjacency_marker`] on the hull) in a result.
pub(crate) trait Store: Sized {
    /// Empty storage with room reserved for `capacity` records.
    fn with_capacity(capacity: usize) -> Self;
    /// Number of records.
    fn len(&self) -> usize;
    /// Most records the layout can hold.
    fn max_len(&self) -> usize;
    /// The vertex field value that is never a vertex.
    fn vertex_marker(&self) -> u32;
    /// The adjacency field value that is never a neighbour.
    fn adjacency_marker(&self) -> u32;
    /// The four vertex fields of record `t`.
    fn verts(&self, t: u32) -> [u32; 4];
    /// Sets the vertex fields of record `t` and clears its flags.
    fn set_verts(&mut self, t: u32, v: [u32; 4]);
    /// The two flag bits of record `t`.
    fn flags(&self, t: u32) -> u8;
    /// Sets flag bits `f` of record `t`.
    fn add_flags(&mut self, t: u32, f: u8);
    /// Clears flag bits `f` of record `t`.
    fn clear_flags(&mut self, t: u32, f: u8);
    /// Adjacency field `i` of record `t`.
    fn adj(&self, t: u32, i: usize) -> u32;
    /// All four adjacency fields of record `t`.
    fn adjs(&self, t: u32) -> [u32; 4];
    /// Sets adjacency field `i` of record `t`.
    fn set_adj(&mut self, t: u32, i: usize, a: u32);
    /// Writes the whole record `t`: vertices, adjacency, no flags.
    fn write(&mut self, t: u32, v: [u32; 4], a: [u32; 4]);
    /// Appends a record (fields unspecified until set); returns its index.
    fn push(&mut self) -> u32;
    /// Keeps the first `len` records (the capacity stays).
    fn truncate(&mut self, len: usize);
    /// Gives unused capacity back (may copy the records).
    fn shrink_to_fit(&mut self);
    /// Heap bytes held.
    fn heap_bytes(&self) -> usize;
}

/// Bits per vertex field of [`Narrow`].
const VB: u32 = 21;
/// Bits per tetrahedron index of [`Narrow`] (its adjacency fields have two more).
const TB: u32 = 24;
/// Bits per adjacency field of [`Narrow`].
const AB: u32 = TB + 2;
/// Bytes per [`Narrow`] record.
const RECORD: usize = 24;

/// `(byte, shift)` of the 8-byte window that holds the field at bit `p` of `width` bits,
/// kept inside the record.
const fn window(p: u32, width: u32) -> (usize, u32) {
    let byte = if p / 8 > (RECORD - 8) as u32 {
        (RECORD - 8) as u32
    } else {
        p / 8
    };
    let shift = p - 8 * byte;
    assert!(shift + width <= 64, "a field does not fit its window");
    (byte as usize, shift)
}

const fn windows(first: u32, width: u32) -> [(usize, u32); 4] {
    [
        window(first, width),
        window(first + width, width),
        window(first + 2 * width, width),
        window(first + 3 * width, width),
    ]
}

const VERT_AT: [(usize, u32); 4] = windows(2, VB);
const ADJ_AT: [(usize, u32); 4] = windows(2 + 4 * VB, AB);
const VMASK: u64 = (1 << VB) - 1;
const AMASK: u64 = (1 << AB) - 1;
const _: () = assert!(2 + 4 * VB + 4 * AB <= 8 * RECORD as u32);

/// 24-byte records with fixed fields (see the module docs).
#[derive(Clone, Debug, Default)]
pub(crate) struct Narrow {
    recs: Vec<[u8; RECORD]>,
}

impl Narrow {
    /// Most points (the infinite vertex, `1..=n` and the free-slot marker fit 21 bits).
    pub(crate) const MAX_POINTS: usize = VMASK as usize - 1;
    /// Most tetrahedra (every `t << 2 | face` stays below the adjacency marker).
    pub(crate) const MAX_TETS: usize = (1 << TB) - 1;

    // `byte.min(RECORD - 8)` changes nothing (every window is inside the record) but lets
    // the compiler drop the bounds check when the field is chosen at run time.
    #[inline(always)]
    fn get(r: &[u8; RECORD], (byte, shift): (usize, u32), mask: u64) -> u32 {
        let byte = byte.min(RECORD - 8);
        let mut w = [0u8; 8];
        w.copy_from_slice(&r[byte..byte + 8]);
        (u64::from_le_bytes(w) >> shift & mask) as u32
    }

    #[inline(always)]
    fn put(r: &mut [u8; RECORD], (byte, shift): (usize, u32), mask: u64, x: u32) {
        let byte = byte.min(RECORD - 8);
        let mut w = [0u8; 8];
        w.copy_from_slice(&r[byte..byte + 8]);
        let w = u64::from_le_bytes(w) & !(mask << shift) | (x as u64 & mask) << shift;
        r[byte..byte + 8].copy_from_slice(&w.to_le_bytes());
    }
}

impl Store for Narrow {
    fn with_capacity(capacity: usize) -> Self {
        Self {
            recs: Vec::with_capacity(capacity.min(Self::MAX_TETS)),
        }
    }

    #[inline(always)]
    fn len(&self) -> usize {
        self.recs.len()
    }

    #[inline(always)]
    fn max_len(&self) -> usize {
        Self::MAX_TETS
    }

    #[inline(always)]
    fn vertex_marker(&self) -> u32 {
        VMASK as u32
    }

    #[inline(always)]
    fn adjacency_marker(&self) -> u32 {
        AMASK as u32
    }

    #[inline(always)]
    fn verts(&self, t: u32) -> [u32; 4] {
        let r = &self.recs[t as usize];
        let f = |i: usize| Self::get(r, VERT_AT[i], VMASK);
        [f(0), f(1), f(2), f(3)]
    }

    #[inline(always)]
    fn set_verts(&mut self, t: u32, v: [u32; 4]) {
        debug_assert!(v.iter().all(|&x| x as u64 <= VMASK));
        let r = &mut self.recs[t as usize];
        r[0] &= !3;
        for (at, x) in VERT_AT.into_iter().zip(v) {
            Self::put(r, at, VMASK, x);
        }
    }

    #[inline(always)]
    fn flags(&self, t: u32) -> u8 {
        self.recs[t as usize][0] & 3
    }

    #[inline(always)]
    fn add_flags(&mut self, t: u32, f: u8) {
        self.recs[t as usize][0] |= f;
    }

    #[inline(always)]
    fn clear_flags(&mut self, t: u32, f: u8) {
        self.recs[t as usize][0] &= !f;
    }

    #[inline(always)]
    fn adj(&self, t: u32, i: usize) -> u32 {
        Self::get(&self.recs[t as usize], ADJ_AT[i], AMASK)
    }

    #[inline(always)]
    fn adjs(&self, t: u32) -> [u32; 4] {
        let r = &self.recs[t as usize];
        let f = |i: usize| Self::get(r, ADJ_AT[i], AMASK);
        [f(0), f(1), f(2), f(3)]
    }

    #[inline(always)]
    fn set_adj(&mut self, t: u32, i: usize, a: u32) {
        debug_assert!(a as u64 <= AMASK);
        Self::put(&mut self.recs[t as usize], ADJ_AT[i], AMASK, a);
    }

    #[inline(always)]
    fn write(&mut self, t: u32, v: [u32; 4], a: [u32; 4]) {
        // Every position is a constant, so this folds into shifts and ors of three words.
        let mut w = [0u64; 3];
        let mut put = |p: u32, width: u32, x: u32| {
            let (word, off) = ((p / 64) as usize, p % 64);
            w[word] |= (x as u64) << off;
            if off + width > 64 {
                w[word + 1] |= (x as u64) >> (64 - off);
            }
        };
        for i in 0..4 {
            put(2 + i as u32 * VB, VB, v[i]);
            put(2 + 4 * VB + i as u32 * AB, AB, a[i]);
        }
        let r = &mut self.recs[t as usize];
        r[0..8].copy_from_slice(&w[0].to_le_bytes());
        r[8..16].copy_from_slice(&w[1].to_le_bytes());
        r[16..24].copy_from_slice(&w[2].to_le_bytes());
    }

    #[inline]
    fn push(&mut self) -> u32 {
        self.recs.push([0; RECORD]);
        (self.recs.len() - 1) as u32
    }

    fn truncate(&mut self, len: usize) {
        self.recs.truncate(len);
    }

    fn shrink_to_fit(&mut self) {
        self.recs.shrink_to_fit();
    }

    fn heap_bytes(&self) -> usize {
        self.recs.capacity() * RECORD
    }
}

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

    /// The same records, one by one, in the wide layout (markers stay markers).
    pub(crate) fn from_narrow(n: &Narrow, spare: usize) -> Self {
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
}

impl Store for Wide {
    fn with_capacity(capacity: usize) -> Self {
        let capacity = capacity.min(Self::MAX_TETS);
        Self {
            tv: Vec::with_capacity(capacity),
            adj: Vec::with_capacity(capacity),
        }
    }

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

/// The result's storage: whichever layout the construction ended in.
#[derive(Clone, Debug)]
pub(crate) enum Tets {
    Narrow(Narrow),
    Wide(Wide),
}

impl Default for Tets {
    fn default() -> Self {
        Self::Narrow(Narrow::default())
    }
}

impl From<Narrow> for Tets {
    fn from(n: Narrow) -> Self {
        Self::Narrow(n)
    }
}

impl From<Wide> for Tets {
    fn from(w: Wide) -> Self {
        Self::Wide(w)
    }
}

/// Calls `$body` with `$s` bound to the storage of `$tets`, whichever layout it is.
macro_rules! with_store {
    ($tets:expr, $s:ident => $body:expr) => {
        match $tets {
            Tets::Narrow($s) => $body,
            Tets::Wide($s) => $body,
        }
    };
}

impl Tets {
    pub(crate) fn len(&self) -> usize {
        with_store!(self, s => s.len())
    }

    pub(crate) fn verts(&self, t: u32) -> [u32; 4] {
        with_store!(self, s => s.verts(t))
    }

    /// Neighbour `i` of `t`, `None` on the hull.
    pub(crate) fn neighbor(&self, t: u32, i: usize) -> Option<u32> {
        with_store!(self, s => {
            let a = s.adj(t, i);
            (a != s.adjacency_marker()).then_some(a)
        })
    }

    pub(crate) fn set_verts(&mut self, t: u32, v: [u32; 4]) {
        with_store!(self, s => s.set_verts(t, v))
    }

    /// Sets neighbour `i` of `t` (`None`: on the hull).
    pub(crate) fn set_neighbor(&mut self, t: u32, i: usize, n: Option<u32>) {
        with_store!(self, s => {
            let a = n.unwrap_or(s.adjacency_marker());
            s.set_adj(t, i, a)
        })
    }

    pub(crate) fn heap_bytes(&self) -> usize {
        with_store!(self, s => s.heap_bytes())
    }

    pub(crate) fn shrink_to_fit(&mut self) {
        with_store!(self, s => s.shrink_to_fit())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Writes every field of records 0..3 in any layout and reads them back.
    fn fields_do_not_disturb_each_other<S: Store>(mut p: S, max_v: u32, max_t: u32) {
        let (vm, am) = (p.vertex_marker(), p.adjacency_marker());
        assert!(vm > max_v && am > (max_t << 2 | 3));
        for t in 0..3 {
            assert_eq!(p.push(), t);
            p.set_verts(t, [vm; 4]);
            for i in 0..4 {
                p.set_adj(t, i, am);
            }
        }
        let v = [max_v, 0, max_v / 2, vm];
        p.set_verts(1, v);
        p.add_flags(1, 2);
        let a = [max_t << 2 | 3, 0, 5, am];
        for (i, &x) in a.iter().enumerate() {
            p.set_adj(1, i, x);
        }
        // Neighbouring records keep their markers.
        for t in [0, 2] {
            assert_eq!(p.verts(t), [vm; 4]);
            assert_eq!(p.flags(t), 0);
            assert_eq!(p.adjs(t), [am; 4]);
        }
        assert_eq!(p.verts(1), v);
        assert_eq!(p.flags(1), 2);
        assert_eq!(p.adjs(1), a);
        assert!((0..4).all(|i| p.adj(1, i) == a[i]));
        // A whole record, then the vertices alone: that clears the flags, keeps the adjacency.
        let b = [0, max_t << 2 | 3, am, 7];
        p.add_flags(1, 3);
        p.write(1, [vm, max_v, 0, 1], b);
        assert_eq!(
            (p.verts(1), p.adjs(1), p.flags(1)),
            ([vm, max_v, 0, 1], b, 0)
        );
        assert_eq!((p.verts(0), p.adjs(2)), ([vm; 4], [am; 4]));
        p.write(1, v, a);
        p.set_verts(1, [1, 2, 3, 4]);
        assert_eq!(p.flags(1), 0);
        assert_eq!(p.adjs(1), a);
        p.add_flags(1, 3);
        p.clear_flags(1, 1);
        assert_eq!(p.flags(1), 2);
        assert_eq!(p.verts(1), [1, 2, 3, 4]);
    }

    #[test]
    fn narrow_fields_do_not_disturb_each_other() {
        let max_t = Narrow::MAX_TETS as u32 - 1;
        fields_do_not_disturb_each_other(
            Narrow::with_capacity(3),
            Narrow::MAX_POINTS as u32,
            max_t,
        );
    }

    #[test]
    fn wide_fields_do_not_disturb_each_other() {
        let max_t = Wide::MAX_TETS as u32 - 1;
        fields_do_not_disturb_each_other(Wide::with_capacity(3), (1 << 30) - 2, max_t);
    }

    #[test]
    fn narrow_records_convert_to_wide_unchanged() {
        let mut n = Narrow::with_capacity(8);
        for t in 0..7u32 {
            n.push();
            n.set_verts(t, [t, t + 1, t + 2, 100]);
            for i in 0..4 {
                n.set_adj(t, i, n.adjacency_marker());
            }
            n.set_adj(t, 1, t << 2 | 1);
        }
        n.set_verts(6, [n.vertex_marker(); 4]);
        n.add_flags(3, 1);
        let w = Wide::from_narrow(&n, 0);
        assert_eq!(w.len(), 7);
        for t in 0..6u32 {
            assert_eq!(w.verts(t), [t, t + 1, t + 2, 100]);
            assert_eq!(w.adj(t, 1), t << 2 | 1);
            assert_eq!(w.adj(t, 0), w.adjacency_marker());
            assert_eq!(w.flags(t), u8::from(t == 3));
        }
        assert_eq!(w.verts(6), [w.vertex_marker(); 4]);
    }
}
