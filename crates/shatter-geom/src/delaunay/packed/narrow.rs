//! The bit-packed layouts: records whose fields sit at fixed bit positions (drawn in the
//! parent module's docs), one [`Layout`] per record size: [`Narrow`] (24 bytes) and
//! [`Medium`] (27 bytes).

use std::fmt::Debug;
use std::marker::PhantomData;

use bytemuck::Pod;

use super::Store;

/// The widths of a bit-packed record: the flags (2 bits), four vertex fields of
/// [`Layout::VB`] bits, then four adjacency fields of [`Layout::TB`] + 2 bits.
pub(crate) trait Layout: Clone + Debug + Default {
    /// Bits per vertex field.
    const VB: u32;
    /// Bits per tetrahedron index (an adjacency field has two more, for the face).
    const TB: u32;
    /// One record as stored: plain bytes (or words), all zero when empty.
    type Rec: Pod + Debug + Default;
    /// Bytes per record.
    const RECORD: usize = std::mem::size_of::<Self::Rec>();
    /// Bits per adjacency field.
    const AB: u32 = Self::TB + 2;
    /// Mask of a vertex field; its largest value is the free-slot marker.
    const VMASK: u64 = (1 << Self::VB) - 1;
    /// Mask of an adjacency field; its largest value is the hull marker.
    const AMASK: u64 = (1 << Self::AB) - 1;
    /// `(byte, shift)` of each vertex field's 8-byte window.
    const VERT_AT: [(usize, u32); 4] = windows(2, Self::VB, Self::RECORD);
    /// `(byte, shift)` of each adjacency field's 8-byte window.
    const ADJ_AT: [(usize, u32); 4] = windows(2 + 4 * Self::VB, Self::AB, Self::RECORD);
}

/// 24-byte records: 21 bits per vertex (about two million points), 24 per tetrahedron.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Bits24;

impl Layout for Bits24 {
    const VB: u32 = 21;
    const TB: u32 = 24;
    /// Words rather than bytes: `vec![[0; 3]; n]` of these is allocated zeroed by the
    /// system, so pages nobody writes never become resident.
    type Rec = Words;
}

/// 27-byte records: 24 bits per vertex (about 16.7 million points), 27 per tetrahedron
/// (134 million), for what [`Bits24`] cannot hold; 2 + 4·24 + 4·29 = 214 of 216 bits.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Bits27;

impl Layout for Bits27 {
    const VB: u32 = 24;
    const TB: u32 = 27;
    type Rec = [u8; 27];
}

/// `(byte, shift)` of the 8-byte window that holds the field at bit `p` of `width` bits,
/// kept inside a record of `record` bytes.
const fn window(p: u32, width: u32, record: usize) -> (usize, u32) {
    let byte = if p / 8 > (record - 8) as u32 {
        (record - 8) as u32
    } else {
        p / 8
    };
    let shift = p - 8 * byte;
    assert!(shift + width <= 64, "a field does not fit its window");
    assert!(
        p + width <= 8 * record as u32,
        "a field does not fit the record"
    );
    (byte as usize, shift)
}

const fn windows(first: u32, width: u32, record: usize) -> [(usize, u32); 4] {
    [
        window(first, width, record),
        window(first + width, width, record),
        window(first + 2 * width, width, record),
        window(first + 3 * width, width, record),
    ]
}

/// One [`Bits24`] record as the words it is stored in.
pub(crate) type Words = [u64; 3];

/// Where packed records live: a vector of their own, or a [`Slab`] of a buffer shared
/// with other constructions.
pub(crate) trait Records<W> {
    /// Every record (a slab's whole span, past its length too).
    fn all(&self) -> &[W];
    /// Every record, mutably.
    fn all_mut(&mut self) -> &mut [W];
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

impl<W: Pod + Default> Records<W> for Vec<W> {
    #[inline(always)]
    fn all(&self) -> &[W] {
        self
    }
    #[inline(always)]
    fn all_mut(&mut self) -> &mut [W] {
        self
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
        Vec::push(self, W::default());
    }
    fn truncate(&mut self, len: usize) {
        Vec::truncate(self, len);
    }
    fn shrink_to_fit(&mut self) {
        Vec::shrink_to_fit(self);
    }
    fn heap_bytes(&self) -> usize {
        self.capacity() * std::mem::size_of::<W>()
    }
}

/// A fixed span of zeroed [`Bits24`] records borrowed from a larger buffer, filled from
/// its start: lets two constructions run on disjoint parts of one allocation, so that
/// joining their results moves records within it instead of copying them into a new one.
#[derive(Debug)]
pub(crate) struct Slab<'a> {
    buf: &'a mut [Words],
    len: usize,
}

impl<'a> Slab<'a> {
    /// An empty slab over `buf`.
    pub(crate) fn new(buf: &'a mut [Words]) -> Self {
        Self { buf, len: 0 }
    }
}

