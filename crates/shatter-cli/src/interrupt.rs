//! Ctrl-C: the first one cancels the running command through the shared
//! [`Progress`] handle; the command stops at its next check, removes its temporary files
//! and exits with code 130. A computation that does not check the handle (a library loop
//! not yet wired to it) is stopped by the handler itself after a grace period: it removes
//! the temporary files the command registered and exits with 130.
//!
//! Outputs are written through temporary files in the same folder
//! ([`shatter_lab::output`], which registers them), so
//! an interrupted command never leaves a half-written output behind.

use std::sync::OnceLock;
use std::time::Duration;

use shatter_geom::progress::Progress;

use crate::error::{EXIT_INTERRUPTED, INTERRUPTED_MESSAGE};

/// How long a cancelled command has to stop by itself before the handler exits for it.
pub const GRACE: Duration = Duration::from_secs(2);

/// The process's progress handle, which Ctrl-C cancels.
static PROGRESS: OnceLock<Progress> = OnceLock::new();

fn progress() -> &'static Progress {
    PROGRESS.get_or_init(Progress::new)
}

/// Installs the Ctrl-C handler (once) and returns the process's progress handle, which
/// Ctrl-C cancels. Without a handler (it could not be installed) Ctrl-C ends the process
/// the default way.
pub fn install() -> Progress {
    static INSTALLED: OnceLock<bool> = OnceLock::new();
    INSTALLED.get_or_init(|| ctrlc::set_handler(on_interrupt).is_ok());
    progress().clone()
}

fn on_interrupt() {
    let progress = progress();
    if progress.is_cancelled() {
        exit_now("");
    }
    progress.cancel();
    eprintln!("\ninterrupted: stopping...");
    std::thread::sleep(GRACE);
    // Still running: the computation does not check the handle.
    exit_now(" (the computation did not stop by itself)");
}

fn exit_now(note: &str) -> ! {
    shatter_lab::output::remove_temp_files();
    eprintln!("error: {INTERRUPTED_MESSAGE}{note}");
    std::process::exit(i32::from(EXIT_INTERRUPTED));
}
