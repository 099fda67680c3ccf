//! The panels' text fields and their validation into typed commands.
//!
//! Each form is a plain struct of strings (what the user typed). `validate` turns it into
//! a typed value or a [`FieldErrors`] naming every bad field with a [`FormError`]; the
//! panels show each error's message next to its field and send nothing.

mod errors;

use std::path::{Path, PathBuf};

use shatter_sim::{FractureParams, FractureSource};

pub use self::errors::{FieldErrors, FormError, MeshCheck, ProjectileLoad};

use crate::commands::{
    ForceSpec, MaterialPreset, MethodKind, ObjectSpec, Pattern, ProjectileShape, ProjectileSpec,
    Shape, SimCommand,
};
use crate::ui::fields::{
    parse_color, parse_count, parse_lifetime, parse_non_negative, parse_positive, parse_real,
    parse_vec3,
};

/// Shape selector of the Add Object and Fire panels: a built-in shape or a file.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ShapeKind {
    /// A built-in shape.
    Builtin(Shape),
    /// A file given in the path field.
    Custom,
}

impl ShapeKind {
    /// The shapes of the Add Object panel: every built-in shape ([`Shape::ALL`]), then a
    /// file.
    pub fn object_options() -> Vec<ShapeKind> {
        Shape::ALL
            .iter()
            .map(|&s| ShapeKind::Builtin(s))
            .chain([ShapeKind::Custom])
            .collect()
    }

    /// The shapes of the Fire panel: the built-in shapes with a primitive collider (see
    /// [`ProjectileShape::primitive`]), then a file.
    pub fn projectile_options() -> Vec<ShapeKind> {
        Shape::ALL
            .iter()
            .filter(|&&s| ProjectileShape::primitive(s).is_some())
            .map(|&s| ShapeKind::Builtin(s))
            .chain([ShapeKind::Custom])
            .collect()
    }

    /// Label shown in the UI: the shape's word, capitalised.
    pub fn label(self) -> String {
        let word = match self {
            Self::Builtin(s) => s.name(),
            Self::Custom => "custom",
        };
        let mut chars = word.chars();
        chars
            .next()
            .map(|c| c.to_uppercase().chain(chars).collect())
            .unwrap_or_default()
    }

    /// The kind of an object's source, and its file's path (empty for a shape). A
    /// prebuilt fracture shows as a cube: editing it rebuilds it from a cube.
    pub fn of(source: &FractureSource) -> (Self, String) {
        match source {
            FractureSource::Shape { shape, .. } => (Self::Builtin(*shape), String::new()),
            FractureSource::MeshFile { path, .. } => (Self::Custom, path.clone()),
            FractureSource::Prebuilt(_) => (Self::Builtin(Shape::Cube), String::new()),
        }
    }

    /// The kind of a projectile's shape.
    pub fn of_projectile(shape: &ProjectileShape) -> Self {
        shape.shape().map_or(Self::Custom, Self::Builtin)
    }
}

/// The trimmed path of the Custom shape, or why there is none.
fn mesh_path(path: &str) -> Result<&Path, FormError> {
    match path.trim() {
        "" => Err(FormError::NoMeshPath),
        p => Ok(Path::new(p)),
    }
}

/// What an object is cut from, before its fracture parameters are known.
enum Picked {
    /// A built-in shape.
    Shape(Shape),
    /// A mesh file.
    File(PathBuf),
}

impl Picked {
    /// The object's source, cut with `params`.
    fn with(self, params: FractureParams) -> FractureSource {
        match self {
            Picked::Shape(shape) => FractureSource::Shape { shape, params },
            Picked::File(path) => FractureSource::MeshFile {
                path: path.display().to_string(),
                params,
            },
        }
    }
}

/// An object's source for a shape kind: a built-in shape, or a file that `check` accepts.
fn object_source(kind: ShapeKind, path: &str, check: MeshCheck<'_>) -> Result<Picked, FormError> {
    Ok(match kind {
        ShapeKind::Builtin(s) => Picked::Shape(s),
        ShapeKind::Custom => {
            let p = mesh_path(path)?;
            check(p)?;
            Picked::File(p.to_path_buf())
        }
    })
}

