//! Loading a model (or just its mesh) from a file or from bytes, by format.

use std::path::Path;

pub use super::context::MAX_TRIANGLES;
use super::context::ReadContext;
use super::files::{FileSource, FileSystem, NoFiles};
use super::{LoadWarning, MeshIoError, WarningKind, gltf, obj, stl};
use crate::TriMesh;
use crate::model::{Model, ModelError};

/// The mesh file formats shatter reads.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MeshFormat {
    /// Wavefront OBJ, with its MTL material libraries.
    Obj,
    /// STL, ASCII or binary (detected from the content).
    Stl,
    /// glTF 2.0 JSON with embedded (data URI) or external buffers and images.
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

    /// The format's usual name (`OBJ`, `STL`, `glTF`, `GLB`).
    pub fn name(self) -> &'static str {
        match self {
            Self::Obj => "OBJ",
            Self::Stl => "STL",
            Self::Gltf => "glTF",
            Self::Glb => "GLB",
        }
    }
}

/// A model read from a file, with what the reader tolerated.
#[derive(Debug, Clone, PartialEq)]
pub struct LoadedModel {
    /// The model (see [`Model`]; it passes [`Model::check`]).
    pub model: Model,
    /// What was skipped, missing or repaired while reading, in the order met.
    pub warnings: Vec<LoadWarning>,
}

/// Loads a model — mesh, UVs, normals, colours, materials and their textures — from an
/// `.obj` (with its MTL files), `.stl`, `.gltf` or `.glb` file. Files it refers to are
/// read relative to its folder, from the file system ([`load_model_from`] reads them
/// from any [`FileSource`]). See `docs/formats.md` for what each reader takes.
///
/// ```
/// use shatter_geom::{io, shapes};
/// let dir = std::env::temp_dir().join("shatter-doc-load-model");
/// std::fs::create_dir_all(&dir).unwrap();
/// let path = dir.join("cube.stl");
/// io::save_stl(&path, &shapes::cube(), io::StlFormat::Binary).unwrap();
/// let loaded = io::load_model(&path).unwrap();
/// assert_eq!(loaded.model.mesh.positions.len(), 8); // STL is welded
/// assert_eq!(loaded.model.materials.len(), 1);
/// assert!(loaded.warnings.is_empty());
/// ```
pub fn load_model(path: impl AsRef<Path>) -> Result<LoadedModel, MeshIoError> {
    load_model_from(path, &FileSystem)
}

/// [`load_model`], reading the file and every file it refers to from `files`.
///
/// ```
/// use shatter_geom::io::{self, MemoryFiles};
/// let files = MemoryFiles::new();
/// files.insert("dir/tri.obj", b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n".to_vec());
/// let loaded = io::load_model_from("dir/tri.obj", &files).unwrap();
/// assert_eq!(loaded.model.mesh.triangles.len(), 1);
/// ```
pub fn load_model_from(
    path: impl AsRef<Path>,
    files: &dyn FileSource,
) -> Result<LoadedModel, MeshIoError> {
    let path = path.as_ref();
    let format = MeshFormat::from_path(path).ok_or_else(|| MeshIoError::UnknownFormat {
        path: path.to_path_buf(),
    })?;
    let bytes = files.read(path).map_err(|e| MeshIoError::io(path, e))?;
    parse(&bytes, format, path, files)
}

/// Parses a model held in memory (a file picked in a browser, say). `name` is used in
/// messages and to resolve references; nothing else is read: a reference to another file
/// (an MTL, a texture, an external buffer) is a warning (or, for a buffer the geometry
/// needs, an error). [`parse_model_with`] takes those files too.
///
/// ```
/// use shatter_geom::io::{self, MeshFormat};
/// let obj = b"v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
/// let tet = io::parse_model(obj, MeshFormat::Obj, "tet.obj").unwrap();
/// assert!((tet.model.mesh.volume() - 1.0 / 6.0).abs() < 1e-12);
/// ```
pub fn parse_model(
    bytes: &[u8],
    format: MeshFormat,
    name: impl AsRef<Path>,
) -> Result<LoadedModel, MeshIoError> {
    parse(bytes, format, name.as_ref(), &NoFiles)
}

/// [`parse_model`], reading the files the model refers to from `files` (relative to
/// `name`'s folder; see [`MemoryFiles`](super::MemoryFiles) for how names are matched).
pub fn parse_model_with(
    bytes: &[u8],
    format: MeshFormat,
    name: impl AsRef<Path>,
    files: &dyn FileSource,
) -> Result<LoadedModel, MeshIoError> {
    parse(bytes, format, name.as_ref(), files)
}

