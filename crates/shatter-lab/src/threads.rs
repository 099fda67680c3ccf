//! The command line's thread pool: rayon's global pool with each worker kept on one of
//! the processors the process may use.
//!
//! Left to itself, Linux often puts a fresh process's two pool threads on one processor:
//! a thread woken by another is placed where the waker ran, and a thread that has just
//! run there counts as cache-hot, so the idle processor does not take it over. Every
//! parallel phase of that process then runs at the speed of one core. On the 2-core VM,
//! the bird into 100 Voronoi cells (`shatter fracture … --seeds-file`, 14 processes
//! each): 6.3–11.5 ms, median 9.5, left alone; 6.3–6.8 ms, median 6.5, kept.
//!
//! A worker kept on a processor cannot move off it when another program keeps that
//! processor busy: `SHATTER_PIN_THREADS=0` leaves the threads to the scheduler. Library
//! users keep their own pools; only the command line calls [`pin_global_pool`].

use crate::error::LabError;

/// The environment variable that turns keeping the pool's threads on processors off
/// (`0`) or on (`1`, the default).
pub const PIN_VARIABLE: &str = "SHATTER_PIN_THREADS";

/// Whether the pool's threads are kept on processors, from [`PIN_VARIABLE`]'s value
/// (`None`: not set, so yes). Anything but `0`, `1`, `off`, `on`, `false` and `true` is
/// bad input naming the variable.
///
/// ```
/// use shatter_lab::threads::pinning;
/// assert_eq!(pinning(None), Ok(true));
/// assert_eq!(pinning(Some("0")), Ok(false));
/// assert!(pinning(Some("maybe")).unwrap_err().to_string().contains("SHATTER_PIN_THREADS"));
/// ```
pub fn pinning(value: Option<&str>) -> Result<bool, LabError> {
    match value.map(str::trim) {
        None | Some("1" | "on" | "true") => Ok(true),
        Some("0" | "off" | "false") => Ok(false),
        Some(other) => Err(LabError::input(format!(
            "{PIN_VARIABLE}={other}: expected 0 (threads left to the scheduler) or 1 (each \
             pool thread kept on one processor, the default)"
        ))),
    }
}

/// Builds rayon's global pool, its size rayon's default (`RAYON_NUM_THREADS`, else one
/// thread per processor), with worker `i` kept on the `i`-th processor this process may
/// use (round robin), unless [`PIN_VARIABLE`] says `0`. Call it before anything uses
/// rayon. Returns how many processors the workers were spread over (0: not kept, as on
/// one processor, off Linux, with the variable at `0`, or when the pool already runs).
pub fn pin_global_pool() -> Result<usize, LabError> {
    let wanted = pinning(std::env::var(PIN_VARIABLE).ok().as_deref())?;
    if !wanted {
        return Ok(0);
    }
    Ok(pin(allowed_processors()))
}

#[cfg(target_os = "linux")]
fn allowed_processors() -> Vec<usize> {
    use rustix::thread::{CpuSet, sched_getaffinity};
    match sched_getaffinity(None) {
        Ok(set) => (0..CpuSet::MAX_CPU).filter(|&c| set.is_set(c)).collect(),
        Err(_) => Vec::new(),
    }
}

#[cfg(not(target_os = "linux"))]
fn allowed_processors() -> Vec<usize> {
    Vec::new()
}

/// The global pool with worker `i` kept on `cpus[i % len]`; the number of processors
/// used (0 when fewer than two, or when the pool was already built).
fn pin(cpus: Vec<usize>) -> usize {
    if cpus.len() < 2 {
        return 0;
    }
    let count = cpus.len();
    let built = rayon::ThreadPoolBuilder::new()
        .start_handler(move |i| keep_on(cpus[i % cpus.len()]))
        .build_global();
    if built.is_ok() { count } else { 0 }
}

#[cfg(target_os = "linux")]
fn keep_on(cpu: usize) {
    use rustix::thread::{CpuSet, sched_setaffinity};
    let mut one = CpuSet::new();
    one.set(cpu);
    // Refused (a processor taken away meanwhile): the thread stays where it may run.
    let _ = sched_setaffinity(None, &one);
}

#[cfg(not(target_os = "linux"))]
fn keep_on(_cpu: usize) {}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_variable_turns_pinning_on_and_off_and_refuses_anything_else() {
        for on in [None, Some("1"), Some("on"), Some(" true ")] {
            assert_eq!(pinning(on), Ok(true), "{on:?}");
        }
        for off in [Some("0"), Some("off"), Some("false")] {
            assert_eq!(pinning(off), Ok(false), "{off:?}");
        }
        for bad in ["", "2", "yes", "maybe"] {
            let e = pinning(Some(bad)).expect_err("refused");
            assert!(
                matches!(&e, LabError::Input(m) if m.contains(PIN_VARIABLE)),
                "{bad:?}: {e:?}"
            );
        }
    }
}
