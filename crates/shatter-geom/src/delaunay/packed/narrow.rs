//! The narrow layout: 24-byte records whose fields sit at fixed bit positions (drawn in
//! the parent module's docs), for up to [`Narrow::MAX_POINTS`] points and
//! [`Narrow::MAX_TETS`] tetrahedra.

use super::Store;

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

/// One record's bytes.
pub(crate) type Record = [u8; RECORD];

/// One record as the words it is stored in: `vec![[0; 3]; n]` of these is allocated
/// zeroed by the system, so pages nobody writes never become resident (a zeroed
/// `[u8; 24]` vector is written element by element).
pub(crate) type Words = [u64; 3];

/// Where [`Narrow`] records live: a vector of their own, or a [`Slab`] of a buffer shared
/// with other constructions.
pub(crate) trait Records {
    /// Every record (a slab's whole span, past its length too).
    fn all(&self) -> &[Record];
    /// Every record, mutably.
    fn all_mut(&mut self) -> &mut [Record];
    /// Number of records in use.
    fn len(&self) -> usize;
    /// Most records it can hold.
    fn room(&self) -> usize;
    /// Appends a record (zero in a vector; as it was in a slab).
    fn push(&mut self);
    /// Keeps the first `len` records.
    fn truncate(&mut self, len: usize);
    /// Gives unused capacity back (may copy).
    fn shrink_to_fit(&mut self);
    /// Heap bytes held.
    fn heap_bytes(&self) -> usize;
}

impl Records for Vec<Words> {
    #[inline(always)]
    fn all(&self) -> &[Record] {
        bytemuck::cast_slice(self)
    }
    #[inline(always)]
    fn all_mut(&mut self) -> &mut [Record] {
        bytemuck::cast_slice_mut(self)
    }
    #[inline(always)]
    fn len(&self) -> usize {
        Vec::len(self)
    }
    fn room(&self) -> usize {
        usize::MAX
    }
    #[inline]
    fn push(&mut self) {
        Vec::push(self, [0; 3]);
    }
    fn truncate(&mut self, len: usize) {
        Vec::truncate(self, len);
    }
    fn shrink_to_fit(&mut self) {
        Vec::shrink_to_fit(self);
    }
    fn heap_bytes(&self) -> usize {
        self.capacity() * RECORD
    }
}

/// A fixed span of zeroed records borrowed from a larger buffer, filled from its start:
/// lets two constructions run on disjoint parts of one allocation, so that joining their
/// results moves records within it instead of copying them into a new one.
#[derive(Debug)]
pub(crate) struct Slab<'a> {
    buf: &'a mut [Record],
    len: usize,
}

impl<'a> Slab<'a> {
    /// An empty slab over `buf`.
    pub(crate) fn new(buf: &'a mut [Record]) -> Self {
        Self { buf, len: 0 }
    }
}

impl Records for Slab<'_> {
    #[inline(always)]
    fn all(&self) -> &[Record] {
        self.buf
    }
    #[inline(always)]
    fn all_mut(&mut self) -> &mut [Record] {
        self.buf
    }
    #[inline(always)]
    fn len(&self) -> usize {
        self.len
    }
    fn room(&self) -> usize {
        self.buf.len()
    }
    #[inline]
    fn push(&mut self) {
        // Its fields are unspecified until set (`Store::push`), so the slot is not cleared.
        assert!(self.len < self.buf.len(), "slab full");
        self.len += 1;
    }
    fn truncate(&mut self, len: usize) {
        self.len = self.len.min(len);
    }
    fn shrink_to_fit(&mut self) {}
    fn heap_bytes(&self) -> usize {
        0
    }
}

/// 24-byte records with fixed fields (see the `packed` module docs), in their own vector
/// or in a [`Slab`].
#[derive(Clone, Debug, Default)]
pub(crate) struct Narrow<R = Vec<Words>> {
    recs: R,
}

impl<'a> Narrow<Slab<'a>> {
    /// Records kept in `slab`.
    pub(crate) fn in_slab(slab: Slab<'a>) -> Self {
        Self { recs: slab }
    }
}

impl Narrow {
    /// Empty records with room reserved for `capacity`.
    pub(crate) fn with_capacity(capacity: usize) -> Self {
        Self {
            recs: Vec::with_capacity(capacity.min(Self::MAX_TETS)),
        }
    }

    /// Records kept in `recs` (its length and contents as they are).
    pub(crate) fn from_records(recs: Vec<Words>) -> Self {
        Self { recs }
    }
}

impl<R> Narrow<R> {
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

impl<R: Records> Store for Narrow<R> {
    #[inline(always)]
    fn len(&self) -> usize {
        self.recs.len()
    }

    #[inline(always)]
    fn max_len(&self) -> usize {
        Self::MAX_TETS.min(self.recs.room())
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
        let r = &self.recs.all()[t as usize];
        let f = |i: usize| Self::get(r, VERT_AT[i], VMASK);
        [f(0), f(1), f(2), f(3)]
    }

    #[inline(always)]
    fn set_verts(&mut self, t: u32, v: [u32; 4]) {
        debug_assert!(v.iter().all(|&x| x as u64 <= VMASK));
        let r = &mut self.recs.all_mut()[t as usize];
        r[0] &= !3;
        for (at, x) in VERT_AT.into_iter().zip(v) {
            Self::put(r, at, VMASK, x);
        }
    }

    #[inline(always)]
    fn flags(&self, t: u32) -> u8 {
        self.recs.all()[t as usize][0] & 3
    }

    #[inline(always)]
    fn add_flags(&mut self, t: u32, f: u8) {
        self.recs.all_mut()[t as usize][0] |= f;
    }

    #[inline(always)]
    fn clear_flags(&mut self, t: u32, f: u8) {
        self.recs.all_mut()[t as usize][0] &= !f;
    }

    #[inline(always)]
    fn adj(&self, t: u32, i: usize) -> u32 {
        Self::get(&self.recs.all()[t as usize], ADJ_AT[i], AMASK)
    }

    #[inline(always)]
    fn adjs(&self, t: u32) -> [u32; 4] {
        let r = &self.recs.all()[t as usize];
        let f = |i: usize| Self::get(r, ADJ_AT[i], AMASK);
        [f(0), f(1), f(2), f(3)]
    }

    #[inline(always)]
    fn set_adj(&mut self, t: u32, i: usize, a: u32) {
        debug_assert!(a as u64 <= AMASK);
        Self::put(&mut self.recs.all_mut()[t as usize], ADJ_AT[i], AMASK, a);
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
        let r = &mut self.recs.all_mut()[t as usize];
        r[0..8].copy_from_slice(&w[0].to_le_bytes());
        r[8..16].copy_from_slice(&w[1].to_le_bytes());
        r[16..24].copy_from_slice(&w[2].to_le_bytes());
    }

    #[inline]
    fn push(&mut self) -> u32 {
        self.recs.push();
        (self.recs.len() - 1) as u32
    }

    fn truncate(&mut self, len: usize) {
        self.recs.truncate(len);
    }

    fn shrink_to_fit(&mut self) {
        self.recs.shrink_to_fit();
    }

    fn heap_bytes(&self) -> usize {
        self.recs.heap_bytes()
    }
}
