//! The CLI's one door into `shatter-geom`: every library call the commands make goes
//! through here, with library errors mapped to exit codes (bad input 2, internal 1).

use std::path::Path;

use shatter_geom::fracture::{Fracture, FractureParams, Method, Pattern};
use shatter_geom::io::{self, ExportObject};
use shatter_geom::mesh::repair::{RepairOptions, RepairReport};
use shatter_geom::model::{Material, Model};
use shatter_geom::progress::Progress;
use shatter_geom::sampling;
use shatter_geom::shapes::Shape;
use shatter_geom::{DVec3, TriMesh};

use crate::args::{Distribution, MeshFormat};
use crate::commands::fracture::{FractureConfig, MethodConfig, VoronoiSeeds};
use crate::error::CliError;
use crate::output;

/// `n` random points from `distribution`, reproducible from `seed`.
pub fn random_points(
    distribution: Distribution,
    n: usize,
    seed: u64,
) -> Result<Vec<DVec3>, CliError> {
    let d = match distribution {
        Distribution::Uniform => sampling::Distribution::Uniform,
        Distribution::Ball => sampling::Distribution::Ball,
        Distribution::Sphere => sampling::Distribution::Sphere,
        Distribution::Gaussian => sampling::Distribution::Gaussian,
        Distribution::Grid => sampling::Distribution::Grid,
    };
    Ok(sampling::sample(d, n, seed))
}

