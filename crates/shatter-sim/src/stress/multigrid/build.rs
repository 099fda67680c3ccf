//! Building a hierarchy a slice at a time, in `f64`: the finest level's blocks from the
//! springs, then level by level the aggregation, the smoothed prolongation and the
//! Galerkin product, the coarsest level's dense factor, and the conversion to the
//! cycle's precision.
//!
//! Every stage goes row by row (or spring by spring, or column by column of the dense
//! factor), so a [`Build`] can stop after any row and go on at the next solve: a step
//! pays for a bounded slice of a hierarchy, never for a whole one. Its work is counted
//! in block operations, one for a 6×6 block times a vector (36 multiply-adds); a block
//! product counts six, and the other steps as much as they took on the 20,097-bond wall
//! (about 12 ns an operation on one core of the 2-core VM). [`Build::advance`] stops at the first row that reaches its budget,
//! so a slice does at most its budget plus one row ([`Build::largest_step`]).

use glam::{DMat3, DVec3};

use crate::stress::block::{Block6, Factoring};
use crate::stress::local::{Dof, LocalSpring, LocalSprings};
use crate::stress::multigrid::Multigrid;
use crate::stress::multigrid::cycle::{Cycle, Level as CycleLevel};
use crate::stress::multigrid::real::Real;
use crate::stress::multigrid::setup::{
    Accumulator, COARSEST, FINE_RINGS, FINE_STRENGTH, Level, POWER_STEPS, SMOOTHING, STALL,
    STRENGTH,
};
use crate::stress::spring::skew;

/// Block operations of a block product (six blocks times a vector).
const PRODUCT: usize = 6;
/// Block operations of a block's inverse.
const INVERSE: usize = 8;
/// Block operations of a spring's blocks added to the finest level's (three blocks of
/// a dozen 3×3 products, and the rows' growth).
const ASSEMBLE: usize = 40;
/// Block operations of moving a block into a level's compressed rows (sorting, merging,
/// copying 288 bytes).
const MOVE: usize = 10;
/// Block operations of converting a block to the cycle's precision.
const CONVERT: usize = 8;

/// What a build does next.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Stage {
    /// The finest level's blocks, spring by spring.
    Assemble,
    /// A level's rows into compressed form (sorted, merged), row by row.
    Rows,
    /// The inverse diagonal of the newest level.
    Inverse,
    /// Which couplings are strong.
    Strong,
    /// Greedy aggregation: the groups' seeds and their neighbours.
    Group,
    /// The nodes left join a neighbouring group.
    Join,
    /// The groups' points (summed, then divided).
    Points,
    /// Each node's offset from its group's point.
    Skews,
    /// The power iteration's start vector.
    PowerStart,
    /// The power iteration for the largest eigenvalue of `D⁻¹·K`.
    Power,
    /// `P`, row by row.
    Prolong,
    /// `K·P`, row by row.
    Product,
    /// `P`'s entries by column.
    Columns,
    /// `Pᵀ·(K·P)`, the upper triangle, by coarse row.
    Galerkin,
    /// Its lower triangle, as transposes of the upper.
    Mirror,
    /// The coarsest level's dense matrix.
    Dense,
    /// Its Cholesky factor, column by column.
    Factor,
    /// The levels in the cycle's precision, row by row.
    Convert,
    /// Finished.
    Done,
}

/// The state of one level's coarsening.
#[derive(Debug, Clone, Default)]
struct Coarsening {
    strong: Vec<bool>,
    /// Frobenius norms of the displacement parts of the diagonal blocks.
    dsize: Vec<f64>,
    parent: Vec<u32>,
    groups: u32,
    pos: Vec<DVec3>,
    count: Vec<usize>,
    skews: Vec<DMat3>,
    /// Power iteration: vectors, step, sums of the current step, estimate.
    x: Vec<Dof>,
    y: Vec<Dof>,
    step: usize,
    yy: f64,
    xx: f64,
    lambda: f64,
    omega: f64,
    kp: Vec<Vec<(u32, Block6)>>,
    by_col: Vec<Vec<u32>>,
    owner: Vec<u32>,
    diag: Vec<Block6>,
    rows: Vec<Vec<(u32, Block6)>>,
    lower: Vec<Vec<(u32, Block6)>>,
}

