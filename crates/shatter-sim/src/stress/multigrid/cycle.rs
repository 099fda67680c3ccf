//! The hierarchy as the preconditioner reads it, in its precision ([`Real`]), and its
//! application: block Jacobi on the finest level plus the coarse correction, added,
//! the coarse problem approximated by one V-cycle.

use crate::stress::block::{Block6, Dense};
use crate::stress::local::Dof;
use crate::stress::multigrid::real::Real;
use crate::stress::multigrid::setup;

/// A node's `(u, θ)` in the preconditioner's precision.
pub(super) type Pair<R> = (<R as Real>::V, <R as Real>::V);

/// A 6×6 block `[[uu, ut], [tu, tt]]` in the preconditioner's precision.
#[derive(Debug, Clone, Copy)]
pub(super) struct Block<R: Real> {
    uu: R::M,
    ut: R::M,
    tu: R::M,
    tt: R::M,
}

impl<R: Real> Block<R> {
    pub fn of(b: &Block6) -> Block<R> {
        Block {
            uu: R::matrix(b.uu),
            ut: R::matrix(b.ut),
            tu: R::matrix(b.tu),
            tt: R::matrix(b.tt),
        }
    }

    #[inline]
    fn apply(&self, (u, t): Pair<R>) -> Pair<R> {
        (
            R::mv(&self.uu, u) + R::mv(&self.ut, t),
            R::mv(&self.tu, u) + R::mv(&self.tt, t),
        )
    }

    /// The transpose applied: `[[uuᵀ, tuᵀ], [utᵀ, ttᵀ]]·(u, θ)`.
    #[inline]
    fn apply_transpose(&self, (u, t): Pair<R>) -> Pair<R> {
        (
            R::mtv(&self.uu, u) + R::mtv(&self.tu, t),
            R::mtv(&self.ut, u) + R::mtv(&self.tt, t),
        )
    }
}

/// One level as the preconditioner reads it.
#[derive(Debug, Clone)]
pub(super) struct Level<R: Real> {
    /// The inverse diagonal, and the rows without the diagonal (empty on the finest
    /// level, which is only smoothed by its inverse diagonal).
    diag_inv: Vec<Block<R>>,
    row_start: Vec<u32>,
    /// Per row, where its columns above the diagonal start.
    upper: Vec<u32>,
    cols: Vec<u32>,
    offd: Vec<Block<R>>,
    /// `P` by rows (empty on the last level); `Pᵀ` is applied through its blocks
    /// transposed on the fly (storing them too doubled what an application reads).
    p_start: Vec<u32>,
    p_cols: Vec<u32>,
    p: Vec<Block<R>>,
}

impl<R: Real> Level<R> {
    /// An empty level `l` (the finest for `l == 0`), to be filled row by row with
    /// [`Level::push_row`].
    pub fn start(l: usize) -> Level<R> {
        Level {
            diag_inv: Vec::new(),
            row_start: if l == 0 { Vec::new() } else { vec![0] },
            upper: Vec::new(),
            cols: Vec::new(),
            offd: Vec::new(),
            p_start: vec![0],
            p_cols: Vec::new(),
            p: Vec::new(),
        }
    }

    /// Appends row `i` of `setup` (the rows before it appended); returns the blocks
    /// converted.
    pub fn push_row(&mut self, setup: &setup::Level, i: usize) -> usize {
        self.diag_inv.push(Block::of(&setup.diag_inv[i]));
        let mut blocks = 1;
        if !self.row_start.is_empty() {
            let row = setup.row(i);
            let above = setup.cols[row.clone()].partition_point(|&j| (j as usize) < i);
            self.upper.push((row.start + above) as u32);
            self.cols.extend_from_slice(&setup.cols[row.clone()]);
            self.offd
                .extend(setup.offd[row.clone()].iter().map(Block::of));
            self.row_start.push(self.cols.len() as u32);
            blocks += row.len();
        }
        if !setup.p_start.is_empty() {
            let row = setup.p_row(i);
            self.p_cols.extend_from_slice(&setup.p_cols[row.clone()]);
            self.p
                .extend(setup.p_blocks[row.clone()].iter().map(Block::of));
            self.p_start.push(self.p_cols.len() as u32);
            blocks += row.len();
        }
        blocks
    }

