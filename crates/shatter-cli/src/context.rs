//! What every long command shares: the resource limits its requests are checked against
//! before any work starts, and the progress handle that Ctrl-C cancels and the progress
//! bar reads.

use std::io::IsTerminal;

use shatter_geom::budget::{self, Estimate, Limits};
use shatter_geom::progress::Progress;

use crate::bar::Bar;
use crate::error::CliError;

/// Limits, progress and whether a bar can be drawn.
#[derive(Debug, Clone)]
pub struct Context {
    /// The limits requests are checked against (none with `--no-limits`).
    pub limits: Limits,
    /// Cancelled by Ctrl-C; long loops check it, the bar reads it.
    pub progress: Progress,
    /// Whether standard error is a terminal (no bar otherwise).
    terminal: bool,
}

impl Context {
    /// The command line's context: this machine's memory and the default time limit
    /// ([`budget::DEFAULT_SECONDS_LIMIT`]), or no limits at all with `--no-limits`; the
    /// Ctrl-C handler is installed.
    pub fn new(no_limits: bool) -> Self {
        Self {
            limits: if no_limits {
                Limits::none()
            } else {
                Limits::machine(Some(budget::DEFAULT_SECONDS_LIMIT))
            },
            progress: crate::interrupt::install(),
            terminal: std::io::stderr().is_terminal(),
        }
    }

    /// A context with the given limits, a fresh progress handle and no bar (unit tests).
    #[cfg(test)]
    pub fn with_limits(limits: Limits) -> Self {
        Self {
            limits,
            progress: Progress::new(),
            terminal: false,
        }
    }

    /// Refuses `estimate` (of `what`, e.g. "--random 3,000,000,000: 3,000,000,000
    /// points") when it is over a limit: a bad-input error with the estimate and the hint
    /// to `--no-limits`. Warns on standard error when it fits the machine but not the
    /// memory available now.
    pub fn check(&self, what: &str, estimate: &Estimate) -> Result<(), CliError> {
        self.limits
            .check(what, estimate)
            .map_err(|e| self.refusal(&e.to_string()))?;
        if self.limits.memory_bytes.is_some()
            && let Some(available) = budget::machine_memory().and_then(|m| m.available)
            && estimate.bytes > available as f64
        {
            eprintln!(
                "warning: {what} need about {}; only {} is available now",
                budget::format_bytes(estimate.bytes),
                budget::format_bytes(available as f64)
            );
        }
        Ok(())
    }

    /// The bad-input error refusing a request over the limits: `message` (what, the
    /// estimate and the limit) and how to run it anyway.
    pub fn refusal(&self, message: &str) -> CliError {
        CliError::input(format!(
            "{message}; refused before starting (estimates: docs/cli.md, \"Resource limits\"; \
             --no-limits runs it anyway)"
        ))
    }

    /// A bar counting `len` units, drawn on standard error unless `quiet` (`--json`) or
    /// standard error is not a terminal.
    pub fn bar(&self, len: u64, quiet: bool) -> Bar {
        Bar::counting(len, self.terminal && !quiet)
    }

    /// A bar that follows this context's progress handle (the stage and counts a library
    /// loop reports), with `message` until the library names a stage; for work expected to
    /// take `estimate`. Drawn only for work estimated at a second or more.
    pub fn follow(&self, message: &str, estimate: &Estimate, quiet: bool) -> Bar {
        let visible = self.terminal && !quiet && estimate.seconds >= 1.0;
        Bar::following(&self.progress, message, visible)
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;

    #[test]
    fn a_refusal_is_bad_input_naming_the_estimate_and_the_override() {
        let ctx = Context::with_limits(Limits {
            memory_bytes: Some(24_000_000_000),
            seconds: Some(3600.0),
            memory_source: "MemTotal in /proc/meminfo",
        });
        let e = ctx
            .check("3,000,000,000 points", &Estimate::delaunay(3_000_000_000))
            .unwrap_err();
        assert_eq!(e.exit_code(), 2);
        let text = e.to_string();
        assert!(
            text.contains("this machine has 24 GB (MemTotal in /proc/meminfo)"),
            "{text}"
        );
        assert!(text.contains("--no-limits"), "{text}");
        assert!(ctx.check("1,000 points", &Estimate::delaunay(1000)).is_ok());
        let none = Context::with_limits(Limits::none());
        assert!(none.check("it", &Estimate::delaunay(u64::MAX)).is_ok());
    }
}
