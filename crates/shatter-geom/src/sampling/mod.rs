//! Deterministic random point sets (ChaCha8 seeded), for tests, benchmarks and the CLI's
//! `--random N --distribution D --seed S`.

mod distributions;

pub use distributions::{Distribution, ball, gaussian, grid, sample, sphere, uniform};
