//! 6×6 blocks of the stiffness matrix: a node's displacement `u` and small rotation `θ`
//! as two 3-vectors, the block as four 3×3 matrices, and the dense Cholesky factor the
//! multigrid's coarsest level is solved with.

use glam::{DMat3, DVec3};

use crate::stress::local::LocalSpring;
#[cfg(test)]
use crate::stress::spring::Spring;
use crate::stress::spring::{invert, outer, skew};

/// A 6×6 block `[[uu, ut], [tu, tt]]` acting on `(u, θ)`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Block6 {
    pub uu: DMat3,
    pub ut: DMat3,
    pub tu: DMat3,
    pub tt: DMat3,
}

impl Block6 {
    pub const ZERO: Block6 = Block6 {
        uu: DMat3::ZERO,
        ut: DMat3::ZERO,
        tu: DMat3::ZERO,
        tt: DMat3::ZERO,
    };

    /// `(u, θ) ↦ (uu·u + ut·θ, tu·u + tt·θ)`.
    #[inline]
    pub fn apply(&self, u: DVec3, t: DVec3) -> (DVec3, DVec3) {
        (self.uu * u + self.ut * t, self.tu * u + self.tt * t)
    }

    pub fn mul(&self, o: &Block6) -> Block6 {
        Block6 {
            uu: self.uu * o.uu + self.ut * o.tu,
            ut: self.uu * o.ut + self.ut * o.tt,
            tu: self.tu * o.uu + self.tt * o.tu,
            tt: self.tu * o.ut + self.tt * o.tt,
        }
    }

    pub fn transpose(&self) -> Block6 {
        Block6 {
            uu: self.uu.transpose(),
            ut: self.tu.transpose(),
            tu: self.ut.transpose(),
            tt: self.tt.transpose(),
        }
    }

    /// `self · s`.
    pub fn scale(&self, s: f64) -> Block6 {
        Block6 {
            uu: self.uu * s,
            ut: self.ut * s,
            tu: self.tu * s,
            tt: self.tt * s,
        }
    }

    pub fn add(&mut self, o: &Block6) {
        self.uu += o.uu;
        self.ut += o.ut;
        self.tu += o.tu;
        self.tt += o.tt;
    }

    pub fn neg(&self) -> Block6 {
        Block6 {
            uu: -self.uu,
            ut: -self.ut,
            tu: -self.tu,
            tt: -self.tt,
        }
    }

    /// The inverse of a symmetric positive block (by its Schur complement; a singular
    /// part falls back to its diagonal, as [`invert`] does).
    pub fn inverse(&self) -> Block6 {
        let ai = invert(self.uu);
        let s = self.tt - self.tu * ai * self.ut;
        let si = invert(s);
        let aib = ai * self.ut;
        let cai = self.tu * ai;
        Block6 {
            uu: ai + aib * si * cai,
            ut: -(aib * si),
            tu: -(si * cai),
            tt: si,
        }
    }

    /// The rigid motion of a group seen at a node offset `r` from the group's point,
    /// `(U, Θ) ↦ (U + Θ × r, Θ)`, given `skew(r)`: `[[I, −skew(r)], [0, I]]`.
    pub fn rigid_of_skew(s: &DMat3) -> Block6 {
        Block6 {
            uu: DMat3::IDENTITY,
            ut: -*s,
            tu: DMat3::ZERO,
            tt: DMat3::IDENTITY,
        }
    }

    /// `self · rigid_of_skew(s)`, in two 3×3 products instead of eight.
    pub fn times_rigid(&self, s: &DMat3) -> Block6 {
        Block6 {
            uu: self.uu,
            ut: self.ut - self.uu * *s,
            tu: self.tu,
            tt: self.tt - self.tu * *s,
        }
    }

    /// `selfᵀ · o`.
    pub fn transpose_mul(&self, o: &Block6) -> Block6 {
        let (a, b, c, d) = (
            self.uu.transpose(),
            self.tu.transpose(),
            self.ut.transpose(),
            self.tt.transpose(),
        );
        Block6 {
            uu: a * o.uu + b * o.tu,
            ut: a * o.ut + b * o.tt,
            tu: c * o.uu + d * o.tu,
            tt: c * o.ut + d * o.tt,
        }
    }

    /// The stiffness blocks `(K_aa, K_ab, K_bb)` of one bond's springs (`K_ba = K_abᵀ`):
    /// the relative motion at the face is `δ = J_a·x_a + J_b·x_b` with
    /// `J = ±[I, −skew(r)]`, and the rotations' `θ_b − θ_a`.
    #[cfg(test)]
    pub fn of_spring(s: &Spring) -> (Block6, Block6, Block6) {
        Block6::of_local(&LocalSpring::new(s, 0, 1))
    }

