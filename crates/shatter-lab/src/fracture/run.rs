//! Running a fracture request: a `shatter_geom` method, or the grid of bricks that
//! `shatter_sim` builds.

use std::time::Instant;

use shatter_geom::DVec3;
use shatter_geom::fracture::{Fracture, FractureParams, Method, Pattern};
use shatter_geom::model::Model;

use super::request::{FractureConfig, MethodConfig, VoronoiSeeds};
use crate::error::LabError;

/// Fractures `model` as `config` says; returns the fracture and its warnings (merged
/// slivers, ...). Every library error describes the input (the mesh or the parameters),
/// so it is bad input.
pub fn fracture(
    model: &Model,
    config: &FractureConfig,
) -> Result<(Fracture, Vec<String>), LabError> {
    if let MethodConfig::Grid { cells } = config.method {
        return Ok((grid_fracture(model, cells)?, Vec::new()));
    }
    let Some(method) = method_params(&config.method) else {
        return Err(LabError::input(format!(
            "{}: not a shatter_geom method",
            config.describe()
        )));
    };
    let params = FractureParams {
        method,
        seed: config.seed,
    };
    let mut result = shatter_geom::fracture::fracture_model(model, &params)
        .map_err(|e| LabError::input(format!("{}: {e}", config.describe())))?;
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

/// The box `model` spans (`--shape cube`, scaled) cut into `cells` bricks, bonded across
/// every shared face.
fn grid_fracture(model: &Model, cells: [u32; 3]) -> Result<Fracture, LabError> {
    let (lo, hi) = model
        .mesh
        .bounds()
        .ok_or_else(|| LabError::input("--method grid: the mesh has no vertices"))?;
    let mut fracture = shatter_sim::testing::box_grid_fracture(cells, hi - lo);
    let centre = (lo + hi) / 2.0;
    if centre != DVec3::ZERO {
        for f in &mut fracture.fragments {
            f.mesh.positions.iter_mut().for_each(|p| *p += centre);
            f.convex_pieces
                .iter_mut()
                .flatten()
                .for_each(|p| *p += centre);
            f.centroid += centre;
        }
        for bond in &mut fracture.bonds {
            bond.centroid += centre;
        }
    }
    Ok(fracture)
}

/// The `shatter_geom` method of `method` (`None` for the grid, which `shatter_sim` builds).
fn method_params(method: &MethodConfig) -> Option<Method> {
    Some(match method {
        MethodConfig::Tetra {
            random_vertices,
            skip,
            center,
            placement,
        } => Method::Tetra {
            random_vertices: *random_vertices,
            skip: *skip,
            center: *center,
            placement: *placement,
        },
        MethodConfig::Voronoi { seeds, impact } => {
            let (pieces, pattern, seeds) = match seeds {
                VoronoiSeeds::Pattern { count, pattern } => (*count, *pattern, None),
                VoronoiSeeds::Points(points) => {
                    (points.len(), Pattern::Uniform, Some(points.clone()))
                }
            };
            Method::Voronoi {
                pieces,
                pattern,
                impact: *impact,
                seeds,
            }
        }
        MethodConfig::Slice { planes } => Method::Slice {
            pieces: *planes,
            planes: None,
        },
        MethodConfig::Grid { .. } => return None,
    })
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;
    use crate::fracture::source::load_source;
    use shatter_geom::shapes::Shape;

    #[test]
    fn a_grid_of_a_moved_box_stays_where_the_box_is() {
        let mut model = Model::from_mesh(Shape::Cube.mesh());
        model.mesh = model
            .mesh
            .transformed(DVec3::ONE, DVec3::new(5.0, 0.0, 0.0));
        let config = FractureConfig::shape(Shape::Cube, MethodConfig::Grid { cells: [2, 1, 1] }, 0);
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
            MethodConfig::voronoi(8, shatter_geom::fracture::Pattern::Uniform),
            1,
        );
        let (model, _) = load_source(&config).unwrap();
        let (f, _, ms) = fracture_timed(&model, &config).unwrap();
        assert!(ms >= 0.0);
        f.validate(Some(1.0)).unwrap();
    }
}
