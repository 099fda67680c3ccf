//! The benchmarks behind `shatter bench`, one module each: `creation` (the thesis's
//! chapter 5, CSV and plots), `delaunay`, `fracture`, `runtime`, `scale`, `step` and `stress`. Each takes plain
//! options and a [`Context`](crate::Context) and returns a serialisable report.

pub mod creation;
pub mod delaunay;
pub mod fracture;
pub mod runtime;
pub mod scale;
pub mod step;
pub mod stress;
