//! A tool's checks of the mesh files a user names or picks, before anything is built
//! from them: a breakable object's file ([`check_mesh_file`]), a projectile's
//! ([`projectile_from_file`]), and a file handed over by a web page ([`pick_file`]).
//!
//! Files are read from a set of picked files first (a browser has no disk), then the disk.

use std::path::{Path, PathBuf};

pub use shatter_geom::io::MemoryFiles;
use shatter_geom::io::{self, FileSystem, Layered, MeshFormat, MeshIoError};
use shatter_sim::ProjectileShape;
use thiserror::Error;

/// Why a mesh file cannot be used. Its `Display` is the message for the user.
#[derive(Debug, Error)]
pub enum MeshFileError {
    /// The extension names no mesh format.
    #[error("'{}': expected an .obj, .stl, .gltf or .glb file", path.display())]
    NotAMeshFormat {
        /// The file.
        path: PathBuf,
    },
    /// A file handed to [`pick_file`] that is neither a mesh nor a file a mesh uses.
    #[error(
        "'{}': expected an .obj, .stl, .gltf or .glb file (or a .bin, .mtl, .png or .jpg it uses)",
        path.display()
    )]
    NotAMeshOrCompanion {
        /// The file.
        path: PathBuf,
    },
    /// A file a web page was not given (a browser has no disk to read it from).
    #[error("no mesh '{}': add it with the page's \"Add mesh…\" button", path.display())]
    NotPicked {
        /// The file.
        path: PathBuf,
        /// What looking for it on the (browser's empty) disk said.
        source: std::io::Error,
    },
    /// A file that cannot be read.
    #[error("cannot read '{}': {source}", path.display())]
    CannotRead {
        /// The file.
        path: PathBuf,
        /// The operating system's error.
        source: std::io::Error,
    },
    /// A path that names a folder or another non-file.
    #[error("'{}' is not a file", path.display())]
    NotAFile {
        /// The path.
        path: PathBuf,
    },
    /// A file that does not read as a mesh.
    #[error("{0}")]
    Mesh(#[from] MeshIoError),
    /// A mesh file without triangles.
    #[error("'{}' has no triangles", path.display())]
    NoTriangles {
        /// The file.
        path: PathBuf,
    },
    /// A projectile's mesh is flat (zero extent), has no vertices or is not finite.
    #[error("projectile: the mesh '{}' is flat, empty or not finite", path.display())]
    FlatProjectile {
        /// The file.
        path: PathBuf,
    },
}

/// Whether the mesh file at `path` (in `picked`, else on the disk) can be a breakable
/// object: its extension is a mesh format, and it reads as a mesh with triangles.
///
/// ```
/// use bevy_shatter::world::{MemoryFiles, MeshFileError, check_mesh_file};
/// let picked = MemoryFiles::new();
/// picked.insert("tri.obj", b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n".to_vec());
/// assert!(check_mesh_file("tri.obj".as_ref(), &picked).is_ok());
/// let e = check_mesh_file("notes.txt".as_ref(), &picked).unwrap_err();
/// assert!(matches!(e, MeshFileError::NotAMeshFormat { .. }));
/// ```
pub fn check_mesh_file(path: &Path, picked: &MemoryFiles) -> Result<(), MeshFileError> {
    read_mesh(path, picked).map(|_| ())
}

fn read_mesh(path: &Path, picked: &MemoryFiles) -> Result<shatter_geom::TriMesh, MeshFileError> {
    if MeshFormat::from_path(path).is_none() {
        return Err(MeshFileError::NotAMeshFormat {
            path: path.to_path_buf(),
        });
    }
    if !picked.contains(path) {
        let meta = std::fs::metadata(path).map_err(|source| {
            let path = path.to_path_buf();
            if cfg!(target_arch = "wasm32") {
                MeshFileError::NotPicked { path, source }
            } else {
                MeshFileError::CannotRead { path, source }
            }
        })?;
        if !meta.is_file() {
            return Err(MeshFileError::NotAFile {
                path: path.to_path_buf(),
            });
        }
    }
    let mesh = io::load_mesh_from(path, &Layered(picked, FileSystem))?;
    if mesh.triangles.is_empty() {
        return Err(MeshFileError::NoTriangles {
            path: path.to_path_buf(),
        });
    }
    Ok(mesh)
}

