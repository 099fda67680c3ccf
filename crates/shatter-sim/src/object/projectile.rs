//! What the user fires: a projectile's shape and launch, as plain data.

use glam::Vec3;
use shatter_geom::shapes::Shape;
use shatter_geom::{DVec3, TriMesh, shapes};

use super::spec::check_color;
use crate::error::SimError;

/// Shape of a projectile.
#[derive(Debug, Clone, PartialEq)]
pub enum ProjectileShape {
    /// A cube with edge `size`.
    Cube,
    /// A sphere of diameter `size`.
    Sphere,
    /// A capsule along its axis, total height `size`, radius `size / 4`.
    Capsule,
    /// A cylinder of height `size` and diameter `size`.
    Cylinder,
    /// The convex hull of these points (a custom mesh's vertices), scaled by `size`.
    Custom(Vec<DVec3>),
}

impl ProjectileShape {
    /// A closed mesh of this shape at `size`, in the projectile body's frame (a capsule's
    /// or cylinder's axis along `+y`, as the body is turned along the flight), matching
    /// its collider: for renderers and exports. A custom shape is the points' convex hull,
    /// or their bounding box when they span no volume.
    ///
    /// ```
    /// use shatter_sim::ProjectileShape;
    /// let (lo, hi) = ProjectileShape::Capsule.mesh(0.4).bounds().expect("vertices");
    /// assert!(((hi - lo).y - 0.4).abs() < 1e-3); // total height `size`
    /// assert!(((hi - lo).x - 0.2).abs() < 1e-3); // radius `size / 4`
    /// ```
    pub fn mesh(&self, size: f32) -> TriMesh {
        let s = f64::from(size);
        match self {
            ProjectileShape::Cube => shapes::cube().transformed(DVec3::splat(s), DVec3::ZERO),
            // Radius 0.5: diameter `size`.
            ProjectileShape::Sphere => {
                shapes::sphere(16, 8).transformed(DVec3::splat(s), DVec3::ZERO)
            }
            // Unity's capsule and cylinder are 2 tall and 1 wide: a capsule of height `size`
            // and radius `size / 4`; a cylinder of height and diameter `size`.
            ProjectileShape::Capsule => {
                shapes::capsule().transformed(DVec3::splat(s / 2.0), DVec3::ZERO)
            }
            ProjectileShape::Cylinder => {
                shapes::cylinder().transformed(DVec3::new(s, s / 2.0, s), DVec3::ZERO)
            }
            ProjectileShape::Custom(points) => {
                let scaled: Vec<DVec3> = points.iter().map(|p| *p * s).collect();
                if let Ok(t) = shatter_geom::delaunay::tetrahedralize(&scaled) {
                    return TriMesh::new(scaled, t.hull_faces());
                }
                let lo = scaled.iter().fold(DVec3::INFINITY, |a, &p| a.min(p));
                let hi = scaled.iter().fold(DVec3::NEG_INFINITY, |a, &p| a.max(p));
                if lo.is_finite() && hi.is_finite() {
                    let extent = (hi - lo).max(DVec3::splat(1e-3));
                    shapes::cube().transformed(extent, (lo + hi) / 2.0)
                } else {
                    shapes::sphere(16, 8).transformed(DVec3::splat(s), DVec3::ZERO)
                }
            }
        }
    }

    /// The primitive projectile of a built-in shape: a cube, sphere, capsule or cylinder
    /// (a torus or the bird has no primitive collider: `None`; use
    /// [`ProjectileShape::Custom`] with its points).
    pub fn primitive(shape: Shape) -> Option<ProjectileShape> {
        match shape {
            Shape::Cube => Some(ProjectileShape::Cube),
            Shape::Sphere => Some(ProjectileShape::Sphere),
            Shape::Capsule => Some(ProjectileShape::Capsule),
            Shape::Cylinder => Some(ProjectileShape::Cylinder),
            Shape::Torus | Shape::Bird => None,
        }
    }