/// A projectile's shape for a shape kind: a primitive, or a file's points from `load`.
fn projectile_shape(
    kind: ShapeKind,
    path: &str,
    load: ProjectileLoad<'_>,
) -> Result<ProjectileShape, FormError> {
    match kind {
        ShapeKind::Builtin(s) => ProjectileShape::primitive(s)
            .or_else(|| ProjectileShape::from_mesh(&s.mesh()))
            .ok_or(FormError::FlatProjectile),
        ShapeKind::Custom => Ok(load(mesh_path(path)?)?),
    }
}

/// The thesis's Add Object panel (first page), plus method, pattern and material.
#[derive(Debug, Clone, PartialEq)]
pub struct AddObjectForm {
    /// Shape selector.
    pub shape: ShapeKind,
    /// Path of the custom mesh.
    pub custom_path: String,
    /// "Random Vertices".
    pub random_vertices: String,
    /// "Breakforce".
    pub break_force: String,
    /// "Skip".
    pub skip: String,
    /// "Center".
    pub center: bool,
    /// "Last" (empty: for ever).
    pub last: String,
    /// "Color" R, G, B in `[0, 1]`.
    pub color: [String; 3],
    /// Fracture method.
    pub method: MethodKind,
    /// Voronoi seed pattern.
    pub pattern: Pattern,
    /// Material preset.
    pub material: MaterialPreset,
}

impl Default for AddObjectForm {
    fn default() -> Self {
        Self {
            shape: ShapeKind::Builtin(Shape::Cube),
            custom_path: String::new(),
            random_vertices: "40".to_owned(),
            // Stone's bond strength: a 1 m stone cube (2.6 t) holds together when it lands.
            break_force: "20000".to_owned(),
            skip: "0".to_owned(),
            center: false,
            last: String::new(),
            color: ["0.8".to_owned(), "0.7".to_owned(), "0.3".to_owned()],
            method: MethodKind::Tetra,
            pattern: Pattern::Uniform,
            material: MaterialPreset::Stone,
        }
    }
}

/// The transform page of Add Object: Position and Scale.
#[derive(Debug, Clone, PartialEq)]
pub struct TransformForm {
    /// Position x, y, z (default (0, 10, 0), as in the thesis).
    pub position: [String; 3],
    /// Scale x, y, z (default (1, 1, 1)).
    pub scale: [String; 3],
}

impl Default for TransformForm {
    fn default() -> Self {
        Self {
            position: ["0".to_owned(), "10".to_owned(), "0".to_owned()],
            scale: ["1".to_owned(), "1".to_owned(), "1".to_owned()],
        }
    }
}

