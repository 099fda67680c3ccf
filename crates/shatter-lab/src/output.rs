//! Writing output files so that no half-written file is ever left at the output's path:
//! everything is written to a temporary file in the same folder (`.NAME.XXXXXX.EXT`), which
//! is renamed over the output only once it is complete, and only if the progress handle
//! was not cancelled meanwhile. A failed or interrupted write removes the temporary file.
//!
//! The temporary files being written are registered, so that a Ctrl-C handler that has
//! to end the process itself can remove them first ([`remove_temp_files`]).

use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::Mutex;

use shatter_geom::progress::Progress;

use crate::error::{LabError, ResultExt};

/// The temporary files being written now.
static TEMP_FILES: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

/// Registers a temporary file to remove if the process is stopped ([`remove_temp_files`]).
pub fn register_temp_file(path: &Path) {
    if let Ok(mut files) = TEMP_FILES.lock() {
        files.push(path.to_path_buf());
    }
}

/// Forgets a temporary file (it was renamed or removed).
pub fn unregister_temp_file(path: &Path) {
    if let Ok(mut files) = TEMP_FILES.lock() {
        files.retain(|p| p != path);
    }
}

/// Removes every registered temporary file: for a handler about to end the process.
pub fn remove_temp_files() {
    if let Ok(files) = TEMP_FILES.lock() {
        for f in files.iter() {
            let _ = std::fs::remove_file(f);
        }
    }
}

/// Writes `path` through a temporary file: `write` gets the temporary file's path (for
/// library writers that take a path, such as a plot or GLB writer) and must create it.
/// The temporary file keeps `path`'s extension, for writers that choose the format by it.
pub fn via_temp_path<T, E: From<LabError>>(
    path: &Path,
    progress: &Progress,
    write: impl FnOnce(&Path) -> Result<T, E>,
) -> Result<T, E> {
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    let stem = path
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default();
    let suffix = path
        .extension()
        .map(|e| format!(".{}", e.to_string_lossy()))
        .unwrap_or_default();
    let temp = tempfile::Builder::new()
        .prefix(&format!(".{stem}."))
        .suffix(&suffix)
        .tempfile_in(dir)
        .map_err(|e| LabError::input(format!("{}: cannot write: {e}", path.display())))?
        .into_temp_path();
    register_temp_file(&temp);
    let result = write(&temp).and_then(|value| {
        progress.check().map_err(LabError::from)?;
        Ok(value)
    });
    unregister_temp_file(&temp);
    let value = result?;
    temp.persist(path)
        .map_err(|e| LabError::input(format!("{}: cannot write: {}", path.display(), e.error)))?;
    Ok(value)
}

/// Writes `path` through a temporary file with `write` (given a buffered writer).
pub fn write_file(
    path: &Path,
    progress: &Progress,
    write: impl FnOnce(&mut dyn Write) -> std::io::Result<()>,
) -> Result<(), LabError> {
    via_temp_path(path, progress, |temp| {
        let fail =
            |e: std::io::Error| LabError::input(format!("{}: cannot write: {e}", path.display()));
        let file = std::fs::File::create(temp).map_err(fail)?;
        let mut out = std::io::BufWriter::new(file);
        write(&mut out).map_err(fail)?;
        out.into_inner()
            .map_err(|e| fail(e.into_error()))?
            .sync_all()
            .map_err(fail)
    })
}

/// Writes `plot` as `base.png` and `base.svg`, each through a temporary file; returns
/// their paths.
pub fn write_plot(
    plot: &shatter_report::plot::LinePlot<'_>,
    base: &Path,
    progress: &Progress,
) -> Result<[PathBuf; 2], LabError> {
    let png = base.with_extension("png");
    let svg = base.with_extension("svg");
    via_temp_path(&png, progress, |temp| {
        plot.write_png(temp).internal_err("writing a plot")
    })?;
    via_temp_path(&svg, progress, |temp| {
        plot.write_svg(temp).internal_err("writing a plot")
    })?;
    Ok([png, svg])
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;

    fn files_in(dir: &Path) -> Vec<String> {
        let mut names: Vec<String> = std::fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        names.sort();
        names
    }

    #[test]
    fn a_complete_write_replaces_the_output_and_leaves_nothing_else() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("out.txt");
        std::fs::write(&path, "old").unwrap();
        write_file(&path, &Progress::none(), |w| w.write_all(b"new")).unwrap();
        assert_eq!(std::fs::read_to_string(&path).unwrap(), "new");
        assert_eq!(files_in(dir.path()), ["out.txt"]);
    }

    #[test]
    fn a_failed_write_leaves_the_old_output_and_no_temporary_file() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("out.txt");
        std::fs::write(&path, "old").unwrap();
        let e = write_file(&path, &Progress::none(), |w| {
            w.write_all(b"half")?;
            Err(std::io::Error::other("disk full"))
        })
        .unwrap_err();
        assert!(e.to_string().contains("disk full"), "{e}");
        assert_eq!(std::fs::read_to_string(&path).unwrap(), "old");
        assert_eq!(files_in(dir.path()), ["out.txt"]);
    }

    #[test]
    fn a_cancelled_write_is_interrupted_and_writes_nothing() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("out.glb");
        let progress = Progress::new();
        let e = via_temp_path(&path, &progress, |temp| {
            assert_eq!(temp.extension().unwrap(), "glb");
            std::fs::write(temp, "complete").unwrap();
            progress.cancel();
            Ok::<(), LabError>(())
        })
        .unwrap_err();
        assert_eq!(e, LabError::Interrupted);
        assert!(
            files_in(dir.path()).is_empty(),
            "{:?}",
            files_in(dir.path())
        );
    }

    #[test]
    fn temp_files_are_registered_and_forgotten() {
        let a = Path::new("/nonexistent/a.tmp");
        let registered = || TEMP_FILES.lock().is_ok_and(|f| f.iter().any(|p| p == a));
        register_temp_file(a);
        assert!(registered());
        unregister_temp_file(a);
        assert!(!registered());
    }
}
