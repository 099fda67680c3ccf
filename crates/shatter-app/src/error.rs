//! The app's error type: why the simulation, a scene file or a custom mesh refused what
//! the user asked for.
//!
//! [`AppError`] keeps the library error it comes from as its
//! [`source`](std::error::Error::source); it becomes text only at the edge (the panels'
//! status line and error labels, the log, the autotest's record). Its `Display` is the
//! message the user sees.

use std::path::Path;

use bevy_shatter::world::MeshFileError;
use shatter_sim::SimError;
use thiserror::Error;

use crate::scene_store::StoreError;

/// Everything a [`SimCommand`](crate::commands::SimCommand), a scene or a custom mesh
/// check can fail with.
///
/// ```
/// use std::error::Error;
/// use bevy_shatter::world::MeshFileError;
/// use shatter_app::error::AppError;
/// use shatter_app::sim_bridge::check_custom_mesh;
/// let e = check_custom_mesh(std::path::Path::new("no/such/rock.obj")).unwrap_err();
/// assert!(matches!(e, AppError::MeshFile(MeshFileError::CannotRead { .. })));
/// assert!(e.source().unwrap().downcast_ref::<std::io::Error>().is_some());
/// ```
#[derive(Debug, Error)]
pub enum AppError {
    /// The simulation refused: building, editing or deleting an object, a projectile or
    /// explosion out of range, a scene that does not build or save.
    #[error("{0}")]
    Sim(#[from] SimError),
    /// The scene store could not save or read a scene.
    #[error("{0}")]
    Store(#[from] StoreError),
    /// A scene's text (read from the web page's storage) does not parse.
    #[error("{}: {source}", path.display())]
    SceneText {
        /// The scene's name (boxed: the error stays small).
        path: Box<Path>,
        /// What the parser reported.
        #[source]
        source: SimError,
    },
    /// No built-in example scene has this name.
    #[error("no example scene `{name}` (there are: {valid})")]
    UnknownExample {
        /// The name asked for.
        name: String,
        /// The example scenes' names, as a list for the message.
        valid: String,
    },
    /// A built-in example scene does not parse.
    #[error("{name}.toml: {source}")]
    ExampleText {
        /// The example's name.
        name: &'static str,
        /// What the parser reported.
        #[source]
        source: SimError,
    },
    /// A custom mesh file (of an object or a projectile) that cannot be used.
    #[error(transparent)]
    MeshFile(#[from] MeshFileError),
}
