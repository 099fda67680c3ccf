//! Resource estimates: how much memory and time a tetrahedralization or a fracture of a
//! given size needs, and the machine's limits to check them against before the work
//! starts, so that an impossible request is refused at once instead of running until the
//! system kills it.
//!
//! ```
//! use shatter_geom::budget::{Estimate, Limits};
//!
//! let limits = Limits { memory_bytes: Some(24e9 as u64), seconds: None, memory_source: "test" };
//! let huge = Estimate::delaunay(3_000_000_000);
//! let err = limits.check("3,000,000,000 points", &huge).unwrap_err();
//! assert!(err.to_string().starts_with("3,000,000,000 points need about 846 GB"), "{err}");
//! assert!(limits.check("1,000 points", &Estimate::delaunay(1000)).is_ok());
//! ```
//!
//! # Basis of the figures
//!
//! Every constant below was measured with the release build on the project's 2-core
//! machine (the commands are in the comments) and is rounded up. Memory is the peak
//! resident set (`VmHWM`) of the run above the process's own; time is CPU time on a
//! machine shared with other builds, which is close to the wall-clock time on a quiet
//! machine. The memory estimates are within a factor of two of a real run (the
//! command line's tests check it at small sizes); the time estimates within a factor of
//! about four on uniform input (time depends on the machine and the input's
//! degeneracy), and are not tested, as tests are not timed. They are estimates for
//! *refusing* requests far beyond the machine, not predictions to the percent.

use crate::TriMesh;
use std::fmt;

/// A shatter process's own resident set before any work (the binary, the thread pool's
/// stacks, the allocator): `shatter tetrahedralize --random 100` peaks at 5.9 MB.
pub const PROCESS_BYTES: f64 = 8.0e6;
/// Peak bytes per point of a Delaunay tetrahedralization above its input (the packed
/// records, the BRIO order, the walk's buffers). `shatter bench delaunay --sizes
/// 100000,1000000,3000000` measured 203, 190 and 244 bytes per point for uniform points
/// (beyond about two million points the records are wider).
pub const DELAUNAY_BYTES_PER_POINT: f64 = 250.0;
/// Bytes of one input point (a `DVec3`) and its share of the sampling buffers.
pub const POINT_BYTES: f64 = 32.0;
/// Points inserted per second by the Delaunay tetrahedralization, uniform points, on a
/// quiet 2-core machine: 1,000,000 points in 3.5-4.2 s (`bench/cgal/README.md`).
/// Degenerate sets (points on a sphere) take up to 5 times longer.
pub const DELAUNAY_POINTS_PER_SECOND: f64 = 2.5e5;
/// Tetrahedra per point of a 3D Delaunay tetrahedralization of uniform points (6.7 for a
/// million points; points on a surface give fewer).
pub const TETRAHEDRA_PER_POINT: f64 = 6.7;
/// Bytes per tetrahedron of a tetra fracture at its peak (each tetrahedron is a piece,
/// clipped to the mesh where the surface enters it, before slivers are merged as
/// unions): `shatter fracture --shape cube --method tetra --random-vertices 20000
/// --json` peaks at 236 MB for about 134,000 tetrahedra.
pub const TETRA_BYTES_PER_TETRAHEDRON: f64 = 1700.0;
/// CPU seconds per tetrahedron of a tetra fracture after the tetrahedralization
/// (clipping and union-based merging: about 3e-5 s on the cube with 500 points, 1e-4 s
/// on the bird, where most tetrahedra touch the surface).
pub const TETRA_SECONDS_PER_TETRAHEDRON: f64 = 3.0e-5;
/// Bytes per Voronoi cell at the peak (its clipped mesh with caps, convex pieces,
/// bonds): `shatter fracture --shape bird --pieces 1000` and `--pieces 4000` peak at
/// 11 and 10.5 kB per cell above the process.
pub const VORONOI_BYTES_PER_CELL: f64 = 12_000.0;
/// Bytes per mesh triangle for each cell being clipped at once (each starts as a copy
/// of the whole mesh) and for the surface the fragments share.
pub const BYTES_PER_TRIANGLE: f64 = 400.0;
/// Seconds per Voronoi cell, whatever the mesh (building its fragment and bonds).
pub const VORONOI_SECONDS_PER_CELL: f64 = 3.0e-5;
/// Seconds per Voronoi cell and mesh triangle (the first cuts see the whole mesh): the
/// bird's 1,394 triangles into 1,000 and 4,000 cells took 0.16 and 0.49 s of CPU on 2
/// threads.
pub const VORONOI_SECONDS_PER_CELL_TRIANGLE: f64 = 5.0e-8;
/// Bytes per slice piece at the peak: `--method slice --pieces 48` on the bird made
/// 1,026 pieces and peaked 11 MB above the process.
pub const SLICE_BYTES_PER_PIECE: f64 = 12_000.0;
/// Seconds per slice piece and per plane (every plane is tried on every piece): the same
/// run took 0.3 s of CPU for 1,026 pieces × 48 planes.
pub const SLICE_SECONDS_PER_PIECE_PLANE: f64 = 6.0e-6;
/// Bytes per brick of a box's grid fracture (a 12-triangle box, its tags and bonds).
pub const GRID_BYTES_PER_BRICK: f64 = 2_000.0;
/// Seconds per brick of a box's grid fracture.
pub const GRID_SECONDS_PER_BRICK: f64 = 2.0e-6;

