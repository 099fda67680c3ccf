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
use crate::stress::spring::Spring;

/// Levels with at most this many nodes are solved densely.
const COARSEST: usize = 48;
/// Gauss-Seidel sweeps before and after the coarse correction.
const SWEEPS: usize = 1;
/// Coarse corrections per level: 1 is a V-cycle, 2 a W-cycle.
const CYCLES: usize = 2;
/// The finest level is smoothed by damped block Jacobi (two passes over the springs per
/// cycle) rather than Gauss-Seidel (six).
const JACOBI: bool = true;
/// The damping of that block Jacobi.
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
    /// The finest level's couplings as its springs: a third of the blocks' memory, so
    /// its sweeps (memory-bound) are faster than through the blocks.
    springs: Option<FineSprings>,
}

/// Per free node, the springs that couple it to other free nodes.
#[derive(Debug, Clone)]
struct FineSprings {
    start: Vec<u32>,
    /// (the spring, the other end's index, whether this node is the spring's `b`).
    ends: Vec<(Spring, u32, bool)>,
    /// Every spring with a free end, with its ends' indices (`u32::MAX`: anchored), for
    /// `K·x` one spring at a time.
    all: Vec<(Spring, u32, u32)>,
}

impl FineSprings {
    fn new(springs: &[&Spring], local: &[u32], n: usize) -> FineSprings {
        let mut lists: Vec<Vec<(Spring, u32, bool)>> = vec![Vec::new(); n];
        for &s in springs {
            let (la, lb) = (local[s.a as usize], local[s.b as usize]);
            if la != u32::MAX && lb != u32::MAX {
                lists[la as usize].push((*s, lb, false));
                lists[lb as usize].push((*s, la, true));
            }
        }
        let mut start = vec![0u32];
        let mut ends = Vec::new();
        for list in lists {
            ends.extend(list);
            start.push(ends.len() as u32);
        }
        let all = springs
            .iter()
            .map(|s| (**s, local[s.a as usize], local[s.b as usize]))
            .filter(|(_, la, lb)| *la != u32::MAX || *lb != u32::MAX)
            .collect();
        FineSprings { start, ends, all }
    }

    /// `out = K·x`, one pass over the springs (each once).
    fn times(&self, x: &[(DVec3, DVec3)], out: &mut [(DVec3, DVec3)]) {
        let zero = (DVec3::ZERO, DVec3::ZERO);
        out.iter_mut().for_each(|v| *v = zero);
        for (s, la, lb) in &self.all {
            let (ua, ta) = if *la != u32::MAX {
                x[*la as usize]
            } else {
                zero
            };
            let (ub, tb) = if *lb != u32::MAX {
                x[*lb as usize]
            } else {
                zero
            };
            let d = (ub + tb.cross(s.rb)) - (ua + ta.cross(s.ra));
            let f = s.ks * d + ((s.kn - s.ks) * s.n.dot(d)) * s.n;
            let dt = tb - ta;
            let m = s.kb * dt + ((s.kt - s.kb) * s.n.dot(dt)) * s.n;
            if *lb != u32::MAX {
                let o = &mut out[*lb as usize];
                o.0 += f;
                o.1 += s.rb.cross(f) + m;
            }
            if *la != u32::MAX {
                let o = &mut out[*la as usize];
                o.0 -= f;
                o.1 -= s.ra.cross(f) + m;
            }
        }
    }

