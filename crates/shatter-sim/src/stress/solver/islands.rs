//! The anchored islands the solver works on: their local numbering and springs, the two
//! load cases each solves (gravity, and the dynamic forces on top of it), and their
//! rebuild when bonds break.

use std::sync::Arc;

use glam::{DMat3, DVec3};

use super::{Preconditioner, StressSolver, merge_strongest};
use crate::stress::graph::BondGraph;
use crate::stress::limits::BondStress;
use crate::stress::local::{Dof, LocalSpring, LocalSprings, ZERO};
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
    /// The norm of the loads the residual is measured against, set at each start.
    pub scale: f64,
    /// The residual's norm when the last run stopped.
    pub residual: f64,
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
    /// The norm of all its loads, gravity's and the dynamic forces' (relieved), while it
    /// has dynamic forces; `None` when they changed since it was computed.
    pub load_scale: Option<f64>,
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
/// When bonds break, the hierarchy is kept the Galerkin hierarchy of the springs left:
/// their stiffness is taken off every level (see `multigrid/update.rs`), a few blocks
/// where building it afresh costs about a hundred milliseconds at 20,000 bonds. An island
/// whose free nodes all come from one island, and are at least half of it, keeps that
/// island's hierarchy: the residual is restricted to its nodes (zero on the others) and
/// the correction read back on them, `M' = Sᵀ·M·S` for the selection `S`, which is still
/// symmetric and positive definite, so the conjugate gradients still converge to the
/// solution of the island's own springs. Since no spring joins it to the nodes it lost,
/// `M` is close to a block diagonal of the two parts and `M'` close to the island's own
/// preconditioner. A smaller island gets a hierarchy of its own (cheaper per iteration
/// than the big one, and quick to build).
#[derive(Debug, Clone)]
pub(super) struct Hierarchy {
    pub multigrid: Multigrid,
    /// The free nodes of the island it was built for (indices into the graph).
    pub nodes: Vec<u32>,
}

/// Nodes a search for a detour around a broken bond visits before it gives up (and the
/// islands are rebuilt).
const DETOUR: usize = 256;

impl StressSolver {
    /// Brings the islands to the bond mask `broken`. When bonds only broke and each still
    /// has a detour between its ends (no island split), the islands stay: the broken
    /// springs are zeroed and taken off their multigrid hierarchies (see
    /// `multigrid/update.rs`); otherwise they are rebuilt ([`StressSolver::rebuild`]).
    /// Returns how many hierarchies were built.
    pub(super) fn update_topology(&mut self, graph: &BondGraph, broken: &[bool]) -> usize {
        let newly = self.topology.as_deref().and_then(|old| {
            (old.len() == broken.len() && old.iter().zip(broken).all(|(o, n)| !o || *n)).then(
                || {
                    (0..broken.len() as u32)
                        .filter(|&b| broken[b as usize] && !old[b as usize])
                        .collect::<Vec<u32>>()
                },
            )
        });
        // A bond outside the anchored islands changes none of them.
        if let Some(newly) = newly
            && newly.iter().all(|&b| {
                self.node_island[graph.bonds()[b as usize].a as usize] == u32::MAX
                    || self.detour(graph, broken, b)
            })
        {
            self.remove_bonds(&newly);
            self.topology = Some(broken.to_vec());
            return 0;
        }
        self.rebuild(graph, broken, self.topology.clone().as_deref())
    }

    /// Whether bond `b`'s ends are still joined by intact bonds (searching at most
    /// [`DETOUR`] nodes).
    fn detour(&mut self, graph: &BondGraph, broken: &[bool], b: u32) -> bool {
        let bond = &graph.bonds()[b as usize];
        let (from, to) = (bond.a, bond.b);
        self.stamp = self.stamp.wrapping_add(1);
        if self.stamp == 0 {
            self.seen.iter_mut().for_each(|s| *s = 0);
            self.stamp = 1;
        }
        let mut queue = std::collections::VecDeque::from([from]);
        self.seen[from as usize] = self.stamp;
        let mut visited = 0;
        while let Some(v) = queue.pop_front() {
            if v == to {
                return true;
            }
            visited += 1;
            if visited > DETOUR {
                return false;
            }
            for &e in &graph.adjacency()[v as usize] {
                if broken[e as usize] {
                    continue;
                }
                let next = &graph.bonds()[e as usize];
                let w = if next.a == v { next.b } else { next.a };
                if self.seen[w as usize] != self.stamp {
                    self.seen[w as usize] = self.stamp;
                    queue.push_back(w);
                }
            }
        }
        false
    }

    /// Zeroes the springs of the bonds `broken` (in place, islands unchanged), takes them
    /// off the hierarchies, and has their islands solved again.
    fn remove_bonds(&mut self, broken: &[u32]) {
        let mut by_island: Vec<(u32, u32)> = broken
            .iter()
            .filter_map(|&b| {
                let s = &self.springs[b as usize];
                let i = self.node_island[s.a as usize];
                (i != u32::MAX).then_some((i, b))
            })
            .collect();
        by_island.sort_unstable();
        for group in by_island.chunk_by(|x, y| x.0 == y.0) {
            let island = &mut self.islands[group[0].0 as usize];
            let mut removed = Vec::with_capacity(group.len());
            for &(_, b) in group {
                self.stress[b as usize] = BondStress::default();
                let Ok(k) = island.bonds.binary_search(&b) else {
                    continue;
                };
                let spring = island.springs.springs[k];
                let s = &mut island.springs.springs[k];
                (s.ks, s.dn, s.kb, s.dt) = (0.0, 0.0, 0.0, 0.0);
                removed.push(match (&island.map, &island.multigrid) {
                    (Some(_), Some(h)) => {
                        let graph_spring = &self.springs[b as usize];
                        LocalSpring::new(
                            graph_spring,
                            hierarchy_end(&h.nodes, graph_spring.a),
                            hierarchy_end(&h.nodes, graph_spring.b),
                        )
                    }
                    _ => spring,
                });
            }
            if let Some(h) = island.multigrid.as_mut() {
                Arc::make_mut(h).multigrid.remove_springs(&removed);
            }
            for part in [&mut island.gravity, &mut island.dynamic] {
                part.converged = false;
                part.resume = None;
            }
            island.load_scale = None;
            island.settled = false;
            island.converged = false;
        }
    }