/// A multigrid hierarchy under construction (see the module's doc).
#[derive(Debug, Clone)]
pub(in crate::stress) struct Build<R: Real> {
    springs: Vec<LocalSpring>,
    n: usize,
    stage: Stage,
    /// The row (spring, column) the stage goes on at.
    next: usize,
    levels: Vec<Level>,
    /// The level being put into compressed form: its diagonal, rows, points.
    diag: Vec<Block6>,
    rows: Vec<Vec<(u32, Block6)>>,
    lower: Vec<Vec<(u32, Block6)>>,
    pos: Vec<DVec3>,
    forming: Level,
    co: Coarsening,
    acc: Accumulator,
    factor: Option<Factoring>,
    cycle: Vec<CycleLevel<R>>,
    /// Block operations done so far, and the most of one row.
    spent: usize,
    largest: usize,
}

impl<R: Real> Build<R> {
    /// A build of the hierarchy of `springs` (free nodes `0..n`, see [`LocalSprings`])
    /// with the free nodes' positions `pos`; nothing is computed yet.
    pub fn new(springs: &LocalSprings, pos: &[DVec3]) -> Build<R> {
        let n = springs.n;
        Build {
            springs: springs.springs.clone(),
            n,
            stage: Stage::Assemble,
            next: 0,
            levels: Vec::new(),
            diag: vec![Block6::ZERO; n],
            rows: vec![Vec::new(); n],
            lower: Vec::new(),
            pos: pos.to_vec(),
            forming: Level::default(),
            co: Coarsening::default(),
            acc: Accumulator::new(0),
            factor: None,
            cycle: Vec::new(),
            spent: 0,
            largest: 0,
        }
    }

    /// Whether the hierarchy is complete.
    pub fn done(&self) -> bool {
        self.stage == Stage::Done
    }

    /// Block operations done so far.
    #[cfg(test)]
    pub fn spent(&self) -> usize {
        self.spent
    }

    /// The most block operations one row (spring, column) took so far: a slice does at
    /// most its budget plus this.
    #[cfg(test)]
    pub fn largest_step(&self) -> usize {
        self.largest
    }

    /// Goes on with the build until it has done `budget` block operations (stopping at
    /// the end of the row that reaches it) or is complete; returns the operations done.
    pub fn advance(&mut self, budget: usize) -> usize {
        let mut done = 0;
        while done < budget && !self.done() {
            let cost = self.step();
            self.largest = self.largest.max(cost);
            done += cost;
        }
        self.spent += done;
        done
    }

    /// The finished hierarchy (after [`Build::done`]).
    pub fn finish(mut self) -> Multigrid<R> {
        debug_assert!(self.done());
        if !cfg!(test) && self.levels.len() > 1 {
            // Neither the cycle nor an update reads them (a single level's dense factor
            // is made again from them when springs break).
            let fine = &mut self.levels[0];
            fine.offd = Vec::new();
            fine.cols = Vec::new();
            fine.row_start = Vec::new();
        }
        Multigrid {
            cycle: Cycle {
                levels: self.cycle,
                coarse: self.factor.map(Factoring::finish),
            },
            setup: self.levels,
        }
    }

