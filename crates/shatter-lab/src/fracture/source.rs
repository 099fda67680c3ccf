//! Loading the model a request names: a file (read, repaired unless strict) or a built-in
//! shape, scaled and checked to be a valid solid (an inward mesh is flipped).

use std::path::Path;

use shatter_geom::io;
use shatter_geom::mesh::repair::{RepairOptions, RepairReport};
use shatter_geom::model::Model;
use shatter_geom::shapes::Shape;
use shatter_geom::{DVec3, TriMesh};

use super::request::{FractureConfig, MeshSource};
use crate::error::LabError;

/// A built-in shape at unit scale.
pub fn builtin_shape(name: Shape) -> Result<TriMesh, LabError> {
    shatter_geom::shapes::by_name(name.name())
        .ok_or_else(|| LabError::internal(format!("built-in shape '{name}' is missing")))
}

/// `mesh` with every vertex multiplied component-wise by `scale` (positive).
pub fn scaled(mesh: TriMesh, scale: DVec3) -> TriMesh {
    if scale == DVec3::ONE {
        mesh
    } else {
        mesh.transformed(scale, DVec3::ZERO)
    }
}

/// `model` with its positions multiplied component-wise by `scale` (positive) and its
/// normals by the inverse scale (renormalised); UVs and colours unchanged.
pub fn scaled_model(mut model: Model, scale: DVec3) -> Model {
    if scale == DVec3::ONE {
        return model;
    }
    model.mesh = model.mesh.transformed(scale, DVec3::ZERO);
    if let Some(normals) = &mut model.corners.normal {
        for n in normals.iter_mut().flatten() {
            let m = (DVec3::new(n[0].into(), n[1].into(), n[2].into()) / scale).normalize_or_zero();
            *n = m.as_vec3().to_array();
        }
    }
    model
}

/// [`validate_solid`] of a model's mesh; when its triangles are flipped, their corner
/// attributes follow (corners 1 and 2 swap; the normals keep their direction, which an
/// inward winding does not tell wrong).
pub fn validate_model(model: &mut Model, origin: &str) -> Result<Option<String>, LabError> {
    let flipped = validate_solid(&mut model.mesh, origin)?;
    if flipped.is_some() {
        let c = &mut model.corners;
        for t in 0..model.mesh.triangles.len() {
            if let Some(v) = &mut c.uv {
                v[t].swap(1, 2);
            }
            if let Some(v) = &mut c.normal {
                v[t].swap(1, 2);
            }
            if let Some(v) = &mut c.color {
                v[t].swap(1, 2);
            }
        }
    }
    Ok(flipped)
}

/// Checks that `mesh` (read from `origin`, a file name or a shape name) is a valid solid.
/// An inward mesh is flipped, and the returned warning says so; any other defect is a
/// bad-input error naming `origin` and the counts ("bird.obj: 12 boundary edges").
pub fn validate_solid(mesh: &mut TriMesh, origin: &str) -> Result<Option<String>, LabError> {
    match mesh.orient_outward() {
        Ok(false) => Ok(None),
        Ok(true) => Ok(Some(format!(
            "{origin}: the mesh was wound inward; flipped it"
        ))),
        Err(e) => Err(LabError::input(format!("{origin}: {e}"))),
    }
}

/// Repairs a model read from `origin` into a closed solid (`mesh::repair` with its
/// default options). A model with nothing solid in it is bad input, named by `origin`
/// ("sheet.obj: 12 open sheets and no closed part").
pub fn repair(model: &Model, origin: &str) -> Result<(Model, RepairReport), LabError> {
    shatter_geom::mesh::repair::repair(model, &RepairOptions::default())
        .map_err(|e| LabError::input(format!("{origin}: {e}")))
}

/// Loads a model (mesh, attributes, materials) with the reader's warnings. Every
/// failure is bad input, named by the file.
pub fn load_model(path: &Path) -> Result<io::LoadedModel, LabError> {
    if !path.exists() {
        return Err(LabError::input(format!("{}: no such file", path.display())));
    }
    io::load_model(path).map_err(LabError::input)
}

/// Loads (and scales) the model a configuration names — mesh, UVs, normals, colours and
/// materials; a built-in shape is a bare mesh — repairs a file's model (unless
/// `strict`) and checks that its mesh is a valid solid; returns it with any warnings
/// (the reader's, each repair's, an inward mesh flipped).
pub fn load_source(config: &FractureConfig) -> Result<(Model, Vec<String>), LabError> {
    let (model, origin, mut warnings): (Model, String, Vec<String>) = match &config.source {
        MeshSource::File(path) => {
            let loaded = load_model(path)?;
            let origin = path.display().to_string();
            let mut warnings: Vec<String> = loaded.warnings.iter().map(|w| w.to_string()).collect();
            let model = if config.strict {
                loaded.model
            } else {
                let (model, report) = repair(&loaded.model, &origin)?;
                warnings.extend(
                    report
                        .warnings()
                        .into_iter()
                        .map(|w| format!("{origin}: {w}")),
                );
                model
            };
            (model, origin, warnings)
        }
        MeshSource::Shape(name) => (
            Model::from_mesh(builtin_shape(*name)?),
            format!("shape {name}"),
            Vec::new(),
        ),
    };
    let mut model = scaled_model(model, config.scale);
    warnings.extend(validate_model(&mut model, &origin)?);
    Ok((model, warnings))
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;
    use shatter_geom::fracture::Method;
    use shatter_geom::fracture::Pattern;

    #[test]
    fn a_shape_loads_scaled_and_outward() {
        let mut config =
            FractureConfig::shape(Shape::Cube, Method::voronoi(4, Pattern::Uniform), 0);
        config.scale = DVec3::new(2.0, 1.0, 1.0);
        let (model, warnings) = load_source(&config).unwrap();
        assert!(warnings.is_empty(), "{warnings:?}");
        assert!((model.mesh.signed_volume() - 2.0).abs() < 1e-12);
    }

    #[test]
    fn an_inward_mesh_is_flipped_with_a_warning_naming_it() {
        let mut mesh = Shape::Cube.mesh();
        mesh.triangles.iter_mut().for_each(|t| t.swap(1, 2));
        let warning = validate_solid(&mut mesh, "shape cube").unwrap();
        assert_eq!(
            warning.as_deref(),
            Some("shape cube: the mesh was wound inward; flipped it")
        );
        assert!(mesh.signed_volume() > 0.0);
    }

    #[test]
    fn a_missing_file_is_bad_input_naming_it() {
        let config = FractureConfig {
            source: MeshSource::File("/nonexistent/bird.obj".into()),
            ..FractureConfig::shape(Shape::Cube, Method::voronoi(4, Pattern::Uniform), 0)
        };
        assert_eq!(
            load_source(&config).unwrap_err(),
            LabError::input("/nonexistent/bird.obj: no such file")
        );
    }
}
