//! The simulation world: controls, stepping, queries.

mod cut;
mod query;
mod run;
mod runtime_step;
mod settings;
mod speed_cap;
pub(crate) mod state;
mod step;
mod stress_step;
mod upkeep;

pub use query::ProjectileView;
pub use settings::{
    BreakCause, DEFAULT_MAX_DEBRIS, DEFAULT_MAX_LAUNCH_SPEED, DEFAULT_STRESS_BUDGET,
    DEFAULT_STRESS_BUILD_BUDGET, DEFAULT_STRESS_SPRING_BUDGET, DEFAULT_TINY_DEBRIS, ObjectId,
    RunState, SimEvent, Stats, WorldSettings,
};
pub use state::World;
