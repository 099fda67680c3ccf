//! One module per command: each has a clap `Args` struct and a `run` function that
//! validates the arguments, calls `shatter_lab` (where the work, the CSV schemas and the
//! plots live) and prints what it returns. A new benchmark is a module of
//! `shatter_lab::bench`, a `bench_NAME.rs` here and a variant of `main.rs`'s
//! `BenchCommand`.

pub mod batch;
pub mod bench_creation;
pub mod bench_delaunay;
pub mod bench_fracture;
pub mod bench_runtime;
pub mod bench_scale;
pub mod bench_step;
pub mod bench_stress;
pub mod fracture;
pub mod fracture_asset;
pub mod inspect;
pub mod shape;
pub mod simulate;
pub mod study;
pub mod tetrahedralize;
