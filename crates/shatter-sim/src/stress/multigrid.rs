//! The stress solver's preconditioner: an aggregation multigrid whose coarse nodes are
//! rigid groups of blocks.
//!
//! A wall, bridge or tower is a thin elastic body: its stiffness matrix has smooth,
//! bending-like modes that a per-node (block-Jacobi) preconditioner barely touches, so
//! conjugate gradients need thousands of iterations on a 20,000-bond graph. Here
//! neighbouring free nodes are grouped (greedy aggregation on the bond graph, about 7
//! per group) and each group moves as one rigid body: a node at `r` from its group's
//! reference point moves by `(U + Θ × r, Θ)`. That prolongation holds the rigid-body
//! modes exactly, and the coarse matrix `Pᵀ·K·P` is again a block matrix on the groups,
//! grouped again until a few dozen nodes are left, which are solved densely. One
//! symmetric W-cycle is the preconditioner: damped block Jacobi before and after the
//! coarse correction on the finest level (two passes over the springs; Gauss-Seidel took
//! six and cost twice as much per iteration for a third fewer iterations), forward block
//! Gauss-Seidel before and backward after on the coarse levels: symmetric and positive,
//! as conjugate gradients need.
//!
//! Anchored nodes are not unknowns: their blocks are dropped (their springs still add to
//! the free nodes' diagonals).

use glam::DVec3;

use crate::stress::block::{Block6, Dense};
use crate::stress::local::{Dof, LocalSprings, ZERO};

/// Levels with at most this many nodes are solved densely.
const COARSEST: usize = 48;
/// Gauss-Seidel sweeps before and after the coarse correction.
const SWEEPS: usize = 1;
/// Coarse corrections per level: 1 is a V-cycle, 2 a W-cycle.
const CYCLES: usize = 2;
/// The damping of the finest level's block Jacobi.
const OMEGA: f64 = 0.7;
/// Coarsening that keeps more than this fraction of the nodes has stalled.
const STALL: f64 = 0.85;

/// One level: a symmetric block matrix, its rows in CSR form without the diagonal.
#[derive(Debug, Clone)]
struct Level {
    diag: Vec<Block6>,
    diag_inv: Vec<Block6>,
    row_start: Vec<u32>,
    cols: Vec<u32>,
    offd: Vec<Block6>,
    /// Each node's reference point.
    pos: Vec<DVec3>,
    /// Each node's group on the next level, and its offset from the group's point.
    parent: Vec<u32>,
    offset: Vec<DVec3>,
}

impl Level {
    fn len(&self) -> usize {
        self.diag.len()
    }

    /// A level from its diagonal and off-diagonal `(row, column, block)` entries
    /// (duplicates are summed).
    fn new(diag: Vec<Block6>, mut entries: Vec<(u32, u32, Block6)>, pos: Vec<DVec3>) -> Level {
        let n = diag.len();
        entries.sort_unstable_by_key(|e| (e.0, e.1));
        let mut row_start = vec![0u32; n + 1];
        let mut cols = Vec::with_capacity(entries.len());
        let mut offd: Vec<Block6> = Vec::with_capacity(entries.len());
        let mut last = None;
        for (i, j, b) in entries {
            if last == Some((i, j)) {
                offd.last_mut().expect("an entry was pushed").add(&b);
                continue;
            }
            last = Some((i, j));
            row_start[i as usize + 1] += 1;
            cols.push(j);
            offd.push(b);
        }
        for i in 0..n {
            row_start[i + 1] += row_start[i];
        }
        let diag_inv = diag.iter().map(Block6::inverse).collect();
        Level {
            diag,
            diag_inv,
            row_start,
            cols,
            offd,
            pos,
            parent: Vec::new(),
            offset: Vec::new(),
        }
    }

    fn row(&self, i: usize) -> std::ops::Range<usize> {
        self.row_start[i] as usize..self.row_start[i + 1] as usize
    }

    /// `b_i − Σ_{j≠i} K_ij·x_j`.
    #[inline]
    fn off_residual(&self, i: usize, x: &[Dof], b: Dof) -> Dof {
        let (mut ru, mut rt) = b;
        for k in self.row(i) {
            let (u, t) = x[self.cols[k] as usize];
            let (fu, ft) = self.offd[k].apply(u, t);
            ru -= fu;
            rt -= ft;
        }
        (ru, rt)
    }

