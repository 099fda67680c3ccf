//! Loading a mesh from a file, by its extension.

use std::path::Path;

use super::{MeshIoError, gltf_read, obj_read, stl};
use crate::TriMesh;

/// The mesh file formats shatter reads.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MeshFormat {
    /// Wavefront OBJ (polygons are triangulated).
    Obj,
    /// STL, ASCII or binary (detected from the content).
    Stl,
    /// glTF 2.0 JSON with embedded (data URI) or external buffers.
    Gltf,
    /// Binary glTF 2.0.
    Glb,
}

impl MeshFormat {
    /// The format named by a file's extension (case-insensitive), if any.
    ///
    /// ```
    /// use shatter_geom::io::MeshFormat;
    /// assert_eq!(MeshFormat::from_path("bird.OBJ"), Some(MeshFormat::Obj));
    /// assert_eq!(MeshFormat::from_path("bird.fbx"), None);
    /// ```
    pub fn from_path(path: impl AsRef<Path>) -> Option<Self> {
        let ext = path.as_ref().extension()?.to_str()?.to_ascii_lowercase();
        match ext.as_str() {
            "obj" => Some(Self::Obj),
            "stl" => Some(Self::Stl),
            "gltf" => Some(Self::Gltf),
            "glb" => Some(Self::Glb),
            _ => None,
        }
    }
}

/// Loads a triangle mesh from an `.obj`, `.stl` (ASCII or binary), `.gltf` or `.glb`
/// file. OBJ: every object and group, polygons fan-triangulated. STL: the triangle soup
/// is welded (exactly equal corners merged). glTF: every triangle primitive (lists,
/// strips, fans) of every mesh instanced in the default scene (or the first, or every
/// mesh if there is no scene), with the node transforms applied. The mesh is not
/// validated as a solid: call [`TriMesh::validate_solid`] for that.
///
/// Errors name the file and the problem, and for OBJ the line where it can be located.
/// A file registered with [`add_memory_file`](super::add_memory_file) under this name is
/// read from memory instead of the file system.
///
/// ```
/// use shatter_geom::{io, shapes};
/// let dir = std::env::temp_dir().join("shatter-doc-load");
/// std::fs::create_dir_all(&dir).unwrap();
/// let path = dir.join("cube.stl");
/// io::save_stl(&path, &shapes::cube(), io::StlFormat::Binary).unwrap();
/// let cube = io::load_mesh(&path).unwrap();
/// assert_eq!(cube.positions.len(), 8); // welded
/// assert_eq!(cube.volume(), 1.0);
/// let err = io::load_mesh(dir.join("missing.obj")).unwrap_err();
/// assert!(err.to_string().contains("missing.obj"));
/// ```
pub fn load_mesh(path: impl AsRef<Path>) -> Result<TriMesh, MeshIoError> {
    let path = path.as_ref();
    let format = MeshFormat::from_path(path).ok_or_else(|| MeshIoError::UnknownFormat {
        path: path.to_path_buf(),
    })?;
    if let Some(bytes) = super::memory_file(path) {
        return parse(&bytes, format, path, None);
    }
    let bytes = std::fs::read(path).map_err(|e| MeshIoError::io(path, e))?;
    let base = path.parent().map(|p| {
        if p.as_os_str().is_empty() {
            Path::new(".")
        } else {
            p
        }
    });
    parse(&bytes, format, path, base)
}

/// Parses a mesh held in memory (for example a file picked in a browser). `name` is used
/// in error messages. A `.gltf` with external buffer files cannot be read this way.
///
/// ```
/// use shatter_geom::io::{self, MeshFormat};
/// let obj = b"v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
/// let tet = io::parse_mesh(obj, MeshFormat::Obj, "tet.obj").unwrap();
/// assert!((tet.volume() - 1.0 / 6.0).abs() < 1e-12);
/// let err = io::parse_mesh(b"f 1 2 9\n", MeshFormat::Obj, "bad.obj").unwrap_err();
/// assert!(err.to_string().starts_with("bad.obj: line 1:"));
/// ```
pub fn parse_mesh(
    bytes: &[u8],
    format: MeshFormat,
    name: impl AsRef<Path>,
) -> Result<TriMesh, MeshIoError> {
    parse(bytes, format, name.as_ref(), None)
}

fn parse(
    bytes: &[u8],
    format: MeshFormat,
    path: &Path,
    base: Option<&Path>,
) -> Result<TriMesh, MeshIoError> {
    let mesh = match format {
        MeshFormat::Obj => obj_read::read_obj(bytes, path)?,
        MeshFormat::Stl => stl::read_stl(bytes, path)?,
        MeshFormat::Gltf | MeshFormat::Glb => gltf_read::read_gltf(bytes, path, base)?,
    };
    if mesh.triangles.is_empty() {
        return Err(MeshIoError::NoTriangles {
            path: path.to_path_buf(),
        });
    }
    Ok(mesh)
}
