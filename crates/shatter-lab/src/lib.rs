//! The work behind shatter's commands, as a library: a command line parses and validates
//! its arguments into the plain option structs here, calls one function, and prints what
//! it returns.
//!
//! - [`fracture`]: validated fracture requests ([`fracture::FractureConfig`]), their
//!   resource estimates, loading the mesh they name, running them, the `--json` report.
//! - [`study`]: the thesis study (a shot at the standard cube against each parameter),
//!   `study.csv` and its plots.
//! - [`bench`](mod@bench): the benchmarks — creation (CSV and plots), Delaunay, fracture, step,
//!   stress.
//! - [`export`]: writing meshes and fractures (OBJ with MTL and textures, GLB, the
//!   pre-fractured asset).
//! - [`simulate`]: running a built scene headless, recording per-step statistics and the
//!   animated glTF export, and the run's report.
//! - What they share: [`Context`] (resource limits, the cancel/progress handle, progress
//!   bars: [`bar`]), [`output`] (writing through temporary files), [`Spread`] (mean, min,
//!   max), [`memory`] (the process's resident set) and [`LabError`] (whose fault a
//!   failure is).
//!
//! ```
//! use shatter_geom::fracture::Pattern;
//! use shatter_geom::shapes::Shape;
//! use shatter_lab::fracture::{FractureConfig, fracture_timed, load_source};
//! use shatter_geom::fracture::Method;
//!
//! let config = FractureConfig::shape(Shape::Cube, Method::voronoi(8, Pattern::Uniform), 1);
//! let (model, _warnings) = load_source(&config)?;
//! let (fracture, _warnings, _ms) = fracture_timed(&model, &config)?;
//! assert!(fracture.fragments.len() >= 2);
//! # Ok::<(), shatter_lab::LabError>(())
//! ```

pub mod bar;
pub mod bench;
mod context;
mod error;
pub mod export;
pub mod fracture;
pub mod memory;
pub mod names;
pub mod output;
pub mod simulate;
mod spread;
pub mod study;
pub mod threads;

pub use context::Context;
pub use error::{LabError, ResultExt, chain};
pub use spread::Spread;