    /// One block Gauss-Seidel sweep, forward or backward.
    fn sweep(&self, x: &mut [Dof], b: &[Dof], forward: bool) {
        let n = self.len();
        for step in 0..n {
            let i = if forward { step } else { n - 1 - step };
            let (ru, rt) = self.off_residual(i, x, b[i]);
            x[i] = self.diag_inv[i].apply(ru, rt);
        }
    }

    /// `out += Pᵀ·(b − K·x)` on the next level: each node's residual, moved to its
    /// group's point.
    fn restrict_residual(&self, x: &[Dof], b: &[Dof], out: &mut [Dof]) {
        out.fill(ZERO);
        for i in 0..self.len() {
            let (ru, rt) = self.off_residual(i, x, b[i]);
            let (du, dt) = self.diag[i].apply(x[i].0, x[i].1);
            let (fu, ft) = (ru - du, rt - dt);
            let g = &mut out[self.parent[i] as usize];
            g.0 += fu;
            g.1 += ft + self.offset[i].cross(fu);
        }
    }

    /// `x += P·xc`: each node moves with its group as a rigid body.
    fn prolong_add(&self, xc: &[Dof], x: &mut [Dof]) {
        for (i, xi) in x.iter_mut().enumerate().take(self.len()) {
            let (u, t) = xc[self.parent[i] as usize];
            xi.0 += u + t.cross(self.offset[i]);
            xi.1 += t;
        }
    }

    /// Groups the nodes (greedy aggregation on the matrix's graph); returns the group
    /// count, after setting `parent`.
    fn aggregate(&mut self) -> usize {
        const NONE: u32 = u32::MAX;
        let n = self.len();
        let mut parent = vec![NONE; n];
        let mut groups = 0u32;
        // A node whose neighbours are all free of a group starts one with them.
        for i in 0..n {
            if parent[i] != NONE || self.row(i).any(|k| parent[self.cols[k] as usize] != NONE) {
                continue;
            }
            parent[i] = groups;
            for k in self.row(i) {
                parent[self.cols[k] as usize] = groups;
            }
            groups += 1;
        }
        // The rest join the neighbouring group they are most strongly bonded to.
        for i in 0..n {
            if parent[i] != NONE {
                continue;
            }
            let weight = |k: usize| {
                let m = self.offd[k].uu;
                m.x_axis.length_squared() + m.y_axis.length_squared() + m.z_axis.length_squared()
            };
            let best = self
                .row(i)
                .filter(|&k| parent[self.cols[k] as usize] != NONE)
                .max_by(|&k, &l| weight(k).total_cmp(&weight(l)));
            parent[i] = match best {
                Some(k) => parent[self.cols[k] as usize],
                None => {
                    groups += 1;
                    groups - 1
                }
            };
        }
        self.parent = parent;
        groups as usize
    }

    /// The next level: groups as rigid bodies, `Pᵀ·K·P`.
    fn coarsen(&mut self, groups: usize) -> Level {
        let mut pos = vec![DVec3::ZERO; groups];
        let mut count = vec![0usize; groups];
        for (i, &g) in self.parent.iter().enumerate() {
            pos[g as usize] += self.pos[i];
            count[g as usize] += 1;
        }
        for (p, &c) in pos.iter_mut().zip(&count) {
            *p /= c.max(1) as f64;
        }
        self.offset = (0..self.len())
            .map(|i| self.pos[i] - pos[self.parent[i] as usize])
            .collect();
        let rigid: Vec<Block6> = self.offset.iter().map(|&r| Block6::rigid(r)).collect();
        let mut diag = vec![Block6::ZERO; groups];
        let mut entries = Vec::new();
        for i in 0..self.len() {
            let gi = self.parent[i] as usize;
            let pt = rigid[i].transpose();
            diag[gi].add(&pt.mul(&self.diag[i]).mul(&rigid[i]));
            for k in self.row(i) {
                let j = self.cols[k] as usize;
                let gj = self.parent[j] as usize;
                let b = pt.mul(&self.offd[k]).mul(&rigid[j]);
                if gi == gj {
                    diag[gi].add(&b);
                } else {
                    entries.push((gi as u32, gj as u32, b));
                }
            }
        }
        Level::new(diag, entries, pos)
    }
}

