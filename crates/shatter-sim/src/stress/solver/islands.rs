//! The anchored islands the solver works on: their local numbering and springs, the two
//! load cases each solves (gravity, and the dynamic forces on top of it), and their
//! rebuild when bonds break.

use std::sync::Arc;

use glam::{DMat3, DVec3};

use super::{Preconditioner, StressSolver};
use crate::stress::graph::BondGraph;
use crate::stress::limits::BondStress;
use crate::stress::local::{Dof, LocalSprings, ZERO};
use crate::stress::multigrid::Multigrid;
use crate::stress::spring::{invert, outer, skew};

/// One load case's solution on an island, and its conjugate gradients.
#[derive(Debug, Clone, Default)]
pub(super) struct Part {
    /// The solution: per free node (island-local), then the anchored slot (zero).
    pub x: Vec<Dof>,
    /// Residual and search direction of the conjugate gradients, kept to resume them.
    pub r: Vec<Dof>,
    pub p: Vec<Dof>,
    /// `r·z` of conjugate gradients stopped by a limit with the loads unchanged since:
    /// the next solve resumes them from `r` and `p`.
    pub resume: Option<f64>,
    /// Converged with the loads it has.
    pub converged: bool,
}

impl Part {
    /// A part of `n` free nodes starting from `x` (its anchored slot is added).
    pub fn starting_at(mut x: Vec<Dof>) -> Part {
        x.push(ZERO);
        Part {
            x,
            ..Part::default()
        }
    }
}

/// An anchored island being solved.
///
/// Its solution is the sum of two load cases, solved one after the other: gravity (which
/// changes only with the bonds or the gravity vector) and the dynamic forces of the
/// steps (a hit, a contact, an explosion). A hit's case is solved on top of the settled
/// gravity solution, and once the hit is gone the island is back at that solution with
/// nothing to solve.
#[derive(Debug, Clone, Default)]
pub(super) struct IslandState {
    /// Its free (not anchored) nodes, ascending: local node `i` is graph node `free[i]`.
    pub free: Vec<u32>,
    /// Its intact bonds, ascending.
    pub bonds: Vec<u32>,
    /// The springs of `bonds`, in the same order, with local ends.
    pub springs: LocalSprings,
    /// Gravity's case.
    pub gravity: Part,
    /// The dynamic forces' case (zero without them).
    pub dynamic: Part,
    /// Converged with no dynamic forces: nothing to do until something changes.
    pub settled: bool,
    /// Took dynamic forces at its last solve (so it must be solved again without them).
    pub had_forces: bool,
    /// Converged at its last solve.
    pub converged: bool,
    /// Dynamic forces (per node, sorted by node) of an unfinished solve, kept until it
    /// converges; a later step's force on a node replaces the carried one if stronger.
    pub carry: Vec<(u32, DVec3)>,
    /// Its multigrid preconditioner (with [`Preconditioner::Multigrid`]); after bonds
    /// broke, possibly the hierarchy of the island it split from (see [`Hierarchy`]).
    pub multigrid: Option<Arc<Hierarchy>>,
    /// With a kept hierarchy: per node of the hierarchy, its local index here
    /// (`u32::MAX`: not in this island).
    pub map: Option<Vec<u32>>,
    /// With [`Preconditioner::BlockJacobi`]: per local node, the inverses of its
    /// displacement and rotation blocks.
    pub jacobi: Vec<(DMat3, DMat3)>,
}

/// A multigrid hierarchy and the free nodes it was built on, in its order.
///
/// When bonds break, an island whose free nodes all come from one island, and are most
/// of it, keeps that island's hierarchy instead of building one: the residual is
/// restricted to its nodes (zero on the others) and the correction read back on them,
/// `M' = Sᵀ·M·S` for the selection `S`, which is still symmetric and positive definite,
/// so the conjugate gradients still converge to the solution of the island's own
/// springs, in a few more iterations. The hierarchy is built afresh once the island has
/// lost more than a twentieth of its nodes (the preconditioner's quality falls with each
/// node lost: on `collapse.toml`, keeping it down to three quarters took 2.5 times the
/// iterations, down to 95 % 1.25 times).
#[derive(Debug)]
pub(super) struct Hierarchy {
    pub multigrid: Multigrid,
    /// The free nodes of the island it was built for (indices into the graph).
    pub nodes: Vec<u32>,
}

