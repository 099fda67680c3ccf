//! Breakable objects, projectiles and explosions: their specs and their preparation.

pub mod prepare;
pub mod spec;

pub use prepare::Prepared;
pub use spec::{
    BondModel, ExplosionSpec, FractureParams, FractureSource, ObjectSpec, ProjectileShape,
    ProjectileSpec,
};
