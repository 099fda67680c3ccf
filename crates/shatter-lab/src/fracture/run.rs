//! Running a fracture request: its `shatter_geom` method on the loaded model.

use std::time::Instant;

use shatter_geom::fracture::{Fracture, FractureParams};
use shatter_geom::model::Model;

use super::request::FractureConfig;
use crate::error::LabError;

/// Fractures `model` as `config` says; returns the fracture and its warnings (merged
/// slivers, ...). Every library error describes the input (the mesh or the parameters),
/// so it is bad input.
pub fn fracture(
    model: &Model,
    config: &FractureConfig,
) -> Result<(Fracture, Vec<String>), LabError> {
    let params = FractureParams {
        method: config.method.clone(),
        seed: config.seed,
    };
    let result = if config.convex_pieces {
        shatter_geom::fracture::fracture_model(model, &params)
    } else {
        shatter_geom::fracture::fracture_model_surfaces(model, &params)
    };
    let mut result = result.map_err(|e| {
        let message = format!("{}: {e}", config.describe());
        // An invalid result is shatter's error, not the input's (exit 1, not 2).
        if matches!(e, shatter_geom::fracture::FractureError::Invalid(_)) {
            LabError::internal(message)
        } else {
            LabError::input(message)
        }
    })?;
    let warnings = std::mem::take(&mut result.warnings);
    Ok((result, warnings))
}

/// Fractures an already loaded model; returns the fracture, its warnings and the time in
/// ms (the attributes included).
pub fn fracture_timed(
    model: &Model,
    config: &FractureConfig,
) -> Result<(Fracture, Vec<String>, f64), LabError> {
    let start = Instant::now();
    let (fracture, warnings) = fracture(model, config)?;
    let millis = start.elapsed().as_secs_f64() * 1e3;
    Ok((fracture, warnings, millis))
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;
    use crate::fracture::source::load_source;
    use shatter_geom::DVec3;
    use shatter_geom::fracture::Method;
    use shatter_geom::shapes::Shape;

    #[test]
    fn a_grid_of_a_moved_box_stays_where_the_box_is() {
        let mut model = Model::from_mesh(Shape::Cube.mesh());
        model.mesh = model
            .mesh
            .transformed(DVec3::ONE, DVec3::new(5.0, 0.0, 0.0));
        let config = FractureConfig::shape(
            Shape::Cube,
            Method::Grid {
                cells: [2, 1, 1],
                voids: Vec::new(),
            },
            0,
        );
        let (f, warnings) = fracture(&model, &config).unwrap();
        assert!(warnings.is_empty());
        assert_eq!((f.fragments.len(), f.bonds.len()), (2, 1));
        let total: f64 = f.fragments.iter().map(|g| g.volume).sum();
        assert!((total - 1.0).abs() < 1e-9, "{total}");
        assert!((f.bonds[0].centroid - DVec3::new(5.0, 0.0, 0.0)).length() < 1e-9);
    }

    #[test]
    fn voronoi_of_the_cube_adds_up_to_its_volume() {
        let config = FractureConfig::shape(
            Shape::Cube,
            Method::voronoi(8, shatter_geom::fracture::Pattern::Uniform),
            1,
        );
        let (model, _) = load_source(&config).unwrap();
        let (f, _, ms) = fracture_timed(&model, &config).unwrap();
        assert!(ms >= 0.0);
        f.validate(Some(1.0)).unwrap();
    }
}