    /// One row of the current stage, and the moves to the next stages once it was the
    /// last; returns its block operations (at least one).
    fn step(&mut self) -> usize {
        self.skip_finished();
        if self.done() {
            return 1;
        }
        let i = self.next;
        self.next += 1;
        let cost = match self.stage {
            Stage::Assemble => self.assemble(i),
            Stage::Rows => self.compress(i),
            Stage::Inverse => {
                let last = self.levels.last_mut().expect("a level");
                last.diag_inv[i] = last.diag[i].inverse();
                INVERSE
            }
            Stage::Strong => self.strong(i),
            Stage::Group => self.group(i),
            Stage::Join => self.join(i),
            Stage::Points => self.points(i),
            Stage::Skews => {
                let last = self.levels.last().expect("a level");
                let g = self.co.parent[i] as usize;
                self.co.skews.push(skew(last.pos[i] - self.co.pos[g]));
                2
            }
            Stage::PowerStart => {
                let s = ((i * 7919) % 101) as f64 / 101.0 + 0.5;
                self.co
                    .x
                    .push((DVec3::new(s, 1.0 - s, 0.5), DVec3::new(0.5 - s, s, 1.0)));
                2
            }
            Stage::Power => self.power(i),
            Stage::Prolong => self.prolong(i),
            Stage::Product => self.product(i),
            Stage::Columns => {
                let last = self.levels.last().expect("a level");
                for k in last.p_row(i) {
                    self.co.by_col[last.p_cols[k] as usize].push(k as u32);
                    self.co.owner[k] = i as u32;
                }
                2 * (1 + last.p_row(i).len())
            }
            Stage::Galerkin => self.galerkin(i),
            Stage::Mirror => {
                let row = &self.co.rows[i];
                for (h, b) in row {
                    self.co.lower[*h as usize].push((i as u32, b.transpose()));
                }
                2 * (1 + row.len())
            }
            Stage::Dense => {
                let bottom = self.levels.last().expect("a level");
                let factor = Factoring::new(bottom.len(), |i, j| {
                    if i == j {
                        return Some(bottom.diag[i]);
                    }
                    bottom.find(i, j as u32).map(|k| bottom.offd[k])
                });
                let cost = factor.size() * factor.size() / 36 + 1;
                self.factor = Some(factor);
                cost
            }
            Stage::Factor => {
                let factor = self.factor.as_mut().expect("a factor under way");
                factor.column() / 36 + 1
            }
            Stage::Convert => self.convert(i),
            Stage::Done => 0,
        };
        self.skip_finished();
        cost.max(1)
    }

    /// Moves on to the next stage with rows left, if the current one has none.
    fn skip_finished(&mut self) {
        while !self.done() && self.next >= self.rows() {
            self.next_stage();
        }
    }

    /// Rows of the current stage.
    fn rows(&self) -> usize {
        let len = len_of(&self.levels);
        match self.stage {
            Stage::Assemble => self.springs.len(),
            Stage::Rows => self.rows.len(),
            Stage::Inverse
            | Stage::Strong
            | Stage::Group
            | Stage::Join
            | Stage::Skews
            | Stage::PowerStart
            | Stage::Power
            | Stage::Prolong
            | Stage::Product
            | Stage::Columns => len,
            Stage::Points => len,
            Stage::Galerkin | Stage::Mirror => self.co.groups as usize,
            Stage::Dense => 1,
            Stage::Factor => self.factor.as_ref().map_or(0, Factoring::size),
            Stage::Convert => self
                .levels
                .get(self.cycle.len().saturating_sub(1))
                .map_or(0, Level::len),
            Stage::Done => 0,
        }
    }