/// What a computation needs: peak memory in bytes and wall-clock seconds.
///
/// Figures are `f64` so that absurd requests (`usize::MAX` points) are estimated without
/// overflow.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Estimate {
    /// Peak memory in bytes.
    pub bytes: f64,
    /// Wall-clock seconds.
    pub seconds: f64,
}

impl std::ops::Add for Estimate {
    type Output = Estimate;
    /// Two computations one after the other, both results kept: memory and time add.
    fn add(self, other: Estimate) -> Estimate {
        Estimate {
            bytes: self.bytes + other.bytes,
            seconds: self.seconds + other.seconds,
        }
    }
}

impl Estimate {
    /// The 3D Delaunay tetrahedralization of `points` points (the input included).
    pub fn delaunay(points: u64) -> Estimate {
        let n = points as f64;
        Estimate {
            bytes: n * (POINT_BYTES + DELAUNAY_BYTES_PER_POINT),
            seconds: n / DELAUNAY_POINTS_PER_SECOND,
        }
    }

    /// The tetra fracture of a mesh with `points` Delaunay points (surface vertices kept
    /// after `skip`, random points, the centre): the tetrahedralization, then a piece
    /// per tetrahedron (slivers are merged afterwards).
    pub fn tetra_fracture(points: u64) -> Estimate {
        let tetrahedra = points as f64 * TETRAHEDRA_PER_POINT;
        Estimate::delaunay(points)
            + Estimate {
                bytes: tetrahedra * TETRA_BYTES_PER_TETRAHEDRON,
                seconds: tetrahedra * TETRA_SECONDS_PER_TETRAHEDRON,
            }
    }

    /// The Voronoi fracture of a mesh of `triangles` triangles into `cells` cells.
    pub fn voronoi_fracture(cells: u64, triangles: u64) -> Estimate {
        let (k, t) = (cells as f64, triangles as f64);
        // The cells are clipped in parallel, each from a copy of the whole mesh; the
        // finished fragments hold the surface once and the caps per cell.
        let in_flight = k.min(threads());
        Estimate::delaunay(cells)
            + Estimate {
                bytes: k * VORONOI_BYTES_PER_CELL + (in_flight + 1.0) * t * BYTES_PER_TRIANGLE,
                seconds: k * (VORONOI_SECONDS_PER_CELL + t * VORONOI_SECONDS_PER_CELL_TRIANGLE),
            }
    }

