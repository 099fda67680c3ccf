//! The simulation's error type.

use shatter_geom::fracture::FractureError;
use shatter_geom::io::MeshIoError;
use shatter_geom::mesh::repair::RepairError;
use thiserror::Error;

/// Everything that can go wrong when building or editing a simulation.
///
/// The library errors it comes from stay its [`source`](std::error::Error::source):
///
/// ```
/// use std::error::Error;
/// use shatter_sim::{FractureSource, ObjectSpec, SimError, World, WorldSettings};
/// let mut world = World::new(WorldSettings::default());
/// let mut spec = ObjectSpec::from_fracture(Default::default(), [0.0; 3].into());
/// spec.source = FractureSource::MeshFile { path: "no/such.obj".into(), params: Default::default() };
/// let e = world.add_object(spec).unwrap_err();
/// assert!(matches!(e, SimError::Mesh { .. }));
/// assert!(e.source().unwrap().downcast_ref::<shatter_geom::io::MeshIoError>().is_some());
/// ```
#[derive(Debug, Error)]
pub enum SimError {
    /// A parameter has a value outside its domain; `key` names it (e.g. `objects[2].scale`).
    #[error("{key}: {reason}")]
    InvalidParameter {
        /// The offending key or parameter name.
        key: String,
        /// What is wrong with it.
        reason: String,
    },
    /// A material preset name that does not exist.
    #[error("{key}: unknown material `{name}` (expected one of: {})", valid.join(", "))]
    UnknownMaterial {
        /// The key holding the name.
        key: String,
        /// The unknown name.
        name: String,
        /// The preset names there are.
        valid: &'static [&'static str],
    },
    /// A shape name that does not exist.
    #[error(
        "{key}: unknown shape `{name}` (expected one of: {})",
        shatter_geom::shapes::NAMES.join(", ")
    )]
    UnknownShape {
        /// The key holding the name.
        key: String,
        /// The unknown name.
        name: String,
    },
    /// The fracture produced nothing simulable.
    #[error("{key}: fracture has no fragment with a valid collider ({reason})")]
    EmptyFracture {
        /// The object key.
        key: String,
        /// Why.
        reason: String,
    },
    /// The fracture failed (the mesh or the parameters); `key` names the object.
    #[error("{key}: fracture failed: {source}")]
    Fracture {
        /// The object key (or `….roughness` for the roughening of its cut faces).
        key: String,
        /// What the fracture reported.
        #[source]
        source: FractureError,
    },
    /// An object's mesh file could not be repaired into a solid.
    #[error("{key}: {path}: {source}")]
    Repair {
        /// The object key.
        key: String,
        /// The mesh file.
        path: String,
        /// What the repair reported.
        #[source]
        source: RepairError,
    },
    /// A mesh file could not be read or parsed.
    #[error("{path}: {}", mesh_reason(path, source))]
    Mesh {
        /// The file.
        path: String,
        /// What the reader reported (its message names the file too; shown once).
        #[source]
        source: MeshIoError,
    },
    /// A scene file could not be parsed; `line` and `column` are 1-based.
    #[error("line {line}, column {column}: {message}")]
    SceneSyntax {
        /// 1-based line.
        line: usize,
        /// 1-based column.
        column: usize,
        /// The parser's message (names the key when the parser knows it).
        message: String,
    },
    /// A file could not be read.
    #[error("{path}: {source}")]
    Io {
        /// The file.
        path: String,
        /// The OS error.
        #[source]
        source: std::io::Error,
    },
    /// No object has this id.
    #[error("no object with id {0}")]
    NoSuchObject(u32),
}

impl SimError {
    /// Shorthand for [`SimError::InvalidParameter`].
    pub fn invalid(key: impl Into<String>, reason: impl Into<String>) -> Self {
        SimError::InvalidParameter {
            key: key.into(),
            reason: reason.into(),
        }
    }

    /// A mesh file's error, its file named once.
    pub fn mesh(path: impl Into<String>, source: MeshIoError) -> Self {
        SimError::Mesh {
            path: path.into(),
            source,
        }
    }
}

/// The reader's message without its leading `path: ` (the error prints the path itself).
fn mesh_reason(path: &str, e: &MeshIoError) -> String {
    let message = e.to_string();
    message
        .strip_prefix(path)
        .and_then(|r| r.strip_prefix(": "))
        .unwrap_or(&message)
        .to_string()
}
