//! A level of the hierarchy in `f64`, as built (see `build.rs`) and updated (`update.rs`),
//! and the constants of its construction.

use glam::DVec3;

use crate::stress::block::Block6;

/// Levels with at most this many nodes are solved densely.
pub(super) const COARSEST: usize = 48;
/// Coarsening that keeps more than this fraction of the nodes has stalled.
pub(super) const STALL: f64 = 0.85;
/// A coupling is strong, and may join two nodes into one group or widen `P`, when its
/// block is at least this fraction of the geometric mean of the two nodes' diagonal
/// blocks (Frobenius norms of the displacement parts). Without it the smoothed coarse
/// matrices, whose stencils are wide and mostly weak, were grouped 15 to 20 nodes at a
/// time and the coarse levels stopped approximating the fine one (49 iterations on the
/// 20,097-bond wall instead of 13, with the old W-cycle).
pub(super) const STRENGTH: f64 = 0.1;
/// [`STRENGTH`] on the finest level, whose couplings are the bonds themselves: only a
/// bond far weaker than its blocks' others is left out of the groups. (At 0.1 the
/// through-thickness bonds of a wall of 0.1 × 0.1 × 0.2 m bricks, a quarter as stiff as
/// the others, were weak, the two layers were grouped apart, and level 1 had 1,169 nodes
/// instead of 513: the preconditioner cost half as much again.)
pub(super) const FINE_STRENGTH: f64 = 0.02;
/// The finest level's groups are a node, its neighbours and their neighbours (about 20
/// blocks): level 1 has 650 nodes instead of 1,058 on the 20,097-bond wall and the
/// preconditioner costs a third less, for 26 iterations instead of 23.
pub(super) const FINE_RINGS: usize = 2;
/// The prolongation's smoothing weight over the largest eigenvalue of `D⁻¹·K`.
pub(super) const SMOOTHING: f64 = 4.0 / 3.0;
/// Power iterations estimating that eigenvalue.
pub(super) const POWER_STEPS: usize = 12;

/// One level: a symmetric block matrix, its rows in CSR form without the diagonal, and
/// its prolongation from the next level.
#[derive(Debug, Clone, Default)]
pub(super) struct Level {
    pub diag: Vec<Block6>,
    pub diag_inv: Vec<Block6>,
    pub row_start: Vec<u32>,
    pub cols: Vec<u32>,
    pub offd: Vec<Block6>,
    /// Each node's reference point.
    pub pos: Vec<DVec3>,
    /// `P` (nodes × next level's nodes), per node its entries: column, block.
    pub p_start: Vec<u32>,
    pub p_cols: Vec<u32>,
    pub p_blocks: Vec<Block6>,
}

impl Level {
    pub fn len(&self) -> usize {
        self.diag.len()
    }

    pub fn row(&self, i: usize) -> std::ops::Range<usize> {
        self.row_start[i] as usize..self.row_start[i + 1] as usize
    }

    /// The entry of row `i`, column `j` off the diagonal, if it is stored.
    pub fn find(&self, i: usize, j: u32) -> Option<usize> {
        if self.row_start.is_empty() {
            return None;
        }
        let row = self.row(i);
        self.cols[row.clone()]
            .binary_search(&j)
            .ok()
            .map(|k| row.start + k)
    }

    pub fn p_row(&self, i: usize) -> std::ops::Range<usize> {
        self.p_start[i] as usize..self.p_start[i + 1] as usize
    }
}

/// Sums of blocks per column of one row (a sparse accumulator).
#[derive(Debug, Clone)]
pub(super) struct Accumulator {
    slot: Vec<u32>,
    entries: Vec<(u32, Block6)>,
}

impl Accumulator {
    pub fn new(columns: usize) -> Accumulator {
        Accumulator {
            slot: vec![u32::MAX; columns],
            entries: Vec::new(),
        }
    }

    #[inline]
    pub fn add(&mut self, col: u32, b: Block6) {
        match self.slot[col as usize] {
            u32::MAX => {
                self.slot[col as usize] = self.entries.len() as u32;
                self.entries.push((col, b));
            }
            s => self.entries[s as usize].1.add(&b),
        }
    }

    /// The row's entries by column; the accumulator is empty after.
    pub fn drain_sorted(&mut self) -> impl Iterator<Item = (u32, Block6)> + '_ {
        for (c, _) in &self.entries {
            self.slot[*c as usize] = u32::MAX;
        }
        self.entries.sort_unstable_by_key(|(c, _)| *c);
        self.entries.drain(..)
    }
}