/// The hierarchy of one anchored island.
#[derive(Debug, Clone)]
pub(super) struct Multigrid {
    /// The finest level's springs (local ends, anchored ends at `n`): its `K·x` goes
    /// through them, a third of the memory of its blocks.
    springs: LocalSprings,
    levels: Vec<Level>,
    /// The coarsest level's factor, when it is small enough.
    coarse: Option<Dense>,
}

/// The vectors of one level's cycle.
#[derive(Debug, Clone, Default)]
struct LevelWork {
    b: Vec<Dof>,
    x: Vec<Dof>,
    t: Vec<Dof>,
}

/// Reusable vectors for [`Multigrid::apply`] (any hierarchy: they grow as needed).
#[derive(Debug, Clone, Default)]
pub(super) struct Work {
    levels: Vec<LevelWork>,
}

impl Work {
    /// Room for `mg`'s levels.
    fn fit(&mut self, mg: &Multigrid) {
        if self.levels.len() < mg.levels.len() {
            self.levels.resize_with(mg.levels.len(), LevelWork::default);
        }
        for (w, level) in self.levels.iter_mut().zip(&mg.levels) {
            // The finest level has the anchored slot too.
            let n = level.len() + 1;
            for v in [&mut w.b, &mut w.x, &mut w.t] {
                if v.len() != n {
                    v.clear();
                    v.resize(n, ZERO);
                }
            }
        }
    }
}

