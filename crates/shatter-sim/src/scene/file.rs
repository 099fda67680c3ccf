//! The TOML schema of a scene file (see `docs/scene-format.md`). Unknown keys are errors;
//! vectors must have exactly three components and `f32` numbers must fit `f32` (the
//! readers in [`super::values`]).

use serde::{Deserialize, Serialize};
use toml::Spanned;

use super::values;

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
    #[serde(default, deserialize_with = "values::opt_vec3")]
    pub gravity: Option<[f32; 3]>,
    /// Fixed step in seconds (default 1/60).
    #[serde(default, deserialize_with = "values::opt_spanned_f32")]
    pub dt: Option<Spanned<f32>>,
    /// `joints` or `clusters` (default).
    pub bond_model: Option<Spanned<String>>,
    /// Static ground at y = 0 (default true).
    pub ground: Option<bool>,
    /// Box-shaped pieces collide as cuboids (default false).
    pub box_colliders: Option<bool>,
    /// Enclosed fragments of cluster objects have colliders from the start (default false).
    pub enclosed_colliders: Option<bool>,
    /// Joints-model fragments held within three bonds skip their contacts (default false).
    pub skip_held_contacts: Option<bool>,
    /// No body leaves a step much faster than what touched it moved (default true).
    pub contact_speed_cap: Option<bool>,
    /// Debris bodies kept: an integer ≥ 0, or `"none"` (no cap). Default
    /// [`crate::world::DEFAULT_MAX_DEBRIS`].
    pub max_debris: Option<Spanned<toml::Value>>,
    /// Fastest an explosion throws a body (m/s): a float > 0. Default
    /// [`crate::world::DEFAULT_MAX_LAUNCH_SPEED`].
    #[serde(default, deserialize_with = "values::opt_spanned_f32")]
    pub max_launch_speed: Option<Spanned<f32>>,
    /// Debris under this size (m) does not collide with such debris: a float ≥ 0.
    /// Default [`crate::world::DEFAULT_TINY_DEBRIS`].
    #[serde(default, deserialize_with = "values::opt_spanned_f32")]
    pub tiny_debris: Option<Spanned<f32>>,
    /// Stress-solver iterations per object per step: an integer ≥ 1, or `"none"` (solve
    /// to convergence every step). Default [`crate::world::DEFAULT_STRESS_BUDGET`].
    pub stress_budget: Option<Spanned<toml::Value>>,
    /// Springs the stress solver visits per object per step: an integer ≥ 1, or `"none"`.
    /// Default [`crate::world::DEFAULT_STRESS_SPRING_BUDGET`].
    pub stress_spring_budget: Option<Spanned<toml::Value>>,
    /// Block operations of multigrid hierarchy building per object per step: an integer
    /// ≥ 1, or `"none"` (build at once). Default
    /// [`crate::world::DEFAULT_STRESS_BUILD_BUDGET`].
    pub stress_build_budget: Option<Spanned<toml::Value>>,
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
    #[serde(default, deserialize_with = "values::opt_spanned_ivec3")]
    pub grid: Option<Spanned<[i64; 3]>>,
    /// Boxes of grid cells left out: `[[x0, y0, z0, x1, y1, z1], ...]`, cells `x0..x1` etc.
    pub grid_voids: Option<Spanned<Vec<[i64; 6]>>>,
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
    #[serde(default, deserialize_with = "values::opt_f32")]
    pub density: Option<f32>,
    /// Friction override.
    #[serde(default, deserialize_with = "values::opt_f32")]
    pub friction: Option<f32>,
    /// Restitution override.
    #[serde(default, deserialize_with = "values::opt_f32")]
    pub restitution: Option<f32>,
    /// The thesis's Breakforce (N); default: the material's strength.
    #[serde(default, deserialize_with = "values::opt_spanned_f32")]
    pub break_force: Option<Spanned<f32>>,
    /// The thesis's Last (s).
    #[serde(default, deserialize_with = "values::opt_spanned_f32")]
    pub last: Option<Spanned<f32>>,
    /// RGB in 0..=1.
    #[serde(default, deserialize_with = "values::opt_spanned_vec3")]
    pub color: Option<Spanned<[f32; 3]>>,
    /// Position (default `[0, 10, 0]`, the thesis's default).
    #[serde(default, deserialize_with = "values::opt_vec3")]
    pub position: Option<[f32; 3]>,
    /// Euler angles in degrees (XYZ).
    #[serde(default, deserialize_with = "values::opt_vec3")]
    pub rotation: Option<[f32; 3]>,
    /// Scale (default `[1, 1, 1]`).
    #[serde(default, deserialize_with = "values::opt_spanned_vec3")]
    pub scale: Option<Spanned<[f32; 3]>>,
    /// joints or clusters (default: the world's).
    pub bond_model: Option<Spanned<String>>,
    /// Bond the lowest fragments to the world.
    pub anchored: Option<bool>,
    /// When the object is cut: `precomputed` (default) or `on_impact`.
    pub fracture: Option<Spanned<String>>,
    /// Contact impulse (N·s) of a hit that cuts (default: break force × dt).
    #[serde(default, deserialize_with = "values::opt_spanned_f32")]
    pub fracture_impulse: Option<Spanned<f32>>,
    /// Fracture levels: fragments below it are cut again when hit (default 1).
    pub depth: Option<Spanned<i64>>,
    /// Fragments smaller than this (m, bounding-box diagonal) are not cut again.
    #[serde(default, deserialize_with = "values::opt_spanned_f32")]
    pub min_size: Option<Spanned<f32>>,
    /// Rough cut faces: the largest displacement (m); 0 makes them flat (default: the
    /// material's).
    #[serde(default, deserialize_with = "values::opt_spanned_f32")]
    pub roughness: Option<Spanned<f32>>,
    /// Cycles per metre of the roughness's first octave (default: the material's).
    #[serde(default, deserialize_with = "values::opt_spanned_f32")]
    pub roughness_frequency: Option<Spanned<f32>>,
    /// Octaves of the roughness's noise, 1 to 8 (default: the material's).
    pub roughness_octaves: Option<Spanned<i64>>,
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
    #[serde(default, deserialize_with = "values::opt_spanned_f32")]
    pub size: Option<Spanned<f32>>,
    /// Density in kg/m³.
    #[serde(default, deserialize_with = "values::opt_spanned_f32")]
    pub density: Option<Spanned<f32>>,
    /// Speed in m/s.
    #[serde(default, deserialize_with = "values::opt_spanned_f32")]
    pub speed: Option<Spanned<f32>>,
    /// RGB in 0..=1.
    #[serde(default, deserialize_with = "values::opt_spanned_vec3")]
    pub color: Option<Spanned<[f32; 3]>>,
    /// Lifetime in seconds.
    #[serde(default, deserialize_with = "values::opt_spanned_f32")]
    pub last: Option<Spanned<f32>>,
    /// Start point.
    #[serde(deserialize_with = "values::vec3")]
    pub from: [f32; 3],
    /// Aim point.
    #[serde(deserialize_with = "values::vec3")]
    pub to: [f32; 3],
}

/// `[[explosions]]`.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ExplosionEntry {
    /// Seconds after start (default 0).
    pub at: Option<Spanned<f64>>,
    /// Centre.
    #[serde(deserialize_with = "values::vec3")]
    pub position: [f32; 3],
    /// Radius in metres.
    #[serde(deserialize_with = "values::spanned_f32")]
    pub radius: Spanned<f32>,
    /// Impulse at the centre (N·s).
    #[serde(deserialize_with = "values::spanned_f32")]
    pub power: Spanned<f32>,
}