impl AddObjectForm {
    /// Validate both pages into the simulation's object. `base` is the object being
    /// edited: what the panels do not show (rotation, anchoring, a brick grid's other
    /// counts, material overrides, a seed, runtime fracture) is kept from it.
    pub fn validate(
        &self,
        transform: &TransformForm,
        check: MeshCheck<'_>,
        base: Option<&ObjectSpec>,
    ) -> Result<ObjectSpec, FieldErrors> {
        let mut e = FieldErrors::default();
        let source = e.check("shape", object_source(self.shape, &self.custom_path, check));
        let random_vertices = e.check("random_vertices", parse_count(&self.random_vertices));
        let break_force = e.check("break_force", parse_positive(&self.break_force));
        let skip = e.check("skip", parse_count(&self.skip));
        let lifetime = e.check("last", parse_lifetime(&self.last));
        let color = e.check("color", parse_color(&self.color));
        if self.method != MethodKind::Tetra && random_vertices == Some(0) {
            e.insert(
                "random_vertices",
                FormError::NoPieces {
                    method: self.method,
                },
            );
        }
        let position = e.check("position", parse_vec3(&transform.position, parse_real));
        let scale = e.check("scale", parse_vec3(&transform.scale, parse_positive));
        let (
            Some(source),
            Some(random_vertices),
            Some(break_force),
            Some(skip),
            Some(lifetime),
            Some(color),
            Some(position),
            Some(scale),
        ) = (
            source,
            random_vertices,
            break_force,
            skip,
            lifetime,
            color,
            position,
            scale,
        )
        else {
            return Err(e);
        };
        if !e.is_empty() {
            return Err(e);
        }
        let base_params = base.and_then(|b| b.source.params().cloned());
        let mut params = base_params.clone().unwrap_or_default();
        params.method = Some(self.method);
        params.pattern = Some(self.pattern);
        params.skip = skip;
        params.center = self.center;
        match self.method {
            MethodKind::Tetra => params.random_vertices = random_vertices,
            MethodKind::Voronoi | MethodKind::Slice => params.pieces = random_vertices,
            MethodKind::Grid => {
                // Keep an edited object's grid if its x count did not change; otherwise
                // cut cubes of about equal size along each axis.
                let keep = base_params
                    .as_ref()
                    .is_some_and(|p| p.grid[0] == random_vertices);
                if !keep {
                    let n = random_vertices.max(1);
                    let cell = scale.x / f64::from(n);
                    let along = |len: f64| ((len / cell).round() as u32).clamp(1, 64);
                    params.grid = [n, along(scale.y), along(scale.z)];
                }
            }
        }
        let source = source.with(params);
        let mut out = match base {
            Some(b) => ObjectSpec {
                source,
                ..b.clone()
            },
            None => ObjectSpec::new(self.shape.label().to_lowercase(), source),
        };
        // An edited object keeps its material overrides while the preset stays the same.
        if base.is_none_or(|b| MaterialPreset::of(&b.material) != Some(self.material)) {
            out.material = self.material.material();
        }
        out.break_force = Some(break_force as f32);
        out.position = position.as_vec3();
        out.scale = scale.as_vec3();
        out.color = color;
        out.last = lifetime.map(|t| t as f32);
        Ok(out)
    }

    /// Fill both pages from an existing object (Edit).
    pub fn from_spec(spec: &ObjectSpec) -> (AddObjectForm, TransformForm) {
        let f = |v: f64| format!("{v}");
        let (shape, custom_path) = ShapeKind::of(&spec.source);
        let params = spec.source.params().cloned().unwrap_or_default();
        let method = params.method.unwrap_or(spec.material.method);
        let random_vertices = match method {
            MethodKind::Tetra => params.random_vertices,
            MethodKind::Voronoi | MethodKind::Slice => params.pieces,
            MethodKind::Grid => params.grid[0],
        };
        let form = AddObjectForm {
            shape,
            custom_path,
            random_vertices: random_vertices.to_string(),
            break_force: f(f64::from(spec.effective_break_force())),
            skip: params.skip.to_string(),
            center: params.center,
            last: spec.last.map(|t| f(f64::from(t))).unwrap_or_default(),
            color: spec.color.map(|c| format!("{c}")),
            method,
            pattern: params.pattern.unwrap_or(spec.material.pattern),
            material: MaterialPreset::of(&spec.material).unwrap_or_default(),
        };
        let transform = TransformForm {
            position: spec.position.as_dvec3().to_array().map(f),
            scale: spec.scale.as_dvec3().to_array().map(f),
        };
        (form, transform)
    }
}

/// The thesis's Fire panel.
#[derive(Debug, Clone, PartialEq)]
pub struct FireForm {
    /// Projectile shape.
    pub shape: ShapeKind,
    /// Path of a custom projectile mesh.
    pub custom_path: String,
    /// "Last" (empty: for ever).
    pub last: String,
    /// Colour R, G, B in `[0, 1]`.
    pub color: [String; 3],
    /// "Speed" in m/s.
    pub speed: String,
    /// Size in m.
    pub size: String,
    /// Density in kg/m³.
    pub density: String,
}