    pub fn len(&self) -> usize {
        self.diag_inv.len()
    }

    pub fn set_diag_inv(&mut self, i: usize, b: Block<R>) {
        self.diag_inv[i] = b;
    }

    /// Sets the off-diagonal entry `k` (nothing on the finest level, which keeps none).
    pub fn set_offd(&mut self, k: usize, b: Block<R>) {
        if let Some(o) = self.offd.get_mut(k) {
            *o = b;
        }
    }

    fn row(&self, i: usize) -> std::ops::Range<usize> {
        self.row_start[i] as usize..self.row_start[i + 1] as usize
    }

    fn p_row(&self, i: usize) -> std::ops::Range<usize> {
        self.p_start[i] as usize..self.p_start[i + 1] as usize
    }

    /// `b_i − Σ_{j≠i} K_ij·x_j`.
    #[inline]
    fn off_residual(&self, i: usize, x: &[Pair<R>], b: Pair<R>) -> Pair<R> {
        let (mut ru, mut rt) = b;
        for k in self.row(i) {
            let (fu, ft) = self.offd[k].apply(x[self.cols[k] as usize]);
            ru -= fu;
            rt -= ft;
        }
        (ru, rt)
    }

    /// A forward Gauss-Seidel sweep from `x = 0`: row `i` meets only the `x_j`, `j < i`,
    /// already swept, so only the blocks below the diagonal are read.
    fn sweep_from_zero(&self, x: &mut [Pair<R>], b: &[Pair<R>]) {
        for i in 0..self.len() {
            let (mut ru, mut rt) = b[i];
            for k in self.row_start[i] as usize..self.upper[i] as usize {
                let (fu, ft) = self.offd[k].apply(x[self.cols[k] as usize]);
                ru -= fu;
                rt -= ft;
            }
            x[i] = self.diag_inv[i].apply((ru, rt));
        }
    }

    /// `(b − K·x)_i` right after [`Level::sweep_from_zero`]: row `i`'s diagonal and lower
    /// part cancel `b_i` by construction, which leaves `−Σ_{j>i} K_ij·x_j`.
    #[inline]
    fn residual_after_sweep(&self, i: usize, x: &[Pair<R>]) -> Pair<R> {
        let (mut ru, mut rt) = (R::ZERO, R::ZERO);
        for k in self.upper[i] as usize..self.row_start[i + 1] as usize {
            let (fu, ft) = self.offd[k].apply(x[self.cols[k] as usize]);
            ru -= fu;
            rt -= ft;
        }
        (ru, rt)
    }

    /// One block Gauss-Seidel sweep, forward or backward.
    fn sweep(&self, x: &mut [Pair<R>], b: &[Pair<R>], forward: bool) {
        let n = self.len();
        for step in 0..n {
            let i = if forward { step } else { n - 1 - step };
            x[i] = self.diag_inv[i].apply(self.off_residual(i, x, b[i]));
        }
    }

    /// `out += Pᵀ·e_i·f` for row `i`'s `f`.
    #[inline]
    fn restrict_row(&self, i: usize, f: Pair<R>, out: &mut [Pair<R>]) {
        for k in self.p_row(i) {
            let (u, t) = self.p[k].apply_transpose(f);
            let o = &mut out[self.p_cols[k] as usize];
            o.0 += u;
            o.1 += t;
        }
    }

    /// `x_i += (P·xc)_i`.
    #[inline]
    fn prolong_row(&self, i: usize, xc: &[Pair<R>], x: &mut [Pair<R>]) {
        let (mut u, mut t) = x[i];
        for k in self.p_row(i) {
            let (du, dt) = self.p[k].apply(xc[self.p_cols[k] as usize]);
            u += du;
            t += dt;
        }
        x[i] = (u, t);
    }

    /// `out = Pᵀ·f`.
    pub fn restrict(&self, f: &[Pair<R>], out: &mut [Pair<R>]) {
        out.fill((R::ZERO, R::ZERO));
        for (i, &fi) in f.iter().enumerate().take(self.len()) {
            for k in self.p_row(i) {
                let (u, t) = self.p[k].apply_transpose(fi);
                let o = &mut out[self.p_cols[k] as usize];
                o.0 += u;
                o.1 += t;
            }
        }
    }

