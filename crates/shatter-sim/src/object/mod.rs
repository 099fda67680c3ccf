//! Breakable objects, projectiles and explosions: their specs and their preparation.

pub(crate) mod cuboid;
pub mod prepare;
pub mod projectile;
pub mod spec;

pub use prepare::{PieceShape, Prepared};
pub use projectile::{ProjectileShape, ProjectileSpec};
pub use spec::{BondModel, ExplosionSpec, FractureParams, FractureSource, ObjectSpec};
