//! Writing output files so that no half-written file is ever left at the output's path:
//! everything is written to a temporary file in the same folder (`.NAME.XXXXXX.EXT`), which
//! is renamed over the output only once it is complete, and only if Ctrl-C did not cancel
//! the command meanwhile. A failed or interrupted write removes the temporary file.

use std::io::Write;
use std::path::Path;

use shatter_geom::progress::Progress;

use crate::error::CliError;
use crate::interrupt;

/// Writes `path` through a temporary file: `write` gets the temporary file's path (for
/// library writers that take a path, such as a plot or GLB writer) and must create it.
/// The temporary file keeps `path`'s extension, for writers that choose the format by it.
pub fn via_temp_path<T>(
    path: &Path,
    progress: &Progress,
    write: impl FnOnce(&Path) -> Result<T, CliError>,
) -> Result<T, CliError> {
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
        .map_err(|e| CliError::input(format!("{}: cannot write: {e}", path.display())))?
        .into_temp_path();
    interrupt::register_temp_file(&temp);
    let result = write(&temp).and_then(|value| {
        progress.check()?;
        Ok(value)
    });
    interrupt::unregister_temp_file(&temp);
    let value = result?;
    temp.persist(path)
        .map_err(|e| CliError::input(format!("{}: cannot write: {}", path.display(), e.error)))?;
    Ok(value)
}

/// Writes `path` through a temporary file with `write` (given a buffered writer).
pub fn write_file(
    path: &Path,
    progress: &Progress,
    write: impl FnOnce(&mut dyn Write) -> std::io::Result<()>,
) -> Result<(), CliError> {
    via_temp_path(path, progress, |temp| {
        let fail =
            |e: std::io::Error| CliError::input(format!("{}: cannot write: {e}", path.display()));
        let file = std::fs::File::create(temp).map_err(fail)?;
        let mut out = std::io::BufWriter::new(file);
        write(&mut out).map_err(fail)?;
        out.into_inner()
            .map_err(|e| fail(e.into_error()))?
            .sync_all()
            .map_err(fail)
    })
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
            Ok(())
        })
        .unwrap_err();
        assert!(matches!(e, CliError::Interrupted));
        assert!(
            files_in(dir.path()).is_empty(),
            "{:?}",
            files_in(dir.path())
        );
    }
}