    /// `x += P·xc`.
    pub fn prolong_add(&self, xc: &[Pair<R>], x: &mut [Pair<R>]) {
        for (i, xi) in x.iter_mut().enumerate().take(self.len()) {
            let (mut u, mut t) = *xi;
            for k in self.p_row(i) {
                let (du, dt) = self.p[k].apply(xc[self.p_cols[k] as usize]);
                u += du;
                t += dt;
            }
            *xi = (u, t);
        }
    }
}

/// The vectors of one level.
#[derive(Debug, Clone, Default)]
struct LevelWork<R: Real> {
    b: Vec<Pair<R>>,
    x: Vec<Pair<R>>,
    t: Vec<Pair<R>>,
}

/// Reusable vectors for the preconditioner (of any hierarchy: they are sized at each
/// use).
#[derive(Debug, Clone, Default)]
pub(in crate::stress) struct Work<R: Real> {
    levels: Vec<LevelWork<R>>,
    /// The coarsest level's vector in `f64`.
    dense: Vec<Dof>,
}

/// The weight of the finest level's block Jacobi.
const OMEGA: f64 = 0.7;

/// The hierarchy in the preconditioner's precision.
#[derive(Debug, Clone)]
pub(super) struct Cycle<R: Real> {
    pub levels: Vec<Level<R>>,
    pub coarse: Option<Dense>,
}

impl<R: Real> Cycle<R> {
    fn fit(&self, work: &mut Work<R>) {
        if work.levels.len() < self.levels.len() {
            work.levels
                .resize_with(self.levels.len(), LevelWork::default);
        }
        // Grown only: islands with hierarchies of other sizes share the vectors, and every
        // pass reads the first `len()` entries of its level's.
        for (w, level) in work.levels.iter_mut().zip(&self.levels) {
            let n = level.len();
            for v in [&mut w.b, &mut w.x, &mut w.t] {
                if v.len() < n {
                    v.resize(n, (R::ZERO, R::ZERO));
                }
            }
        }
    }

    /// `z = ω·D⁻¹·r + P·V(Pᵀ·r)`, `V` one V-cycle on the coarse levels; `r` and `z` in
    /// `f64` with the anchored slot (`r`'s is ignored, `z`'s left zero). Returns `r·z`.
    pub fn apply(&self, r: &[Dof], z: &mut [Dof], work: &mut Work<R>) -> f64 {
        self.fit(work);
        let level = &self.levels[0];
        let n = level.len();
        let (fine, coarse) = work.levels.split_at_mut(1);
        let w = &mut fine[0];
        for (b, r) in w.b.iter_mut().zip(&r[..n]) {
            *b = (R::vector(r.0), R::vector(r.1));
        }
        if self.levels.len() == 1 {
            self.bottom(&w.b, &mut w.x, &mut work.dense);
        } else {
            let omega = R::scalar(OMEGA);
            for i in 0..n {
                let (u, t) = level.diag_inv[i].apply(w.b[i]);
                w.x[i] = (omega * u, omega * t);
            }
            level.restrict(&w.b, &mut coarse[0].b);
            self.cycle(1, coarse, &mut work.dense);
            level.prolong_add(&coarse[0].x, &mut w.x);
        }
        let mut rz = 0.0;
        for ((z, x), r) in z[..n].iter_mut().zip(&w.x).zip(r) {
            *z = (R::to_f64(x.0), R::to_f64(x.1));
            rz += r.0.dot(z.0) + r.1.dot(z.1);
        }
        z[n] = (glam::DVec3::ZERO, glam::DVec3::ZERO);
        rz
    }

