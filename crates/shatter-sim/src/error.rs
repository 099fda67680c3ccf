//! The simulation's error type.

use thiserror::Error;

/// Everything that can go wrong when building or editing a simulation.
#[derive(Debug, Error, Clone, PartialEq)]
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
    #[error(
        "{key}: unknown material `{name}` (expected one of: {})",
        crate::material::MATERIAL_NAMES.join(", ")
    )]
    UnknownMaterial {
        /// The key holding the name.
        key: String,
        /// The unknown name.
        name: String,
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
    /// The fracture method cannot be run (e.g. not available in this build) or failed.
    #[error("{key}: fracture failed: {reason}")]
    Fracture {
        /// The object key.
        key: String,
        /// The reason reported by the fracture code.
        reason: String,
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
    #[error("{path}: {reason}")]
    Io {
        /// The file.
        path: String,
        /// The OS error.
        reason: String,
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
}
