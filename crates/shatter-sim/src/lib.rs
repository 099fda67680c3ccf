//! Breakable objects simulated on Rapier.
//!
//! A [`World`] holds breakable objects (a fracture from `shatter_geom` + a [`Material`] +
//! a transform + the thesis's parameters, see [`ObjectSpec`]), projectiles and explosions.
//! Fragments hold together by one of two [`BondModel`]s: the thesis's breakable fixed
//! joints, or cluster bodies whose bond graph breaks under contact forces and explosions.
//! Scenes are TOML files ([`scene`]).
//!
//! ```
//! use shatter_sim::testing::box_grid_fracture;
//! use shatter_sim::{ObjectSpec, ProjectileSpec, World, WorldSettings};
//!
//! let mut world = World::new(WorldSettings::default());
//! let wall = box_grid_fracture([6, 3, 1], [3.0, 1.5, 0.3].into());
//! world.add_object(ObjectSpec::from_fracture(wall, [0.0, 0.75, 0.0].into()))?;
//! world.start();
//! world.fire(ProjectileSpec {
//!     from: [0.0, 0.8, 5.0].into(),
//!     to: [0.0, 0.8, 0.0].into(),
//!     ..ProjectileSpec::default()
//! });
//! for _ in 0..30 {
//!     world.step();
//! }
//! println!("{} bonds broken", world.stats().bonds_broken);
//! # Ok::<(), shatter_sim::SimError>(())
//! ```

#![cfg_attr(test, allow(clippy::unwrap_used))]

pub mod bonds;
pub mod breaking;
pub mod error;
pub mod material;
pub mod object;
pub mod runtime;
pub mod scene;
pub mod stress;
pub mod testing;
pub mod world;

pub use error::SimError;
pub use material::{Material, MaterialPreset, MethodKind, Pattern};
pub use object::{
    BondModel, ExplosionSpec, FractureParams, FractureSource, ObjectSpec, ProjectileShape,
    ProjectileSpec,
};
pub use rapier3d::math::Pose;
pub use shatter_geom::shapes::Shape;
pub use world::{
    BreakCause, DEFAULT_MAX_DEBRIS, DEFAULT_MAX_LAUNCH_SPEED, DEFAULT_STRESS_BUDGET,
    DEFAULT_STRESS_BUILD_BUDGET, DEFAULT_STRESS_SPRING_BUDGET, DEFAULT_TINY_DEBRIS, ObjectId,
    ProjectileView, RunState, SimEvent, Stats, World, WorldSettings,
};
