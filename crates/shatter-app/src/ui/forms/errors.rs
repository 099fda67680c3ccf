//! The errors of the forms: one [`FormError`] per failed field, gathered in
//! [`FieldErrors`]; and the [`MeshCheck`] the forms call for a custom mesh.

use std::collections::BTreeMap;
use std::fmt;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use shatter_sim::ProjectileShape;
use thiserror::Error;

use crate::commands::MethodKind;
use crate::error::AppError;
use crate::scene_store::StoreError;
use crate::ui::fields::FieldError;

/// Why one field of a form is refused. Its `Display` is the message shown next to the
/// field. Errors that are not `Clone` ([`AppError`], [`StoreError`]) are shared.
#[derive(Debug, Clone, Error)]
pub enum FormError {
    /// The text does not parse into the field's value.
    #[error(transparent)]
    Field(#[from] FieldError),
    /// Custom shape chosen, but no path given.
    #[error("give the path of an OBJ, STL or glTF file")]
    NoMeshPath,
    /// A built-in projectile shape with no primitive collider whose mesh spans no extent.
    #[error("this shape has no extent to fire")]
    FlatProjectile,
    /// A fracture method other than tetrahedra asked for no pieces.
    #[error("{} needs at least 1 piece", method.name())]
    NoPieces {
        /// The method.
        method: MethodKind,
    },
    /// The scene field is empty.
    #[error("give a file name ending in .toml")]
    NoScenePath,
    /// The scene field does not name a `.toml` file.
    #[error("'{path}' does not end in .toml")]
    NotToml {
        /// The text of the field.
        path: String,
    },
    /// Load: no scene file of this name.
    #[error("no file '{}'", path.display())]
    NoSceneFile {
        /// The file.
        path: PathBuf,
    },
    /// Save: the scene store cannot save here.
    #[error(transparent)]
    Store(Arc<StoreError>),
    /// The custom mesh check, or the simulation, refused it.
    #[error(transparent)]
    App(Arc<AppError>),
}

impl From<AppError> for FormError {
    fn from(e: AppError) -> Self {
        FormError::App(Arc::new(e))
    }
}

impl From<StoreError> for FormError {
    fn from(e: StoreError) -> Self {
        FormError::Store(Arc::new(e))
    }
}

/// Two form errors are equal when they are of the same kind and say the same (the shared
/// library errors have no equality of their own).
impl PartialEq for FormError {
    fn eq(&self, other: &Self) -> bool {
        std::mem::discriminant(self) == std::mem::discriminant(other)
            && self.to_string() == other.to_string()
    }
}

/// The errors of the fields that failed, keyed by field name.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct FieldErrors(pub BTreeMap<&'static str, FormError>);

impl FieldErrors {
    /// The message for `field`, if it failed (what the panels show).
    pub fn get(&self, field: &str) -> Option<String> {
        self.0.get(field).map(ToString::to_string)
    }

    /// The error of `field`, if it failed.
    pub fn error(&self, field: &str) -> Option<&FormError> {
        self.0.get(field)
    }

    /// Record that `field` failed with `error` (replacing an earlier error of it).
    pub fn insert(&mut self, field: &'static str, error: impl Into<FormError>) {
        self.0.insert(field, error.into());
    }

    /// Whether no field failed.
    pub fn is_empty(&self) -> bool {
        self.0.is_empty()
    }

    /// Record the outcome of parsing `field`, returning the value if it parsed.
    pub fn check<T, E: Into<FormError>>(
        &mut self,
        field: &'static str,
        r: Result<T, E>,
    ) -> Option<T> {
        match r {
            Ok(v) => Some(v),
            Err(e) => {
                self.insert(field, e);
                None
            }
        }
    }

    /// Only `field` failed, with `error`.
    pub(super) fn single(field: &'static str, error: impl Into<FormError>) -> Self {
        let mut e = Self::default();
        e.insert(field, error);
        e
    }
}

/// Every failed field as `field: message`, one after the other (for logs and the
/// autotest's record).
impl fmt::Display for FieldErrors {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for (i, (field, e)) in self.0.iter().enumerate() {
            if i > 0 {
                f.write_str("; ")?;
            }
            write!(f, "{field}: {e}")?;
        }
        Ok(())
    }
}

/// Checks that a custom mesh file can be used; returns why not otherwise
/// ([`crate::sim_bridge::check_custom_mesh`]).
pub type MeshCheck<'a> = &'a dyn Fn(&Path) -> Result<(), AppError>;

/// How the Fire panel reads a custom projectile's mesh file into its shape (the app's
/// [`load_projectile`](crate::sim_bridge::load_projectile); tests pass their own).
pub type ProjectileLoad<'a> = &'a dyn Fn(&Path) -> Result<ProjectileShape, AppError>;
