//! The anchored islands the solver works on: their local numbering and springs, the two
//! load cases each solves (gravity, and the dynamic forces on top of it), and their
//! rebuild when bonds break.

use glam::{DMat3, DVec3};

use super::hierarchies::{Hierarchies, Hierarchy};
use super::{Preconditioner, StressSolver, merge_strongest};
use crate::stress::graph::BondGraph;
use crate::stress::limits::BondStress;
use crate::stress::local::{Dof, LocalSpring, LocalSprings, ZERO};
use crate::stress::multigrid::real::F32;
use crate::stress::multigrid::{Build, Multigrid};
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
    /// Its multigrid hierarchy (with [`Preconditioner::Multigrid`]), an index into the
    /// solver's hierarchies; after bonds broke, possibly the hierarchy of the island it
    /// split from (see [`Hierarchy`]).
    pub multigrid: Option<u32>,
    /// With a hierarchy built for more nodes: per local node, its row in the hierarchy
    /// (ascending).
    pub rows: Option<Vec<u32>>,
    /// Its own hierarchy, under construction (see [`SolverSettings::build_budget`](super::SolverSettings::build_budget)).
    pub build: Option<Box<Build<F32>>>,
    /// Springs broken since `build` began (its numbering), taken off when it is done.
    pub build_removed: Vec<LocalSpring>,
    /// With [`Preconditioner::BlockJacobi`], or while its first hierarchy is built: per
    /// local node, the inverses of its displacement and rotation blocks.
    pub jacobi: Vec<(DMat3, DMat3)>,
}

impl IslandState {
    /// Its conjugate gradients start again from their solutions (its preconditioner
    /// changed).
    pub fn restart(&mut self) {
        for part in [&mut self.gravity, &mut self.dynamic] {
            part.resume = None;
        }
    }

    /// Springs an iteration (or a start) costs about as much as: its bonds, and the coarse
    /// levels of a hierarchy built for more nodes (see [`Hierarchy::coarse_springs`]).
    pub fn cost(&self, hierarchies: &Hierarchies) -> usize {
        let coarse = match (self.multigrid, &self.rows) {
            (Some(k), Some(_)) => hierarchies.get(k).map_or(0, |h| h.coarse_springs),
            _ => 0,
        };
        self.bonds.len().max(1) + coarse
    }
}

/// Nodes a search for a detour around a broken bond visits before it gives up (and the
/// islands are rebuilt).
const DETOUR: usize = 256;

