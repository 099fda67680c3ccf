//! Typed commands the user interface sends to the simulation.
//!
//! The panels never touch the simulation: they validate their text fields into these
//! values (see [`crate::ui::forms`]) and the [`crate::sim_bridge`] applies them. This keeps
//! every decision about user input testable without a window.

use std::path::PathBuf;

use glam::{DVec3, Vec3};

/// Identifier of a breakable object in the simulation.
pub type ObjectId = u64;

/// The shape a breakable object or a projectile is made from.
#[derive(Debug, Clone, PartialEq)]
pub enum ShapeChoice {
    /// Unity's cube (24 vertices).
    Cube,
    /// Unity's capsule (550 vertices).
    Capsule,
    /// Unity's cylinder (88 vertices).
    Cylinder,
    /// A sphere (radius 0.5).
    Sphere,
    /// A torus (a shape with a hole).
    Torus,
    /// The thesis's concave test model (958 vertices, 1394 triangles).
    Bird,
    /// A user mesh read from a file (OBJ, STL, glTF/GLB).
    Custom(PathBuf),
}

impl ShapeChoice {
    /// Short lower-case name, as used in scene files.
    pub fn name(&self) -> &'static str {
        match self {
            ShapeChoice::Cube => "cube",
            ShapeChoice::Capsule => "capsule",
            ShapeChoice::Cylinder => "cylinder",
            ShapeChoice::Sphere => "sphere",
            ShapeChoice::Torus => "torus",
            ShapeChoice::Bird => "bird",
            ShapeChoice::Custom(_) => "custom",
        }
    }
}

/// How an object is cut into fragments.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MethodChoice {
    /// The thesis: Delaunay tetrahedra of surface + random points.
    Tetra,
    /// Voronoi cells clipped to the mesh.
    Voronoi,
    /// Random planes slicing the mesh.
    Slice,
    /// A regular grid of bricks (box-shaped objects only).
    Grid,
}

impl MethodChoice {
    /// Every method, in the order the UI lists them.
    pub const ALL: [MethodChoice; 4] = [Self::Tetra, Self::Voronoi, Self::Slice, Self::Grid];

    /// Lower-case name, as in scene files and the CLI.
    pub fn name(self) -> &'static str {
        match self {
            Self::Tetra => "tetra",
            Self::Voronoi => "voronoi",
            Self::Slice => "slice",
            Self::Grid => "grid",
        }
    }
}

/// Seed pattern of the Voronoi method.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PatternChoice {
    /// Seeds uniform in the mesh.
    Uniform,
    /// Seeds around a few centres.
    Clustered,
    /// Dense near an impact point, coarser outward (glass).
    Radial,
    /// Cells stretched along an axis (wood).
    Splinter,
}

impl PatternChoice {
    /// Every pattern, in the order the UI lists them.
    pub const ALL: [PatternChoice; 4] =
        [Self::Uniform, Self::Clustered, Self::Radial, Self::Splinter];

    /// Lower-case name, as in scene files and the CLI.
    pub fn name(self) -> &'static str {
        match self {
            Self::Uniform => "uniform",
            Self::Clustered => "clustered",
            Self::Radial => "radial",
            Self::Splinter => "splinter",
        }
    }
}

/// How fragments are held together.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BondModelChoice {
    /// The thesis: a rigid body per fragment and a breakable fixed joint per bond.
    Joints,
    /// Connected fragments form one rigid body; a bond graph breaks and splits it.
    Clusters,
}

impl BondModelChoice {
    /// Both models, in the order the UI lists them.
    pub const ALL: [BondModelChoice; 2] = [Self::Clusters, Self::Joints];

    /// Lower-case name, as in scene files and the CLI.
    pub fn name(self) -> &'static str {
        match self {
            Self::Joints => "joints",
            Self::Clusters => "clusters",
        }
    }
}

/// Material presets offered by the UI.
pub const MATERIAL_PRESETS: [&str; 6] = ["stone", "glass", "concrete", "wood", "ceramic", "ice"];

/// Everything needed to build (or rebuild) a breakable object: the thesis's Add Object
/// panel, its transform panel, and the fracture/material choices beyond the thesis.
#[derive(Debug, Clone, PartialEq)]
pub struct ObjectSpec {
    /// Source shape.
    pub shape: ShapeChoice,
    /// Fracture method.
    pub method: MethodChoice,
    /// Seed pattern (Voronoi).
    pub pattern: PatternChoice,
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
    /// Material preset name (one of [`MATERIAL_PRESETS`]).
    pub material: String,
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

impl Default for ProjectileSpec {
    fn default() -> Self {
        Self {
            shape: ShapeChoice::Sphere,
            lifetime: Some(10.0),
            color: [0.9, 0.2, 0.1],
            speed: 40.0,
            size: 0.5,
            density: 5000.0,
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
    SetBondModel(BondModelChoice),
    /// Save the scene as TOML.
    SaveScene(PathBuf),
    /// Replace the scene with a TOML file.
    LoadScene(PathBuf),
}
