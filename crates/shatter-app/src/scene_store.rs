//! Where the Scene field's Save and Load keep scene files: the file system on the
//! desktop; the browser's `localStorage` in the web build (a page cannot write files),
//! keyed by the name typed in the field.

use std::path::Path;

/// Whether a scene of this name can be loaded.
pub fn exists(path: &Path) -> bool {
    imp::exists(path)
}

/// Whether a scene of this name could be saved (its folder exists).
pub fn can_save(path: &Path) -> Result<(), String> {
    imp::can_save(path)
}

/// Saves the scene text.
pub fn write(path: &Path, text: &str) -> Result<(), String> {
    imp::write(path, text)
}

/// Reads a scene's text.
pub fn read(path: &Path) -> Result<String, String> {
    imp::read(path)
}

#[cfg(not(target_arch = "wasm32"))]
mod imp {
    use std::path::{Path, PathBuf};

    pub fn exists(path: &Path) -> bool {
        path.is_file()
    }

    pub fn can_save(path: &Path) -> Result<(), String> {
        let dir = match path.parent() {
            Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
            _ => PathBuf::from("."),
        };
        if dir.is_dir() {
            Ok(())
        } else {
            Err(format!("folder '{}' does not exist", dir.display()))
        }
    }

    pub fn write(path: &Path, text: &str) -> Result<(), String> {
        std::fs::write(path, text).map_err(|e| format!("cannot write '{}': {e}", path.display()))
    }

    pub fn read(path: &Path) -> Result<String, String> {
        std::fs::read_to_string(path).map_err(|e| format!("cannot read '{}': {e}", path.display()))
    }
}

#[cfg(target_arch = "wasm32")]
mod imp {
    use std::path::Path;

    fn key(path: &Path) -> String {
        format!("shatter-scene:{}", path.display())
    }

    fn storage() -> Result<web_sys::Storage, String> {
        web_sys::window()
            .and_then(|w| w.local_storage().ok().flatten())
            .ok_or_else(|| "this browser gives the page no localStorage".to_owned())
    }

    pub fn exists(path: &Path) -> bool {
        storage()
            .ok()
            .and_then(|s| s.get_item(&key(path)).ok().flatten())
            .is_some()
    }

    pub fn can_save(_path: &Path) -> Result<(), String> {
        storage().map(|_| ())
    }

    pub fn write(path: &Path, text: &str) -> Result<(), String> {
        storage()?
            .set_item(&key(path), text)
            .map_err(|_| format!("cannot save '{}' (storage full?)", path.display()))
    }

    pub fn read(path: &Path) -> Result<String, String> {
        storage()?
            .get_item(&key(path))
            .ok()
            .flatten()
            .ok_or_else(|| format!("no saved scene '{}'", path.display()))
    }
}