/// A projectile of the mesh file at `path`: the convex hull of its vertices, as
/// [`ProjectileShape::from_mesh`] makes it.
///
/// ```
/// use bevy_shatter::world::{MemoryFiles, projectile_from_file};
/// use shatter_sim::ProjectileShape;
/// let picked = MemoryFiles::new();
/// let tet = b"v 0 0 0\nv 4 0 0\nv 0 2 0\nv 0 0 2\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
/// picked.insert("rock.obj", tet.to_vec());
/// let ProjectileShape::Custom(points) = projectile_from_file("rock.obj".as_ref(), &picked).unwrap()
/// else { panic!("a custom shape") };
/// assert_eq!(points[1].x - points[0].x, 1.0); // the largest extent is 1
/// ```
pub fn projectile_from_file(
    path: &Path,
    picked: &MemoryFiles,
) -> Result<ProjectileShape, MeshFileError> {
    let mesh = read_mesh(path, picked)?;
    ProjectileShape::from_mesh(&mesh).ok_or_else(|| MeshFileError::FlatProjectile {
        path: path.to_path_buf(),
    })
}

/// The files a mesh refers to that a page may hand over beside it.
const COMPANIONS: [&str; 5] = ["bin", "mtl", "png", "jpg", "jpeg"];

/// Keep a file a user picked in a web page in `picked`: a mesh file, once it reads as a
/// mesh (with the files already picked beside it), or a file a mesh refers to (a
/// `.gltf`'s `.bin`, an OBJ's `.mtl`, a texture). Nothing is kept on error.
///
/// ```
/// use bevy_shatter::world::{MemoryFiles, pick_file};
/// let picked = MemoryFiles::new();
/// pick_file(&picked, "skin.png", vec![1, 2, 3]).unwrap();
/// assert!(pick_file(&picked, "broken.obj", b"f 1 2 3\n".to_vec()).is_err());
/// assert!(picked.contains("skin.png") && !picked.contains("broken.obj"));
/// ```
pub fn pick_file(picked: &MemoryFiles, name: &str, bytes: Vec<u8>) -> Result<(), MeshFileError> {
    let Some(format) = MeshFormat::from_path(name) else {
        let ext = Path::new(name)
            .extension()
            .map(|e| e.to_string_lossy().to_ascii_lowercase());
        if ext.is_some_and(|e| COMPANIONS.contains(&e.as_str())) {
            picked.insert(name, bytes);
            return Ok(());
        }
        return Err(MeshFileError::NotAMeshOrCompanion { path: name.into() });
    };
    io::parse_model_with(&bytes, format, name, picked)?;
    picked.insert(name, bytes);
    Ok(())
}

#[cfg(test)]
mod tests {
    use std::error::Error;

    use super::*;

    #[test]
    fn a_mesh_that_does_not_parse_keeps_the_readers_error() {
        let dir = tempfile::tempdir().unwrap();
        let broken = dir.path().join("broken.obj");
        std::fs::write(&broken, "v 0 0 0\nf 1 2 3\n").unwrap();
        let e = check_mesh_file(&broken, &MemoryFiles::new()).unwrap_err();
        assert!(matches!(e, MeshFileError::Mesh(_)), "{e:?}");
        let source = e.source().unwrap().downcast_ref::<MeshIoError>().unwrap();
        assert_eq!(
            e.to_string(),
            source.to_string(),
            "shown as the reader says"
        );
    }

    #[test]
    fn a_missing_mesh_keeps_the_os_error() {
        let path = Path::new("no/such/dir/rock.stl");
        let e = check_mesh_file(path, &MemoryFiles::new()).unwrap_err();
        let io = e
            .source()
            .unwrap()
            .downcast_ref::<std::io::Error>()
            .unwrap();
        assert_eq!(io.kind(), std::io::ErrorKind::NotFound);
        assert_eq!(
            e.to_string(),
            format!("cannot read 'no/such/dir/rock.stl': {io}")
        );
        let dir = tempfile::tempdir().unwrap();
        let e = check_mesh_file(&dir.path().join("a.obj"), &MemoryFiles::new());
        assert!(matches!(e, Err(MeshFileError::CannotRead { .. })));
        std::fs::create_dir(dir.path().join("folder.obj")).unwrap();
        let e = check_mesh_file(&dir.path().join("folder.obj"), &MemoryFiles::new());
        assert!(matches!(e, Err(MeshFileError::NotAFile { .. })), "{e:?}");
    }

    #[test]
    fn a_stray_file_and_a_point_sized_projectile_are_refused() {
        let picked = MemoryFiles::new();
        let e = pick_file(&picked, "notes.txt", vec![]).unwrap_err();
        assert!(matches!(e, MeshFileError::NotAMeshOrCompanion { .. }));
        // A mesh with a triangle, but all of it in one point: no size to scale.
        picked.insert("dot.obj", b"v 1 1 1\nv 1 1 1\nv 1 1 1\nf 1 2 3\n".to_vec());
        let e = projectile_from_file("dot.obj".as_ref(), &picked).unwrap_err();
        assert!(matches!(e, MeshFileError::FlatProjectile { .. }), "{e:?}");
    }
}
