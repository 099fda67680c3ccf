//! The solver's multigrid hierarchies: kept in one set, so the islands an island splits
//! into can share its hierarchy (each restricted to its own nodes) while their own are
//! built a slice at a time, and an update reaches every island that uses it.

use crate::stress::multigrid::{Build, Multigrid};

use super::StressSolver;

/// Springs visited by the conjugate gradients' `K·p` (in `f64`) that cost about as much as
/// one block operation of the preconditioner (in `f32`): a spring is about 150
/// instructions, a block times a vector about 40.
const BLOCK_OPS_PER_SPRING: usize = 4;

/// A multigrid hierarchy and the free nodes it was built on, in its order.
///
/// When bonds break, the hierarchy is kept the Galerkin hierarchy of the springs left:
/// their stiffness is taken off every level (see `multigrid/update.rs`), a few blocks
/// where building it afresh costs about a hundred milliseconds at 20,000 bonds. An island
/// whose free nodes all come from one island uses that island's hierarchy restricted to
/// them: the residual on its nodes (zero on the others) and the correction read back on
/// them, `M' = Sᵀ·M·S` for the selection `S`, which is still symmetric and positive
/// definite, so the conjugate gradients still converge to the solution of the island's
/// own springs. Since no spring joins it to the nodes it lost, `M` is close to a block
/// diagonal of the parts and `M'` close to the island's own preconditioner. An island with
/// at least half the hierarchy's nodes keeps it; a smaller one gets a hierarchy of its
/// own (cheaper per iteration than the big one), built a slice per solve under
/// [`SolverSettings::build_budget`](super::SolverSettings::build_budget) while it uses the
/// big one.
#[derive(Debug, Clone)]
pub(super) struct Hierarchy {
    pub multigrid: Multigrid,
    /// The free nodes of the island it was built for (indices into the graph).
    pub nodes: Vec<u32>,
    /// Springs an application of its coarse levels costs about as much as (see
    /// [`BLOCK_OPS_PER_SPRING`]): what an iteration of an island that uses it restricted
    /// costs on top of its own springs.
    pub coarse_springs: usize,
}

impl Hierarchy {
    pub fn new(multigrid: Multigrid, nodes: Vec<u32>) -> Hierarchy {
        let (coarse, _) = multigrid.cost();
        Hierarchy {
            multigrid,
            nodes,
            coarse_springs: coarse.div_ceil(BLOCK_OPS_PER_SPRING),
        }
    }
}

/// The hierarchies in use, by index.
#[derive(Debug, Clone, Default)]
pub(super) struct Hierarchies {
    slots: Vec<Option<Hierarchy>>,
}

impl Hierarchies {
    /// Stores `h` in a free slot; returns its index.
    pub fn insert(&mut self, h: Hierarchy) -> u32 {
        match self.slots.iter().position(Option::is_none) {
            Some(k) => {
                self.slots[k] = Some(h);
                k as u32
            }
            None => {
                self.slots.push(Some(h));
                (self.slots.len() - 1) as u32
            }
        }
    }

    pub fn get(&self, k: u32) -> Option<&Hierarchy> {
        self.slots.get(k as usize).and_then(Option::as_ref)
    }

    pub fn get_mut(&mut self, k: u32) -> Option<&mut Hierarchy> {
        self.slots.get_mut(k as usize).and_then(Option::as_mut)
    }

    /// Slots, used or not.
    pub fn len(&self) -> usize {
        self.slots.len()
    }

    /// Drops every hierarchy not in `used`.
    pub fn keep_only(&mut self, used: impl Iterator<Item = u32>) {
        let mut keep = vec![false; self.slots.len()];
        for k in used {
            if let Some(flag) = keep.get_mut(k as usize) {
                *flag = true;
            }
        }
        for (slot, keep) in self.slots.iter_mut().zip(keep) {
            if !keep {
                *slot = None;
            }
        }
        while self.slots.last().is_some_and(Option::is_none) {
            self.slots.pop();
        }
    }
}

impl StressSolver {
    /// Goes on with the islands' hierarchies under construction, in island order, for at
    /// most `budget` block operations in all (plus the rest of the row that reaches it:
    /// see [`Build::largest_step`]); an island whose hierarchy is complete uses it from
    /// its next iteration on (its conjugate gradients start again from where they are).
    /// Returns the block operations done and the hierarchies completed.
    pub(super) fn advance_builds(&mut self, budget: usize) -> (usize, usize) {
        let (mut spent, mut built) = (0usize, 0);
        for i in 0..self.islands.len() {
            if spent >= budget {
                break;
            }
            let island = &mut self.islands[i];
            let Some(build) = island.build.as_mut() else {
                continue;
            };
            spent = spent.saturating_add(build.advance(budget - spent));
            if !build.done() {
                continue;
            }
            let build: Box<Build<_>> = island.build.take().expect("a build");
            let mut multigrid = build.finish();
            let removed = std::mem::take(&mut island.build_removed);
            if !removed.is_empty() {
                multigrid.remove_springs(&removed);
            }
            let h = Hierarchy::new(multigrid, island.free.clone());
            let k = self.hierarchies.insert(h);
            let island = &mut self.islands[i];
            island.multigrid = Some(k);
            island.rows = None;
            island.jacobi = Vec::new();
            island.restart();
            built += 1;
            self.hierarchies
                .keep_only(self.islands.iter().filter_map(|i| i.multigrid));
        }
        (spent, built)
    }
}
