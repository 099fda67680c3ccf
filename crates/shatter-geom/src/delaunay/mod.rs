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
//! # Storage
//! Two parallel arrays, indexed by tetrahedron, 32 bytes per tetrahedron in all:
//! ```text
//!  tv[t]  = [v0, v1, v2, v3]         internal vertex ids (0 = infinite vertex,
//!                                    bit 31 of v3 = "in the current cavity")
//!  adj[t] = [a0, a1, a2, a3]         a_i = neighbour across the face opposite v_i:
//!
//!           31                           2 1   0
//!          +------------------------------+-----+
//!          |   neighbour tetrahedron n    |  j  |   j = index of that face in n
//!          +------------------------------+-----+   (adj[n][j] >> 2 == t)
//! ```
//! Freed slots (a cavity larger than its star) go to a free list. Scratch buffers (cavity,
//! stack, boundary faces, an open-addressing edge table with generation stamps) are reused
//! across insertions, so an insertion allocates nothing. The result drops the infinite
//! tetrahedra and renumbers in place with a rank bitmap.

mod build;
mod insert;
mod order;
mod output;
mod predicates;
mod storage;
mod types;
mod validate;

pub use build::tetrahedralize;
pub use predicates::{MAX_MAGNITUDE, MIN_MAGNITUDE, insphere_perturbed, insphere_raw, orient};
pub use types::{DelaunayError, FACES, NO_NEIGHBOR, Tetrahedralization};
pub use validate::ValidationError;