impl Default for FireForm {
    /// The simulator's projectile ([`ProjectileSpec::default`]): one definition for the
    /// Fire panel, the scene files and the CLI.
    fn default() -> Self {
        let d = ProjectileSpec::default();
        Self {
            shape: ShapeKind::of_projectile(&d.shape),
            custom_path: String::new(),
            last: d.last.map(|v| v.to_string()).unwrap_or_default(),
            color: d.color.map(|c| c.to_string()),
            speed: d.speed.to_string(),
            size: d.size.to_string(),
            density: d.density.to_string(),
        }
    }
}

impl FireForm {
    /// Validate into the projectile that later clicks fire ("OK"); a click sets its
    /// launch and aim points.
    pub fn validate(&self, load: ProjectileLoad<'_>) -> Result<ProjectileSpec, FieldErrors> {
        let mut e = FieldErrors::default();
        let shape = e.check(
            "shape",
            projectile_shape(self.shape, &self.custom_path, load),
        );
        let last = e.check("last", parse_lifetime(&self.last));
        let color = e.check("color", parse_color(&self.color));
        let speed = e.check("speed", parse_positive(&self.speed));
        let size = e.check("size", parse_positive(&self.size));
        let density = e.check("density", parse_positive(&self.density));
        match (shape, last, color, speed, size, density) {
            (Some(shape), Some(last), Some(color), Some(speed), Some(size), Some(density)) => {
                Ok(ProjectileSpec {
                    shape,
                    last: last.map(|t| t as f32),
                    color,
                    speed: speed as f32,
                    size: size as f32,
                    density: density as f32,
                    ..ProjectileSpec::default()
                })
            }
            _ => Err(e),
        }
    }
}

/// The thesis's Add Force panel.
#[derive(Debug, Clone, PartialEq)]
pub struct ForceForm {
    /// "isOn".
    pub enabled: bool,
    /// "Radius" in m.
    pub radius: String,
    /// "Power".
    pub power: String,
}

impl Default for ForceForm {
    fn default() -> Self {
        let d = ForceSpec::default();
        Self {
            enabled: d.enabled,
            radius: d.radius.to_string(),
            power: d.power.to_string(),
        }
    }
}

impl ForceForm {
    /// Validate into the explosion that later clicks set off.
    pub fn validate(&self) -> Result<ForceSpec, FieldErrors> {
        let mut e = FieldErrors::default();
        let radius = e.check("radius", parse_positive(&self.radius));
        let power = e.check("power", parse_non_negative(&self.power));
        match (radius, power) {
            (Some(radius), Some(power)) => Ok(ForceSpec {
                enabled: self.enabled,
                radius,
                power,
            }),
            _ => Err(e),
        }
    }
}

/// The scene file field (save / load, TOML).
#[derive(Debug, Clone, PartialEq)]
pub struct SceneFileForm {
    /// Path of the TOML file.
    pub path: String,
}

impl Default for SceneFileForm {
    fn default() -> Self {
        Self {
            path: "my_scene.toml".to_owned(),
        }
    }
}

impl SceneFileForm {
    fn toml_path(&self) -> Result<PathBuf, FieldErrors> {
        let p = self.path.trim();
        if p.is_empty() {
            Err(FieldErrors::single("path", FormError::NoScenePath))
        } else if Path::new(p).extension().and_then(|x| x.to_str()) != Some("toml") {
            Err(FieldErrors::single(
                "path",
                FormError::NotToml { path: p.to_owned() },
            ))
        } else {
            Ok(PathBuf::from(p))
        }
    }

    /// The Save command, if the path can be written to.
    pub fn save(&self) -> Result<SimCommand, FieldErrors> {
        let path = self.toml_path()?;
        if let Err(e) = crate::scene_store::can_save(&path) {
            return Err(FieldErrors::single("path", e));
        }
        Ok(SimCommand::SaveScene(path))
    }

    /// The Load command, if the file exists.
    pub fn load(&self) -> Result<SimCommand, FieldErrors> {
        let path = self.toml_path()?;
        if !crate::scene_store::exists(&path) {
            return Err(FieldErrors::single("path", FormError::NoSceneFile { path }));
        }
        Ok(SimCommand::LoadScene(path))
    }
}
