//! The check behind the Custom shape of the Add Object and Fire panels: whether a mesh
//! file named in the path field can be used, before any command is sent.

use std::path::Path;

use crate::error::AppError;

/// Whether a custom mesh file can be used (for the forms' validation): the extension is a
/// mesh format, and the file reads as a mesh.
pub fn check_custom_mesh(path: &Path) -> Result<(), AppError> {
    if shatter_geom::io::MeshFormat::from_path(path).is_none() {
        return Err(AppError::NotAMeshFormat {
            path: path.to_path_buf(),
        });
    }
    // A mesh picked in the web page lives in memory.
    if !crate::picked_files::picked_files().contains(path) {
        let meta = std::fs::metadata(path).map_err(|source| {
            let path = path.to_path_buf();
            if cfg!(target_arch = "wasm32") {
                AppError::MeshNotPicked { path, source }
            } else {
                AppError::CannotRead { path, source }
            }
        })?;
        if !meta.is_file() {
            return Err(AppError::NotAFile {
                path: path.to_path_buf(),
            });
        }
    }
    let mesh = shatter_geom::io::load_mesh_from(path, &crate::picked_files::sources())?;
    if mesh.triangles.is_empty() {
        return Err(AppError::NoTriangles {
            path: path.to_path_buf(),
        });
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use std::error::Error;

    use shatter_geom::io::MeshIoError;

    use super::*;

    #[test]
    fn a_mesh_that_does_not_parse_keeps_the_readers_error() {
        let dir = std::env::temp_dir().join(format!("shatter-app-check-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let broken = dir.join("broken.obj");
        std::fs::write(&broken, "v 0 0 0\nf 1 2 3\n").unwrap();
        let e = check_custom_mesh(&broken).unwrap_err();
        assert!(matches!(e, AppError::Mesh(_)), "{e:?}");
        let source = e.source().unwrap().downcast_ref::<MeshIoError>().unwrap();
        assert_eq!(
            e.to_string(),
            source.to_string(),
            "shown as the reader says"
        );
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn a_missing_mesh_keeps_the_os_error_and_the_old_message() {
        let path = Path::new("no/such/dir/rock.stl");
        let e = check_custom_mesh(path).unwrap_err();
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
        assert_eq!(
            check_custom_mesh(Path::new("notes.txt"))
                .unwrap_err()
                .to_string(),
            "'notes.txt': expected an .obj, .stl, .gltf or .glb file"
        );
    }
}
