//! Errors of mesh import and export.

use std::path::PathBuf;

use thiserror::Error;

/// A mesh file could not be read or written. Every variant names the file (or the
/// source given to an in-memory reader) and the problem.
#[derive(Debug, Error)]
pub enum MeshIoError {
    /// The file could not be opened, read or written.
    #[error("{path}: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// The operating system's error.
        source: std::io::Error,
    },
    /// The extension names no supported format.
    #[error("{path}: unknown mesh format (expected .obj, .stl, .gltf or .glb)")]
    UnknownFormat {
        /// The file.
        path: PathBuf,
    },
    /// A malformed OBJ file.
    #[error("{path}: {}{message}", line.map(|l| format!("line {l}: ")).unwrap_or_default())]
    Obj {
        /// The file.
        path: PathBuf,
        /// The 1-based line of the problem, where it can be located.
        line: Option<usize>,
        /// What is wrong.
        message: String,
    },
    /// A malformed STL file.
    #[error("{path}: {message}")]
    Stl {
        /// The file.
        path: PathBuf,
        /// What is wrong.
        message: String,
    },
    /// A malformed glTF or GLB file.
    #[error("{path}: {message}")]
    Gltf {
        /// The file.
        path: PathBuf,
        /// What is wrong.
        message: String,
    },
    /// The file is a glTF without the `SHATTER_fracture` extension (an ordinary mesh,
    /// not a pre-fractured asset).
    #[error(
        "{path}: no SHATTER_fracture extension: the file is not a pre-fractured shatter asset (write one with `shatter fracture ... --out FILE.glb`)"
    )]
    NoFractureExtension {
        /// The file.
        path: PathBuf,
    },
    /// The file's `SHATTER_fracture` extension is malformed (a bad index, a wrong
    /// length, a non-finite number, a bond to a missing fragment, ...).
    #[error("{path}: malformed SHATTER_fracture extension: {message}")]
    FractureExtension {
        /// The file.
        path: PathBuf,
        /// What is wrong, naming the node, bond or field.
        message: String,
    },
    /// The file holds no triangles.
    #[error("{path}: no triangles in the file{found}")]
    NoTriangles {
        /// The file.
        path: PathBuf,
        /// What the reader skipped instead, as `" (it skipped ...)"`, or empty.
        found: String,
    },
    /// A vertex has a NaN or infinite coordinate.
    #[error("{path}: vertex {vertex} has a non-finite coordinate")]
    NotFinite {
        /// The file.
        path: PathBuf,
        /// The vertex (0-based, in the order read).
        vertex: usize,
    },
    /// The file asks for more than shatter takes (triangles, nesting), refused before the
    /// memory is spent.
    #[error("{path}: {message}")]
    TooLarge {
        /// The file.
        path: PathBuf,
        /// What, and the limit.
        message: String,
    },
    /// An attribute value (UV, normal, colour) is NaN or infinite.
    #[error("{path}: {attribute} of triangle {triangle} is not finite")]
    NotFiniteAttribute {
        /// The file.
        path: PathBuf,
        /// Which attribute.
        attribute: &'static str,
        /// The triangle (0-based, in the order read).
        triangle: usize,
    },
    /// A reader produced a model whose parts disagree (a bug in shatter, not the file).
    #[error("{path}: internal error: the model read is inconsistent: {message}")]
    Inconsistent {
        /// The file.
        path: PathBuf,
        /// What disagrees.
        message: String,
    },
    /// An exported object's attributes do not fit its triangles or materials.
    #[error("object {object}: {message}")]
    BadObject {
        /// The object's name.
        object: String,
        /// What is wrong.
        message: String,
    },
    /// An exported object's interior flags do not match its triangles.
    #[error("object {object}: {flags} interior flags for {triangles} triangles")]
    InteriorFlags {
        /// The object's name.
        object: String,
        /// Number of flags given.
        flags: usize,
        /// Number of triangles.
        triangles: usize,
    },
    /// An exported mesh has a triangle index out of range.
    #[error("object {object}: triangle {triangle} references vertex {index} of {vertices}")]
    BadIndex {
        /// The object's name.
        object: String,
        /// The triangle.
        triangle: usize,
        /// The offending index.
        index: u32,
        /// Number of vertices.
        vertices: usize,
    },
}

impl MeshIoError {
    /// An I/O error on `path`.
    pub(crate) fn io(path: impl Into<PathBuf>, source: std::io::Error) -> Self {
        Self::Io {
            path: path.into(),
            source,
        }
    }
}
