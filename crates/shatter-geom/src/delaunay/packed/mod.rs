//! Tetrahedron storage: the construction's working records and the result's.
//!
//! Three layouts behind one trait, [`Store`]:
//!
//! - [`Narrow`]: one 24-byte record per tetrahedron, with fields at fixed bit positions,
//!   for up to [`Narrow::MAX_POINTS`] points (about two million) and [`Narrow::MAX_TETS`]
//!   tetrahedra:
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
//! - [`Medium`]: the same in 27 bytes, 24 bits per vertex (about 16.7 million points)
//!   and 29 per adjacency field (a 27-bit tetrahedron, 134 million): the layout of
//!   large inputs, where the 32 bytes of the wide one would take the peak past 200 bytes
//!   per point.
//! - [`Wide`]: two arrays of `[u32; 4]` (vertices with the flags in the top bits of `v3`,
//!   and adjacency), 32 bytes per tetrahedron, for anything larger.
//!
//! A construction starts in the smallest layout the points allow and moves to the wide
//! one if the tetrahedra outgrow it ([`Wide::from_store`]).

mod narrow;
mod wide;

#[cfg(test)]
use narrow::{Bits27, Layout};
pub(crate) use narrow::{Medium, Narrow, Slab, Words};
pub(crate) use wide::Wide;

/// The operations the construction and the result need from a tetrahedron storage.
///
/// Vertex fields hold ids up to [`Store::vertex_marker`] (exclusive: the marker itself
/// marks a free slot); adjacency fields hold `t << 2 | face` during the construction, or a
/// tetrahedron (or [`Store::adjacency_marker`] on the hull) in a result.
pub(crate) trait Store: Sized {
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

/// The result's storage: whichever layout the construction ended in.
#[derive(Clone, Debug)]
pub(crate) enum Tets {
    Narrow(Narrow),
    Medium(Medium),
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

impl From<Medium> for Tets {
    fn from(m: Medium) -> Self {
        Self::Medium(m)
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
            Tets::Medium($s) => $body,
            Tets::Wide($s) => $body,
        }
    };
}
pub(crate) use with_store;

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
mod tests;
