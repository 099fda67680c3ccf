//! What the user asks for: breakable objects, projectiles and explosions, as plain data.

use std::sync::Arc;

use glam::{Quat, Vec3};
use shatter_geom::fracture::{Fracture, Placement};
use shatter_geom::shapes::Shape;

use crate::error::SimError;
use crate::material::{Material, MethodKind, Pattern};
use crate::runtime::{FractureTiming, RuntimeFracture};

shatter_geom::vocabulary! {
    /// How the fragments of a breakable object hold together.
    ///
    /// ```
    /// use shatter_sim::BondModel;
    /// assert_eq!("joints".parse(), Ok(BondModel::Joints));
    /// assert_eq!(BondModel::default().to_string(), "clusters");
    /// ```
    pub enum BondModel: "bond model", default Clusters {
        /// Connected fragments form one rigid body with a compound collider. Contact forces
        /// and explosions load the bonds; a bond whose load in a step exceeds the break force
        /// breaks and the body splits into its connected components.
        Clusters = "clusters",
        /// The thesis: one rigid body per fragment and a breakable fixed joint per bond. A
        /// joint breaks when the force it applied during the step, `|linear impulse| /
        /// substep dt`, exceeds the object's break force.
        Joints = "joints",
    }
}

/// Parameters of a fracture computed by `shatter_geom::fracture` (the thesis's object
/// parameters plus the method).
#[derive(Debug, Clone, PartialEq)]
pub struct FractureParams {
    /// Method; `None` uses the material's default.
    pub method: Option<MethodKind>,
    /// Voronoi seed pattern; `None` uses the material's default.
    pub pattern: Option<Pattern>,
    /// Number of pieces (Voronoi cells, slices).
    pub pieces: u32,
    /// The thesis's "Random Vertices".
    pub random_vertices: u32,
    /// The thesis's "Skip": take every (skip+1)-th surface vertex.
    pub skip: u32,
    /// The thesis's "Center": also add the centre point.
    pub center: bool,
    /// Tetra only: where the random points go.
    pub placement: Placement,
    /// Random seed.
    pub seed: u64,
    /// Grid cells for [`MethodKind::Grid`].
    pub grid: [u32; 3],
    /// Boxes of grid cells left out, `[x0, y0, z0, x1, y1, z1]` (from cell `x0` up to but
    /// not including `x1`, ...): a bridge is a box with the space under its span left out.
    pub grid_voids: Vec<[u32; 6]>,
}

impl Default for FractureParams {
    fn default() -> Self {
        FractureParams {
            method: None,
            pattern: None,
            pieces: 32,
            random_vertices: 50,
            skip: 0,
            center: false,
            placement: Placement::Interior,
            seed: 1,
            grid: [4, 4, 4],
            grid_voids: Vec::new(),
        }
    }
}

/// Where an object's fragments come from.
///
/// Two prebuilt sources are equal when they share one fracture (`Arc::ptr_eq`).
#[derive(Debug, Clone)]
pub enum FractureSource {
    /// An already fractured object (in its own frame, before scaling).
    Prebuilt(Arc<Fracture>),
    /// A built-in shape fractured with `params`. A `cube` with [`MethodKind::Grid`] is cut
    /// into a brick grid.
    Shape {
        /// The shape.
        shape: Shape,
        /// Fracture parameters.
        params: FractureParams,
    },
    /// A mesh file (OBJ, STL, glTF) fractured with `params`.
    MeshFile {
        /// Path to the file.
        path: String,
        /// Fracture parameters.
        params: FractureParams,
    },
}

impl PartialEq for FractureSource {
    fn eq(&self, other: &Self) -> bool {
        match (self, other) {
            (FractureSource::Prebuilt(a), FractureSource::Prebuilt(b)) => Arc::ptr_eq(a, b),
            (
                FractureSource::Shape { shape, params },
                FractureSource::Shape {
                    shape: s,
                    params: p,
                },
            ) => shape == s && params == p,
            (
                FractureSource::MeshFile { path, params },
                FractureSource::MeshFile { path: q, params: p },
            ) => path == q && params == p,
            _ => false,
        }
    }
}

