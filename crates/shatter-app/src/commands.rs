//! Typed commands the user interface sends to the simulation.
//!
//! The panels never touch the simulation: they validate their text fields into these
//! values (see [`crate::ui::forms`]) and the [`crate::sim_bridge`] applies them. This keeps
//! every decision about user input testable without a window.

use std::path::PathBuf;

use glam::{DVec3, Vec3};
pub use shatter_sim::{BondModel, MaterialPreset, MethodKind, Pattern, Shape};

/// Identifier of a breakable object in the simulation.
pub type ObjectId = u64;

/// The shape a breakable object or a projectile is made from: a built-in shape (the
/// words of [`Shape`]) or a user mesh file.
#[derive(Debug, Clone, PartialEq)]
pub enum ShapeChoice {
    /// A built-in shape.
    Builtin(Shape),
    /// A user mesh read from a file (OBJ, STL, glTF/GLB).
    Custom(PathBuf),
}

impl ShapeChoice {
    /// The built-in shape's word (as in scene files), or `custom`.
    pub fn name(&self) -> &'static str {
        match self {
            ShapeChoice::Builtin(s) => s.name(),
            ShapeChoice::Custom(_) => "custom",
        }
    }
}

/// Everything needed to build (or rebuild) a breakable object: the thesis's Add Object
/// panel, its transform panel, and the fracture/material choices beyond the thesis.
#[derive(Debug, Clone, PartialEq)]
pub struct ObjectSpec {
    /// Source shape.
    pub shape: ShapeChoice,
    /// Fracture method.
    pub method: MethodKind,
    /// Seed pattern (Voronoi).
    pub pattern: Pattern,
    /// "Random Vertices": random points added (tetra), number of pieces (voronoi, slice)
    /// or bricks along x (grid).
    pub random_vertices: u32,
    /// "Skip": take only every (skip+1)-th surface vertex.
    pub skip: u32,
    /// "Center": add the centre point.
    pub center: bool,
    /// "Breakforce": break threshold of each bond.
    pub break_force: f64,
    /// "Last": seconds the object lives after Start; `None` for ever.
    pub lifetime: Option<f64>,
    /// "Color": linear RGB components in `[0, 1]`.
    pub color: [f32; 3],
    /// Material preset.
    pub material: MaterialPreset,
    /// Position of the object's centre.
    pub position: DVec3,
    /// Scale along each axis (all positive).
    pub scale: DVec3,
}

/// The projectile fired by a click (the thesis's Fire panel).
#[derive(Debug, Clone, PartialEq)]
pub struct ProjectileSpec {
    /// Shape of the projectile.
    pub shape: ShapeChoice,
    /// "Last": seconds the projectile lives; `None` for ever.
    pub lifetime: Option<f64>,
    /// Colour, components in `[0, 1]`.
    pub color: [f32; 3],
    /// Launch speed in m/s.
    pub speed: f64,
    /// Size (edge or diameter) in m.
    pub size: f64,
    /// Density in kg/m³.
    pub density: f64,
}

/// The simulator's defaults ([`shatter_sim::ProjectileSpec::default`]): one definition
/// for the Fire panel, the scene files and the CLI.
impl Default for ProjectileSpec {
    fn default() -> Self {
        let d = shatter_sim::ProjectileSpec::default();
        Self {
            shape: ShapeChoice::Builtin(d.shape.shape().unwrap_or(Shape::Sphere)),
            lifetime: d.last.map(f64::from),
            color: d.color,
            speed: f64::from(d.speed),
            size: f64::from(d.size),
            density: f64::from(d.density),
        }
    }
}

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
    /// Add a breakable object.
    AddObject(ObjectSpec),
    /// Rebuild an object with new parameters.
    EditObject(ObjectId, ObjectSpec),
    /// Remove an object.
    DeleteObject(ObjectId),
    /// Fire a projectile between two points.
    Fire {
        /// The projectile.
        spec: ProjectileSpec,
        /// Launch point.
        from: Vec3,
        /// Aim point.
        to: Vec3,
    },
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