    /// The slice fracture of a mesh of `triangles` triangles by `planes` planes, making
    /// [`slice_pieces`] pieces.
    pub fn slice_fracture(planes: u64, triangles: u64) -> Estimate {
        let pieces = slice_pieces(planes);
        Estimate {
            bytes: pieces * SLICE_BYTES_PER_PIECE + triangles as f64 * BYTES_PER_TRIANGLE,
            seconds: pieces * planes as f64 * SLICE_SECONDS_PER_PIECE_PLANE,
        }
    }

    /// The grid fracture of a mesh of `triangles` triangles into `cells` cells: bricks
    /// when the mesh is a box (`boxed`, see [`is_box`]), else a slice by the grid's
    /// planes, each plane tried on every piece.
    ///
    /// ```
    /// use shatter_geom::budget::Estimate;
    /// let bricks = Estimate::grid_fracture([40, 25, 20], 12, true);
    /// let clipped = Estimate::grid_fracture([40, 25, 20], 12, false);
    /// assert!(bricks.seconds < clipped.seconds && bricks.bytes < clipped.bytes);
    /// ```
    pub fn grid_fracture(cells: [u32; 3], triangles: u64, boxed: bool) -> Estimate {
        let n: f64 = cells.iter().map(|&c| f64::from(c)).product();
        if boxed {
            return Estimate {
                bytes: n * GRID_BYTES_PER_BRICK,
                seconds: n * GRID_SECONDS_PER_BRICK,
            };
        }
        let planes: f64 = cells.iter().map(|&c| f64::from(c.max(1) - 1)).sum();
        Estimate {
            bytes: n * SLICE_BYTES_PER_PIECE + triangles as f64 * BYTES_PER_TRIANGLE,
            seconds: n * planes * SLICE_SECONDS_PER_PIECE_PLANE,
        }
    }

    /// This estimate with the process's own memory ([`PROCESS_BYTES`]) added: what the
    /// peak resident set of a process doing only this work is expected to be.
    pub fn with_process(self) -> Estimate {
        Estimate {
            bytes: self.bytes + PROCESS_BYTES,
            ..self
        }
    }
}

/// Pieces `planes` random slice planes are expected to make: `0.6 p² + p`, fitted on the
/// bird (4, 8, 16, 32 and 48 planes made 12, 36, 159, 540 and 1,026 pieces; the fit
/// gives 14, 46, 170, 646 and 1,430), and never more than [`slice_pieces_at_most`].
pub fn slice_pieces(planes: u64) -> f64 {
    let p = planes as f64;
    (0.6 * p * p + p).min(slice_pieces_at_most(planes)).max(1.0)
}

/// Fragments a fracture can return at most: pieces below
/// [`SLIVER_VOLUME_FRACTION`](crate::fracture::SLIVER_VOLUME_FRACTION) of the mesh's
/// volume are merged into a neighbour, so `n` requested pieces give at most
/// `min(n, 1 / fraction)` fragments (10,000).
pub fn fragments_at_most(pieces: f64) -> f64 {
    pieces.min(1.0 / crate::fracture::SLIVER_VOLUME_FRACTION)
}

/// The most pieces `planes` planes can cut a convex solid into: the cells of an
/// arrangement of planes in general position, `(p³ + 5p + 6) / 6`.
pub fn slice_pieces_at_most(planes: u64) -> f64 {
    let p = planes as f64;
    (p * p * p + 5.0 * p + 6.0) / 6.0
}

/// Worker threads a parallel fracture uses at once.
fn threads() -> f64 {
    std::thread::available_parallelism().map_or(1.0, |n| n.get() as f64)
}

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
fn meminfo_kib(meminfo: &str, field: &str) -> Option<u64> {
    let line = meminfo.lines().find(|l| l.starts_with(field))?;
    line[field.len()..].split_whitespace().next()?.parse().ok()
}

/// `1234567` → `"1,234,567"`.
pub fn format_count(n: u64) -> String {
    let digits = n.to_string();
    let mut out = String::with_capacity(digits.len() + digits.len() / 3);
    for (i, c) in digits.chars().enumerate() {
        if i > 0 && (digits.len() - i).is_multiple_of(3) {
            out.push(',');
        }
        out.push(c);
    }
    out
}