    /// `b_i − Σ_{j≠i} K_ij·x_j` from the springs: the load each spring puts on node `i`
    /// when only its other end moves.
    #[inline]
    fn off_residual(&self, i: usize, x: &[(DVec3, DVec3)], b: (DVec3, DVec3)) -> (DVec3, DVec3) {
        let (mut ru, mut rt) = b;
        for (s, j, is_b) in &self.ends[self.start[i] as usize..self.start[i + 1] as usize] {
            let (u, t) = x[*j as usize];
            // Only the other end moves: δ and dθ are its motion at the face, signed.
            let (d, dt, r) = if *is_b {
                (-(u + t.cross(s.ra)), -t, s.rb)
            } else {
                (u + t.cross(s.rb), t, s.ra)
            };
            let f = s.ks * d + ((s.kn - s.ks) * s.n.dot(d)) * s.n;
            let m = s.kb * dt + ((s.kt - s.kb) * s.n.dot(dt)) * s.n;
            if *is_b {
                ru -= f;
                rt -= r.cross(f) + m;
            } else {
                ru += f;
                rt += r.cross(f) + m;
            }
        }
        (ru, rt)
    }
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
            springs: None,
        }
    }

    fn row(&self, i: usize) -> std::ops::Range<usize> {
        self.row_start[i] as usize..self.row_start[i + 1] as usize
    }

    /// `b_i − Σ_{j≠i} K_ij·x_j`.
    #[inline]
    fn off_residual(&self, i: usize, x: &[(DVec3, DVec3)], b: (DVec3, DVec3)) -> (DVec3, DVec3) {
        if let Some(springs) = &self.springs {
            return springs.off_residual(i, x, b);
        }
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
    fn sweep(&self, x: &mut [(DVec3, DVec3)], b: &[(DVec3, DVec3)], forward: bool) {
        let n = self.len();
        for step in 0..n {
            let i = if forward { step } else { n - 1 - step };
            let (ru, rt) = self.off_residual(i, x, b[i]);
            x[i] = self.diag_inv[i].apply(ru, rt);
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
    levels: Vec<Level>,
    /// The coarsest level's factor, when it is small enough.
    coarse: Option<Dense>,
}

impl Multigrid {
    /// The hierarchy of the free nodes `local` (`local[v]`: node `v`'s index among the
    /// island's free nodes, `u32::MAX` when anchored or elsewhere) over `springs`, with
    /// the nodes' positions `pos` (indexed by node).
    pub fn new(springs: &[&Spring], local: &[u32], free: &[u32], pos: &[DVec3]) -> Multigrid {
        let n = free.len();
        let mut diag = vec![Block6::ZERO; n];
        let mut entries = Vec::with_capacity(2 * springs.len());
        for s in springs {
            let (kaa, kab, kbb) = Block6::of_spring(s);
            let (la, lb) = (local[s.a as usize], local[s.b as usize]);
            if la != u32::MAX {
                diag[la as usize].add(&kaa);
            }
            if lb != u32::MAX {
                diag[lb as usize].add(&kbb);
            }
            if la != u32::MAX && lb != u32::MAX {
                entries.push((la, lb, kab));
                entries.push((lb, la, kab.transpose()));
            }
        }
        let points = free.iter().map(|&v| pos[v as usize]).collect();
        let mut fine = Level::new(diag, entries, points);
        fine.springs = Some(FineSprings::new(springs, local, n));
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
        Multigrid { levels, coarse }
    }

    /// Levels, the finest first.
    #[cfg(test)]
    pub fn depth(&self) -> usize {
        self.levels.len()
    }

    /// Nodes of level `l`.
    #[cfg(test)]
    pub fn len(&self, l: usize) -> usize {
        self.levels[l].len()
    }

    /// `K_l·x` (for tests).
    #[cfg(test)]
    pub fn times(&self, l: usize, x: &[(DVec3, DVec3)]) -> Vec<(DVec3, DVec3)> {
        let level = &self.levels[l];
        let zero = vec![(DVec3::ZERO, DVec3::ZERO); x.len()];
        (0..level.len())
            .map(|i| {
                let (ru, rt) = level.off_residual(i, x, zero[i]);
                let (du, dt) = level.diag[i].apply(x[i].0, x[i].1);
                (du - ru, dt - rt)
            })
            .collect()
    }

    /// `P·X` from level `l + 1` to level `l` (for tests).
    #[cfg(test)]
    pub fn prolong(&self, l: usize, xc: &[(DVec3, DVec3)]) -> Vec<(DVec3, DVec3)> {
        let level = &self.levels[l];
        (0..level.len())
            .map(|i| {
                let (u, t) = xc[level.parent[i] as usize];
                (u + t.cross(level.offset[i]), t)
            })
            .collect()
    }

    /// `Pᵀ·f` from level `l` to level `l + 1` (for tests).
    #[cfg(test)]
    pub fn restrict(&self, l: usize, f: &[(DVec3, DVec3)]) -> Vec<(DVec3, DVec3)> {
        let level = &self.levels[l];
        let mut out = vec![(DVec3::ZERO, DVec3::ZERO); self.levels[l + 1].len()];
        for (i, &(fu, ft)) in f.iter().enumerate() {
            let g = &mut out[level.parent[i] as usize];
            g.0 += fu;
            g.1 += ft + level.offset[i].cross(fu);
        }
        out
    }

    /// `z ≈ K⁻¹·r`: one symmetric W-cycle.
    pub fn apply(&self, r: &[(DVec3, DVec3)]) -> Vec<(DVec3, DVec3)> {
        self.cycle(0, r)
    }

    /// The finest level's cycle with damped block-Jacobi smoothing: `x = ω·D⁻¹·b`, the
    /// coarse correction of `b − K·x`, then `x += ω·D⁻¹·(b − K·x)`. Two passes over the
    /// springs where Gauss-Seidel makes six (each sweep and residual visits every
    /// spring from both ends), and symmetric, as conjugate gradients need.
    fn fine_cycle(
        &self,
        level: &Level,
        springs: &FineSprings,
        b: &[(DVec3, DVec3)],
    ) -> Vec<(DVec3, DVec3)> {
        let n = level.len();
        let zero = (DVec3::ZERO, DVec3::ZERO);
        let mut x: Vec<(DVec3, DVec3)> = (0..n)
            .map(|i| {
                let (u, t) = level.diag_inv[i].apply(b[i].0, b[i].1);
                (u * OMEGA, t * OMEGA)
            })
            .collect();
        let mut kx = vec![zero; n];
        springs.times(&x, &mut kx);
        let mut bc = vec![zero; self.levels[1].len()];
        for i in 0..n {
            let (fu, ft) = (b[i].0 - kx[i].0, b[i].1 - kx[i].1);
            let g = &mut bc[level.parent[i] as usize];
            g.0 += fu;
            g.1 += ft + level.offset[i].cross(fu);
        }
        let xc = self.cycle(1, &bc);
        for i in 0..n {
            let (u, t) = xc[level.parent[i] as usize];
            x[i].0 += u + t.cross(level.offset[i]);
            x[i].1 += t;
        }
        springs.times(&x, &mut kx);
        for i in 0..n {
            let (u, t) = level.diag_inv[i].apply(b[i].0 - kx[i].0, b[i].1 - kx[i].1);
            x[i].0 += u * OMEGA;
            x[i].1 += t * OMEGA;
        }
        x
    }

    fn cycle(&self, l: usize, b: &[(DVec3, DVec3)]) -> Vec<(DVec3, DVec3)> {
        let level = &self.levels[l];
        let zero = (DVec3::ZERO, DVec3::ZERO);
        if l + 1 == self.levels.len() {
            let mut x = b.to_vec();
            match &self.coarse {
                Some(dense) => dense.solve(&mut x),
                None => {
                    x.iter_mut().for_each(|v| *v = zero);
                    level.sweep(&mut x, b, true);
                    level.sweep(&mut x, b, false);
                }
            }
            return x;
        }
        if l == 0
            && JACOBI
            && let Some(springs) = &level.springs
        {
            return self.fine_cycle(level, springs, b);
        }
        let mut x = vec![zero; level.len()];
        for _ in 0..SWEEPS {
            level.sweep(&mut x, b, true);
        }
        let coarse_n = self.levels[l + 1].len();
        for _ in 0..CYCLES {
            let mut bc = vec![zero; coarse_n];
            for i in 0..level.len() {
                let (ru, rt) = level.off_residual(i, &x, b[i]);
                let (du, dt) = level.diag[i].apply(x[i].0, x[i].1);
                let (fu, ft) = (ru - du, rt - dt);
                let g = &mut bc[level.parent[i] as usize];
                g.0 += fu;
                g.1 += ft + level.offset[i].cross(fu);
            }
            let xc = self.cycle(l + 1, &bc);
            for i in 0..level.len() {
                let (u, t) = xc[level.parent[i] as usize];
                x[i].0 += u + t.cross(level.offset[i]);
                x[i].1 += t;
            }
        }
        for _ in 0..SWEEPS {
            level.sweep(&mut x, b, false);
        }
        x
    }
}
