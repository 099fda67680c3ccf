//! A validated fracture request (mesh, scale, method, seed) and its resource estimate:
//! what `shatter fracture` validates its flags into, and what the study and the benchmarks
//! build for their cases.

use std::path::PathBuf;

use shatter_geom::budget::{Estimate, format_count};
use shatter_geom::fracture::{Method, Seeds};
use shatter_geom::shapes::Shape;
use shatter_geom::{DVec3, TriMesh};

use crate::context::Context;
use crate::error::LabError;

/// Where the mesh comes from.
#[derive(Debug, Clone)]
pub enum MeshSource {
    /// A mesh file.
    File(PathBuf),
    /// A built-in shape.
    Shape(Shape),
}

/// A fully validated fracture request.
#[derive(Debug, Clone)]
pub struct FractureConfig {
    /// The mesh.
    pub source: MeshSource,
    /// Its scale.
    pub scale: DVec3,
    /// Method and parameters.
    pub method: Method,
    /// Random seed.
    pub seed: u64,
    /// Refuse a file that is not a valid solid instead of repairing it.
    pub strict: bool,
    /// Decompose the fragments into convex pieces, their collision shapes (a GLB carries
    /// them, an OBJ does not). Without, the fracture is the same but for the pieces, and
    /// about 40 % faster ([`fracture_model_surfaces`](shatter_geom::fracture::fracture_model_surfaces)).
    pub convex_pieces: bool,
}

impl FractureConfig {
    /// A built-in shape at unit scale cut by `method` with `seed` (strict: a shape is a
    /// valid solid).
    pub fn shape(shape: Shape, method: Method, seed: u64) -> Self {
        Self {
            source: MeshSource::Shape(shape),
            scale: DVec3::ONE,
            method,
            seed,
            strict: true,
            convex_pieces: true,
        }
    }

    /// A one-line description of the method and its parameters.
    pub fn describe(&self) -> String {
        let method = match &self.method {
            Method::Tetra {
                random_vertices,
                skip,
                center,
                placement,
            } => format!(
                "tetra, {random_vertices} random vertices ({placement:?}), skip {skip}, center {center}"
            ),
            Method::Voronoi { seeds } => match seeds {
                Seeds::Pattern {
                    count,
                    pattern,
                    impact,
                } => {
                    let seeds = format!("{count} {pattern:?} seeds");
                    match impact {
                        Some(i) => format!("voronoi, {seeds}, impact {},{},{}", i.x, i.y, i.z),
                        None => format!("voronoi, {seeds}"),
                    }
                }
                Seeds::Points(p) => format!("voronoi, {} seeds from a file", p.len()),
            },
            Method::Slice { pieces, planes } => match planes {
                Some(list) => format!("slice, {} given planes", list.len()),
                None => format!("slice, {pieces} planes"),
            },
            Method::Grid {
                cells: [x, y, z],
                voids,
            } => match voids.len() {
                0 => format!("grid, {x}x{y}x{z} cells"),
                n => format!("grid, {x}x{y}x{z} cells, {n} voids"),
            },
        };
        format!("{method}, seed {}", self.seed)
    }
}

/// The estimate of fracturing `mesh` as `config` says, and what it is called in a
/// refusal ("--random-vertices 4,000,000,000: a tetra fracture of 4,000,000,958 points").
pub fn fracture_estimate(mesh: &TriMesh, config: &FractureConfig) -> (String, Estimate) {
    let triangles = mesh.triangles.len() as u64;
    match &config.method {
        Method::Tetra {
            random_vertices,
            skip,
            center,
            ..
        } => {
            let surface = (mesh.positions.len() as u64).div_ceil(*skip as u64 + 1);
            let points = surface
                .saturating_add(*random_vertices as u64)
                .saturating_add(u64::from(*center));
            (
                format!(
                    "--random-vertices {random_vertices}: a tetra fracture of {} points",
                    format_count(points)
                ),
                Estimate::tetra_fracture(points, surface).with_process(),
            )
        }
        Method::Voronoi { seeds } => {
            let (flag, cells) = match seeds {
                Seeds::Pattern { count, .. } => (format!("--pieces {count}"), *count),
                Seeds::Points(p) => ("--seeds-file".to_string(), p.len()),
            };
            (
                format!(
                    "{flag}: {} Voronoi cells of a {}-triangle mesh",
                    format_count(cells as u64),
                    format_count(triangles)
                ),
                Estimate::voronoi_fracture(cells as u64, triangles).with_process(),
            )
        }
        Method::Slice { pieces, planes } => {
            let planes = planes.as_ref().map_or(*pieces, Vec::len);
            (
                format!(
                    "--pieces {planes}: {} slice planes (about {} pieces)",
                    format_count(planes as u64),
                    format_count(shatter_geom::budget::slice_pieces(planes as u64) as u64)
                ),
                Estimate::slice_fracture(planes as u64, triangles).with_process(),
            )
        }
        Method::Grid { cells, .. } => {
            let n: f64 = cells.iter().map(|&c| f64::from(c)).product();
            let boxed = shatter_geom::budget::is_box(mesh);
            (
                format!(
                    "--grid {},{},{}: {} {}",
                    cells[0],
                    cells[1],
                    cells[2],
                    format_count(n as u64),
                    if boxed { "bricks" } else { "cells" }
                ),
                Estimate::grid_fracture(*cells, triangles, boxed).with_process(),
            )
        }
    }
}

/// Refuses a fracture whose estimate does not fit the limits; returns the estimate.
pub fn check_fracture(
    ctx: &Context,
    mesh: &TriMesh,
    config: &FractureConfig,
) -> Result<Estimate, LabError> {
    let (what, estimate) = fracture_estimate(mesh, config);
    ctx.check(&what, &estimate)?;
    Ok(estimate)
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;
    use shatter_geom::budget::Limits;
    use shatter_geom::fracture::{Pattern, Placement};

    #[test]
    fn a_request_describes_its_method_and_seed() {
        let c = FractureConfig::shape(Shape::Cube, Method::voronoi(20, Pattern::Uniform), 3);
        assert_eq!(c.describe(), "voronoi, 20 Uniform seeds, seed 3");
        let c = FractureConfig::shape(
            Shape::Cube,
            Method::Grid {
                cells: [2, 3, 4],
                voids: Vec::new(),
            },
            0,
        );
        assert_eq!(c.describe(), "grid, 2x3x4 cells, seed 0");
    }

    #[test]
    fn estimates_grow_with_the_request_and_name_its_flag() {
        let cube = Shape::Cube.mesh();
        let tetra =
            |n| FractureConfig::shape(Shape::Cube, Method::tetra(n, Placement::Interior), 0);
        let (what, small) = fracture_estimate(&cube, &tetra(10));
        assert_eq!(what, "--random-vertices 10: a tetra fracture of 34 points");
        let (_, large) = fracture_estimate(&cube, &tetra(1_000_000));
        assert!(large.bytes > small.bytes && large.seconds > small.seconds);
        let huge = tetra(4_000_000_000);
        let ctx = Context::quiet(Limits {
            memory_bytes: Some(24_000_000_000),
            seconds: None,
            memory_source: "test",
        });
        let e = check_fracture(&ctx, &cube, &huge).unwrap_err();
        assert!(
            e.to_string().contains("--random-vertices 4000000000"),
            "{e}"
        );
        assert!(check_fracture(&ctx, &cube, &tetra(10)).is_ok());
    }
}
