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
//! assert!(err.to_string().starts_with("3,000,000,000 points need about 786 GB"), "{err}");
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

mod format;
mod limits;

pub use format::{format_bytes, format_count, format_duration};
pub use limits::{
    BudgetError, DEFAULT_SECONDS_LIMIT, Limits, MachineMemory, USABLE_MEMORY_FRACTION,
    machine_memory,
};

use crate::TriMesh;
use std::fmt;

/// A shatter process's own resident set before any work (the binary, the thread pool's
/// stacks, the allocator): `shatter tetrahedralize --random 100` peaks at 5.9 MB.
pub const PROCESS_BYTES: f64 = 8.0e6;
/// Peak bytes per point of a Delaunay tetrahedralization above its input (the packed
/// records, the BRIO order, the walk's buffers). `shatter bench delaunay --sizes
/// 100000,1000000,3000000,10000000` measured 207, 218, 188 and 188 bytes per point for
/// uniform points (beyond about two million points the records are 27 bytes and the
/// points are read in place, not copied).
pub const DELAUNAY_BYTES_PER_POINT: f64 = 230.0;
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
/// Seconds per surface vertex of a tetra fracture on top of
/// [`TETRA_SECONDS_PER_TETRAHEDRON`] (its tetrahedra clipped to the mesh, its slivers
/// merged): `shatter fracture FILE --method tetra --random-vertices 20` on 2 cores took
/// 266 s for the 2-cylinder engine's 87,000 surface vertices (3.1 ms each) and 11–17 s
/// for the Stanford bunny's 34,834 (0.3–0.5 ms each).
pub const TETRA_SECONDS_PER_SURFACE_POINT: f64 = 2.0e-3;
/// Bytes per surface vertex of a tetra fracture on top of
/// [`TETRA_BYTES_PER_TETRAHEDRON`]: the engine's peaks at about 2.1 GB.
pub const TETRA_BYTES_PER_SURFACE_POINT: f64 = 12_000.0;
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
    /// after `skip`, random points, the centre), `surface` of them surface vertices: the
    /// tetrahedralization, then a piece per tetrahedron (slivers are merged
    /// afterwards). The tetrahedra at the surface, about three per surface vertex, are
    /// clipped to the mesh and mostly merged, and cost far more than the others.
    ///
    /// ```
    /// use shatter_geom::budget::Estimate;
    /// let inside = Estimate::tetra_fracture(10_000, 100);
    /// let dense = Estimate::tetra_fracture(10_000, 9_900);
    /// assert!(dense.seconds > 5.0 * inside.seconds);
    /// ```
    pub fn tetra_fracture(points: u64, surface: u64) -> Estimate {
        let tetrahedra = points as f64 * TETRAHEDRA_PER_POINT;
        let surface = surface.min(points) as f64;
        Estimate::delaunay(points)
            + Estimate {
                bytes: tetrahedra * TETRA_BYTES_PER_TETRAHEDRON
                    + surface * TETRA_BYTES_PER_SURFACE_POINT,
                seconds: tetrahedra * TETRA_SECONDS_PER_TETRAHEDRON
                    + surface * TETRA_SECONDS_PER_SURFACE_POINT,
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
mod tests;
