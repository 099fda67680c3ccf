//! The simulation world: controls, stepping, queries.

mod query;
mod run;
mod settings;
pub(crate) mod state;
mod step;

pub use query::ProjectileView;
pub use settings::{SimEvent, Stats, WorldSettings};
pub use state::{ObjectId, RunState, World};