    /// [`Cycle::apply`] restricted to the finest rows `rows` (ascending): `r` and `z` are
    /// an island's vectors (its anchored slot last), `r[l]` the residual on row `rows[l]`
    /// and zero on the rows not listed, `z[l]` the correction read back on it. The same as
    /// `apply` on the vectors spread over every row, `Sᵀ·M·S` for the selection `S`, at
    /// the cost of the listed rows and the coarse levels. Returns `r·z`.
    pub fn apply_rows(&self, rows: &[u32], r: &[Dof], z: &mut [Dof], work: &mut Work<R>) -> f64 {
        self.fit(work);
        let level = &self.levels[0];
        let (fine, coarse) = work.levels.split_at_mut(1);
        let w = &mut fine[0];
        if self.levels.len() == 1 {
            w.b[..level.len()].fill((R::ZERO, R::ZERO));
            for (&i, r) in rows.iter().zip(r) {
                w.b[i as usize] = (R::vector(r.0), R::vector(r.1));
            }
            self.bottom(&w.b, &mut w.x, &mut work.dense);
        } else {
            let omega = R::scalar(OMEGA);
            let out = &mut coarse[0].b;
            out.fill((R::ZERO, R::ZERO));
            for (&i, r) in rows.iter().zip(r) {
                let i = i as usize;
                let b = (R::vector(r.0), R::vector(r.1));
                let (u, t) = level.diag_inv[i].apply(b);
                w.x[i] = (omega * u, omega * t);
                level.restrict_row(i, b, out);
            }
            self.cycle(1, coarse, &mut work.dense);
            for &i in rows {
                level.prolong_row(i as usize, &coarse[0].x, &mut w.x);
            }
        }
        let mut rz = 0.0;
        for ((z, &i), r) in z.iter_mut().zip(rows).zip(r) {
            let x = w.x[i as usize];
            *z = (R::to_f64(x.0), R::to_f64(x.1));
            rz += r.0.dot(z.0) + r.1.dot(z.1);
        }
        z[rows.len()] = (glam::DVec3::ZERO, glam::DVec3::ZERO);
        rz
    }

    /// Block operations of one [`Cycle::apply`] on the coarse levels (all but the
    /// finest), and of the finest level's part per row (its inverse diagonal, its rows of
    /// `P` and `Pᵀ`), the mean over its rows.
    pub fn cost(&self) -> (usize, f64) {
        let mut coarse = 0;
        for (l, level) in self.levels.iter().enumerate().skip(1) {
            let n = level.len();
            let last = l + 1 == self.levels.len();
            coarse += if last {
                match &self.coarse {
                    Some(_) => (6 * n) * (6 * n) / 18 + n,
                    None => 2 * (level.offd.len() + n),
                }
            } else {
                // Forward sweep and residual, backward sweep, Pᵀ and P.
                2 * (level.offd.len() + n) + 2 * level.p_cols.len()
            };
        }
        let fine = &self.levels[0];
        let per_row = 1.0 + 2.0 * fine.p_cols.len() as f64 / fine.len().max(1) as f64;
        (coarse, per_row)
    }

    /// The coarsest level: `x = K⁻¹·b` densely, or two Gauss-Seidel sweeps.
    fn bottom(&self, b: &[Pair<R>], x: &mut [Pair<R>], dense: &mut Vec<Dof>) {
        let level = self.levels.last().expect("one level");
        match &self.coarse {
            Some(factor) => {
                dense.clear();
                dense.extend(
                    b[..level.len()]
                        .iter()
                        .map(|v| (R::to_f64(v.0), R::to_f64(v.1))),
                );
                factor.solve(dense);
                for (x, d) in x.iter_mut().zip(dense.iter()) {
                    *x = (R::vector(d.0), R::vector(d.1));
                }
            }
            None => {
                x[..level.len()].fill((R::ZERO, R::ZERO));
                level.sweep(x, b, true);
                level.sweep(x, b, false);
            }
        }
    }

    /// Level `l`'s V-cycle (`l ≥ 1`): `work[0].x ≈ K_l⁻¹·work[0].b`, deeper levels in
    /// `work[1..]`; forward Gauss-Seidel before the coarse correction, backward after.
    /// The forward sweep and the residual after it read each block once between them.
    fn cycle(&self, l: usize, work: &mut [LevelWork<R>], dense: &mut Vec<Dof>) {
        let level = &self.levels[l];
        let (here, deeper) = work.split_at_mut(1);
        let w = &mut here[0];
        if l + 1 == self.levels.len() {
            self.bottom(&w.b, &mut w.x, dense);
            return;
        }
        level.sweep_from_zero(&mut w.x, &w.b);
        for i in 0..level.len() {
            w.t[i] = level.residual_after_sweep(i, &w.x);
        }
        level.restrict(&w.t, &mut deeper[0].b);
        self.cycle(l + 1, deeper, dense);
        level.prolong_add(&deeper[0].x, &mut w.x);
        level.sweep(&mut w.x, &w.b, false);
    }
}
