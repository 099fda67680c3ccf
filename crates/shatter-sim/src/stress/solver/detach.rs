//! Pieces that break off an anchored island without an anchor of their own (a brick
//! knocked out of a wall, a chunk an explosion throws) are taken off the island in place:
//! their springs zeroed and taken off its hierarchy, their nodes dropped from its loads,
//! the island's numbering and hierarchy kept. Rebuilding the islands instead reads every
//! bond of the object (about 10 ms at 50,000 bonds).

use crate::stress::graph::BondGraph;
use crate::stress::local::ZERO;

use super::StressSolver;

/// Nodes a loose piece may have (a search that visits more gives up, and the islands are
/// rebuilt).
const PIECE: usize = 256;

impl StressSolver {
    /// Whether the intact bonds (`broken[b]`: bond `b` is gone) join `start`, a node of an
    /// anchored island, to at most [`PIECE`] nodes and no anchor: then those nodes are
    /// added to `pieces` (unless they are there already).
    pub(super) fn loose_piece(
        &mut self,
        graph: &BondGraph,
        broken: &[bool],
        start: u32,
        pieces: &mut Vec<u32>,
    ) -> bool {
        if pieces.contains(&start) {
            return true;
        }
        if self.anchored[start as usize] {
            return false;
        }
        self.stamp = self.stamp.wrapping_add(1);
        if self.stamp == 0 {
            self.seen.iter_mut().for_each(|s| *s = 0);
            self.stamp = 1;
        }
        let mut found = vec![start];
        self.seen[start as usize] = self.stamp;
        let mut next = 0;
        while let Some(&v) = found.get(next) {
            next += 1;
            for &e in &graph.adjacency()[v as usize] {
                if broken[e as usize] {
                    continue;
                }
                let bond = &graph.bonds()[e as usize];
                let w = if bond.a == v { bond.b } else { bond.a };
                if self.seen[w as usize] == self.stamp {
                    continue;
                }
                if self.anchored[w as usize] || found.len() >= PIECE {
                    return false;
                }
                self.seen[w as usize] = self.stamp;
                found.push(w);
            }
        }
        pieces.extend(found);
        true
    }

    /// The intact bonds (`broken[b]`: bond `b` is gone) between the nodes of `pieces`.
    pub(super) fn piece_bonds(
        &self,
        graph: &BondGraph,
        broken: &[bool],
        pieces: &[u32],
    ) -> Vec<u32> {
        let mut bonds = Vec::new();
        for &v in pieces {
            for &e in &graph.adjacency()[v as usize] {
                let bond = &graph.bonds()[e as usize];
                if !broken[e as usize] && bond.a == v {
                    bonds.push(e);
                }
            }
        }
        bonds
    }

    /// Drops the nodes `pieces` (their springs already taken off) from their islands: no
    /// island, no load, no displacement; forces carried on them are dropped.
    pub(super) fn drop_nodes(&mut self, pieces: &[u32]) {
        let mut touched = Vec::new();
        for &v in pieces {
            let i = self.node_island[v as usize];
            if i == u32::MAX {
                continue;
            }
            let l = self.local[v as usize];
            let island = &mut self.islands[i as usize];
            if l != u32::MAX {
                for part in [&mut island.gravity, &mut island.dynamic] {
                    if let Some(x) = part.x.get_mut(l as usize) {
                        *x = ZERO;
                    }
                }
            }
            self.node_island[v as usize] = u32::MAX;
            self.local[v as usize] = u32::MAX;
            touched.push(i);
        }
        touched.sort_unstable();
        touched.dedup();
        for i in touched {
            let node_island = &self.node_island;
            let island = &mut self.islands[i as usize];
            island
                .carry
                .retain(|(node, _)| node_island[*node as usize] == i);
            island.load_scale = None;
        }
    }
}
