//! Exact 3D Delaunay tetrahedralization.
//!
//! API contract:
//! - [`tetrahedralize`] takes any slice of points and returns a [`Tetrahedralization`]
//!   or a typed [`DelaunayError`].
//! - Every tetrahedron `[a, b, c, d]` is positively oriented:
//!   `(b - a) · ((c - a) × (d - a)) > 0` (exactly, by `robust::orient3d`), i.e. `d` sees
//!   the triangle `a, b, c` counter-clockwise. The face opposite vertex `i`, wound
//!   outward, is [`FACES`]`[i]`.
//! - `neighbors[t][i]` is the tetrahedron across the face opposite vertex `i` of `t`,
//!   or [`NO_NEIGHBOR`] on the convex hull.
//! - Indices refer to the input slice; a duplicate point maps to its first occurrence.
//!
//! # Algorithm
//! Bowyer–Watson insertion in BRIO order (random rounds, each sorted along a Hilbert
//! curve), a visibility walk from the last created tetrahedron with a random face order,
//! exact predicates (`robust`'s adaptive `orient3d` and `insphere`) and a symbolic
//! perturbation of the lifted coordinate ordered lexicographically by position
//! ([`insphere_perturbed`]) for cospherical cases. The convex hull is closed by an
//! infinite vertex (CGAL style): every hull face carries an infinite tetrahedron, so there
//! is no inexact bounding box and no special case in the walk or the cavity search.
//!
//! From 200,000 points on, the points are split in two halves triangulated at once on two
//! threads and joined exactly (`split.rs`: the halves' tetrahedra whose circumspheres
//! stay on their side are kept, the gap between is triangulated again); the result is
//! the same set of tetrahedra.
//!
//! # Storage
//! One record per tetrahedron: its four vertices (internal ids, `0` = infinite vertex),
//! two flags ("in the current cavity", "tested, not in conflict") and its face adjacency
//! `a_i = n << 2 | j`: tetrahedron `n` is across the face opposite `v_i`, and that face is
//! opposite vertex `j` in `n`. Up to about two million points the records are packed into
//! 24 bytes (21 bits per vertex, 26 per adjacency field) at fixed bit positions; up to
//! about 16.7 million into 27 bytes (24 and 29 bits); beyond, or if the tetrahedra
//! outgrow a packed layout, two `[u32; 4]` arrays (32 bytes) take over (see `packed/`).
//! The result keeps the same records, so it is as compact.
//!
//! Up to about two million points, the points are copied in insertion order and numbered
//! in it, so an insertion reads memory the previous ones read; beyond, they are read in
//! place, numbered by their input index, which saves the copy's 24 bytes per point and
//! costs about 15 % more time (the reads are scattered).
//!
//! An infinite tetrahedron `(a, b, c, ∞)` is in conflict with `p` when `p` is strictly
//! beyond the hull face `abc`, or on its plane and in conflict with the finite tetrahedron
//! behind it (so flat hull regions are 2D Delaunay under the same perturbation).
//!
//! Freed slots (a cavity larger than its star) go to a free list. Scratch buffers (cavity,
//! stack, boundary faces, an open-addressing edge table with generation stamps) are reused
//! across insertions, so an insertion allocates nothing. The result drops the infinite
//! tetrahedra and renumbers in place with a rank bitmap.
//!
//! # Memory
//! About 6.75 tetrahedra per point for uniform points, so up to two million points the
//! result takes about 6.75 × 24 + 4 (`representative`) ≈ 166 bytes per point, and the
//! construction adds the points in insertion order (24) and the order itself (4): a peak
//! of about 190 bytes per point on top of the input (CGAL 5.5: about 550). Beyond, the
//! result takes 6.75 × 27 + 4 ≈ 187 bytes per point, which is also the peak (10 million
//! uniform points: 1.88 GB).
//!
//! # Speed
//! On uniform points nearly every predicate is decided by the inlined floating-point
//! filters; side by side with CGAL 5.5 on the same million points it takes 0.46–0.47 of
//! CGAL's sequential time on two cores, 0.70 of CGAL's parallel insertion on the same two,
//! and about 0.9 of CGAL's time on one core (see `bench/cgal/README.md`). Inputs where most tests are (nearly) cospherical need exact
//! stages: when the coordinates' magnitudes are within about 2^37 of each other, the
//! determinant is evaluated in 128-bit (lattices, grids) or 512-bit integers (`exact.rs`),
//! otherwise by `robust`'s expansion arithmetic. A 200k-point grid then takes about 1.4×
//! CGAL's time, 200k points on a sphere about 2.5× CGAL's.
//!
//! # Example
//! ```
//! use shatter_geom::delaunay::tetrahedralize;
//! use shatter_geom::sampling::uniform;
//! let pts = uniform(1000, 1);
//! let t = tetrahedralize(&pts).expect("points in general position");
//! t.validate(&pts).expect("exactly Delaunay");
//! assert_eq!(t.unique_points, 1000);
//! ```

mod build;
mod exact;
mod insert;
mod order;
mod output;
mod packed;
mod predicates;
mod sequential;
mod split;
mod storage;
mod types;
mod validate;

pub use build::tetrahedralize;
pub use predicates::{MAX_MAGNITUDE, MIN_MAGNITUDE, insphere_perturbed, insphere_raw, orient};
pub use types::{DelaunayError, FACES, NO_NEIGHBOR, Tetrahedralization};
pub use validate::ValidationError;