    /// [`Block6::of_spring`] of a spring with local ends.
    pub fn of_local(s: &LocalSpring) -> (Block6, Block6, Block6) {
        let nn = outer(s.n, s.n);
        let k = DMat3::from_diagonal(DVec3::splat(s.ks)) + nn * s.dn;
        let kr = DMat3::from_diagonal(DVec3::splat(s.kb)) + nn * s.dt;
        let (sa, sb) = (skew(s.ra), skew(s.rb));
        let block = |si: DMat3, sj: DMat3| Block6 {
            uu: k,
            ut: -(k * sj),
            tu: -(si.transpose() * k),
            tt: si.transpose() * k * sj + kr,
        };
        (block(sa, sa), block(sa, sb).neg(), block(sb, sb))
    }
}

/// A dense Cholesky factor `L·Lᵀ` of a symmetric positive matrix of `6n` unknowns.
#[derive(Debug, Clone)]
pub(super) struct Dense {
    n: usize,
    l: Vec<f64>,
}

impl Dense {
    /// Factors the matrix whose `(i, j)` 6×6 block `block(i, j)` gives (lower half read).
    /// A pivot that is not positive (a part with no stiffness) is replaced by a tiny one.
    pub fn factor(nodes: usize, block: impl Fn(usize, usize) -> Option<Block6>) -> Dense {
        let mut factor = Factoring::new(nodes, block);
        while !factor.done() {
            factor.column();
        }
        factor.finish()
    }

    /// Solves in place; `x` holds `(u, θ)` per node.
    pub fn solve(&self, x: &mut [(DVec3, DVec3)]) {
        let n = self.n;
        let mut v = Vec::with_capacity(n);
        for (u, t) in x.iter() {
            v.extend_from_slice(&[u.x, u.y, u.z, t.x, t.y, t.z]);
        }
        for i in 0..n {
            let row = &self.l[i * n..i * n + i];
            let s = v[i] - row.iter().zip(&v[..i]).map(|(l, x)| l * x).sum::<f64>();
            v[i] = s / self.l[i * n + i];
        }
        for i in (0..n).rev() {
            let s = v[i]
                - (i + 1..n)
                    .zip(&v[i + 1..])
                    .map(|(k, x)| self.l[k * n + i] * x)
                    .sum::<f64>();
            v[i] = s / self.l[i * n + i];
        }
        for (i, (u, t)) in x.iter_mut().enumerate() {
            *u = DVec3::new(v[6 * i], v[6 * i + 1], v[6 * i + 2]);
            *t = DVec3::new(v[6 * i + 3], v[6 * i + 4], v[6 * i + 5]);
        }
    }
}

/// A dense Cholesky factorisation under way, a column at a time (see [`Dense::factor`]).
#[derive(Debug, Clone)]
pub(super) struct Factoring {
    n: usize,
    a: Vec<f64>,
    floor: f64,
    next: usize,
}

impl Factoring {
    /// The matrix whose `(i, j)` 6×6 block `block(i, j)` gives (lower half read), not
    /// factored yet.
    pub fn new(nodes: usize, block: impl Fn(usize, usize) -> Option<Block6>) -> Factoring {
        let n = 6 * nodes;
        let mut a = vec![0.0; n * n];
        for i in 0..nodes {
            for j in 0..=i {
                if let Some(b) = block(i, j) {
                    let parts = [(b.uu, 0, 0), (b.ut, 0, 3), (b.tu, 3, 0), (b.tt, 3, 3)];
                    for (m, r0, c0) in parts {
                        let cols = m.to_cols_array_2d();
                        for (c, col) in cols.iter().enumerate() {
                            for (r, &v) in col.iter().enumerate() {
                                let (row, column) = (6 * i + r0 + r, 6 * j + c0 + c);
                                if column <= row {
                                    a[row * n + column] = v;
                                }
                            }
                        }
                    }
                }
            }
        }
        let scale = (0..n).map(|i| a[i * n + i].abs()).fold(0.0, f64::max);
        let floor = (scale * 1e-14).max(f64::MIN_POSITIVE);
        Factoring {
            n,
            a,
            floor,
            next: 0,
        }
    }

    /// The unknowns (six per node).
    pub fn size(&self) -> usize {
        self.n
    }

    pub fn done(&self) -> bool {
        self.next >= self.n
    }

    /// Factors the next column; returns its multiply-adds.
    pub fn column(&mut self) -> usize {
        let (n, j, a) = (self.n, self.next, &mut self.a);
        if j >= n {
            return 0;
        }
        let mut d = a[j * n + j];
        for k in 0..j {
            d -= a[j * n + k] * a[j * n + k];
        }
        let d = if d > self.floor {
            d.sqrt()
        } else {
            self.floor.sqrt()
        };
        a[j * n + j] = d;
        for i in j + 1..n {
            let mut v = a[i * n + j];
            for k in 0..j {
                v -= a[i * n + k] * a[j * n + k];
            }
            a[i * n + j] = v / d;
        }
        self.next += 1;
        (n - j) * (j + 1)
    }

    /// The factor (all columns factored).
    pub fn finish(self) -> Dense {
        Dense {
            n: self.n,
            l: self.a,
        }
    }
}
