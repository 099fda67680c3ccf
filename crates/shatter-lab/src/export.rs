//! Writing meshes and fractures: OBJ (with its MTL and the textures next to it) or GLB,
//! and the pre-fractured asset (a GLB with the `SHATTER_fracture` extension), each file
//! through a temporary file renamed into place. A failure to write is bad input (the
//! user's path: a full disk, a race); an export error from the writer is internal.

use std::path::Path;

use shatter_geom::TriMesh;
use shatter_geom::fracture::Fracture;
use shatter_geom::io::{self, ExportObject};
use shatter_geom::model::Material;
use shatter_geom::progress::Progress;

use crate::error::LabError;
use crate::output;

/// A mesh file format the writers here write.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MeshFormat {
    /// Wavefront OBJ.
    Obj,
    /// Binary glTF.
    Glb,
}

impl MeshFormat {
    /// Whether a fracture written in this format carries the fragments' convex pieces
    /// (a GLB is a pre-fractured asset, [`write_fracture`]; an OBJ has surfaces only), so
    /// whether a fracture to write in it needs them made
    /// ([`FractureConfig::convex_pieces`](crate::fracture::FractureConfig::convex_pieces)).
    pub fn carries_convex_pieces(self) -> bool {
        self == MeshFormat::Glb
    }

    /// The format of an output path, from its extension (case-insensitive).
    pub fn from_output_path(path: &Path) -> Result<Self, LabError> {
        let ext = path
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase);
        match ext.as_deref() {
            Some("obj") => Ok(Self::Obj),
            Some("glb") => Ok(Self::Glb),
            _ => Err(LabError::input(format!(
                "{}: unknown output format; use a .obj or .glb file name",
                path.display()
            ))),
        }
    }
}

/// Writes one mesh (no interior faces).
pub fn write_mesh(
    path: &Path,
    format: MeshFormat,
    mesh: &TriMesh,
    progress: &Progress,
) -> Result<(), LabError> {
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
) -> Result<(), LabError> {
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
) -> Result<(), LabError> {
    output::via_temp_path(path, progress, |temp| {
        io::save_fracture_glb(temp, fracture, meta).map_err(|e| match e {
            io::MeshIoError::Io { source, .. } => {
                LabError::input(format!("{}: cannot write: {source}", path.display()))
            }
            other => LabError::internal(format!("{}: export failed: {other}", path.display())),
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
) -> Result<(), LabError> {
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
) -> Result<(), LabError> {
    let materials = materials.filter(|m| !m.is_empty());
    let mapped = |e: io::MeshIoError| match e {
        // Failing to create or write the file: the user's path (checked up front, so
        // this is rare: a full disk, a race).
        io::MeshIoError::Io { source, .. } => {
            LabError::input(format!("{}: cannot write: {source}", path.display()))
        }
        // Anything else means shatter produced an inconsistent mesh: a bug.
        other => LabError::internal(format!("{}: export failed: {other}", path.display())),
    };
    let create = |temp: &Path| {
        std::fs::File::create(temp)
            .map(std::io::BufWriter::new)
            .map_err(|e| LabError::input(format!("{}: cannot write: {e}", path.display())))
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
                    .map_err(|e| LabError::input(format!("{}: cannot write: {e}", path.display())))
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
                .map_err(|e| LabError::input(format!("{}: cannot write: {e}", path.display())))
        }),
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;
    use shatter_geom::shapes::Shape;

    #[test]
    fn output_format_comes_from_the_extension() {
        assert_eq!(
            MeshFormat::from_output_path(Path::new("a/b.OBJ")).unwrap(),
            MeshFormat::Obj
        );
        assert_eq!(
            MeshFormat::from_output_path(Path::new("b.glb")).unwrap(),
            MeshFormat::Glb
        );
        assert!(MeshFormat::from_output_path(Path::new("b.stl")).is_err());
        assert!(MeshFormat::from_output_path(Path::new("b")).is_err());
    }

    #[test]
    fn a_mesh_is_written_as_obj_with_its_mtl_and_as_glb() {
        let dir = tempfile::tempdir().unwrap();
        let cube = Shape::Cube.mesh();
        let obj = dir.path().join("cube.obj");
        write_mesh(&obj, MeshFormat::Obj, &cube, &Progress::none()).unwrap();
        let text = std::fs::read_to_string(&obj).unwrap();
        assert!(text.contains("mtllib cube.mtl"), "{text}");
        assert_eq!(text.lines().filter(|l| l.starts_with("f ")).count(), 12);
        assert!(dir.path().join("cube.mtl").is_file());
        let glb = dir.path().join("cube.glb");
        write_mesh(&glb, MeshFormat::Glb, &cube, &Progress::none()).unwrap();
        assert_eq!(&std::fs::read(&glb).unwrap()[..4], b"glTF");
        let missing = dir.path().join("none/cube.obj");
        let e = write_mesh(&missing, MeshFormat::Obj, &cube, &Progress::none()).unwrap_err();
        assert!(matches!(e, LabError::Input(_)), "{e:?}");
    }
}