    /// Rebuilds the anchored islands and their preconditioner from the bond mask; the
    /// last solutions stay as the warm start. Returns how many hierarchies it built.
    fn rebuild(&mut self, graph: &BondGraph, broken: &[bool], old_mask: Option<&[bool]>) -> usize {
        let mut built = 0;
        // Hierarchies that islands split from this mask may keep: only bonds broke since
        // (no bond came back, no island grew).
        let only_broke = old_mask.is_some_and(|t| {
            t.len() == broken.len() && t.iter().zip(broken).all(|(o, n)| !o || *n)
        });
        let old_island = std::mem::take(&mut self.node_island);
        let nodes = self.mass.len();
        // The last solutions per graph node, for the warm start.
        let mut old_gravity = vec![ZERO; nodes];
        let mut old_dynamic = vec![ZERO; nodes];
        let mut old: Vec<Option<IslandState>> = self
            .islands
            .drain(..)
            .map(|i| {
                for (k, &v) in i.free.iter().enumerate() {
                    old_gravity[v as usize] = i.gravity.x.get(k).copied().unwrap_or(ZERO);
                    old_dynamic[v as usize] = i.dynamic.x.get(k).copied().unwrap_or(ZERO);
                }
                Some(i)
            })
            .collect();
        let old_stress = std::mem::take(&mut self.stress);
        self.stress = vec![BondStress::default(); old_stress.len()];
        self.node_island = vec![u32::MAX; nodes];
        self.local.iter_mut().for_each(|i| *i = u32::MAX);
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
            // The island it was, if it is the same one (other islands changed): it goes
            // on where it was, its solves under way included.
            let origin = free
                .first()
                .or(island.nodes.first())
                .map(|&v| old_island[v as usize])
                .filter(|&o| o != u32::MAX);
            if let Some(o) = origin
                && old[o as usize]
                    .as_ref()
                    .is_some_and(|i| i.free == free && i.bonds == island.bonds)
                && let Some(state) = old[o as usize].take()
            {
                for &b in &state.bonds {
                    self.stress[b as usize] = old_stress[b as usize];
                }
                self.islands.push(state);
                continue;
            }
            let springs = LocalSprings::new(&self.springs, &island.bonds, &self.local, free.len());
            let jacobi = if self.settings.preconditioner == Preconditioner::BlockJacobi {
                self.jacobi_blocks(&springs)
            } else {
                Vec::new()
            };
            let kept = origin
                .filter(|&o| {
                    only_broke
                        && old[o as usize]
                            .as_ref()
                            .and_then(|i| i.multigrid.as_ref())
                            .is_some_and(|h| 2 * free.len() >= h.nodes.len())
                        && free.iter().all(|&v| old_island[v as usize] == o)
                })
                .and_then(|o| old[o as usize].as_mut().and_then(|i| i.multigrid.take()))
                .map(|mut h| {
                    // The springs broken since, taken off it.
                    let removed: Vec<LocalSpring> = old_mask
                        .into_iter()
                        .flat_map(|t| (0..broken.len()).filter(|&b| broken[b] && !t[b]))
                        .map(|b| &self.springs[b])
                        .filter(|s| {
                            h.nodes.binary_search(&s.a).is_ok()
                                || h.nodes.binary_search(&s.b).is_ok()
                        })
                        .map(|s| {
                            LocalSpring::new(
                                s,
                                hierarchy_end(&h.nodes, s.a),
                                hierarchy_end(&h.nodes, s.b),
                            )
                        })
                        .collect();
                    if !removed.is_empty() {
                        Arc::make_mut(&mut h).multigrid.remove_springs(&removed);
                    }
                    h
                });
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
        // Forces of unfinished solves stay on their nodes, in whichever island they are
        // now (an island that went on keeps its own); per node, the strongest.
        let mut carried: Vec<(u32, DVec3)> =
            old.into_iter().flatten().flat_map(|i| i.carry).collect();
        carried.sort_unstable_by(|a, b| {
            a.0.cmp(&b.0)
                .then(b.1.length_squared().total_cmp(&a.1.length_squared()))
        });
        carried.dedup_by_key(|(node, _)| *node);
        for (node, f) in carried {
            let i = self.node_island[node as usize];
            if i != u32::MAX {
                let island = &mut self.islands[i as usize];
                merge_strongest(&mut island.carry, vec![(node, f)]);
                island.load_scale = None;
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

/// A graph node's index in a hierarchy built on the free nodes `nodes` (ascending): its
/// position, or `nodes.len()` (the anchored slot) for a node not among them.
fn hierarchy_end(nodes: &[u32], v: u32) -> u32 {
    nodes.binary_search(&v).unwrap_or(nodes.len()) as u32
}
