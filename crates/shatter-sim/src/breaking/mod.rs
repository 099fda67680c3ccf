//! Engine-free break logic: the bond state of one breakable object, loading bonds from
//! contact impulses and explosions given as plain vectors, the break rule, and splitting a
//! body into the islands of its intact bonds. No physics-engine types appear here: a
//! caller (shatter-sim's own [`World`](crate::World) on Rapier, or `bevy_shatter` on
//! avian) reads its engine's contacts, feeds them in, and applies what comes out.
//!
//! ```
//! use shatter_sim::breaking::{BondState, Graph, Loads, components};
//! use shatter_sim::testing::box_grid_fracture;
//!
//! // Two cubes side by side, one bond between them, 1 kg each, break force 100 N.
//! let fracture = box_grid_fracture([2, 1, 1], [2.0, 1.0, 1.0].into());
//! let adjacency = Graph::adjacency_of(&fracture.bonds, 2);
//! let masses = [1.0, 1.0];
//! let graph = Graph { bonds: &fracture.bonds, adjacency: &adjacency, masses: &masses };
//! let mut state = BondState::new(graph.bonds.len(), 100.0, 0.0);
//!
//! // A 500 N hit on fragment 0 of a dynamic 2 kg body: half of it passes the bond.
//! let mut loads = Loads::default();
//! let share = shatter_sim::breaking::contact_share(1.0, Some(2.0));
//! loads.add_contact(&graph, &state, 0, 500.0 * share, [0.0, 0.0, -5.0].into(), 0.0);
//! let broken = state.apply(&graph, &loads);
//! assert_eq!(broken.len(), 1);
//!
//! // Both fragments were on body 7; now they are two islands.
//! let body_of = [Some(7u32), Some(7)];
//! assert_eq!(components(&graph, &state, &body_of, 7), vec![vec![0], vec![1]]);
//! ```

mod bonds;
mod events;
mod islands;

pub use bonds::{
    BondState, ENDURANCE, EVENT_THRESHOLD_FRACTION, Graph, LOAD_ATTENUATION, LOAD_DEPTH, Loads,
    contact_share, explosion_load, weight_relief,
};
pub use events::{BondBroken, BreakCause, BreakEvent, Split};
pub use islands::{components, inherited_velocity, launch_velocity, part_centre};
