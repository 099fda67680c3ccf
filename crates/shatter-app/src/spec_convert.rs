//! Conversions between the panels' specifications ([`crate::commands`]) and the
//! simulation's ([`shatter_sim`]).
//!
//! The panels show the thesis's fields; a simulation object carries more (rotation,
//! anchoring, a brick grid, material overrides, a seed). Editing an object therefore
//! starts from its current simulation spec and replaces only what the panels show.

use glam::DVec3;
use shatter_sim::material::MATERIAL_NAMES;
use shatter_sim::{
    BondModel, FractureMethod, FractureParams, FractureSource, Material, ObjectSpec as SimSpec,
    Pattern,
};

use crate::commands::{BondModelChoice, MethodChoice, ObjectSpec, PatternChoice, ShapeChoice};

/// The simulation's bond model for the panels' choice.
pub fn to_sim_bond_model(m: BondModelChoice) -> BondModel {
    match m {
        BondModelChoice::Joints => BondModel::Joints,
        BondModelChoice::Clusters => BondModel::Clusters,
    }
}

fn to_sim_method(m: MethodChoice) -> FractureMethod {
    match m {
        MethodChoice::Tetra => FractureMethod::Tetra,
        MethodChoice::Voronoi => FractureMethod::Voronoi,
        MethodChoice::Slice => FractureMethod::Slice,
        MethodChoice::Grid => FractureMethod::Grid,
    }
}

fn from_sim_method(m: FractureMethod) -> MethodChoice {
    match m {
        FractureMethod::Tetra => MethodChoice::Tetra,
        FractureMethod::Voronoi => MethodChoice::Voronoi,
        FractureMethod::Slice => MethodChoice::Slice,
        FractureMethod::Grid => MethodChoice::Grid,
    }
}

fn to_sim_pattern(p: PatternChoice) -> Pattern {
    match p {
        PatternChoice::Uniform => Pattern::Uniform,
        PatternChoice::Clustered => Pattern::Clustered,
        PatternChoice::Radial => Pattern::Radial,
        PatternChoice::Splinter => Pattern::Splinter,
    }
}

fn from_sim_pattern(p: Pattern) -> PatternChoice {
    match p {
        Pattern::Uniform => PatternChoice::Uniform,
        Pattern::Clustered => PatternChoice::Clustered,
        Pattern::Radial => PatternChoice::Radial,
        Pattern::Splinter => PatternChoice::Splinter,
    }
}

/// The preset a material was made from: the first whose density, friction and
/// restitution match (strength is the break force, shown on its own).
fn preset_name(m: &Material) -> Option<&'static str> {
    MATERIAL_NAMES.into_iter().find(|name| {
        Material::preset(name).is_some_and(|p| {
            p.density == m.density && p.friction == m.friction && p.restitution == m.restitution
        })
    })
}

/// The simulation's spec for what the panels ask for. `base` is the object being edited
/// (its hidden properties are kept); `bond_model` the model chosen in the panel.
pub fn to_sim_spec(
    spec: &ObjectSpec,
    base: Option<&SimSpec>,
    bond_model: Option<BondModelChoice>,
) -> Result<SimSpec, String> {
    let base_params = base.and_then(|b| match &b.source {
        FractureSource::Shape { params, .. } | FractureSource::MeshFile { params, .. } => {
            Some(params.clone())
        }
        FractureSource::Prebuilt(_) => None,
    });
    let mut params = base_params.clone().unwrap_or_default();
    params.method = Some(to_sim_method(spec.method));
    params.pattern = Some(to_sim_pattern(spec.pattern));
    params.skip = spec.skip;
    params.center = spec.center;
    match spec.method {
        MethodChoice::Tetra => params.random_vertices = spec.random_vertices,
        MethodChoice::Voronoi | MethodChoice::Slice => params.pieces = spec.random_vertices,
        MethodChoice::Grid => {
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
        shape => FractureSource::Shape {
            name: shape.name().to_owned(),
            params,
        },
    };
    let preset = Material::preset(&spec.material)
        .ok_or_else(|| format!("unknown material '{}'", spec.material))?;
    // An edited object keeps its material overrides while the preset stays the same.
    let material = match base {
        Some(b) if preset_name(&b.material) == Some(spec.material.as_str()) => b.material,
        _ => preset,
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
        },
    };
    out.material = material;
    out.break_force = Some(spec.break_force as f32);
    out.position = spec.position.as_vec3();
    out.scale = spec.scale.as_vec3();
    out.color = spec.color;
    out.last = spec.lifetime.map(|t| t as f32);
    if let Some(m) = bond_model {
        out.bond_model = Some(to_sim_bond_model(m));
    }
    Ok(out)
}

/// The panels' view of a simulation object (for Edit). An object built from a prebuilt
/// fracture shows as a cube; editing it rebuilds it from a cube.
pub fn from_sim_spec(spec: &SimSpec) -> ObjectSpec {
    let material_name = preset_name(&spec.material).unwrap_or("stone");
    let (shape, params) = match &spec.source {
        FractureSource::Shape { name, params } => (
            match name.as_str() {
                "capsule" => ShapeChoice::Capsule,
                "cylinder" => ShapeChoice::Cylinder,
                "sphere" => ShapeChoice::Sphere,
                "torus" => ShapeChoice::Torus,
                "bird" => ShapeChoice::Bird,
                _ => ShapeChoice::Cube,
            },
            params.clone(),
        ),
        FractureSource::MeshFile { path, params } => {
            (ShapeChoice::Custom(path.into()), params.clone())
        }
        FractureSource::Prebuilt(_) => (ShapeChoice::Cube, FractureParams::default()),
    };
    let method = params.method.unwrap_or(spec.material.method);
    let pattern = params.pattern.unwrap_or(spec.material.pattern);
    let random_vertices = match method {
        FractureMethod::Tetra => params.random_vertices,
        FractureMethod::Voronoi | FractureMethod::Slice => params.pieces,
        FractureMethod::Grid => params.grid[0],
    };
    ObjectSpec {
        shape,
        method: from_sim_method(method),
        pattern: from_sim_pattern(pattern),
        random_vertices,
        skip: params.skip,
        center: params.center,
        break_force: f64::from(spec.effective_break_force()),
        lifetime: spec.last.map(f64::from),
        color: spec.color,
        material: material_name.to_owned(),
        position: spec.position.as_dvec3(),
        scale: spec.scale.as_dvec3(),
    }
}

/// The vertices of a projectile shape that has no primitive collider (a custom mesh, the
/// bird, a torus), centred on their bounds and scaled so the largest extent is 1: the
/// projectile's Size is then its largest extent.
pub fn projectile_points(shape: &ShapeChoice) -> Result<Vec<DVec3>, String> {
    let mesh = match shape {
        ShapeChoice::Custom(path) => {
            shatter_geom::io::load_mesh(path).map_err(|e| format!("projectile: {e}"))?
        }
        other => shatter_geom::shapes::by_name(other.name())
            .ok_or_else(|| format!("projectile: no built-in shape '{}'", other.name()))?,
    };
    let (lo, hi) = mesh
        .bounds()
        .ok_or_else(|| "projectile: the mesh has no vertices".to_owned())?;
    let extent = (hi - lo).max_element();
    if !(extent.is_finite() && extent > 0.0) {
        return Err("projectile: the mesh is flat or not finite".to_owned());
    }
    let centre = (lo + hi) * 0.5;
    Ok(mesh
        .positions
        .iter()
        .map(|p| (*p - centre) / extent)
        .collect())
}
