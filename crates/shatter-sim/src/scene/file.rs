//! The TOML schema of a scene file (see `docs/scene-format.md`). Unknown keys are errors.

use serde::{Deserialize, Serialize};
use toml::Spanned;

/// A whole scene file.
#[derive(Debug, Clone, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SceneFile {
    /// World settings.
    #[serde(default)]
    pub world: WorldSection,
    /// Breakable objects.
    #[serde(default)]
    pub objects: Vec<ObjectEntry>,
    /// Timed projectiles.
    #[serde(default)]
    pub projectiles: Vec<ProjectileEntry>,
    /// Timed explosions.
    #[serde(default)]
    pub explosions: Vec<ExplosionEntry>,
}

/// `[world]`.
#[derive(Debug, Clone, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct WorldSection {
    /// Gravity vector, m/s² (default `[0, -9.81, 0]`).
    pub gravity: Option<[f32; 3]>,
    /// Fixed step in seconds (default 1/60).
    pub dt: Option<Spanned<f32>>,
    /// `joints` or `clusters` (default).
    pub bond_model: Option<Spanned<String>>,
    /// Static ground at y = 0 (default true).
    pub ground: Option<bool>,
    /// Cap on debris bodies.
    pub max_debris: Option<usize>,
    /// How long `shatter simulate` runs by default, in seconds (default 3).
    pub seconds: Option<Spanned<f64>>,
}

/// `[[objects]]`: a breakable object with every thesis parameter.
#[derive(Debug, Clone, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ObjectEntry {
    /// Label.
    pub name: Option<String>,
    /// Built-in shape: cube, capsule, cylinder, sphere, torus, bird.
    pub shape: Option<Spanned<String>>,
    /// A mesh file instead of a shape (relative to the scene file).
    pub mesh: Option<String>,
    /// tetra, voronoi, slice or grid (default: the material's).
    pub method: Option<Spanned<String>>,
    /// uniform, clustered, radial, splinter (default: the material's).
    pub pattern: Option<Spanned<String>>,
    /// Pieces for voronoi / slice.
    pub pieces: Option<Spanned<i64>>,
    /// Cells per axis for the grid method.
    pub grid: Option<Spanned<[i64; 3]>>,
    /// The thesis's Random Vertices.
    pub random_vertices: Option<Spanned<i64>>,
    /// The thesis's Skip.
    pub skip: Option<Spanned<i64>>,
    /// The thesis's Center.
    pub center: Option<bool>,
    /// Tetra random-point placement: `interior` (default) or `thesis`.
    pub placement: Option<Spanned<String>>,
    /// Random seed.
    pub seed: Option<u64>,
    /// Material preset (default stone).
    pub material: Option<Spanned<String>>,
    /// Density override (kg/m³).
    pub density: Option<f32>,
    /// Friction override.
    pub friction: Option<f32>,
    /// Restitution override.
    pub restitution: Option<f32>,
    /// The thesis's Breakforce (N); default: the material's strength.
    pub break_force: Option<Spanned<f32>>,
    /// The thesis's Last (s).
    pub last: Option<Spanned<f32>>,
    /// RGB in 0..=1.
    pub color: Option<Spanned<[f32; 3]>>,
    /// Position (default `[0, 10, 0]`, the thesis's default).
    pub position: Option<[f32; 3]>,
    /// Euler angles in degrees (XYZ).
    pub rotation: Option<[f32; 3]>,
    /// Scale (default `[1, 1, 1]`).
    pub scale: Option<Spanned<[f32; 3]>>,
    /// joints or clusters (default: the world's).
    pub bond_model: Option<Spanned<String>>,
    /// Bond the lowest fragments to the world.
    pub anchored: Option<bool>,
}

/// `[[projectiles]]`.
#[derive(Debug, Clone, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ProjectileEntry {
    /// Seconds after start (default 0).
    pub at: Option<Spanned<f64>>,
    /// cube, sphere, capsule, cylinder (default sphere).
    pub shape: Option<Spanned<String>>,
    /// A mesh file whose convex hull is the projectile.
    pub mesh: Option<String>,
    /// Size in metres.
    pub size: Option<Spanned<f32>>,
    /// Density in kg/m³.
    pub density: Option<Spanned<f32>>,
    /// Speed in m/s.
    pub speed: Option<Spanned<f32>>,
    /// RGB in 0..=1.
    pub color: Option<Spanned<[f32; 3]>>,
    /// Lifetime in seconds.
    pub last: Option<Spanned<f32>>,
    /// Start point.
    pub from: [f32; 3],
    /// Aim point.
    pub to: [f32; 3],
}

/// `[[explosions]]`.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ExplosionEntry {
    /// Seconds after start (default 0).
    pub at: Option<Spanned<f64>>,
    /// Centre.
    pub position: [f32; 3],
    /// Radius in metres.
    pub radius: Spanned<f32>,
    /// Impulse at the centre (N·s).
    pub power: Spanned<f32>,
}