    /// Parses `cube`, `sphere`, `capsule`, `cylinder` (custom meshes come with points).
    pub fn from_name(name: &str) -> Option<ProjectileShape> {
        name.parse().ok().and_then(ProjectileShape::primitive)
    }

    /// A custom shape of a mesh's vertices (a user's file, or a built-in shape with no
    /// primitive collider), centred on their bounds and scaled so the largest extent is
    /// 1: the projectile's size is then its largest extent. `None` when the vertices span
    /// no extent or are not finite.
    ///
    /// ```
    /// use shatter_sim::{ProjectileShape, Shape};
    /// let Some(ProjectileShape::Custom(points)) = ProjectileShape::from_mesh(&Shape::Bird.mesh())
    /// else { panic!("the bird has an extent") };
    /// let extent = points.iter().fold(0.0f64, |m, p| m.max(p.x.abs()).max(p.y.abs()).max(p.z.abs()));
    /// assert!((extent - 0.5).abs() < 1e-9); // half the largest extent, about the centre
    /// ```
    pub fn from_mesh(mesh: &TriMesh) -> Option<ProjectileShape> {
        let (lo, hi) = mesh.bounds()?;
        let extent = (hi - lo).max_element();
        if !(extent.is_finite() && extent > 0.0) {
            return None;
        }
        let centre = (lo + hi) * 0.5;
        Some(ProjectileShape::Custom(
            mesh.positions
                .iter()
                .map(|p| (*p - centre) / extent)
                .collect(),
        ))
    }

    /// The built-in shape this projectile is, if any (`None` for a custom one).
    pub fn shape(&self) -> Option<Shape> {
        match self {
            ProjectileShape::Cube => Some(Shape::Cube),
            ProjectileShape::Sphere => Some(Shape::Sphere),
            ProjectileShape::Capsule => Some(Shape::Capsule),
            ProjectileShape::Cylinder => Some(Shape::Cylinder),
            ProjectileShape::Custom(_) => None,
        }
    }
}

/// A projectile, fired from `from` towards `to` (the thesis's Fire panel).
#[derive(Debug, Clone, PartialEq)]
pub struct ProjectileSpec {
    /// Shape.
    pub shape: ProjectileShape,
    /// Size in metres (see [`ProjectileShape`]).
    pub size: f32,
    /// Density in kg/m³.
    pub density: f32,
    /// Speed in m/s.
    pub speed: f32,
    /// Colour.
    pub color: [f32; 3],
    /// Lifetime in seconds after firing; `None` = forever.
    pub last: Option<f32>,
    /// Start point.
    pub from: Vec3,
    /// Aim point.
    pub to: Vec3,
}

impl Default for ProjectileSpec {
    fn default() -> Self {
        ProjectileSpec {
            shape: ProjectileShape::Sphere,
            size: 0.3,
            density: 7800.0,
            speed: 30.0,
            color: [0.2, 0.2, 0.2],
            last: Some(10.0),
            from: Vec3::new(0.0, 1.0, 10.0),
            to: Vec3::new(0.0, 1.0, 0.0),
        }
    }
}

impl ProjectileSpec {
    /// Checks the parameters; `key` prefixes the errors.
    pub fn validate(&self, key: &str) -> Result<(), SimError> {
        for (v, name) in [(self.size, "size"), (self.density, "density")] {
            if !(v.is_finite() && v > 0.0) {
                return Err(SimError::invalid(
                    format!("{key}.{name}"),
                    format!("must be a positive number, got {v}"),
                ));
            }
        }
        if !(self.speed.is_finite() && self.speed >= 0.0) {
            return Err(SimError::invalid(
                format!("{key}.speed"),
                format!("must be >= 0, got {}", self.speed),
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
        if !(self.from.is_finite() && self.to.is_finite()) || (self.to - self.from).length() < 1e-6
        {
            return Err(SimError::invalid(
                format!("{key}.to"),
                "must be finite and differ from `from`",
            ));
        }
        check_color(self.color, &format!("{key}.color"))
    }
}