/// Bytes in decimal units with two or three significant digits: `"570 GB"`, `"1.5 MB"`.
pub fn format_bytes(bytes: f64) -> String {
    const UNITS: [&str; 7] = ["bytes", "kB", "MB", "GB", "TB", "PB", "EB"];
    let mut value = bytes.max(0.0);
    let mut unit = 0;
    while value >= 1000.0 && unit + 1 < UNITS.len() {
        value /= 1000.0;
        unit += 1;
    }
    if value >= 1000.0 {
        return format!("{bytes:.1e} bytes");
    }
    format!("{} {}", significant(value), UNITS[unit])
}

/// Seconds as a readable duration: `"40 seconds"`, `"3.2 hours"`, `"95 years"`.
pub fn format_duration(seconds: f64) -> String {
    const STEPS: [(f64, &str); 5] = [
        (60.0, "minutes"),
        (3600.0, "hours"),
        (86_400.0, "days"),
        (365.25 * 86_400.0, "years"),
        (f64::INFINITY, ""),
    ];
    // NaN is printed as seconds too.
    if seconds.is_nan() || seconds < 60.0 {
        return format!("{} seconds", significant(seconds.max(0.0)));
    }
    let mut unit = (60.0, "minutes");
    for w in STEPS.windows(2) {
        if seconds >= w[0].0 {
            unit = w[0];
        }
    }
    let value = seconds / unit.0;
    if value >= 1e6 {
        return format!("{value:.1e} {}", unit.1);
    }
    let number = significant(value);
    // "1 hour", not "1 hours".
    let name = if number == "1" {
        unit.1.trim_end_matches('s')
    } else {
        unit.1
    };
    format!("{number} {name}")
}

/// Two significant digits below 100, whole numbers above.
fn significant(v: f64) -> String {
    if v >= 10.0 || v == v.round() {
        format!("{v:.0}")
    } else {
        format!("{v:.1}")
    }
}

impl fmt::Display for Estimate {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "about {} and {}",
            format_bytes(self.bytes),
            format_duration(self.seconds)
        )
    }
}

