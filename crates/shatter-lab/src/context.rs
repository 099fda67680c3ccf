//! What every long piece of work shares: the resource limits its requests are checked
//! against before any work starts, and the progress handle that cancels it (Ctrl-C on the
//! command line) and that progress bars read.

use shatter_geom::budget::{self, Estimate, Limits};
use shatter_geom::progress::Progress;

use crate::bar::Bar;
use crate::error::LabError;

/// Limits, progress and whether a bar can be drawn.
#[derive(Debug, Clone)]
pub struct Context {
    /// The limits requests are checked against ([`Limits::none`] for none).
    pub limits: Limits,
    /// Cancelled to stop the work; long loops check it, the bars read it.
    pub progress: Progress,
    /// Whether bars are drawn (on standard error; a terminal).
    terminal: bool,
}

impl Context {
    /// A context with these limits and progress handle; `terminal`: whether progress
    /// bars are drawn on standard error.
    pub fn new(limits: Limits, progress: Progress, terminal: bool) -> Self {
        Self {
            limits,
            progress,
            terminal,
        }
    }

    /// A context with the given limits, a fresh progress handle and no bar (tests).
    pub fn quiet(limits: Limits) -> Self {
        Self::new(limits, Progress::new(), false)
    }

    /// Refuses `estimate` (of `what`, e.g. "--random 3,000,000,000: 3,000,000,000
    /// points") when it is over a limit: a bad-input error with the estimate and the hint
    /// to `--no-limits`. Warns on standard error when it fits the machine but not the
    /// memory available now.
    pub fn check(&self, what: &str, estimate: &Estimate) -> Result<(), LabError> {
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
    pub fn refusal(&self, message: &str) -> LabError {
        LabError::input(format!(
            "{message}; refused before starting (estimates: docs/cli.md, \"Resource limits\"; \
             --no-limits runs it anyway)"
        ))
    }

    /// A bar counting `len` units, drawn on standard error unless `quiet` (`--json`) or
    /// bars are off.
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
        let ctx = Context::quiet(Limits {
            memory_bytes: Some(24_000_000_000),
            seconds: Some(3600.0),
            memory_source: "MemTotal in /proc/meminfo",
        });
        let e = ctx
            .check("3,000,000,000 points", &Estimate::delaunay(3_000_000_000))
            .unwrap_err();
        let LabError::Input(text) = e else {
            panic!("not bad input: {e:?}");
        };
        assert!(
            text.contains("this machine has 24 GB (MemTotal in /proc/meminfo)"),
            "{text}"
        );
        assert!(text.contains("--no-limits"), "{text}");
        assert!(ctx.check("1,000 points", &Estimate::delaunay(1000)).is_ok());
        let none = Context::quiet(Limits::none());
        assert!(none.check("it", &Estimate::delaunay(u64::MAX)).is_ok());
    }
}