impl FractureSource {
    /// The fracture parameters of a shape or a mesh file (`None` for a prebuilt fracture).
    pub fn params(&self) -> Option<&FractureParams> {
        match self {
            FractureSource::Shape { params, .. } | FractureSource::MeshFile { params, .. } => {
                Some(params)
            }
            FractureSource::Prebuilt(_) => None,
        }
    }
}

/// A breakable object: a fracture, a material, a transform and the thesis's parameters.
#[derive(Debug, Clone, PartialEq)]
pub struct ObjectSpec {
    /// A label (shown by the app; not required to be unique).
    pub name: String,
    /// The fragments.
    pub source: FractureSource,
    /// Material (density, friction, restitution, default strength).
    pub material: Material,
    /// Break force of each bond in newtons; `None` uses `material.strength`.
    pub break_force: Option<f32>,
    /// Position of the object's origin.
    pub position: Vec3,
    /// Orientation.
    pub rotation: Quat,
    /// Scale, applied to the geometry before the colliders are built.
    pub scale: Vec3,
    /// Colour (linear RGB, 0..=1) for the renderer.
    pub color: [f32; 3],
    /// The thesis's "Last": the object is removed this many seconds after Start.
    pub last: Option<f32>,
    /// Bond model; `None` uses the world's default.
    pub bond_model: Option<BondModel>,
    /// Bonds the fragments touching the object's lowest face to the world (walls).
    pub anchored: bool,
    /// When the object is cut (at once or on impact) and how deep its fragments are cut
    /// again when hit ([`crate::runtime`]).
    pub runtime: RuntimeFracture,
}

impl ObjectSpec {
    /// An object named `name` from `source`, with the default material, at the origin,
    /// unrotated and unscaled, grey, living for ever, with the world's bond model.
    ///
    /// ```
    /// use shatter_sim::{FractureParams, FractureSource, ObjectSpec, Shape};
    /// let spec = ObjectSpec::new("crate", FractureSource::Shape {
    ///     shape: Shape::Cube,
    ///     params: FractureParams::default(),
    /// });
    /// assert_eq!(spec.effective_break_force(), spec.material.strength);
    /// ```
    pub fn new(name: impl Into<String>, source: FractureSource) -> ObjectSpec {
        ObjectSpec {
            name: name.into(),
            source,
            material: Material::default(),
            break_force: None,
            position: Vec3::ZERO,
            rotation: Quat::IDENTITY,
            scale: Vec3::ONE,
            color: [0.7, 0.7, 0.7],
            last: None,
            bond_model: None,
            anchored: false,
            runtime: RuntimeFracture::default(),
        }
    }

    /// An object from a prebuilt fracture with default material, placed at `position`.
    pub fn from_fracture(fracture: Fracture, position: Vec3) -> ObjectSpec {
        ObjectSpec {
            position,
            ..ObjectSpec::new("object", FractureSource::Prebuilt(Arc::new(fracture)))
        }
    }

    /// The break force in effect.
    pub fn effective_break_force(&self) -> f32 {
        self.break_force.unwrap_or(self.material.strength)
    }

