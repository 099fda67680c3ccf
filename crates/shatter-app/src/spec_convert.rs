//! Conversions between the panels' specifications ([`crate::commands`]) and the
//! simulation's ([`shatter_sim`]).
//!
//! The panels show the thesis's fields; a simulation object carries more (rotation,
//! anchoring, a brick grid, material overrides, a seed). Editing an object therefore
//! starts from its current simulation spec and replaces only what the panels show.

use glam::DVec3;
use shatter_sim::{
    BondModel, FractureParams, FractureSource, MaterialPreset, MethodKind, ObjectSpec as SimSpec,
    Shape,
};

use crate::commands::{ObjectSpec, ShapeChoice};
use crate::error::AppError;

/// The simulation's spec for what the panels ask for. `base` is the object being edited
/// (its hidden properties are kept); `bond_model` the model chosen in the panel.
pub fn to_sim_spec(
    spec: &ObjectSpec,
    base: Option<&SimSpec>,
    bond_model: Option<BondModel>,
) -> Result<SimSpec, AppError> {
    let base_params = base.and_then(|b| match &b.source {
        FractureSource::Shape { params, .. } | FractureSource::MeshFile { params, .. } => {
            Some(params.clone())
        }
        FractureSource::Prebuilt(_) => None,
    });
    let mut params = base_params.clone().unwrap_or_default();
    params.method = Some(spec.method);
    params.pattern = Some(spec.pattern);
    params.skip = spec.skip;
    params.center = spec.center;
    match spec.method {
        MethodKind::Tetra => params.random_vertices = spec.random_vertices,
        MethodKind::Voronoi | MethodKind::Slice => params.pieces = spec.random_vertices,
        MethodKind::Grid => {
            // Keep an edited object's grid if its x count did not change; otherwise cut
            // cubes of about equal size along each axis.
            let keep = base_params
                .as_ref()
                .is_some_and(|p| p.grid[0] == spec.random_vertices);
            if !keep {
                let n = spec.random_vertices.max(1);
                let cell = spec.scale.x / f64::from(n);
                let along = |len: f64| ((len / cell).round() as u32).clamp(1, 64);
                params.grid = [n, along(spec.scale.y), along(spec.scale.z)];
            }
        }
    }
    let source = match &spec.shape {
        ShapeChoice::Custom(path) => FractureSource::MeshFile {
            path: path.display().to_string(),
            params,
        },
        ShapeChoice::Builtin(shape) => FractureSource::Shape {
            shape: *shape,
            params,
        },
    };
    // An edited object keeps its material overrides while the preset stays the same.
    let material = match base {
        Some(b) if MaterialPreset::of(&b.material) == Some(spec.material) => b.material,
        _ => spec.material.material(),
    };
    let mut out = match base {
        Some(b) => SimSpec {
            source,
            ..b.clone()
        },
        None => SimSpec {
            name: spec.shape.name().to_owned(),
            source,
            material,
            break_force: None,
            position: glam::Vec3::ZERO,
            rotation: glam::Quat::IDENTITY,
            scale: glam::Vec3::ONE,
            color: spec.color,
            last: None,
            bond_model: None,
            anchored: false,
            runtime: Default::default(),
        },
    };
    out.material = material;
    out.break_force = Some(spec.break_force as f32);
    out.position = spec.position.as_vec3();
    out.scale = spec.scale.as_vec3();
    out.color = spec.color;
    out.last = spec.lifetime.map(|t| t as f32);
    if let Some(m) = bond_model {
        out.bond_model = Some(m);
    }
    Ok(out)
}

/// The panels' view of a simulation object (for Edit). An object built from a prebuilt
/// fracture shows as a cube; editing it rebuilds it from a cube.
pub fn from_sim_spec(spec: &SimSpec) -> ObjectSpec {
    let material = MaterialPreset::of(&spec.material).unwrap_or_default();
    let (shape, params) = match &spec.source {
        FractureSource::Shape { shape, params } => (ShapeChoice::Builtin(*shape), params.clone()),
        FractureSource::MeshFile { path, params } => {
            (ShapeChoice::Custom(path.into()), params.clone())
        }
        FractureSource::Prebuilt(_) => {
            (ShapeChoice::Builtin(Shape::Cube), FractureParams::default())
        }
    };
    let method = params.method.unwrap_or(spec.material.method);
    let pattern = params.pattern.unwrap_or(spec.material.pattern);
    let random_vertices = match method {
        MethodKind::Tetra => params.random_vertices,
        MethodKind::Voronoi | MethodKind::Slice => params.pieces,
        MethodKind::Grid => params.grid[0],
    };
    ObjectSpec {
        shape,
        method,
        pattern,
        random_vertices,
        skip: params.skip,
        center: params.center,
        break_force: f64::from(spec.effective_break_force()),
        lifetime: spec.last.map(f64::from),
        color: spec.color,
        material,
        position: spec.position.as_dvec3(),
        scale: spec.scale.as_dvec3(),
    }
}

/// The vertices of a projectile shape that has no primitive collider (a custom mesh, the
/// bird, a torus), centred on their bounds and scaled so the largest extent is 1: the
/// projectile's Size is then its largest extent.
pub fn projectile_points(shape: &ShapeChoice) -> Result<Vec<DVec3>, AppError> {
    let mesh = match shape {
        ShapeChoice::Custom(path) => {
            shatter_geom::io::load_mesh_from(path, &crate::picked_files::sources())
                .map_err(AppError::ProjectileMesh)?
        }
        ShapeChoice::Builtin(shape) => shape.mesh(),
    };
    let (lo, hi) = mesh.bounds().ok_or(AppError::ProjectileNoVertices)?;
    let extent = (hi - lo).max_element();
    if !(extent.is_finite() && extent > 0.0) {
        return Err(AppError::FlatProjectile);
    }
    let centre = (lo + hi) * 0.5;
    Ok(mesh
        .positions
        .iter()
        .map(|p| (*p - centre) / extent)
        .collect())
}