/// Loads the triangle mesh of a file: [`load_model`]'s mesh, without the attributes,
/// materials and warnings. OBJ: every object and group, polygons ear-clipped. STL: the
/// triangle soup is welded (exactly equal corners merged). glTF: every triangle primitive
/// (lists, strips, fans) of every mesh instanced in the default scene (or the first, or
/// every mesh if there is no scene), with the node transforms applied. The mesh is not
/// validated as a solid: call [`TriMesh::validate_solid`] for that.
///
/// Errors name the file and the problem, and for OBJ the line.
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
    load_model(path).map(|l| l.model.mesh)
}

/// [`load_mesh`], reading the file and every file it refers to from `files`.
///
/// ```
/// use shatter_geom::io::{self, FileSystem, Layered, MemoryFiles};
/// let picked = MemoryFiles::new();
/// picked.insert("picked/tri.obj", b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n".to_vec());
/// // The picked files first, then the disk.
/// let mesh = io::load_mesh_from("picked/tri.obj", &Layered(&picked, FileSystem)).unwrap();
/// assert_eq!(mesh.triangles.len(), 1);
/// assert!(io::load_mesh("picked/tri.obj").is_err());
/// ```
pub fn load_mesh_from(
    path: impl AsRef<Path>,
    files: &dyn FileSource,
) -> Result<TriMesh, MeshIoError> {
    load_model_from(path, files).map(|l| l.model.mesh)
}

/// The mesh of a file's bytes, its format from `name`'s extension (see [`parse_mesh`];
/// files it refers to are not read).
///
/// ```
/// use shatter_geom::io;
/// let tet = b"v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
/// assert_eq!(io::load_mesh_from_bytes("tet.obj", tet).unwrap().triangles.len(), 4);
/// let err = io::load_mesh_from_bytes("tet.txt", tet).unwrap_err();
/// assert!(err.to_string().contains("tet.txt"), "{err}");
/// ```
pub fn load_mesh_from_bytes(name: impl AsRef<Path>, bytes: &[u8]) -> Result<TriMesh, MeshIoError> {
    let name = name.as_ref();
    let format = MeshFormat::from_path(name).ok_or_else(|| MeshIoError::UnknownFormat {
        path: name.to_path_buf(),
    })?;
    parse_mesh(bytes, format, name)
}

/// Parses the mesh of a file held in memory (see [`parse_model`]).
///
/// ```
/// use shatter_geom::io::{self, MeshFormat};
/// let err = io::parse_mesh(b"f 1 2 9\n", MeshFormat::Obj, "bad.obj").unwrap_err();
/// assert!(err.to_string().starts_with("bad.obj: line 1:"));
/// ```
pub fn parse_mesh(
    bytes: &[u8],
    format: MeshFormat,
    name: impl AsRef<Path>,
) -> Result<TriMesh, MeshIoError> {
    parse_model(bytes, format, name).map(|l| l.model.mesh)
}

fn parse(
    bytes: &[u8],
    format: MeshFormat,
    path: &Path,
    files: &dyn FileSource,
) -> Result<LoadedModel, MeshIoError> {
    let mut cx = ReadContext::new(path, files);
    let model = match format {
        MeshFormat::Obj => obj::read_obj(bytes, &mut cx)?,
        MeshFormat::Stl => stl::read_stl(bytes, &mut cx)?,
        MeshFormat::Gltf | MeshFormat::Glb => gltf::read_gltf(bytes, &mut cx)?,
    };
    if model.mesh.triangles.is_empty() {
        let prefix = format!("{}: ", path.display());
        let skipped: Vec<&str> = cx
            .warnings
            .iter()
            .filter(|w| w.kind == WarningKind::SkippedElements)
            .map(|w| w.message.strip_prefix(&prefix).unwrap_or(&w.message))
            .collect();
        return Err(MeshIoError::NoTriangles {
            path: path.to_path_buf(),
            found: if skipped.is_empty() {
                String::new()
            } else {
                format!(" ({})", skipped.join("; "))
            },
        });
    }
    if let Some(v) = model.mesh.positions.iter().position(|p| !p.is_finite()) {
        return Err(MeshIoError::NotFinite {
            path: path.to_path_buf(),
            vertex: v,
        });
    }
    // The readers build consistent models; a failure here is a reader bug, reported as
    // an error rather than passed on.
    model.check().map_err(|e| match e {
        ModelError::NotFinite {
            attribute,
            triangle,
        } => MeshIoError::NotFiniteAttribute {
            path: path.to_path_buf(),
            attribute,
            triangle,
        },
        other => MeshIoError::Inconsistent {
            path: path.to_path_buf(),
            message: other.to_string(),
        },
    })?;
    Ok(LoadedModel {
        model,
        warnings: cx.warnings,
    })
}
