//! The command line's [`Context`] (shatter-lab's): this machine's limits unless
//! `--no-limits`, the progress handle that Ctrl-C cancels, and bars on a terminal.

use std::io::IsTerminal;

use shatter_geom::budget::{self, Limits};
pub use shatter_lab::Context;

/// The command line's context: this machine's memory and the default time limit
/// ([`budget::DEFAULT_SECONDS_LIMIT`]), or no limits at all with `--no-limits`; the
/// Ctrl-C handler is installed; bars are drawn when standard error is a terminal.
pub fn new(no_limits: bool) -> Context {
    let limits = if no_limits {
        Limits::none()
    } else {
        Limits::machine(Some(budget::DEFAULT_SECONDS_LIMIT))
    };
    Context::new(
        limits,
        crate::interrupt::install(),
        std::io::stderr().is_terminal(),
    )
}