/// A built-in shape at unit scale.
pub fn builtin_shape(name: Shape) -> Result<TriMesh, CliError> {
    shatter_geom::shapes::by_name(name.name())
        .ok_or_else(|| CliError::internal(format!("built-in shape '{name}' is missing")))
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
pub fn validate_model(model: &mut Model, origin: &str) -> Result<Option<String>, CliError> {
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
pub fn validate_solid(mesh: &mut TriMesh, origin: &str) -> Result<Option<String>, CliError> {
    match mesh.orient_outward() {
        Ok(false) => Ok(None),
        Ok(true) => Ok(Some(format!(
            "{origin}: the mesh was wound inward; flipped it"
        ))),
        Err(e) => Err(CliError::input(format!("{origin}: {e}"))),
    }
}

/// Repairs a model read from `origin` into a closed solid (`mesh::repair` with its
/// default options). A model with nothing solid in it is bad input (exit code 2),
/// named by `origin` ("sheet.obj: 12 open sheets and no closed part").
pub fn repair(
    model: &shatter_geom::model::Model,
    origin: &str,
) -> Result<(shatter_geom::model::Model, RepairReport), CliError> {
    shatter_geom::mesh::repair::repair(model, &RepairOptions::default())
        .map_err(|e| CliError::input(format!("{origin}: {e}")))
}

/// Loads a model (mesh, attributes, materials) with the reader's warnings. Every
/// failure is bad input (exit code 2), named by the file.
pub fn load_model(path: &Path) -> Result<io::LoadedModel, CliError> {
    if !path.exists() {
        return Err(CliError::input(format!("{}: no such file", path.display())));
    }
    io::load_model(path).map_err(CliError::input)
}

/// Writes one mesh (no interior faces).
pub fn write_mesh(
    path: &Path,
    format: MeshFormat,
    mesh: &TriMesh,
    progress: &Progress,
) -> Result<(), CliError> {
    let name = path
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "mesh".to_string());
    save(path, format, &[ExportObject::new(&name, mesh)], progress)
}

/// Writes a fracture: one object (OBJ `o fragment_i`) or node (GLB) per fragment with
/// its corner attributes (UVs, normals, colours), each triangle under its material of
/// [`Fracture::materials`] (the input's, then `interior` for the cut faces). A GLB embeds
/// the textures and is a pre-fractured asset ([`write_fracture_asset`], no anchors or
/// material); an OBJ's MTL file references them, copied next to it.
pub fn write_fracture(
    path: &Path,
    format: MeshFormat,
    fracture: &Fracture,
    progress: &Progress,
) -> Result<(), CliError> {
    if format == MeshFormat::Glb {
        return write_fracture_asset(path, fracture, &io::FractureAssetMeta::default(), progress);
    }
    let names = io::fragment_names(fracture.fragments.len());
    let objects = ExportObject::of_fragments(&fracture.fragments, &names);
    save_with(path, format, &objects, Some(&fracture.materials), progress)
}

/// Writes a fracture as a pre-fractured asset: a GLB with the `SHATTER_fracture`
/// extension (convex pieces, mass properties, bonds, and `meta`'s anchors, material and
/// thresholds), through a temporary file renamed into place.
pub fn write_fracture_asset(
    path: &Path,
    fracture: &Fracture,
    meta: &io::FractureAssetMeta,
    progress: &Progress,
) -> Result<(), CliError> {
    output::via_temp_path(path, progress, |temp| {
        io::save_fracture_glb(temp, fracture, meta).map_err(|e| match e {
            io::MeshIoError::Io { source, .. } => {
                CliError::input(format!("{}: cannot write: {source}", path.display()))
            }
            other => CliError::internal(format!("{}: export failed: {other}", path.display())),
        })
    })
}

/// Writes the objects through temporary files renamed into place (an interrupted or
/// failed write leaves no partial output). An OBJ's `.mtl` is written next to it, under
/// the final name its `mtllib` line gives.
fn save(
    path: &Path,
    format: MeshFormat,
    objects: &[ExportObject<'_>],
    progress: &Progress,
) -> Result<(), CliError> {
    save_with(path, format, objects, None, progress)
}

/// [`save`] with a material list (`None` or empty: `surface` / `interior`); an OBJ's
/// textures are written next to it, each through a temporary file.
fn save_with(
    path: &Path,
    format: MeshFormat,
    objects: &[ExportObject<'_>],
    materials: Option<&[Material]>,
    progress: &Progress,
) -> Result<(), CliError> {
    let materials = materials.filter(|m| !m.is_empty());
    let mapped = |e: io::MeshIoError| match e {
        // Failing to create or write the file: the user's path (checked up front, so
        // this is rare: a full disk, a race).
        io::MeshIoError::Io { source, .. } => {
            CliError::input(format!("{}: cannot write: {source}", path.display()))
        }
        // Anything else means shatter produced an inconsistent mesh: a bug.
        other => CliError::internal(format!("{}: export failed: {other}", path.display())),
    };
    let create = |temp: &Path| {
        std::fs::File::create(temp)
            .map(std::io::BufWriter::new)
            .map_err(|e| CliError::input(format!("{}: cannot write: {e}", path.display())))
    };
    match format {
        MeshFormat::Obj => {
            let mtl_path = path.with_extension("mtl");
            let mtl_name = mtl_path
                .file_name()
                .map(|n| n.to_string_lossy().into_owned())
                .unwrap_or_else(|| "materials.mtl".into());
            // The material file first: the OBJ, the output that matters, is renamed
            // into place last.
            match materials {
                Some(list) => {
                    let stem = path
                        .file_stem()
                        .map(|s| s.to_string_lossy().into_owned())
                        .unwrap_or_else(|| "model".into());
                    let (names, files) = io::texture_files(&stem, list);
                    let dir = match path.parent() {
                        Some(d) if !d.as_os_str().is_empty() => d,
                        _ => Path::new("."),
                    };
                    for f in &files {
                        output::write_file(&dir.join(&f.name), progress, |w| {
                            w.write_all(&f.image.bytes)
                        })?;
                    }
                    output::write_file(&mtl_path, progress, |w| {
                        io::write_mtl_with_materials(w, list, &names)
                    })?;
                }
                None => output::write_file(&mtl_path, progress, |w| io::write_mtl(w))?,
            }
            output::via_temp_path(path, progress, |temp| {
                let mut out = create(temp)?;
                io::write_obj_with_materials(&mut out, objects, materials, Some(&mtl_name))
                    .map_err(mapped)?;
                std::io::Write::flush(&mut out)
                    .map_err(|e| CliError::input(format!("{}: cannot write: {e}", path.display())))
            })
        }
        MeshFormat::Glb => output::via_temp_path(path, progress, |temp| {
            let mut out = create(temp)?;
            match materials {
                Some(list) => io::write_glb_with_materials(&mut out, objects, list),
                None => io::write_glb(&mut out, objects),
            }
            .map_err(mapped)?;
            std::io::Write::flush(&mut out)
                .map_err(|e| CliError::input(format!("{}: cannot write: {e}", path.display())))
        }),
    }
}

/// Fractures `mesh` as `config` says; returns the fracture and its warnings (an inward
/// mesh that was flipped, merged slivers, ...). Every library error describes the input
/// (the mesh or the parameters), so it is bad input (exit code 2).
pub fn fracture(
    model: &Model,
    config: &FractureConfig,
) -> Result<(Fracture, Vec<String>), CliError> {
    if let MethodConfig::Grid { cells } = config.method {
        return Ok((grid_fracture(model, cells)?, Vec::new()));
    }
    let Some(method) = method_params(&config.method) else {
        return Err(CliError::input(format!(
            "{}: not a shatter_geom method",
            config.describe()
        )));
    };
    let params = FractureParams {
        method,
        seed: config.seed,
    };
    let mut result = shatter_geom::fracture::fracture_model(model, &params)
        .map_err(|e| CliError::input(format!("{}: {e}", config.describe())))?;
    let warnings = std::mem::take(&mut result.warnings);
    Ok((result, warnings))
}

/// The box `model` spans (`--shape cube`, scaled) cut into `cells` bricks, bonded across
/// every shared face.
fn grid_fracture(model: &Model, cells: [u32; 3]) -> Result<Fracture, CliError> {
    let (lo, hi) = model
        .mesh
        .bounds()
        .ok_or_else(|| CliError::input("--method grid: the mesh has no vertices"))?;
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