impl StressSolver {
    /// Rebuilds the anchored islands and their preconditioner from the bond mask; the
    /// last solutions stay as the warm start. Returns how many hierarchies it built.
    pub(super) fn rebuild(&mut self, graph: &BondGraph, broken: &[bool]) -> usize {
        let mut built = 0;
        // Hierarchies that islands split from this mask may keep: only bonds broke since
        // (no bond came back, no island grew).
        let only_broke = self.topology.as_deref().is_some_and(|t| {
            t.len() == broken.len() && t.iter().zip(broken).all(|(o, n)| !o || *n)
        });
        let old_island = std::mem::take(&mut self.node_island);
        let nodes = self.mass.len();
        // The last solutions per graph node, for the warm start; forces of unfinished
        // solves stay on their nodes, in whichever island they are now.
        let mut old_gravity = vec![ZERO; nodes];
        let mut old_dynamic = vec![ZERO; nodes];
        let mut carried = Vec::new();
        let old: Vec<Option<Arc<Hierarchy>>> = self
            .islands
            .drain(..)
            .map(|i| {
                for (k, &v) in i.free.iter().enumerate() {
                    old_gravity[v as usize] = i.gravity.x.get(k).copied().unwrap_or(ZERO);
                    old_dynamic[v as usize] = i.dynamic.x.get(k).copied().unwrap_or(ZERO);
                }
                carried.extend(i.carry);
                i.multigrid.filter(|_| only_broke)
            })
            .collect();
        self.node_island = vec![u32::MAX; nodes];
        self.local.iter_mut().for_each(|i| *i = u32::MAX);
        self.stress
            .iter_mut()
            .for_each(|s| *s = BondStress::default());
        for island in graph.islands(broken) {
            if !island.anchored {
                continue;
            }
            let id = self.islands.len() as u32;
            let mut free = Vec::new();
            for &v in &island.nodes {
                self.node_island[v as usize] = id;
                if !self.anchored[v as usize] {
                    self.local[v as usize] = free.len() as u32;
                    free.push(v);
                }
            }
            let springs = LocalSprings::new(&self.springs, &island.bonds, &self.local, free.len());
            let jacobi = if self.settings.preconditioner == Preconditioner::BlockJacobi {
                self.jacobi_blocks(&springs)
            } else {
                Vec::new()
            };
            let kept = free
                .first()
                .and_then(|&v| old.get(old_island[v as usize] as usize))
                .and_then(Option::as_ref)
                .filter(|h| {
                    let o = old_island[free[0] as usize];
                    20 * free.len() >= 19 * h.nodes.len()
                        && free.iter().all(|&v| old_island[v as usize] == o)
                })
                .cloned();
            let (multigrid, map) = if self.settings.preconditioner == Preconditioner::Multigrid {
                match kept {
                    Some(h) => {
                        let map = h
                            .nodes
                            .iter()
                            .map(|&v| {
                                if self.node_island[v as usize] == id {
                                    self.local[v as usize]
                                } else {
                                    u32::MAX
                                }
                            })
                            .collect();
                        (Some(h), Some(map))
                    }
                    None => {
                        built += 1;
                        let pos: Vec<DVec3> =
                            free.iter().map(|&v| self.centroid[v as usize]).collect();
                        let h = Hierarchy {
                            multigrid: Multigrid::new(&springs, &pos),
                            nodes: free.clone(),
                        };
                        (Some(Arc::new(h)), None)
                    }
                }
            } else {
                (None, None)
            };
            let gravity = free.iter().map(|&v| old_gravity[v as usize]).collect();
            let dynamic = free.iter().map(|&v| old_dynamic[v as usize]).collect();
            self.islands.push(IslandState {
                free,
                bonds: island.bonds,
                springs,
                gravity: Part::starting_at(gravity),
                dynamic: Part::starting_at(dynamic),
                multigrid,
                map,
                jacobi,
                ..IslandState::default()
            });
        }
        carried.sort_unstable_by_key(|(node, _)| *node);
        for (node, f) in carried {
            let i = self.node_island[node as usize];
            if i != u32::MAX {
                self.islands[i as usize].carry.push((node, f));
            }
        }
        self.topology = Some(broken.to_vec());
        built
    }

    /// The inverses of each free node's displacement and rotation blocks.
    fn jacobi_blocks(&self, springs: &LocalSprings) -> Vec<(DMat3, DMat3)> {
        let mut blocks = vec![(DMat3::ZERO, DMat3::ZERO); springs.n + 1];
        for s in &springs.springs {
            let nn = outer(s.n, s.n);
            let k = DMat3::from_diagonal(DVec3::splat(s.ks)) + nn * s.dn;
            let kr = DMat3::from_diagonal(DVec3::splat(s.kb)) + nn * s.dt;
            for (v, r) in [(s.a, s.ra), (s.b, s.rb)] {
                let rx = skew(r);
                let block = &mut blocks[v as usize];
                block.0 += k;
                block.1 += rx.transpose() * k * rx + kr;
            }
        }
        blocks.truncate(springs.n);
        blocks
            .into_iter()
            .map(|(u, t)| (invert(u), invert(t)))
            .collect()
    }
}