    /// Moves to the next stage (the current one has done its last row).
    fn next_stage(&mut self) {
        let len = len_of(&self.levels);
        self.next = 0;
        self.stage = match self.stage {
            Stage::Assemble => {
                self.springs = Vec::new();
                self.forming = Level {
                    row_start: vec![0],
                    ..Level::default()
                };
                Stage::Rows
            }
            Stage::Rows => {
                let mut level = std::mem::take(&mut self.forming);
                level.diag = std::mem::take(&mut self.diag);
                level.diag_inv = vec![Block6::ZERO; level.diag.len()];
                level.pos = std::mem::take(&mut self.pos);
                self.rows = Vec::new();
                self.lower = Vec::new();
                self.levels.push(level);
                if len_of(&self.levels) == 0 {
                    return self.end_levels();
                }
                Stage::Inverse
            }
            Stage::Inverse => {
                let last = self.levels.last().expect("a level");
                if last.len() <= COARSEST {
                    return self.end_levels();
                }
                let size = |m: &DMat3| {
                    (m.x_axis.length_squared()
                        + m.y_axis.length_squared()
                        + m.z_axis.length_squared())
                    .sqrt()
                };
                self.co = Coarsening {
                    dsize: last.diag.iter().map(|b| size(&b.uu)).collect(),
                    parent: vec![u32::MAX; last.len()],
                    ..Coarsening::default()
                };
                Stage::Strong
            }
            Stage::Strong => Stage::Group,
            Stage::Group => Stage::Join,
            Stage::Join => {
                let last = self.levels.last().expect("a level");
                let groups = self.co.groups as usize;
                if groups as f64 > STALL * last.len() as f64 || groups == 0 {
                    return self.end_levels();
                }
                self.co.pos = vec![DVec3::ZERO; groups];
                self.co.count = vec![0; groups];
                Stage::Points
            }
            Stage::Points => {
                for (p, &c) in self.co.pos.iter_mut().zip(&self.co.count) {
                    *p /= c.max(1) as f64;
                }
                self.co.skews = Vec::with_capacity(len);
                Stage::Skews
            }
            Stage::Skews => {
                self.co.x = Vec::with_capacity(len);
                Stage::PowerStart
            }
            Stage::PowerStart => {
                self.co.y = vec![(DVec3::ZERO, DVec3::ZERO); len];
                self.co.step = 0;
                (self.co.yy, self.co.xx, self.co.lambda) = (0.0, 0.0, 0.0);
                Stage::Power
            }
            Stage::Power => {
                let co = &mut self.co;
                let stop = !(co.xx > 0.0 && co.yy.is_finite());
                if !stop {
                    co.lambda = (co.yy / co.xx).sqrt();
                    std::mem::swap(&mut co.x, &mut co.y);
                }
                co.step += 1;
                (co.yy, co.xx) = (0.0, 0.0);
                if !stop && co.step < POWER_STEPS {
                    return;
                }
                co.omega = match co.lambda {
                    l if l > 0.0 && l.is_finite() => SMOOTHING / l,
                    _ => 0.0,
                };
                co.x = Vec::new();
                co.y = Vec::new();
                self.acc = Accumulator::new(co.groups as usize);
                let last = self.levels.last_mut().expect("a level");
                last.p_start = vec![0];
                last.p_cols = Vec::new();
                last.p_blocks = Vec::new();
                Stage::Prolong
            }
            Stage::Prolong => {
                self.co.kp = Vec::with_capacity(len);
                Stage::Product
            }
            Stage::Product => {
                let groups = self.co.groups as usize;
                let entries = self.levels.last().map_or(0, |l| l.p_cols.len());
                self.co.by_col = vec![Vec::new(); groups];
                self.co.owner = vec![0; entries];
                Stage::Columns
            }
            Stage::Columns => {
                let groups = self.co.groups as usize;
                self.co.diag = vec![Block6::ZERO; groups];
                self.co.rows = vec![Vec::new(); groups];
                Stage::Galerkin
            }
            Stage::Galerkin => {
                self.co.kp = Vec::new();
                self.co.lower = vec![Vec::new(); self.co.groups as usize];
                Stage::Mirror
            }
            Stage::Mirror => {
                // The next level's rows: the lower triangle, then the upper.
                let co = std::mem::take(&mut self.co);
                self.diag = co.diag;
                self.rows = co.rows;
                self.lower = co.lower;
                self.pos = co.pos;
                self.forming = Level {
                    row_start: vec![0],
                    ..Level::default()
                };
                Stage::Rows
            }
            Stage::Dense => Stage::Factor,
            Stage::Factor => self.begin_convert(),
            Stage::Convert => {
                if self.cycle.len() < self.levels.len() {
                    let l = self.cycle.len();
                    self.cycle.push(CycleLevel::start(l));
                    return;
                }
                Stage::Done
            }
            Stage::Done => Stage::Done,
        };
    }

    /// After the last level: its dense factor if it is small enough, then the cycle.
    fn end_levels(&mut self) {
        self.next = 0;
        let small = self.levels.last().is_some_and(|l| l.len() <= COARSEST);
        self.stage = if small && len_of(&self.levels) > 0 {
            Stage::Dense
        } else {
            self.begin_convert()
        };
    }

    fn begin_convert(&mut self) -> Stage {
        self.cycle = vec![CycleLevel::start(0)];
        if len_of(&self.levels) == 0 {
            // No free node: an empty level.
            return Stage::Done;
        }
        Stage::Convert
    }

    /// Spring `k`'s blocks added to the finest level's.
    fn assemble(&mut self, k: usize) -> usize {
        let n = self.n;
        let s = &self.springs[k];
        let (kaa, kab, kbb) = Block6::of_local(s);
        let (la, lb) = (s.a as usize, s.b as usize);
        if la < n {
            self.diag[la].add(&kaa);
        }
        if lb < n {
            self.diag[lb].add(&kbb);
        }
        if la < n && lb < n {
            self.rows[la].push((lb as u32, kab));
            self.rows[lb].push((la as u32, kab.transpose()));
        }
        ASSEMBLE
    }

