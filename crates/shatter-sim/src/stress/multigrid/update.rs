//! Keeping a hierarchy exact when springs break: the broken springs' stiffness taken off
//! every level, `K_l' = K_l − Pᵀ·ΔK·P` level by level with the same `P`, so the hierarchy
//! stays the Galerkin hierarchy of the springs that are left. A few blocks per level
//! change, where building the hierarchy afresh costs a hundred milliseconds at 20,000
//! bonds.

use std::collections::BTreeMap;

use crate::stress::block::{Block6, Dense};
use crate::stress::local::LocalSpring;
use crate::stress::multigrid::Multigrid;
use crate::stress::multigrid::cycle::Block;
use crate::stress::multigrid::real::Real;

impl<R: Real> Multigrid<R> {
    /// Takes `springs` (ends numbered as the hierarchy's finest level, an anchored end as
    /// its node count) off the hierarchy.
    pub fn remove_springs(&mut self, springs: &[LocalSpring]) {
        let n = self.setup[0].len();
        // The change of the finest level's matrix, as (row, column, block).
        let mut delta: BTreeMap<(u32, u32), Block6> = BTreeMap::new();
        let add = |delta: &mut BTreeMap<(u32, u32), Block6>, i: u32, j: u32, b: Block6| {
            delta.entry((i, j)).or_insert(Block6::ZERO).add(&b);
        };
        for s in springs {
            let (kaa, kab, kbb) = Block6::of_local(s);
            let (a, b) = (s.a as usize, s.b as usize);
            if a < n {
                add(&mut delta, s.a, s.a, kaa.neg());
            }
            if b < n {
                add(&mut delta, s.b, s.b, kbb.neg());
            }
            if a < n && b < n {
                add(&mut delta, s.a, s.b, kab.neg());
                add(&mut delta, s.b, s.a, kab.transpose().neg());
            }
        }
        let depth = self.setup.len();
        for l in 0..depth {
            if delta.is_empty() {
                return;
            }
            let level = &mut self.setup[l];
            let cycle = &mut self.cycle.levels[l];
            for (&(i, j), b) in &delta {
                if i == j {
                    level.diag[i as usize].add(b);
                    let inverse = level.diag[i as usize].inverse();
                    level.diag_inv[i as usize] = inverse;
                    cycle.set_diag_inv(i as usize, Block::of(&inverse));
                } else if let Some(k) = level.find(i as usize, j) {
                    level.offd[k].add(b);
                    cycle.set_offd(k, Block::of(&level.offd[k]));
                }
            }
            if l + 1 == depth {
                if let Some(dense) = &mut self.cycle.coarse {
                    *dense = Dense::factor(level.len(), |i, j| {
                        if i == j {
                            return Some(level.diag[i]);
                        }
                        level.find(i, j as u32).map(|k| level.offd[k])
                    });
                }
                return;
            }
            // The next level's change, Pᵀ·Δ·P.
            let mut next: BTreeMap<(u32, u32), Block6> = BTreeMap::new();
            for (&(i, j), b) in &delta {
                for ki in level.p_row(i as usize) {
                    let pt_b = level.p_blocks[ki].transpose_mul(b);
                    for kj in level.p_row(j as usize) {
                        add(
                            &mut next,
                            level.p_cols[ki],
                            level.p_cols[kj],
                            pt_b.mul(&level.p_blocks[kj]),
                        );
                    }
                }
            }
            delta = next;
        }
    }
}
