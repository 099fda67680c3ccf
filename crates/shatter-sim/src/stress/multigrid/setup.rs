//! Building the hierarchy, in `f64`: the finest level's blocks from the springs, then
//! level by level the aggregation, the smoothed prolongation and the Galerkin product.

use glam::{DMat3, DVec3};

use crate::stress::block::{Block6, Dense};
use crate::stress::local::{Dof, LocalSprings};
use crate::stress::spring::skew;

/// Levels with at most this many nodes are solved densely.
pub(super) const COARSEST: usize = 48;
/// Coarsening that keeps more than this fraction of the nodes has stalled.
const STALL: f64 = 0.85;
/// A coupling is strong, and may join two nodes into one group or widen `P`, when its
/// block is at least this fraction of the geometric mean of the two nodes' diagonal
/// blocks (Frobenius norms of the displacement parts). Without it the smoothed coarse
/// matrices, whose stencils are wide and mostly weak, were grouped 15 to 20 nodes at a
/// time and the coarse levels stopped approximating the fine one (49 iterations on the
/// 20,097-bond wall instead of 13, with the old W-cycle).
const STRENGTH: f64 = 0.1;
/// [`STRENGTH`] on the finest level, whose couplings are the bonds themselves: only a
/// bond far weaker than its blocks' others is left out of the groups. (At 0.1 the
/// through-thickness bonds of a wall of 0.1 × 0.1 × 0.2 m bricks, a quarter as stiff as
/// the others, were weak, the two layers were grouped apart, and level 1 had 1,169 nodes
/// instead of 513: the preconditioner cost half as much again.)
const FINE_STRENGTH: f64 = 0.02;
/// The finest level's groups are a node, its neighbours and their neighbours (about 20
/// blocks): level 1 has 650 nodes instead of 1,058 on the 20,097-bond wall and the
/// preconditioner costs a third less, for 26 iterations instead of 23.
const FINE_RINGS: usize = 2;
/// The prolongation's smoothing weight over the largest eigenvalue of `D⁻¹·K`.
const SMOOTHING: f64 = 4.0 / 3.0;
/// Power iterations estimating that eigenvalue.
const POWER_STEPS: usize = 12;

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

    /// A level from its diagonal and its off-diagonal rows (each sorted by column, no
    /// duplicates).
    fn from_rows(diag: Vec<Block6>, rows: Vec<Vec<(u32, Block6)>>, pos: Vec<DVec3>) -> Level {
        let mut row_start = vec![0u32];
        let mut cols = Vec::new();
        let mut offd = Vec::new();
        for row in rows {
            for (j, b) in row {
                cols.push(j);
                offd.push(b);
            }
            row_start.push(cols.len() as u32);
        }
        let diag_inv = diag.iter().map(Block6::inverse).collect();
        Level {
            diag,
            diag_inv,
            row_start,
            cols,
            offd,
            pos,
            ..Level::default()
        }
    }

    /// `out = K·x`.
    fn times(&self, x: &[Dof], out: &mut [Dof]) {
        for i in 0..self.len() {
            let (mut u, mut t) = self.diag[i].apply(x[i].0, x[i].1);
            for k in self.row(i) {
                let (fu, ft) =
                    self.offd[k].apply(x[self.cols[k] as usize].0, x[self.cols[k] as usize].1);
                u += fu;
                t += ft;
            }
            out[i] = (u, t);
        }
    }

    /// The largest eigenvalue of `D⁻¹·K` (power iteration from a fixed start).
    fn lambda_max(&self) -> f64 {
        let n = self.len();
        let mut x: Vec<Dof> = (0..n)
            .map(|i| {
                let s = ((i * 7919) % 101) as f64 / 101.0 + 0.5;
                (DVec3::new(s, 1.0 - s, 0.5), DVec3::new(0.5 - s, s, 1.0))
            })
            .collect();
        let mut y = vec![(DVec3::ZERO, DVec3::ZERO); n];
        let mut lambda = 0.0;
        for _ in 0..POWER_STEPS {
            self.times(&x, &mut y);
            let (mut yy, mut xx) = (0.0, 0.0);
            for i in 0..n {
                let (u, t) = self.diag_inv[i].apply(y[i].0, y[i].1);
                y[i] = (u, t);
                yy += u.length_squared() + t.length_squared();
                xx += x[i].0.length_squared() + x[i].1.length_squared();
            }
            if !(xx > 0.0 && yy.is_finite()) {
                break;
            }
            lambda = (yy / xx).sqrt();
            std::mem::swap(&mut x, &mut y);
        }
        lambda
    }

    /// Per off-diagonal entry, whether the coupling is strong (see [`STRENGTH`]).
    fn strong(&self, theta: f64) -> Vec<bool> {
        let n = self.len();
        let size = |m: &DMat3| {
            (m.x_axis.length_squared() + m.y_axis.length_squared() + m.z_axis.length_squared())
                .sqrt()
        };
        let dsize: Vec<f64> = self.diag.iter().map(|b| size(&b.uu)).collect();
        (0..n)
            .flat_map(|i| self.row(i).map(move |k| (i, k)))
            .map(|(i, k)| {
                size(&self.offd[k].uu) >= theta * (dsize[i] * dsize[self.cols[k] as usize]).sqrt()
            })
            .collect()
    }

    /// Groups the nodes (greedy aggregation on the strong couplings): each group is a node
    /// and its strong neighbours, and with `rings == 2` their free strong neighbours too;
    /// returns each node's group and the group count.
    fn aggregate(&self, strong: &[bool], rings: usize) -> (Vec<u32>, usize) {
        const NONE: u32 = u32::MAX;
        let n = self.len();
        let size = |m: &DMat3| {
            (m.x_axis.length_squared() + m.y_axis.length_squared() + m.z_axis.length_squared())
                .sqrt()
        };
        let mut parent = vec![NONE; n];
        let mut groups = 0u32;
        // A node whose strong neighbours are all free of a group starts one with them.
        for i in 0..n {
            if parent[i] != NONE
                || self
                    .row(i)
                    .any(|k| strong[k] && parent[self.cols[k] as usize] != NONE)
            {
                continue;
            }
            parent[i] = groups;
            for k in self.row(i) {
                if strong[k] {
                    parent[self.cols[k] as usize] = groups;
                }
            }
            if rings == 2 {
                // And the neighbours' neighbours whose own neighbours are free or here.
                for k in self.row(i) {
                    if !strong[k] {
                        continue;
                    }
                    for kk in self.row(self.cols[k] as usize) {
                        let m = self.cols[kk] as usize;
                        if strong[kk]
                            && parent[m] == NONE
                            && self.row(m).all(|q| {
                                let p = parent[self.cols[q] as usize];
                                p == NONE || p == groups
                            })
                        {
                            parent[m] = groups;
                        }
                    }
                }
            }
            groups += 1;
        }
        // The rest join the neighbouring group they are most strongly bonded to.
        for i in 0..n {
            if parent[i] != NONE {
                continue;
            }
            let best = self
                .row(i)
                .filter(|&k| strong[k] && parent[self.cols[k] as usize] != NONE)
                .max_by(|&k, &l| size(&self.offd[k].uu).total_cmp(&size(&self.offd[l].uu)));
            parent[i] = match best {
                Some(k) => parent[self.cols[k] as usize],
                None => {
                    groups += 1;
                    groups - 1
                }
            };
        }
        (parent, groups as usize)
    }

    /// The next level of `groups` groups (`parent`: each node's): each group moves as a
    /// rigid body about its nodes' mean point (the tentative prolongation `T`), smoothed
    /// by one damped Jacobi step, `P = (I − ω·D⁻¹·K_f)·T`; the coarse matrix is `Pᵀ·K·P`.
    /// Sets this level's `P`. `K_f` is `K` with each weak coupling (`strong[k]` false)
    /// moved onto its row's own group (the rigid motion of the row's group seen at the
    /// weak neighbour): rigid motions stay exact, and a row of `P` gains no group through
    /// a weak coupling, so the coarse matrices of blocky 3D objects stay sparse (on a
    /// 20 × 20 × 20 cube, level 2's 199 nodes had 119 neighbours each without it, 25
    /// with it, for the same iterations).
    fn coarsen(&mut self, parent: &[u32], groups: usize, strong: &[bool]) -> Level {
        let n = self.len();
        let mut pos = vec![DVec3::ZERO; groups];
        let mut count = vec![0usize; groups];
        for (i, &g) in parent.iter().enumerate() {
            pos[g as usize] += self.pos[i];
            count[g as usize] += 1;
        }
        for (p, &c) in pos.iter_mut().zip(&count) {
            *p /= c.max(1) as f64;
        }
        let skews: Vec<DMat3> = (0..n)
            .map(|i| skew(self.pos[i] - pos[parent[i] as usize]))
            .collect();
        let omega = match self.lambda_max() {
            l if l > 0.0 && l.is_finite() => SMOOTHING / l,
            _ => 0.0,
        };
        // P, row by row: P_iG = [g(i) = G]·T_i − ω·D_i⁻¹·Σ_{j in G} K_ij·T_j.
        let mut acc = Accumulator::new(groups);
        let mut p_start = vec![0u32];
        let mut p_cols = Vec::new();
        let mut p_blocks = Vec::new();
        for i in 0..n {
            acc.add(parent[i], self.diag[i].times_rigid(&skews[i]));
            for k in self.row(i) {
                let j = self.cols[k] as usize;
                if strong[k] {
                    acc.add(parent[j], self.offd[k].times_rigid(&skews[j]));
                } else {
                    // A weak coupling moves with i's group (its rigid motion seen at j), so
                    // that rigid motions stay exact and the row gains no group.
                    let r = self.pos[j] - pos[parent[i] as usize];
                    acc.add(parent[i], self.offd[k].times_rigid(&skew(r)));
                }
            }
            let row: Vec<(u32, Block6)> = acc
                .drain_sorted()
                .map(|(g, b)| {
                    let mut block = self.diag_inv[i].mul(&b).scale(-omega);
                    if g == parent[i] {
                        block.add(&Block6::rigid_of_skew(&skews[i]));
                    }
                    (g, block)
                })
                .collect();
            for (g, block) in row {
                p_cols.push(g);
                p_blocks.push(block);
            }
            p_start.push(p_cols.len() as u32);
        }
        self.p_start = p_start;
        self.p_cols = p_cols;
        self.p_blocks = p_blocks;
        // K·P, row by row.
        let mut kp: Vec<Vec<(u32, Block6)>> = Vec::with_capacity(n);
        for i in 0..n {
            for k in self.p_row(i) {
                acc.add(self.p_cols[k], self.diag[i].mul(&self.p_blocks[k]));
            }
            for kk in self.row(i) {
                let j = self.cols[kk] as usize;
                for k in self.p_row(j) {
                    acc.add(self.p_cols[k], self.offd[kk].mul(&self.p_blocks[k]));
                }
            }
            kp.push(acc.drain_sorted().collect());
        }
        // Pᵀ·(K·P), by coarse row: the upper triangle, mirrored.
        let mut by_col: Vec<Vec<u32>> = vec![Vec::new(); groups];
        for i in 0..n {
            for k in self.p_row(i) {
                by_col[self.p_cols[k] as usize].push(k as u32);
            }
        }
        let mut owner = vec![0u32; self.p_cols.len()];
        for i in 0..n {
            for k in self.p_row(i) {
                owner[k] = i as u32;
            }
        }
        let mut diag = vec![Block6::ZERO; groups];
        let mut rows: Vec<Vec<(u32, Block6)>> = vec![Vec::new(); groups];
        for g in 0..groups {
            for &k in &by_col[g] {
                let pt = &self.p_blocks[k as usize];
                for (h, b) in &kp[owner[k as usize] as usize] {
                    if *h as usize >= g {
                        acc.add(*h, pt.transpose_mul(b));
                    }
                }
            }
            for (h, b) in acc.drain_sorted() {
                if h as usize == g {
                    diag[g] = b;
                } else {
                    rows[g].push((h, b));
                }
            }
        }
        // The lower triangle, as transposes of the upper.
        let mut lower: Vec<Vec<(u32, Block6)>> = vec![Vec::new(); groups];
        for (g, row) in rows.iter().enumerate() {
            for (h, b) in row {
                lower[*h as usize].push((g as u32, b.transpose()));
            }
        }
        for (row, low) in rows.iter_mut().zip(lower) {
            let upper = std::mem::take(row);
            *row = low;
            row.extend(upper);
        }
        Level::from_rows(diag, rows, pos)
    }
}

