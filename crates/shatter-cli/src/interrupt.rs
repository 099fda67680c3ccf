//! Ctrl-C: the first one cancels the running command through the shared
//! [`Progress`] handle; the command stops at its next check, removes its temporary files
//! and exits with code 130. A computation that does not check the handle (a library loop
//! not yet wired to it) is stopped by the handler itself after a grace period: it removes
//! the temporary files the command registered and exits with 130.
//!
//! Outputs are written through temporary files in the same folder ([`crate::output`]), so
//! an interrupted command never leaves a half-written output behind.

use std::path::{Path, PathBuf};
use std::sync::{Mutex, OnceLock};
use std::time::Duration;

use shatter_geom::progress::Progress;

use crate::error::{EXIT_INTERRUPTED, INTERRUPTED_MESSAGE};

/// How long a cancelled command has to stop by itself before the handler exits for it.
pub const GRACE: Duration = Duration::from_secs(2);

struct State {
    progress: Progress,
    temp_files: Mutex<Vec<PathBuf>>,
}

static STATE: OnceLock<State> = OnceLock::new();

fn state() -> &'static State {
    STATE.get_or_init(|| State {
        progress: Progress::new(),
        temp_files: Mutex::new(Vec::new()),
    })
}

/// Installs the Ctrl-C handler (once) and returns the process's progress handle, which
/// Ctrl-C cancels. Without a handler (it could not be installed) Ctrl-C ends the process
/// the default way.
pub fn install() -> Progress {
    static INSTALLED: OnceLock<bool> = OnceLock::new();
    INSTALLED.get_or_init(|| ctrlc::set_handler(on_interrupt).is_ok());
    state().progress.clone()
}

fn on_interrupt() {
    let s = state();
    if s.progress.is_cancelled() {
        exit_now("");
    }
    s.progress.cancel();
    eprintln!("\ninterrupted: stopping...");
    std::thread::sleep(GRACE);
    // Still running: the computation does not check the handle.
    exit_now(" (the computation did not stop by itself)");
}

fn exit_now(note: &str) -> ! {
    remove_temp_files();
    eprintln!("error: {INTERRUPTED_MESSAGE}{note}");
    std::process::exit(i32::from(EXIT_INTERRUPTED));
}

/// Registers a temporary file to remove if the process is stopped by Ctrl-C.
pub fn register_temp_file(path: &Path) {
    if let Ok(mut files) = state().temp_files.lock() {
        files.push(path.to_path_buf());
    }
}

/// Forgets a temporary file (it was renamed or removed).
pub fn unregister_temp_file(path: &Path) {
    if let Ok(mut files) = state().temp_files.lock() {
        files.retain(|p| p != path);
    }
}

fn remove_temp_files() {
    if let Ok(files) = state().temp_files.lock() {
        for f in files.iter() {
            let _ = std::fs::remove_file(f);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn temp_files_are_registered_and_forgotten() {
        let a = Path::new("/nonexistent/a.tmp");
        register_temp_file(a);
        assert!(
            state()
                .temp_files
                .lock()
                .is_ok_and(|f| f.iter().any(|p| p == a))
        );
        unregister_temp_file(a);
        assert!(
            state()
                .temp_files
                .lock()
                .is_ok_and(|f| !f.iter().any(|p| p == a))
        );
    }
}