/// Whether `mesh` fills its bounding box (its volume that of the box to 1e-12): a box,
/// which the grid method cuts into bricks without clipping.
///
/// ```
/// use shatter_geom::{budget::is_box, shapes, DVec3};
/// assert!(is_box(&shapes::cube().transformed(DVec3::new(4.0, 2.5, 0.4), DVec3::ZERO)));
/// assert!(!is_box(&shapes::sphere(16, 8)));
/// ```
pub fn is_box(mesh: &TriMesh) -> bool {
    let Some((lo, hi)) = mesh.bounds() else {
        return false;
    };
    crate::fracture::fills_box(mesh.signed_volume(), lo, hi)
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;

    fn limits(gb: f64, seconds: Option<f64>) -> Limits {
        Limits {
            memory_bytes: Some((gb * 1e9) as u64),
            seconds,
            memory_source: "test",
        }
    }

    #[test]
    fn the_issue_example_is_refused_with_both_figures() {
        let e = limits(24.0, None)
            .check("3,000,000,000 points", &Estimate::delaunay(3_000_000_000))
            .unwrap_err();
        let text = e.to_string();
        assert!(
            text.starts_with("3,000,000,000 points need about 846 GB"),
            "{text}"
        );
        assert!(
            text.contains(" GB; this machine has 24 GB (test)"),
            "{text}"
        );
        let BudgetError::Memory { needs_bytes, .. } = e else {
            panic!("not a memory refusal: {e}");
        };
        // 3e9 points at 244 bytes each (bench delaunay) and their 24 bytes.
        assert!((8.0e11..9.0e11).contains(&needs_bytes), "{needs_bytes}");
    }

    #[test]
    fn a_request_is_refused_above_the_usable_share_of_the_memory() {
        let l = limits(10.0, None);
        let at = |gb: f64| Estimate {
            bytes: gb * 1e9,
            seconds: 0.0,
        };
        assert!(l.check("it", &at(7.9)).is_ok());
        let e = l.check("it", &at(9.0)).unwrap_err().to_string();
        assert_eq!(
            e,
            "it need about 9 GB; this machine has 10 GB (test), of which a run may use 8 GB"
        );
    }

    #[test]
    fn absurd_counts_are_estimated_without_overflow() {
        for e in [
            Estimate::delaunay(u64::MAX),
            Estimate::tetra_fracture(u64::MAX),
            Estimate::voronoi_fracture(u64::MAX, u64::MAX),
            Estimate::slice_fracture(u64::MAX, 10),
        ] {
            assert!(e.bytes.is_finite() && e.bytes > 1e20, "{e:?}");
            assert!(limits(24.0, None).check("it", &e).is_err());
        }
    }

    #[test]
    fn a_time_limit_refuses_with_the_duration() {
        let e = Estimate {
            bytes: 1.0,
            seconds: 3.0e9,
        };
        let err = limits(24.0, Some(3600.0))
            .check("the scene", &e)
            .unwrap_err();
        assert_eq!(
            err.to_string(),
            "the scene would take about 95 years; the limit is 1 hour"
        );
        assert!(limits(24.0, None).check("the scene", &e).is_ok());
        assert!(
            Limits::none()
                .check("it", &Estimate::delaunay(u64::MAX))
                .is_ok()
        );
    }

    #[test]
    fn estimates_grow_with_the_request() {
        assert!(Estimate::delaunay(2000).bytes > Estimate::delaunay(1000).bytes);
        let (small, big) = (
            Estimate::voronoi_fracture(10, 1000),
            Estimate::voronoi_fracture(1000, 1000),
        );
        assert!(big.bytes > small.bytes && big.seconds > small.seconds);
        assert!(Estimate::tetra_fracture(100).bytes > Estimate::delaunay(100).bytes);
        assert_eq!(slice_pieces_at_most(0), 1.0);
        assert_eq!(slice_pieces_at_most(1), 2.0);
        assert_eq!(slice_pieces_at_most(3), 8.0);
        assert_eq!(slice_pieces(1), 1.6);
        assert_eq!(slice_pieces(48), 0.6 * 48.0 * 48.0 + 48.0);
        assert_eq!(fragments_at_most(4000.0), 4000.0);
        assert_eq!(fragments_at_most(1e9), 10_000.0);
    }

    #[test]
    fn meminfo_fields_are_read_in_kib() {
        let text = "MemTotal:       24576000 kB\nMemFree:  100 kB\nMemAvailable:   20000000 kB\n";
        assert_eq!(meminfo_kib(text, "MemTotal:"), Some(24_576_000));
        assert_eq!(meminfo_kib(text, "MemAvailable:"), Some(20_000_000));
        assert_eq!(meminfo_kib(text, "SwapTotal:"), None);
    }

    #[test]
    fn this_machine_has_a_memory_figure_on_linux() {
        if std::path::Path::new("/proc/meminfo").exists() {
            let m = machine_memory().unwrap();
            assert!(m.limit > 1 << 28, "{m:?}");
            assert!(m.available.is_none_or(|a| a <= m.limit), "{m:?}");
        }
    }

    #[test]
    fn figures_are_formatted_for_people() {
        assert_eq!(format_count(3_000_000_000), "3,000,000,000");
        assert_eq!(format_count(999), "999");
        assert_eq!(format_count(1000), "1,000");
        assert_eq!(format_bytes(570e9), "570 GB");
        assert_eq!(format_bytes(1.5e6), "1.5 MB");
        assert_eq!(format_bytes(24e9), "24 GB");
        assert_eq!(format_bytes(12.0), "12 bytes");
        assert_eq!(format_duration(40.0), "40 seconds");
        assert_eq!(format_duration(2.5), "2.5 seconds");
        assert_eq!(format_duration(3.2 * 3600.0), "3.2 hours");
        assert_eq!(format_duration(90.0), "1.5 minutes");
    }
}
