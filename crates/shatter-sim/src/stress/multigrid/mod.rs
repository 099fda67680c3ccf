//! The stress solver's preconditioner: a smoothed-aggregation multigrid whose coarse
//! nodes are groups of blocks moving as rigid bodies.
//!
//! A wall, bridge or tower is a thin elastic body: its stiffness matrix has smooth,
//! bending-like modes that a per-node (block-Jacobi) preconditioner barely touches, so
//! conjugate gradients need thousands of iterations on a 20,000-bond graph. Here
//! neighbouring free nodes are grouped (greedy aggregation over the strong couplings,
//! about 7 per group on the finest level) and each group moves as one rigid body: a node
//! at `r` from its group's point moves by `(U + Θ × r, Θ)`. That tentative prolongation
//! `T` holds the rigid-body modes exactly; one damped Jacobi step smooths it,
//! `P = (I − ω·D⁻¹·K)·T`, so that the coarse functions bend instead of jumping at the
//! groups' borders (plain rigid groups took 88 iterations on the 20,097-bond wall, 47
//! even with the coarse level solved exactly). The coarse matrix `Pᵀ·K·P` is again a
//! block matrix on the groups, grouped again until a few dozen nodes are left, which are
//! solved densely (`setup.rs`, in `f64`).
//!
//! The preconditioner (`cycle.rs`) adds the finest level's block Jacobi and the coarse
//! correction, `z = ω·D⁻¹·r + P·V(Pᵀ·r)`, where `V` is one V-cycle on the coarse levels
//! (forward block Gauss-Seidel before the coarse correction, backward after): symmetric
//! and positive, as conjugate gradients need, and with no pass over the finest level's
//! springs, so one iteration costs the conjugate gradients' own `K·p`, the two products
//! with `P` and the coarse levels (a V-cycle with Jacobi smoothing before and after on the
//! finest level took 14 iterations instead of 25 on the 20,097-bond wall, each twice as
//! dear). It runs in `f32` ([`real`]): it only has to approximate `K⁻¹`; the conjugate
//! gradients themselves stay in `f64`.
//!
//! Anchored nodes are not unknowns: their blocks are dropped (their springs still add to
//! the free nodes' diagonals).

mod build;
mod cycle;
pub(super) mod real;
mod setup;
mod update;

use glam::DVec3;

use crate::stress::local::{Dof, LocalSprings};
pub(in crate::stress) use build::Build;
use cycle::Cycle;
pub(super) use cycle::Work;
use real::{F32, Real};

/// The hierarchy of one anchored island, applied in precision `R`.
#[derive(Debug, Clone)]
pub(super) struct Multigrid<R: Real = F32> {
    cycle: Cycle<R>,
    /// The levels in `f64`, as built and updated since (see `update.rs`); the finest
    /// level without its blocks off the diagonal, outside tests.
    setup: Vec<setup::Level>,
}

impl<R: Real> Multigrid<R> {
    /// The hierarchy of an island's springs (free nodes `0..n`, see [`LocalSprings`])
    /// with the free nodes' positions `pos`.
    pub fn new(springs: &LocalSprings, pos: &[DVec3]) -> Multigrid<R> {
        let mut build = Build::new(springs, pos);
        build.advance(usize::MAX);
        build.finish()
    }

    /// `z ≈ K⁻¹·r` (see the module's doc). `r` and `z` have the finest level's nodes and
    /// the anchored slot (`r`'s is ignored, `z`'s left zero). Returns `r·z`.
    pub fn apply(&self, r: &[Dof], z: &mut [Dof], work: &mut Work<R>) -> f64 {
        self.cycle.apply(r, z, work)
    }

    /// [`Multigrid::apply`] restricted to the finest rows `rows` (see
    /// [`Cycle::apply_rows`]): an island's preconditioner from a hierarchy built for more
    /// nodes than it has.
    pub fn apply_rows(&self, rows: &[u32], r: &[Dof], z: &mut [Dof], work: &mut Work<R>) -> f64 {
        self.cycle.apply_rows(rows, r, z, work)
    }

    /// Block operations of one application: on the coarse levels, and per finest row.
    pub fn cost(&self) -> (usize, f64) {
        self.cycle.cost()
    }
}

#[cfg(test)]
impl<R: Real> Multigrid<R> {
    /// Levels, the finest first.
    pub fn depth(&self) -> usize {
        self.cycle.levels.len()
    }

    /// Nodes of level `l`.
    pub fn level_len(&self, l: usize) -> usize {
        self.cycle.levels[l].len()
    }

    fn pairs(x: &[Dof]) -> Vec<cycle::Pair<R>> {
        x.iter().map(|v| (R::vector(v.0), R::vector(v.1))).collect()
    }

    fn dofs(x: &[cycle::Pair<R>]) -> Vec<Dof> {
        x.iter().map(|v| (R::to_f64(v.0), R::to_f64(v.1))).collect()
    }

    /// `K_l·x`, through level `l`'s blocks as built.
    pub fn times(&self, l: usize, x: &[Dof]) -> Vec<Dof> {
        let level = &self.setup[l];
        (0..level.len())
            .map(|i| {
                let (mut u, mut t) = level.diag[i].apply(x[i].0, x[i].1);
                for k in level.row(i) {
                    let xj = x[level.cols[k] as usize];
                    let (fu, ft) = level.offd[k].apply(xj.0, xj.1);
                    u += fu;
                    t += ft;
                }
                (u, t)
            })
            .collect()
    }

    /// `P·X` from level `l + 1` to level `l`.
    pub fn prolong(&self, l: usize, xc: &[Dof]) -> Vec<Dof> {
        let mut x = vec![(R::ZERO, R::ZERO); self.cycle.levels[l].len()];
        self.cycle.levels[l].prolong_add(&Self::pairs(xc), &mut x);
        Self::dofs(&x)
    }

    /// `Pᵀ·f` from level `l` to level `l + 1`.
    pub fn restrict(&self, l: usize, f: &[Dof]) -> Vec<Dof> {
        let mut out = vec![(R::ZERO, R::ZERO); self.cycle.levels[l + 1].len()];
        self.cycle.levels[l].restrict(&Self::pairs(f), &mut out);
        Self::dofs(&out)
    }

    /// [`Multigrid::apply`] on vectors without the anchored slot, allocating its work.
    pub fn apply_alloc(&self, r: &[Dof]) -> Vec<Dof> {
        let mut rs = r.to_vec();
        rs.push((DVec3::ZERO, DVec3::ZERO));
        let mut z = rs.clone();
        self.apply(&rs, &mut z, &mut Work::default());
        z.pop();
        z
    }
}
