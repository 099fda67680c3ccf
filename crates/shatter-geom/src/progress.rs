//! Progress and cancellation of long computations: a shared handle that a long loop
//! advances and checks, and that another thread (a progress bar, a Ctrl-C handler, an app's
//! Cancel button) reads and cancels.
//!
//! A [`Progress`] is cheap to clone (an `Arc`): every clone is the same handle. The work
//! names its stage and its total with [`Progress::start_stage`], counts finished units with
//! [`Progress::advance`] (thread-safe, so a rayon loop may call it from every worker) and
//! calls [`Progress::check`] between units; once someone has called [`Progress::cancel`],
//! `check` returns [`Cancelled`] and the loop returns early with it. Nothing here blocks or
//! allocates per call except [`Progress::start_stage`] (it stores the stage's name).
//!
//! ```
//! use shatter_geom::progress::{Cancelled, Progress};
//!
//! fn sum_of_squares(n: u64, progress: &Progress) -> Result<u64, Cancelled> {
//!     progress.start_stage("squares", n);
//!     let mut sum = 0;
//!     for i in 0..n {
//!         progress.check()?;
//!         sum += i * i;
//!         progress.advance(1);
//!     }
//!     Ok(sum)
//! }
//!
//! let progress = Progress::new();
//! assert_eq!(sum_of_squares(4, &progress), Ok(14));
//! assert_eq!(progress.snapshot().done, 4);
//!
//! let watcher = progress.clone();
//! watcher.cancel();
//! assert_eq!(sum_of_squares(4, &progress), Err(Cancelled));
//! ```
//!
//! [`Progress::none`] is a handle nobody else holds: it is never cancelled, and library
//! functions without a progress parameter pass it on.

use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::{Arc, Mutex};

/// The computation was cancelled through its [`Progress`] handle before it finished.
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
#[error("cancelled")]
pub struct Cancelled;

#[derive(Debug, Default)]
struct Shared {
    cancelled: AtomicBool,
    done: AtomicU64,
    total: AtomicU64,
    stage: Mutex<String>,
}

/// A shared progress and cancellation handle (see the [module docs](self)).
#[derive(Debug, Clone, Default)]
pub struct Progress {
    shared: Arc<Shared>,
}

/// What a [`Progress`] handle says at one moment.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Snapshot {
    /// The current stage's name ("" before the first stage).
    pub stage: String,
    /// Units of the current stage done.
    pub done: u64,
    /// Units in the current stage (0: unknown).
    pub total: u64,
    /// Whether [`Progress::cancel`] was called.
    pub cancelled: bool,
}

impl Progress {
    /// A new handle: no stage, not cancelled.
    pub fn new() -> Self {
        Self::default()
    }

    /// A handle for callers that neither show progress nor cancel: a fresh handle that
    /// nobody else can cancel.
    pub fn none() -> Self {
        Self::default()
    }

    /// Starts a stage named `name` of `total` units (0 when unknown): resets the count.
    pub fn start_stage(&self, name: &str, total: u64) {
        if let Ok(mut stage) = self.shared.stage.lock() {
            stage.clear();
            stage.push_str(name);
        }
        self.shared.done.store(0, Ordering::Relaxed);
        self.shared.total.store(total, Ordering::Relaxed);
    }

    /// Counts `units` more units of the current stage as done.
    pub fn advance(&self, units: u64) {
        self.shared.done.fetch_add(units, Ordering::Relaxed);
    }

    /// Sets the number of units done in the current stage.
    pub fn set_done(&self, done: u64) {
        self.shared.done.store(done, Ordering::Relaxed);
    }

    /// Asks the computation to stop at its next [`check`](Self::check). Safe to call from
    /// any thread (a signal handler's thread included), any number of times.
    pub fn cancel(&self) {
        self.shared.cancelled.store(true, Ordering::Relaxed);
    }

    /// Whether [`cancel`](Self::cancel) was called.
    pub fn is_cancelled(&self) -> bool {
        self.shared.cancelled.load(Ordering::Relaxed)
    }

    /// `Err(Cancelled)` once [`cancel`](Self::cancel) was called: long loops call it
    /// between units of work and return the error.
    pub fn check(&self) -> Result<(), Cancelled> {
        if self.is_cancelled() {
            Err(Cancelled)
        } else {
            Ok(())
        }
    }

    /// The stage, counts and cancel flag now.
    pub fn snapshot(&self) -> Snapshot {
        Snapshot {
            stage: self
                .shared
                .stage
                .lock()
                .map(|s| s.clone())
                .unwrap_or_default(),
            done: self.shared.done.load(Ordering::Relaxed),
            total: self.shared.total.load(Ordering::Relaxed),
            cancelled: self.is_cancelled(),
        }
    }

    /// Whether `other` is a clone of this handle.
    pub fn same_handle(&self, other: &Progress) -> bool {
        Arc::ptr_eq(&self.shared, &other.shared)
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;

    #[test]
    fn clones_share_counts_and_the_cancel_flag() {
        let a = Progress::new();
        let b = a.clone();
        a.start_stage("cells", 10);
        b.advance(3);
        a.advance(2);
        let s = b.snapshot();
        assert_eq!((s.stage.as_str(), s.done, s.total), ("cells", 5, 10));
        assert!(a.check().is_ok());
        b.cancel();
        assert_eq!(a.check(), Err(Cancelled));
        assert!(a.snapshot().cancelled);
        assert!(a.same_handle(&b));
    }

    #[test]
    fn a_new_stage_resets_the_count_but_not_the_cancel_flag() {
        let p = Progress::new();
        p.start_stage("one", 4);
        p.advance(4);
        p.cancel();
        p.start_stage("two", 7);
        let s = p.snapshot();
        assert_eq!((s.stage.as_str(), s.done, s.total), ("two", 0, 7));
        assert!(s.cancelled);
    }

    #[test]
    fn none_is_its_own_handle() {
        let a = Progress::none();
        let b = Progress::none();
        a.cancel();
        assert!(b.check().is_ok());
        assert!(!a.same_handle(&b));
    }

    #[test]
    fn advance_is_counted_from_many_threads() {
        let p = Progress::new();
        p.start_stage("parallel", 4000);
        std::thread::scope(|s| {
            for _ in 0..4 {
                let p = p.clone();
                s.spawn(move || {
                    for _ in 0..1000 {
                        p.advance(1);
                    }
                });
            }
        });
        assert_eq!(p.snapshot().done, 4000);
    }
}