impl StressSolver {
    /// Brings the islands to the bond mask `broken`. When bonds only broke and each still
    /// has a detour between its ends, or cut off a small piece without an anchor, the
    /// islands stay: the broken springs (and the pieces') are zeroed and taken off their
    /// multigrid hierarchies (see `multigrid/update.rs`), the pieces' nodes dropped;
    /// otherwise they are rebuilt ([`StressSolver::rebuild`]).
    /// Returns how many hierarchies were built.
    pub(super) fn update_topology(
        &mut self,
        graph: &BondGraph,
        broken: &[bool],
        at_once: bool,
    ) -> usize {
        let newly = self.topology.as_deref().and_then(|old| {
            (old.len() == broken.len() && old.iter().zip(broken).all(|(o, n)| !o || *n)).then(
                || {
                    (0..broken.len() as u32)
                        .filter(|&b| broken[b as usize] && !old[b as usize])
                        .collect::<Vec<u32>>()
                },
            )
        });
        // A bond outside the anchored islands changes none of them; a bond with a detour
        // leaves its island whole; one whose side is a small piece without an anchor
        // drops that piece from its island (see `detach.rs`).
        if let Some(newly) = newly {
            let mut pieces = Vec::new();
            let in_place = newly.iter().all(|&b| {
                let bond = &graph.bonds()[b as usize];
                self.node_island[bond.a as usize] == u32::MAX
                    || self.detour(graph, broken, b)
                    || self.loose_piece(graph, broken, bond.a, &mut pieces)
                    || self.loose_piece(graph, broken, bond.b, &mut pieces)
            });
            if in_place {
                let mut bonds = newly;
                bonds.extend(self.piece_bonds(graph, broken, &pieces));
                self.remove_bonds(&bonds);
                self.drop_nodes(&pieces);
                self.topology = Some(broken.to_vec());
                return 0;
            }
        }
        self.rebuild(graph, broken, self.topology.clone().as_deref(), at_once)
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
    /// off the hierarchies (and queues them for a hierarchy under construction), and has
    /// their islands solved again.
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
        let mut changed = Vec::new();
        for group in by_island.chunk_by(|x, y| x.0 == y.0) {
            let island = &mut self.islands[group[0].0 as usize];
            let h = island.multigrid.and_then(|k| self.hierarchies.get(k));
            let mut removed = Vec::with_capacity(group.len());
            let mut local = Vec::with_capacity(group.len());
            for &(_, b) in group {
                self.stress[b as usize] = BondStress::default();
                let Ok(k) = island.bonds.binary_search(&b) else {
                    continue;
                };
                let spring = island.springs.springs[k];
                let s = &mut island.springs.springs[k];
                (s.ks, s.dn, s.kb, s.dt) = (0.0, 0.0, 0.0, 0.0);
                local.push(spring);
                removed.push(match (&island.rows, h) {
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
            if island.build.is_some() {
                island.build_removed.extend_from_slice(&local);
            }
            if let Some(k) = island.multigrid
                && let Some(h) = self.hierarchies.get_mut(k)
            {
                h.multigrid.remove_springs(&removed);
                changed.push(k);
            }
            if !island.jacobi.is_empty() {
                island.jacobi = jacobi_blocks(&island.springs);
            }
            for part in [&mut island.gravity, &mut island.dynamic] {
                part.converged = false;
                part.resume = None;
            }
            island.load_scale = None;
            island.settled = false;
            island.converged = false;
        }
        // Other islands that use a hierarchy changed here start their conjugate gradients
        // again with it.
        for island in &mut self.islands {
            if island.multigrid.is_some_and(|k| changed.contains(&k)) {
                island.restart();
            }
        }
    }

    /// Rebuilds the anchored islands and their preconditioner from the bond mask; the
    /// last solutions stay as the warm start. An island split from one with a hierarchy
    /// uses that hierarchy restricted to its nodes (see [`Hierarchy`]) and, if it has
    /// less than half of its nodes, gets its own: built here when `at_once` or without a
    /// [`SolverSettings::build_budget`](super::SolverSettings::build_budget), else a slice per solve (an island without a
    /// hierarchy to use meanwhile is preconditioned by block Jacobi). Returns how many
    /// hierarchies it built.
    fn rebuild(
        &mut self,
        graph: &BondGraph,
        broken: &[bool],
        old_mask: Option<&[bool]>,
        at_once: bool,
    ) -> usize {
        let mut built = 0;
        self.rebuilds += 1;
        let sliced = self.settings.build_budget.is_some() && !at_once;
        // Hierarchies that islands split from this mask may use: only bonds broke since
        // (no bond came back, no island grew).
        let only_broke = old_mask.is_some_and(|t| {
            t.len() == broken.len() && t.iter().zip(broken).all(|(o, n)| !o || *n)
        });
        // Per hierarchy, whether the springs broken since were taken off it.
        let mut updated = vec![false; self.hierarchies.len()];
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
            // (An island without free nodes has nothing to solve.)
            let multigrid =
                self.settings.preconditioner == Preconditioner::Multigrid && !free.is_empty();
            // The hierarchy of the island it split from, and its rows there.
            let parent = origin
                .filter(|&o| {
                    multigrid && only_broke && free.iter().all(|&v| old_island[v as usize] == o)
                })
                .and_then(|o| old[o as usize].as_ref().and_then(|i| i.multigrid))
                .filter(|&k| self.hierarchies.get(k).is_some());
            if let Some(k) = parent
                && !updated[k as usize]
            {
                updated[k as usize] = true;
                self.take_off_broken(k, broken, old_mask, &old_island);
            }
            let parent = parent.and_then(|k| {
                let h = self.hierarchies.get(k)?;
                let rows: Option<Vec<u32>> = free
                    .iter()
                    .map(|v| h.nodes.binary_search(v).ok().map(|r| r as u32))
                    .collect();
                Some((k, rows?, 2 * free.len() >= h.nodes.len()))
            });
            let pos =
                || -> Vec<DVec3> { free.iter().map(|&v| self.centroid[v as usize]).collect() };
            let (mut multigrid_k, mut rows, mut build) = (None, None, None);
            if multigrid {
                match parent {
                    Some((k, r, true)) => (multigrid_k, rows) = (Some(k), Some(r)),
                    Some((k, r, false)) if sliced => {
                        (multigrid_k, rows) = (Some(k), Some(r));
                        build = Some(Box::new(Build::new(&springs, &pos())));
                    }
                    None if sliced => build = Some(Box::new(Build::new(&springs, &pos()))),
                    _ => {
                        built += 1;
                        let h = Hierarchy::new(Multigrid::new(&springs, &pos()), free.clone());
                        multigrid_k = Some(self.hierarchies.insert(h));
                    }
                }
            }
            let jacobi = if !multigrid || multigrid_k.is_none() {
                jacobi_blocks(&springs)
            } else {
                Vec::new()
            };
            let gravity = free.iter().map(|&v| old_gravity[v as usize]).collect();
            let dynamic = free.iter().map(|&v| old_dynamic[v as usize]).collect();
            self.islands.push(IslandState {
                free,
                bonds: island.bonds,
                springs,
                gravity: Part::starting_at(gravity),
                dynamic: Part::starting_at(dynamic),
                multigrid: multigrid_k,
                rows,
                build,
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
        self.hierarchies
            .keep_only(self.islands.iter().filter_map(|i| i.multigrid));
        self.topology = Some(broken.to_vec());
        built
    }

    /// Takes the springs broken since `old_mask` with an end among hierarchy `k`'s nodes
    /// off it; not those of nodes that were in no anchored island (`old_island`), such as
    /// pieces dropped in place, whose springs were taken off then.
    fn take_off_broken(
        &mut self,
        k: u32,
        broken: &[bool],
        old_mask: Option<&[bool]>,
        old_island: &[u32],
    ) {
        let Some(h) = self.hierarchies.get(k) else {
            return;
        };
        let removed: Vec<LocalSpring> = old_mask
            .into_iter()
            .flat_map(|t| (0..broken.len()).filter(|&b| broken[b] && !t[b]))
            .map(|b| &self.springs[b])
            .filter(|s| old_island[s.a as usize] != u32::MAX)
            .filter(|s| h.nodes.binary_search(&s.a).is_ok() || h.nodes.binary_search(&s.b).is_ok())
            .map(|s| {
                LocalSpring::new(
                    s,
                    hierarchy_end(&h.nodes, s.a),
                    hierarchy_end(&h.nodes, s.b),
                )
            })
            .collect();
        if !removed.is_empty()
            && let Some(h) = self.hierarchies.get_mut(k)
        {
            h.multigrid.remove_springs(&removed);
        }
    }
}

/// The inverses of each free node's displacement and rotation blocks.
pub(super) fn jacobi_blocks(springs: &LocalSprings) -> Vec<(DMat3, DMat3)> {
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

/// A graph node's index in a hierarchy built on the free nodes `nodes` (ascending): its
/// position, or `nodes.len()` (the anchored slot) for a node not among them.
fn hierarchy_end(nodes: &[u32], v: u32) -> u32 {
    nodes.binary_search(&v).unwrap_or(nodes.len()) as u32
}
