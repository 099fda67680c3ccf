//! The machine's limits (memory, time) and the refusal of an estimate beyond them.

use super::{Estimate, format_bytes, format_duration};

/// Limits to check estimates against.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Limits {
    /// The machine's memory; a computation may use [`USABLE_MEMORY_FRACTION`] of it.
    /// `None`: no memory limit.
    pub memory_bytes: Option<u64>,
    /// Wall-clock seconds a computation may take; `None`: no time limit.
    pub seconds: Option<f64>,
    /// Where the memory figure comes from ("MemTotal in /proc/meminfo", ...).
    pub memory_source: &'static str,
}

/// The share of the machine's memory a request may be estimated at: the rest is left to
/// the system and the other processes, and covers the estimates' error (within a factor
/// of two).
pub const USABLE_MEMORY_FRACTION: f64 = 0.8;

/// The default time limit of the command line: one hour of estimated work.
pub const DEFAULT_SECONDS_LIMIT: f64 = 3600.0;

impl Limits {
    /// No limits at all.
    pub fn none() -> Limits {
        Limits {
            memory_bytes: None,
            seconds: None,
            memory_source: "no limit",
        }
    }

    /// This machine's memory ([`machine_memory`]) and the time limit `seconds`.
    pub fn machine(seconds: Option<f64>) -> Limits {
        let memory = machine_memory();
        Limits {
            memory_bytes: memory.map(|m| m.limit),
            seconds,
            memory_source: memory.map_or("unknown", |m| m.source),
        }
    }

    /// `Ok` when `estimate` fits both limits; otherwise the error says what (`what`, e.g.
    /// "3,000,000,000 points"), how much it needs and how much there is.
    pub fn check(&self, what: &str, estimate: &Estimate) -> Result<(), BudgetError> {
        if let Some(limit) = self.memory_bytes
            && estimate.bytes > limit as f64 * USABLE_MEMORY_FRACTION
        {
            return Err(BudgetError::Memory {
                what: what.to_string(),
                needs_bytes: estimate.bytes,
                limit_bytes: limit,
                limit_source: self.memory_source,
            });
        }
        if let Some(limit) = self.seconds
            && estimate.seconds > limit
        {
            return Err(BudgetError::Time {
                what: what.to_string(),
                needs_seconds: estimate.seconds,
                limit_seconds: limit,
            });
        }
        Ok(())
    }
}

/// A request refused because its estimate exceeds a limit.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum BudgetError {
    /// More memory than the machine has.
    #[error(
        "{what} need about {}; this machine has {} ({limit_source}), of which a run may use {}",
        format_bytes(*needs_bytes),
        format_bytes(*limit_bytes as f64),
        format_bytes(*limit_bytes as f64 * USABLE_MEMORY_FRACTION)
    )]
    Memory {
        /// What was asked for.
        what: String,
        /// The estimate, in bytes.
        needs_bytes: f64,
        /// The machine's memory, in bytes.
        limit_bytes: u64,
        /// Where that figure comes from.
        limit_source: &'static str,
    },
    /// More time than the limit.
    #[error(
        "{what} would take about {}; the limit is {}",
        format_duration(*needs_seconds),
        format_duration(*limit_seconds)
    )]
    Time {
        /// What was asked for.
        what: String,
        /// The estimate, in seconds.
        needs_seconds: f64,
        /// The limit, in seconds.
        limit_seconds: f64,
    },
}

/// The machine's memory as read from the system.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct MachineMemory {
    /// The limit requests are refused against: `MemTotal`, or the control group's
    /// `memory.max` when that is lower.
    pub limit: u64,
    /// `MemAvailable` now (free memory plus what the kernel can reclaim), if known.
    pub available: Option<u64>,
    /// Where `limit` comes from.
    pub source: &'static str,
}

/// The machine's memory, from `/proc/meminfo` (and cgroup v2's `memory.max`).
///
/// Requests are refused against **`MemTotal`**, not `MemAvailable`: a request above the
/// total can never succeed, whatever else runs, while `MemAvailable` changes from one
/// second to the next with the other processes of a shared machine and the page cache,
/// so a refusal based on it would not be reproducible and would refuse runs that
/// succeed once the cache shrinks. Callers may warn when an estimate is above
/// [`MachineMemory::available`].
///
/// Where `/proc/meminfo` cannot be read: in WebAssembly the limit is a fixed 4 GiB, all
/// that a wasm32 module can address; elsewhere (not Linux) `None`, and nothing is
/// refused for memory.
pub fn machine_memory() -> Option<MachineMemory> {
    if cfg!(target_arch = "wasm32") {
        return Some(MachineMemory {
            limit: 4 << 30,
            available: None,
            source: "the 4 GiB a wasm32 module can address",
        });
    }
    let meminfo = std::fs::read_to_string("/proc/meminfo").ok()?;
    let total = meminfo_kib(&meminfo, "MemTotal:")? * 1024;
    let available = meminfo_kib(&meminfo, "MemAvailable:").map(|k| k * 1024);
    let cgroup = std::fs::read_to_string("/sys/fs/cgroup/memory.max")
        .ok()
        .and_then(|s| s.trim().parse::<u64>().ok());
    Some(match cgroup {
        Some(max) if max < total => MachineMemory {
            limit: max,
            available: available.map(|a| a.min(max)),
            source: "memory.max of this control group",
        },
        _ => MachineMemory {
            limit: total,
            available,
            source: "MemTotal in /proc/meminfo",
        },
    })
}

/// A `kB` field of `/proc/meminfo`.
pub(super) fn meminfo_kib(meminfo: &str, field: &str) -> Option<u64> {
    let line = meminfo.lines().find(|l| l.starts_with(field))?;
    line[field.len()..].split_whitespace().next()?.parse().ok()
}
