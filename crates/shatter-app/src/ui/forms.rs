//! The panels' text fields and their validation into typed commands.
//!
//! Each form is a plain struct of strings (what the user typed). `validate` turns it into
//! a typed value or a [`FieldErrors`] naming every bad field with a [`FormError`]; the
//! panels show each error's message next to its field and send nothing.

mod errors;

use std::path::{Path, PathBuf};

use shatter_sim::ProjectileShape;

pub use self::errors::{FieldErrors, FormError, MeshCheck};

use crate::commands::{
    ForceSpec, MaterialPreset, MethodKind, ObjectSpec, Pattern, ProjectileSpec, Shape, ShapeChoice,
    SimCommand,
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

    /// The kind of an already chosen shape.
    pub fn of(shape: &ShapeChoice) -> Self {
        match shape {
            ShapeChoice::Builtin(s) => Self::Builtin(*s),
            ShapeChoice::Custom(_) => Self::Custom,
        }
    }
}

fn shape_choice(
    kind: ShapeKind,
    path: &str,
    check: MeshCheck<'_>,
) -> Result<ShapeChoice, FormError> {
    Ok(match kind {
        ShapeKind::Builtin(s) => ShapeChoice::Builtin(s),
        ShapeKind::Custom => {
            let p = path.trim();
            if p.is_empty() {
                return Err(FormError::NoMeshPath);
            }
            check(Path::new(p))?;
            ShapeChoice::Custom(PathBuf::from(p))
        }
    })
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
    /// Validate both pages into an object specification.
    pub fn validate(
        &self,
        transform: &TransformForm,
        check: MeshCheck<'_>,
    ) -> Result<ObjectSpec, FieldErrors> {
        let mut e = FieldErrors::default();
        let shape = e.check("shape", shape_choice(self.shape, &self.custom_path, check));
        let random_vertices = e.check("random_vertices", parse_count(&self.random_vertices));
        let break_force = e.check("break_force", parse_positive(&self.break_force));
        let skip = e.check("skip", parse_count(&self.skip));
        let lifetime = e.check("last", parse_lifetime(&self.last));
        let color = e.check("color", parse_color(&self.color));
        let material = Some(self.material);
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
        match (
            shape,
            random_vertices,
            break_force,
            skip,
            lifetime,
            color,
            material,
            position,
            scale,
        ) {
            (
                Some(shape),
                Some(random_vertices),
                Some(break_force),
                Some(skip),
                Some(lifetime),
                Some(color),
                Some(material),
                Some(position),
                Some(scale),
            ) if e.is_empty() => Ok(ObjectSpec {
                shape,
                method: self.method,
                pattern: self.pattern,
                random_vertices,
                skip,
                center: self.center,
                break_force,
                lifetime,
                color,
                material,
                position,
                scale,
            }),
            _ => Err(e),
        }
    }

    /// Fill both pages from an existing object (Edit).
    pub fn from_spec(spec: &ObjectSpec) -> (AddObjectForm, TransformForm) {
        let f = |v: f64| format!("{v}");
        let form = AddObjectForm {
            shape: ShapeKind::of(&spec.shape),
            custom_path: match &spec.shape {
                ShapeChoice::Custom(p) => p.display().to_string(),
                _ => String::new(),
            },
            random_vertices: spec.random_vertices.to_string(),
            break_force: f(spec.break_force),
            skip: spec.skip.to_string(),
            center: spec.center,
            last: spec.lifetime.map(f).unwrap_or_default(),
            color: spec.color.map(|c| format!("{c}")),
            method: spec.method,
            pattern: spec.pattern,
            material: spec.material,
        };
        let transform = TransformForm {
            position: spec.position.to_array().map(f),
            scale: spec.scale.to_array().map(f),
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
    fn default() -> Self {
        let d = ProjectileSpec::default();
        Self {
            shape: ShapeKind::of(&d.shape),
            custom_path: String::new(),
            last: d.lifetime.map(|v| v.to_string()).unwrap_or_default(),
            color: d.color.map(|c| c.to_string()),
            speed: d.speed.to_string(),
            size: d.size.to_string(),
            density: d.density.to_string(),
        }
    }
}

impl FireForm {
    /// Validate into the projectile that later clicks fire ("OK").
    pub fn validate(&self, check: MeshCheck<'_>) -> Result<ProjectileSpec, FieldErrors> {
        let mut e = FieldErrors::default();
        let shape = e.check("shape", shape_choice(self.shape, &self.custom_path, check));
        let lifetime = e.check("last", parse_lifetime(&self.last));
        let color = e.check("color", parse_color(&self.color));
        let speed = e.check("speed", parse_positive(&self.speed));
        let size = e.check("size", parse_positive(&self.size));
        let density = e.check("density", parse_positive(&self.density));
        match (shape, lifetime, color, speed, size, density) {
            (Some(shape), Some(lifetime), Some(color), Some(speed), Some(size), Some(density)) => {
                Ok(ProjectileSpec {
                    shape,
                    lifetime,
                    color,
                    speed,
                    size,
                    density,
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