    /// Row `i` of the level being formed: sorted, the blocks of the same column merged.
    fn compress(&mut self, i: usize) -> usize {
        let mut row = self
            .lower
            .get_mut(i)
            .map(std::mem::take)
            .unwrap_or_default();
        row.append(&mut self.rows[i]);
        row.sort_unstable_by_key(|(j, _)| *j);
        row.dedup_by(|next, kept| {
            if next.0 == kept.0 {
                kept.1.add(&next.1);
                true
            } else {
                false
            }
        });
        let cost = MOVE * (1 + row.len());
        let level = &mut self.forming;
        for (j, b) in row {
            level.cols.push(j);
            level.offd.push(b);
        }
        level.row_start.push(level.cols.len() as u32);
        cost
    }

    /// Row `i`'s strong couplings (see [`STRENGTH`]).
    fn strong(&mut self, i: usize) -> usize {
        let last = self.levels.last().expect("a level");
        let theta = if self.levels.len() == 1 {
            FINE_STRENGTH
        } else {
            STRENGTH
        };
        let co = &mut self.co;
        for k in last.row(i) {
            let m = &last.offd[k].uu;
            let size =
                (m.x_axis.length_squared() + m.y_axis.length_squared() + m.z_axis.length_squared())
                    .sqrt();
            co.strong
                .push(size >= theta * (co.dsize[i] * co.dsize[last.cols[k] as usize]).sqrt());
        }
        2 * (1 + last.row(i).len())
    }

    /// Greedy aggregation, node `i`: a node whose strong neighbours are all free of a
    /// group starts one with them (and, on the finest level, with their free strong
    /// neighbours whose own neighbours are free or in it).
    fn group(&mut self, i: usize) -> usize {
        const NONE: u32 = u32::MAX;
        let last = self.levels.last().expect("a level");
        let rings = if self.levels.len() == 1 {
            FINE_RINGS
        } else {
            1
        };
        let co = &mut self.co;
        let (strong, parent) = (&co.strong, &mut co.parent);
        let mut cost = 1 + last.row(i).len() / 4;
        if parent[i] != NONE
            || last
                .row(i)
                .any(|k| strong[k] && parent[last.cols[k] as usize] != NONE)
        {
            return cost;
        }
        let groups = co.groups;
        parent[i] = groups;
        for k in last.row(i) {
            if strong[k] {
                parent[last.cols[k] as usize] = groups;
            }
        }
        if rings == 2 {
            for k in last.row(i) {
                if !strong[k] {
                    continue;
                }
                for kk in last.row(last.cols[k] as usize) {
                    let m = last.cols[kk] as usize;
                    cost += 1 + last.row(m).len() / 4;
                    if strong[kk]
                        && parent[m] == NONE
                        && last.row(m).all(|q| {
                            let p = parent[last.cols[q] as usize];
                            p == NONE || p == groups
                        })
                    {
                        parent[m] = groups;
                    }
                }
            }
        }
        co.groups += 1;
        cost
    }

    /// Node `i`, if no group took it, joins the neighbouring group it is most strongly
    /// bonded to (or starts one alone).
    fn join(&mut self, i: usize) -> usize {
        let last = self.levels.last().expect("a level");
        let co = &mut self.co;
        if co.parent[i] != u32::MAX {
            return 1;
        }
        let size = |m: &DMat3| {
            (m.x_axis.length_squared() + m.y_axis.length_squared() + m.z_axis.length_squared())
                .sqrt()
        };
        let best = last
            .row(i)
            .filter(|&k| co.strong[k] && co.parent[last.cols[k] as usize] != u32::MAX)
            .max_by(|&k, &l| size(&last.offd[k].uu).total_cmp(&size(&last.offd[l].uu)));
        co.parent[i] = match best {
            Some(k) => co.parent[last.cols[k] as usize],
            None => {
                co.groups += 1;
                co.groups - 1
            }
        };
        1 + last.row(i).len()
    }

    /// Node `i`'s point added to its group's.
    fn points(&mut self, i: usize) -> usize {
        let last = self.levels.last().expect("a level");
        let g = self.co.parent[i] as usize;
        self.co.pos[g] += last.pos[i];
        self.co.count[g] += 1;
        2
    }

