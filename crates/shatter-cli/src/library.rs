//! The CLI's one door into `shatter-geom`: every library call the commands make goes
//! through here, with library errors mapped to exit codes (bad input 2, internal 1).

use std::path::Path;

use shatter_geom::fracture::Fracture;
use shatter_geom::{DVec3, TriMesh};

use crate::args::{Distribution, MeshFormat, ShapeName};
use crate::error::CliError;

fn not_landed(what: &str) -> CliError {
    CliError::internal(format!(
        "{what} is not available in this build of shatter-geom"
    ))
}

/// `n` random points from `distribution`, reproducible from `seed`.
pub fn random_points(
    distribution: Distribution,
    n: usize,
    seed: u64,
) -> Result<Vec<DVec3>, CliError> {
    let _ = (distribution, n, seed);
    Err(not_landed("random point sampling"))
}

/// A built-in shape at unit scale.
pub fn builtin_shape(name: ShapeName) -> Result<TriMesh, CliError> {
    shatter_geom::shapes::by_name(name.as_str())
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

/// Loads a mesh file (OBJ, STL or GLB/glTF, by extension).
pub fn load_mesh(path: &Path) -> Result<TriMesh, CliError> {
    if !path.is_file() {
        return Err(CliError::input(format!("{}: no such file", path.display())));
    }
    Err(not_landed("mesh import"))
}

/// Writes one mesh.
pub fn write_mesh(path: &Path, format: MeshFormat, mesh: &TriMesh) -> Result<(), CliError> {
    let _ = (path, format, mesh);
    Err(not_landed("mesh export"))
}

/// Writes a fracture: one object / node per fragment, interior faces in their own material.
pub fn write_fracture(
    path: &Path,
    format: MeshFormat,
    fracture: &Fracture,
) -> Result<(), CliError> {
    let _ = (path, format, fracture);
    Err(not_landed("fracture export"))
}

/// Fractures `mesh` as `config` says; returns the fracture and any warnings (such as an
/// inward mesh that was flipped).
pub fn fracture(
    mesh: &TriMesh,
    config: &crate::commands::fracture::FractureConfig,
) -> Result<(Fracture, Vec<String>), CliError> {
    let _ = mesh;
    Err(not_landed(&format!("fracture ({})", config.describe())))
}
