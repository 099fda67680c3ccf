//! The app's error type: why the simulation, a scene file or a custom mesh refused what
//! the user asked for.
//!
//! [`AppError`] keeps the library error it comes from as its
//! [`source`](std::error::Error::source); it becomes text only at the edge (the panels'
//! status line and error labels, the log, the autotest's record). Its `Display` is the
//! message the user sees.

use std::path::{Path, PathBuf};

use shatter_geom::io::MeshIoError;
use shatter_sim::SimError;
use thiserror::Error;

use crate::commands::ObjectId;
use crate::scene_store::StoreError;

/// Everything a [`SimCommand`](crate::commands::SimCommand), a scene or a custom mesh
/// check can fail with.
///
/// ```
/// use std::error::Error;
/// use shatter_app::error::AppError;
/// use shatter_app::sim_bridge::check_custom_mesh;
/// let e = check_custom_mesh(std::path::Path::new("no/such/rock.obj")).unwrap_err();
/// assert!(matches!(e, AppError::CannotRead { .. }));
/// assert!(e.source().unwrap().downcast_ref::<std::io::Error>().is_some());
/// ```
#[derive(Debug, Error)]
pub enum AppError {
    /// The simulation refused: building, editing or deleting an object, a projectile or
    /// explosion out of range, a scene that does not build or save.
    #[error("{0}")]
    Sim(#[from] SimError),
    /// No object has this id.
    #[error("no object {0}")]
    NoObject(ObjectId),
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
    #[error("no example scene `{name}` (there are: {})", example_names())]
    UnknownExample {
        /// The name asked for.
        name: String,
    },
    /// A built-in example scene does not parse.
    #[error("{name}.toml: {source}")]
    ExampleText {
        /// The example's name (one of [`EXAMPLE_SCENES`](crate::sim_bridge::EXAMPLE_SCENES)).
        name: &'static str,
        /// What the parser reported.
        #[source]
        source: SimError,
    },
    /// A custom mesh's extension names no mesh format.
    #[error("'{}': expected an .obj, .stl, .gltf or .glb file", path.display())]
    NotAMeshFormat {
        /// The file.
        path: PathBuf,
    },
    /// A custom mesh file the web page was not given.
    #[error("no mesh '{}': add it with the page's \"Add mesh…\" button", path.display())]
    MeshNotPicked {
        /// The file.
        path: PathBuf,
        /// What looking for it on the (browser's empty) disk said.
        source: std::io::Error,
    },
    /// A custom mesh file that cannot be read.
    #[error("cannot read '{}': {source}", path.display())]
    CannotRead {
        /// The file.
        path: PathBuf,
        /// The operating system's error.
        source: std::io::Error,
    },
    /// A custom mesh path that names a folder or another non-file.
    #[error("'{}' is not a file", path.display())]
    NotAFile {
        /// The path.
        path: PathBuf,
    },
    /// A custom mesh file that does not read as a mesh.
    #[error("{0}")]
    Mesh(#[from] MeshIoError),
    /// A custom mesh file without triangles.
    #[error("'{}' has no triangles", path.display())]
    NoTriangles {
        /// The file.
        path: PathBuf,
    },
    /// A custom projectile's mesh file does not read as a mesh.
    #[error("projectile: {0}")]
    ProjectileMesh(#[source] MeshIoError),
    /// A custom projectile's mesh has no vertices.
    #[error("projectile: the mesh has no vertices")]
    ProjectileNoVertices,
    /// A custom projectile's mesh is flat (zero extent) or not finite.
    #[error("projectile: the mesh is flat or not finite")]
    FlatProjectile,
}

/// The names of the example scenes, as a list for a message.
fn example_names() -> String {
    let names: Vec<&str> = crate::sim_bridge::EXAMPLE_SCENES
        .iter()
        .map(|(n, _)| *n)
        .collect();
    names.join(", ")
}