impl Records<Words> for Slab<'_> {
    #[inline(always)]
    fn all(&self) -> &[Words] {
        self.buf
    }
    #[inline(always)]
    fn all_mut(&mut self) -> &mut [Words] {
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

/// Bit-packed records of layout `L` (see the `packed` module docs), in their own vector
/// or in a [`Slab`].
#[derive(Clone, Debug, Default)]
pub(crate) struct Packed<L: Layout, R = Vec<<L as Layout>::Rec>> {
    recs: R,
    layout: PhantomData<L>,
}

/// 24-byte records.
pub(crate) type Narrow<R = Vec<Words>> = Packed<Bits24, R>;
/// 27-byte records.
pub(crate) type Medium = Packed<Bits27>;

impl<'a> Narrow<Slab<'a>> {
    /// Records kept in `slab`.
    pub(crate) fn in_slab(slab: Slab<'a>) -> Self {
        Self {
            recs: slab,
            layout: PhantomData,
        }
    }
}

impl<L: Layout> Packed<L> {
    /// Empty records with room reserved for `capacity`.
    pub(crate) fn with_capacity(capacity: usize) -> Self {
        Self {
            recs: Vec::with_capacity(capacity.min(Self::MAX_TETS)),
            layout: PhantomData,
        }
    }

    /// Records kept in `recs` (its length and contents as they are).
    pub(crate) fn from_records(recs: Vec<L::Rec>) -> Self {
        Self {
            recs,
            layout: PhantomData,
        }
    }
}

impl<L: Layout, R> Packed<L, R> {
    /// Most points (the infinite vertex, `1..=n` and the free-slot marker fit the vertex
    /// fields).
    pub(crate) const MAX_POINTS: usize = L::VMASK as usize - 1;
    /// Most tetrahedra (every `t << 2 | face` stays below the adjacency marker).
    pub(crate) const MAX_TETS: usize = (1 << L::TB) - 1;

    // `byte.min(RECORD - 8)` changes nothing (every window is inside the record) but lets
    // the compiler drop the bounds check when the field is chosen at run time.
    #[inline(always)]
    fn get(r: &[u8], (byte, shift): (usize, u32), mask: u64) -> u32 {
        let byte = byte.min(L::RECORD - 8);
        let mut w = [0u8; 8];
        w.copy_from_slice(&r[byte..byte + 8]);
        (u64::from_le_bytes(w) >> shift & mask) as u32
    }

    #[inline(always)]
    fn put(r: &mut [u8], (byte, shift): (usize, u32), mask: u64, x: u32) {
        let byte = byte.min(L::RECORD - 8);
        let mut w = [0u8; 8];
        w.copy_from_slice(&r[byte..byte + 8]);
        let w = u64::from_le_bytes(w) & !(mask << shift) | (x as u64 & mask) << shift;
        r[byte..byte + 8].copy_from_slice(&w.to_le_bytes());
    }
}

impl<L: Layout, R: Records<L::Rec>> Packed<L, R> {
    #[inline(always)]
    fn rec(&self, t: u32) -> &[u8] {
        bytemuck::bytes_of(&self.recs.all()[t as usize])
    }

    #[inline(always)]
    fn rec_mut(&mut self, t: u32) -> &mut [u8] {
        bytemuck::bytes_of_mut(&mut self.recs.all_mut()[t as usize])
    }
}

impl<L: Layout, R: Records<L::Rec>> Store for Packed<L, R> {
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
        L::VMASK as u32
    }

    #[inline(always)]
    fn adjacency_marker(&self) -> u32 {
        L::AMASK as u32
    }

    #[inline(always)]
    fn verts(&self, t: u32) -> [u32; 4] {
        let r = self.rec(t);
        let f = |i: usize| Self::get(r, L::VERT_AT[i], L::VMASK);
        [f(0), f(1), f(2), f(3)]
    }

    #[inline(always)]
    fn set_verts(&mut self, t: u32, v: [u32; 4]) {
        debug_assert!(v.iter().all(|&x| x as u64 <= L::VMASK));
        let r = self.rec_mut(t);
        r[0] &= !3;
        for (at, x) in L::VERT_AT.into_iter().zip(v) {
            Self::put(r, at, L::VMASK, x);
        }
    }

    #[inline(always)]
    fn flags(&self, t: u32) -> u8 {
        self.rec(t)[0] & 3
    }

    #[inline(always)]
    fn add_flags(&mut self, t: u32, f: u8) {
        self.rec_mut(t)[0] |= f;
    }

    #[inline(always)]
    fn clear_flags(&mut self, t: u32, f: u8) {
        self.rec_mut(t)[0] &= !f;
    }

    #[inline(always)]
    fn adj(&self, t: u32, i: usize) -> u32 {
        Self::get(self.rec(t), L::ADJ_AT[i], L::AMASK)
    }

    #[inline(always)]
    fn adjs(&self, t: u32) -> [u32; 4] {
        let r = self.rec(t);
        let f = |i: usize| Self::get(r, L::ADJ_AT[i], L::AMASK);
        [f(0), f(1), f(2), f(3)]
    }

    #[inline(always)]
    fn set_adj(&mut self, t: u32, i: usize, a: u32) {
        debug_assert!(a as u64 <= L::AMASK);
        Self::put(self.rec_mut(t), L::ADJ_AT[i], L::AMASK, a);
    }

    #[inline(always)]
    fn write(&mut self, t: u32, v: [u32; 4], a: [u32; 4]) {
        // Every position is a constant, so this folds into shifts and ors of a few words.
        let mut w = [0u64; 4];
        let mut put = |p: u32, width: u32, x: u32| {
            let (word, off) = ((p / 64) as usize, p % 64);
            w[word] |= (x as u64) << off;
            if off + width > 64 {
                w[word + 1] |= (x as u64) >> (64 - off);
            }
        };
        for i in 0..4 {
            put(2 + i as u32 * L::VB, L::VB, v[i]);
            put(2 + 4 * L::VB + i as u32 * L::AB, L::AB, a[i]);
        }
        let mut bytes = [0u8; 32];
        for (chunk, word) in bytes.chunks_exact_mut(8).zip(w) {
            chunk.copy_from_slice(&word.to_le_bytes());
        }
        self.rec_mut(t).copy_from_slice(&bytes[..L::RECORD]);
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