impl Multigrid {
    /// The hierarchy of an island's springs (free nodes `0..n`, see
    /// [`LocalSprings`]) with the free nodes' positions `pos`.
    pub fn new(springs: &LocalSprings, pos: &[DVec3]) -> Multigrid {
        let n = springs.n;
        let mut diag = vec![Block6::ZERO; n];
        let mut entries = Vec::with_capacity(2 * springs.springs.len());
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
                entries.push((la as u32, lb as u32, kab));
                entries.push((lb as u32, la as u32, kab.transpose()));
            }
        }
        let fine = Level::new(diag, entries, pos.to_vec());
        let mut levels = vec![fine];
        loop {
            let last = levels.last_mut().expect("one level");
            if last.len() <= COARSEST {
                break;
            }
            let groups = last.aggregate();
            if groups as f64 > STALL * last.len() as f64 {
                last.parent.clear();
                break;
            }
            let next = last.coarsen(groups);
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
        Multigrid {
            springs: springs.clone(),
            levels,
            coarse,
        }
    }

    /// Free nodes of the finest level.
    pub fn len(&self) -> usize {
        self.levels[0].len()
    }

    /// Levels, the finest first.
    #[cfg(test)]
    pub fn depth(&self) -> usize {
        self.levels.len()
    }

    /// Nodes of level `l`.
    #[cfg(test)]
    pub fn level_len(&self, l: usize) -> usize {
        self.levels[l].len()
    }

    /// `K_l·x` (for tests; the finest level through its springs).
    #[cfg(test)]
    pub fn times(&self, l: usize, x: &[Dof]) -> Vec<Dof> {
        let level = &self.levels[l];
        if l == 0 {
            let mut xs = x.to_vec();
            xs.push(ZERO);
            let mut out = vec![ZERO; xs.len()];
            self.springs.times(&xs, &mut out);
            out.pop();
            return out;
        }
        (0..level.len())
            .map(|i| {
                let (ru, rt) = level.off_residual(i, x, ZERO);
                let (du, dt) = level.diag[i].apply(x[i].0, x[i].1);
                (du - ru, dt - rt)
            })
            .collect()
    }

    /// `P·X` from level `l + 1` to level `l` (for tests).
    #[cfg(test)]
    pub fn prolong(&self, l: usize, xc: &[Dof]) -> Vec<Dof> {
        let mut x = vec![ZERO; self.levels[l].len()];
        self.levels[l].prolong_add(xc, &mut x);
        x
    }

    /// `Pᵀ·f` from level `l` to level `l + 1` (for tests).
    #[cfg(test)]
    pub fn restrict(&self, l: usize, f: &[Dof]) -> Vec<Dof> {
        let level = &self.levels[l];
        let mut out = vec![ZERO; self.levels[l + 1].len()];
        for (i, &(fu, ft)) in f.iter().enumerate() {
            let g = &mut out[level.parent[i] as usize];
            g.0 += fu;
            g.1 += ft + level.offset[i].cross(fu);
        }
        out
    }

    /// `z ≈ K⁻¹·r` (one symmetric W-cycle), allocating its work (for tests).
    #[cfg(test)]
    pub fn apply_alloc(&self, r: &[Dof]) -> Vec<Dof> {
        let mut rs = r.to_vec();
        rs.push(ZERO);
        let mut z = vec![ZERO; rs.len()];
        self.apply(&rs, &mut z, &mut Work::default());
        z.pop();
        z
    }

    /// `z ≈ K⁻¹·r`: one symmetric W-cycle. `r` and `z` have the finest level's nodes and
    /// the anchored slot (`r`'s is ignored, `z`'s left zero).
    pub fn apply(&self, r: &[Dof], z: &mut [Dof], work: &mut Work) {
        work.fit(self);
        let (fine, coarse) = work.levels.split_at_mut(1);
        let w = &mut fine[0];
        let n = self.len();
        w.b[..n].copy_from_slice(&r[..n]);
        w.b[n] = ZERO;
        if self.levels.len() == 1 {
            self.bottom(&w.b[..n], &mut w.x[..n]);
        } else {
            self.fine_cycle(w, coarse);
        }
        z[..n].copy_from_slice(&w.x[..n]);
        z[n] = ZERO;
    }

    /// The finest level's cycle with damped block-Jacobi smoothing: `x = ω·D⁻¹·b`, the
    /// coarse correction of `b − K·x`, then `x += ω·D⁻¹·(b − K·x)`. Two passes over the
    /// springs where Gauss-Seidel makes six (each sweep and residual visits every
    /// spring from both ends), and symmetric, as conjugate gradients need.
    fn fine_cycle(&self, w: &mut LevelWork, coarse: &mut [LevelWork]) {
        let level = &self.levels[0];
        let n = level.len();
        for i in 0..n {
            let (u, t) = level.diag_inv[i].apply(w.b[i].0, w.b[i].1);
            w.x[i] = (u * OMEGA, t * OMEGA);
        }
        w.x[n] = ZERO;
        self.springs.times(&w.x, &mut w.t);
        let bc = &mut coarse[0].b;
        bc.fill(ZERO);
        for i in 0..n {
            let (fu, ft) = (w.b[i].0 - w.t[i].0, w.b[i].1 - w.t[i].1);
            let g = &mut bc[level.parent[i] as usize];
            g.0 += fu;
            g.1 += ft + level.offset[i].cross(fu);
        }
        self.cycle(1, coarse);
        level.prolong_add(&coarse[0].x, &mut w.x[..n]);
        self.springs.times(&w.x, &mut w.t);
        for i in 0..n {
            let (u, t) = level.diag_inv[i].apply(w.b[i].0 - w.t[i].0, w.b[i].1 - w.t[i].1);
            w.x[i].0 += u * OMEGA;
            w.x[i].1 += t * OMEGA;
        }
    }

    /// The coarsest level: `x = K⁻¹·b` densely, or two Gauss-Seidel sweeps.
    fn bottom(&self, b: &[Dof], x: &mut [Dof]) {
        let level = self.levels.last().expect("one level");
        match &self.coarse {
            Some(dense) => {
                x.copy_from_slice(b);
                dense.solve(x);
            }
            None => {
                x.fill(ZERO);
                level.sweep(x, b, true);
                level.sweep(x, b, false);
            }
        }
    }

    /// Level `l`'s cycle: `work[0].x ≈ K_l⁻¹·work[0].b`, deeper levels in `work[1..]`.
    fn cycle(&self, l: usize, work: &mut [LevelWork]) {
        let level = &self.levels[l];
        let n = level.len();
        let (here, deeper) = work.split_at_mut(1);
        let w = &mut here[0];
        if l + 1 == self.levels.len() {
            self.bottom(&w.b[..n], &mut w.x[..n]);
            return;
        }
        let x = &mut w.x[..n];
        let b = &w.b[..n];
        x.fill(ZERO);
        for _ in 0..SWEEPS {
            level.sweep(x, b, true);
        }
        for _ in 0..CYCLES {
            level.restrict_residual(x, b, &mut deeper[0].b[..self.levels[l + 1].len()]);
            self.cycle(l + 1, deeper);
            level.prolong_add(&deeper[0].x, x);
        }
        for _ in 0..SWEEPS {
            level.sweep(x, b, false);
        }
    }
}