    /// Row `i` of one power step: `y_i = D_i⁻¹·(K·x)_i` and the step's sums.
    fn power(&mut self, i: usize) -> usize {
        let last = self.levels.last().expect("a level");
        let co = &mut self.co;
        let x = &co.x;
        let (mut u, mut t) = last.diag[i].apply(x[i].0, x[i].1);
        for k in last.row(i) {
            let xj = x[last.cols[k] as usize];
            let (fu, ft) = last.offd[k].apply(xj.0, xj.1);
            u += fu;
            t += ft;
        }
        let (u, t) = last.diag_inv[i].apply(u, t);
        co.y[i] = (u, t);
        co.yy += u.length_squared() + t.length_squared();
        co.xx += x[i].0.length_squared() + x[i].1.length_squared();
        2 + last.row(i).len()
    }

    /// Row `i` of the smoothed prolongation, `P_iG = [g(i) = G]·T_i − ω·D_i⁻¹·Σ_{j in G}
    /// K_ij·T_j`, with each weak coupling moved onto the row's own group (the rigid
    /// motion of `i`'s group seen at the weak neighbour): rigid motions stay exact and a
    /// row of `P` gains no group through a weak coupling, so the coarse matrices of
    /// blocky 3D objects stay sparse (on a 20 × 20 × 20 cube, level 2's 199 nodes had
    /// 119 neighbours each without it, 25 with it, for the same iterations).
    fn prolong(&mut self, i: usize) -> usize {
        let last = self.levels.last_mut().expect("a level");
        let co = &self.co;
        let acc = &mut self.acc;
        let parent = &co.parent;
        acc.add(parent[i], last.diag[i].times_rigid(&co.skews[i]));
        for k in last.row(i) {
            let j = last.cols[k] as usize;
            if co.strong[k] {
                acc.add(parent[j], last.offd[k].times_rigid(&co.skews[j]));
            } else {
                let r = last.pos[j] - co.pos[parent[i] as usize];
                acc.add(parent[i], last.offd[k].times_rigid(&skew(r)));
            }
        }
        let mut entries = 0;
        for (g, b) in acc.drain_sorted() {
            let mut block = last.diag_inv[i].mul(&b).scale(-co.omega);
            if g == parent[i] {
                block.add(&Block6::rigid_of_skew(&co.skews[i]));
            }
            last.p_cols.push(g);
            last.p_blocks.push(block);
            entries += 1;
        }
        last.p_start.push(last.p_cols.len() as u32);
        2 * (1 + last.row(i).len()) + PRODUCT * entries
    }

    /// Row `i` of `K·P`.
    fn product(&mut self, i: usize) -> usize {
        let last = self.levels.last().expect("a level");
        let acc = &mut self.acc;
        let mut products = 0;
        for k in last.p_row(i) {
            acc.add(last.p_cols[k], last.diag[i].mul(&last.p_blocks[k]));
            products += 1;
        }
        for kk in last.row(i) {
            let j = last.cols[kk] as usize;
            for k in last.p_row(j) {
                acc.add(last.p_cols[k], last.offd[kk].mul(&last.p_blocks[k]));
                products += 1;
            }
        }
        self.co.kp.push(acc.drain_sorted().collect());
        1 + PRODUCT * products
    }

    /// Coarse row `g` of `Pᵀ·(K·P)`, its diagonal and the entries above it.
    fn galerkin(&mut self, g: usize) -> usize {
        let last = self.levels.last().expect("a level");
        let co = &mut self.co;
        let acc = &mut self.acc;
        let mut products = 0;
        for &k in &co.by_col[g] {
            let pt = &last.p_blocks[k as usize];
            for (h, b) in &co.kp[co.owner[k as usize] as usize] {
                if *h as usize >= g {
                    acc.add(*h, pt.transpose_mul(b));
                    products += 1;
                }
            }
        }
        for (h, b) in acc.drain_sorted() {
            if h as usize == g {
                co.diag[g] = b;
            } else {
                co.rows[g].push((h, b));
            }
        }
        1 + PRODUCT * products
    }

    /// Row `i` of the newest level not yet in the cycle's precision.
    fn convert(&mut self, i: usize) -> usize {
        let l = self.cycle.len() - 1;
        CONVERT * self.cycle[l].push_row(&self.levels[l], i)
    }
}

/// Nodes of the last level (zero without levels).
fn len_of(levels: &[Level]) -> usize {
    levels.last().map_or(0, Level::len)
}