/// Sums of blocks per column of one row (a sparse accumulator).
struct Accumulator {
    slot: Vec<u32>,
    entries: Vec<(u32, Block6)>,
}

impl Accumulator {
    fn new(columns: usize) -> Accumulator {
        Accumulator {
            slot: vec![u32::MAX; columns],
            entries: Vec::new(),
        }
    }

    #[inline]
    fn add(&mut self, col: u32, b: Block6) {
        match self.slot[col as usize] {
            u32::MAX => {
                self.slot[col as usize] = self.entries.len() as u32;
                self.entries.push((col, b));
            }
            s => self.entries[s as usize].1.add(&b),
        }
    }

    /// The row's entries by column; the accumulator is empty after.
    fn drain_sorted(&mut self) -> impl Iterator<Item = (u32, Block6)> + '_ {
        for (c, _) in &self.entries {
            self.slot[*c as usize] = u32::MAX;
        }
        self.entries.sort_unstable_by_key(|(c, _)| *c);
        self.entries.drain(..)
    }
}

/// The hierarchy of an island's springs (free nodes `0..n`) with the free nodes'
/// positions: the levels (the finest first; all but the last with their `P`) and the
/// coarsest level's dense factor when it is small enough.
pub(super) fn build(springs: &LocalSprings, pos: &[DVec3]) -> (Vec<Level>, Option<Dense>) {
    let n = springs.n;
    let mut diag = vec![Block6::ZERO; n];
    let mut rows: Vec<Vec<(u32, Block6)>> = vec![Vec::new(); n];
    for s in &springs.springs {
        let (kaa, kab, kbb) = Block6::of_local(s);
        let (la, lb) = (s.a as usize, s.b as usize);
        if la < n {
            diag[la].add(&kaa);
        }
        if lb < n {
            diag[lb].add(&kbb);
        }
        if la < n && lb < n {
            rows[la].push((lb as u32, kab));
            rows[lb].push((la as u32, kab.transpose()));
        }
    }
    // Merge the springs between the same two nodes.
    for row in &mut rows {
        row.sort_unstable_by_key(|(j, _)| *j);
        row.dedup_by(|next, kept| {
            if next.0 == kept.0 {
                kept.1.add(&next.1);
                true
            } else {
                false
            }
        });
    }
    let mut levels = vec![Level::from_rows(diag, rows, pos.to_vec())];
    loop {
        let levels_len = levels.len();
        let last = levels.last_mut().expect("one level");
        if last.len() <= COARSEST {
            break;
        }
        let strong = last.strong(if levels_len == 1 {
            FINE_STRENGTH
        } else {
            STRENGTH
        });
        let rings = if levels_len == 1 { FINE_RINGS } else { 1 };
        let (parent, groups) = last.aggregate(&strong, rings);
        if groups as f64 > STALL * last.len() as f64 || groups == 0 {
            break;
        }
        let next = last.coarsen(&parent, groups, &strong);
        levels.push(next);
    }
    let bottom = levels.last().expect("one level");
    let coarse = (bottom.len() <= COARSEST).then(|| {
        Dense::factor(bottom.len(), |i, j| {
            if i == j {
                return Some(bottom.diag[i]);
            }
            bottom
                .row(i)
                .find(|&k| bottom.cols[k] as usize == j)
                .map(|k| bottom.offd[k])
        })
    });
    (levels, coarse)
}
