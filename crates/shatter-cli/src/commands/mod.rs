//! One module per command: each has a clap `Args` struct and a `run` function.

pub mod batch;
pub mod bench_creation;
pub mod bench_delaunay;
pub mod bench_fracture;
pub mod bench_step;
pub mod bench_stress;
pub mod fracture;
pub mod fracture_asset;
pub mod inspect;
pub mod shape;
pub mod simulate;
pub mod study;
pub mod tetrahedralize;
