//! The CLI's writers of meshes and fractures (OBJ with MTL and textures, GLB, the
//! pre-fractured asset) and its random points, with library errors mapped to exit codes
//! (bad input 2, internal 1). Loading, repairing and fracturing a mesh is
//! `shatter_lab::fracture`'s.

use std::path::Path;

use shatter_geom::fracture::Fracture;
use shatter_geom::io::{self, ExportObject};
use shatter_geom::model::Material;
use shatter_geom::progress::Progress;
use shatter_geom::sampling;
use shatter_geom::{DVec3, TriMesh};
use shatter_lab::output;

use crate::args::{Distribution, MeshFormat};
use crate::error::CliError;

/// `n` random points from `distribution`, reproducible from `seed`.
pub fn random_points(
    distribution: Distribution,
    n: usize,
    seed: u64,
) -> Result<Vec<DVec3>, CliError> {
    Ok(sampling::sample(distribution.sampling(), n, seed))
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
