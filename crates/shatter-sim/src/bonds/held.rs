//! Contacts the joints model skips: between fragments of one object still held within
//! [`HELD_HOPS`] intact bonds of each other.
//!
//! A joints-model object is one body per fragment, so neighbouring fragments that share
//! no bond (a brick wall's bricks meeting along an edge or at a corner) touch, and Rapier
//! computes their contacts every step although the joints keep them in place: at 2,000
//! bricks, most of the step. A cluster's fragments share a body and have none. This
//! skips them in the same spirit: the joints hold such pairs, and once the bonds between
//! two fragments break (no path of at most [`HELD_HOPS`] intact bonds is left) they
//! collide again.

use std::collections::BTreeMap;

use rapier3d::prelude::*;

use crate::bonds::tags::{Kind, untag};
use crate::breaking::BondState;
use crate::object::Prepared;

/// Bonds between two fragments (at most) that keep their contacts off: a brick's edge
/// neighbours are two bonds away, its corner neighbours three.
pub(crate) const HELD_HOPS: usize = 3;

/// Per fragment, the other fragments within [`HELD_HOPS`] intact bonds (ascending), at
/// a version of the bond states.
#[derive(Debug, Clone, Default)]
pub(crate) struct Held {
    /// [`BondState::version`](crate::breaking::BondState::version) they were found at
    /// (`u64::MAX`: never).
    pub version: u64,
    /// Per fragment, the fragments it holds.
    pub near: Vec<Vec<u32>>,
}

impl Held {
    /// Whether fragments `a` and `b` are held within [`HELD_HOPS`] intact bonds.
    pub fn holds(&self, a: u32, b: u32) -> bool {
        self.near
            .get(a as usize)
            .is_some_and(|near| near.binary_search(&b).is_ok())
    }

    /// Finds again, when a bond broke since (`state.version`), which fragments of the
    /// object `prepared` hold each other.
    pub fn update(&mut self, prepared: &Prepared, state: &BondState) {
        if self.version == state.version {
            return;
        }
        let bonds = &prepared.fracture.bonds;
        let n = prepared.fracture.fragments.len();
        let mut near = vec![Vec::new(); n];
        // Breadth-first from each fragment over intact bonds, `HELD_HOPS` deep; `seen[g]`
        // holds the last start that reached `g`.
        let mut seen = vec![u32::MAX; n];
        let mut frontier = Vec::new();
        let mut next = Vec::new();
        for (start, list) in near.iter_mut().enumerate() {
            seen[start] = start as u32;
            frontier.clear();
            frontier.push(start as u32);
            for _ in 0..HELD_HOPS {
                next.clear();
                for &f in &frontier {
                    for &b in &prepared.adjacency[f as usize] {
                        if state.broken[b as usize] {
                            continue;
                        }
                        let bond = &bonds[b as usize];
                        let g = if bond.a == f { bond.b } else { bond.a };
                        if seen[g as usize] != start as u32 {
                            seen[g as usize] = start as u32;
                            list.push(g);
                            next.push(g);
                        }
                    }
                }
                std::mem::swap(&mut frontier, &mut next);
            }
            list.sort_unstable();
        }
        *self = Held {
            version: state.version,
            near,
        };
    }
}

/// Rapier's contact filter over the world's live objects: no contacts between two
/// fragments of one joints-model object that it holds ([`Held::holds`]). Only colliders
/// with [`ActiveHooks::FILTER_CONTACT_PAIRS`] (the joints model's) are asked.
pub(crate) struct HeldContacts<'a> {
    /// The joints-model objects' held sets, by object id.
    pub objects: BTreeMap<u32, &'a Held>,
}

impl HeldContacts<'_> {
    /// Whether the two colliders' fragments are held by their object's joints.
    fn held(&self, colliders: &ColliderSet, c1: ColliderHandle, c2: ColliderHandle) -> bool {
        let tag = |c: ColliderHandle| colliders.get(c).and_then(|co| untag(co.user_data));
        let (Some((Kind::Fragment, o1, f1)), Some((Kind::Fragment, o2, f2))) = (tag(c1), tag(c2))
        else {
            return false;
        };
        o1 == o2 && self.objects.get(&o1).is_some_and(|held| held.holds(f1, f2))
    }
}

impl PhysicsHooks for HeldContacts<'_> {
    fn filter_contact_pair(&self, context: &PairFilterContext) -> Option<SolverFlags> {
        if self.held(context.colliders, context.collider1, context.collider2) {
            None
        } else {
            Some(SolverFlags::COMPUTE_RIGID_IMPULSES)
        }
    }

    fn filter_intersection_pair(&self, _context: &PairFilterContext) -> bool {
        true
    }

    fn modify_solver_contacts(&self, _context: &mut ContactModificationContext) {}
}