    /// Checks the numeric parameters; `key` prefixes the errors (e.g. `objects[1]`).
    pub fn validate(&self, key: &str) -> Result<(), SimError> {
        self.material.validate(&format!("{key}.material"))?;
        if let Some(f) = self.break_force
            && !(f.is_finite() && f > 0.0)
        {
            return Err(SimError::invalid(
                format!("{key}.break_force"),
                format!("must be a positive number, got {f}"),
            ));
        }
        if !(self.scale.is_finite() && self.scale.min_element() > 0.0) {
            return Err(SimError::invalid(
                format!("{key}.scale"),
                format!("every component must be positive, got {:?}", self.scale),
            ));
        }
        if !self.position.is_finite() {
            return Err(SimError::invalid(
                format!("{key}.position"),
                "must be finite",
            ));
        }
        if !self.rotation.is_finite() {
            return Err(SimError::invalid(
                format!("{key}.rotation"),
                "must be finite",
            ));
        }
        if let Some(t) = self.last
            && !(t.is_finite() && t > 0.0)
        {
            return Err(SimError::invalid(
                format!("{key}.last"),
                format!("must be a positive number of seconds, got {t}"),
            ));
        }
        check_color(self.color, &format!("{key}.color"))?;
        self.runtime.validate(key)?;
        if self.runtime.timing == FractureTiming::OnImpact {
            self.validate_on_impact(key)?;
        }
        match &self.source {
            FractureSource::Prebuilt(_) => {}
            FractureSource::Shape { params, .. } | FractureSource::MeshFile { params, .. } => {
                if params.pieces == 0 {
                    return Err(SimError::invalid(
                        format!("{key}.pieces"),
                        "must be at least 1",
                    ));
                }
                if params.grid.contains(&0) {
                    return Err(SimError::invalid(
                        format!("{key}.grid"),
                        "every cell count must be at least 1",
                    ));
                }
            }
        }
        Ok(())
    }

    /// An `on_impact` object is cut by radial Voronoi cells around the hit: a method or
    /// pattern that says otherwise, or a prebuilt fracture of several fragments (which is
    /// not one intact body), is an error rather than silently ignored.
    fn validate_on_impact(&self, key: &str) -> Result<(), SimError> {
        let params = match &self.source {
            FractureSource::Prebuilt(f) => {
                if f.fragments.len() != 1 {
                    return Err(SimError::invalid(
                        format!("{key}.fracture"),
                        format!(
                            "on_impact needs one intact body, but the prebuilt fracture has \
                             {} fragments",
                            f.fragments.len()
                        ),
                    ));
                }
                return Ok(());
            }
            FractureSource::Shape { params, .. } | FractureSource::MeshFile { params, .. } => {
                params
            }
        };
        if let Some(m) = params.method
            && m != MethodKind::Voronoi
        {
            return Err(SimError::invalid(
                format!("{key}.method"),
                format!("on_impact cuts with voronoi cells around the hit, got method `{m}`"),
            ));
        }
        if let Some(p) = params.pattern
            && p != Pattern::Radial
        {
            return Err(SimError::invalid(
                format!("{key}.pattern"),
                format!("on_impact cuts with the radial pattern around the hit, got `{p}`"),
            ));
        }
        Ok(())
    }
}

/// An explosion (the thesis's Add Force panel): an impulse of `power` (N·s) at the centre,
/// falling off linearly to zero at `radius`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ExplosionSpec {
    /// Centre.
    pub position: Vec3,
    /// Radius in metres.
    pub radius: f32,
    /// Impulse at the centre, in N·s.
    pub power: f32,
}

impl ExplosionSpec {
    /// Checks the parameters; `key` prefixes the errors.
    pub fn validate(&self, key: &str) -> Result<(), SimError> {
        if !(self.radius.is_finite() && self.radius > 0.0) {
            return Err(SimError::invalid(
                format!("{key}.radius"),
                format!("must be a positive number, got {}", self.radius),
            ));
        }
        if !(self.power.is_finite() && self.power >= 0.0) {
            return Err(SimError::invalid(
                format!("{key}.power"),
                format!("must be >= 0, got {}", self.power),
            ));
        }
        if !self.position.is_finite() {
            return Err(SimError::invalid(
                format!("{key}.position"),
                "must be finite",
            ));
        }
        Ok(())
    }
}

pub(crate) fn check_color(c: [f32; 3], key: &str) -> Result<(), SimError> {
    if c.iter().all(|v| (0.0..=1.0).contains(v)) {
        Ok(())
    } else {
        Err(SimError::invalid(
            key,
            format!("components must be in 0..=1, got {c:?}"),
        ))
    }
}
