//! Typed commands the user interface sends to the simulation.
//!
//! The panels never touch the simulation: they validate their text fields into these
//! values (see [`crate::ui::forms`]) and the [`crate::sim_bridge`] applies them. This keeps
//! every decision about user input testable without a window. Objects and projectiles
//! are the simulator's own specifications ([`ObjectSpec`], [`ProjectileSpec`]): the
//! panels edit them, and there is no second copy of those words here.

use std::path::PathBuf;

use glam::Vec3;
pub use shatter_sim::{
    BondModel, FractureSource, MaterialPreset, MethodKind, ObjectId, ObjectSpec, Pattern,
    ProjectileShape, ProjectileSpec, Shape,
};

/// The explosion set off by a click when Add Force is on.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ForceSpec {
    /// "isOn": clicks explode instead of firing.
    pub enabled: bool,
    /// Radius in m (positive).
    pub radius: f64,
    /// Power: impulse in N·s at the centre (non-negative).
    pub power: f64,
}

impl Default for ForceSpec {
    fn default() -> Self {
        Self {
            enabled: false,
            // Breaks a few bricks of the default wall, not the whole scene.
            radius: 1.5,
            power: 150.0,
        }
    }
}

/// A command to the simulation.
#[derive(Debug, Clone, PartialEq)]
pub enum SimCommand {
    /// Start (or resume) the simulation.
    Start,
    /// Toggle pause.
    TogglePause,
    /// Stop and put every object back where it was.
    Reset,
    /// Remove every object.
    Clean,
    /// Add a breakable object (boxed: the command stays small).
    AddObject(Box<ObjectSpec>),
    /// Rebuild an object with new parameters.
    EditObject(ObjectId, Box<ObjectSpec>),
    /// Remove an object.
    DeleteObject(ObjectId),
    /// Fire a projectile (from its launch point to its aim point).
    Fire(ProjectileSpec),
    /// Set off an explosion.
    Explode {
        /// Centre.
        position: Vec3,
        /// Radius in m.
        radius: f64,
        /// Power.
        power: f64,
    },
    /// Switch the bond model (applies to objects built afterwards and on reset).
    SetBondModel(BondModel),
    /// Save the scene as TOML.
    SaveScene(PathBuf),
    /// Replace the scene with a TOML file.
    LoadScene(PathBuf),
    /// Replace the scene with one of the example scenes built into the app
    /// ([`crate::sim_bridge::EXAMPLE_SCENES`], by name).
    LoadExample(String),
}
