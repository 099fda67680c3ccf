//! The fracture benchmark: the fracture methods timed on the built-in shapes.
//!
//! Cases: the bird into 100 Voronoi fragments (the comparison with Blender's Cell
//! Fracture), the thesis's creation case (cube + 500 random points, tetra), and a few
//! more rows covering every method. Each case is run `runs` times after one untimed
//! warm-up; mean, min and max are reported.

use serde::Serialize;
use shatter_geom::budget::{Estimate, format_count};
use shatter_geom::fracture::{Method, Pattern, Placement};
use shatter_geom::shapes::Shape;

use crate::bar::Bar;
use crate::context::Context;
use crate::error::LabError;
use crate::fracture::{FractureConfig, fracture_estimate, fracture_timed, load_source};
use crate::spread::Spread;

/// One benchmark case.
#[derive(Debug, Clone)]
pub struct Case {
    /// Its name in the table.
    pub name: &'static str,
    /// The shape fractured.
    pub shape: Shape,
    /// How.
    pub method: Method,
}

/// The cases, in the order they run.
pub fn cases() -> Vec<Case> {
    let voronoi = Method::voronoi;
    let tetra = Method::tetra;
    let case = |name, shape, method| Case {
        name,
        shape,
        method,
    };
    vec![
        case(
            "bird voronoi 100",
            Shape::Bird,
            voronoi(100, Pattern::Uniform),
        ),
        case(
            "cube tetra 500 thesis",
            Shape::Cube,
            tetra(500, Placement::Thesis),
        ),
        case(
            "cube tetra 500 interior",
            Shape::Cube,
            tetra(500, Placement::Interior),
        ),
        case(
            "bird tetra 200 interior",
            Shape::Bird,
            tetra(200, Placement::Interior),
        ),
        case(
            "capsule voronoi 50",
            Shape::Capsule,
            voronoi(50, Pattern::Uniform),
        ),
        case(
            "cylinder voronoi 50",
            Shape::Cylinder,
            voronoi(50, Pattern::Uniform),
        ),
        case(
            "bird voronoi 100 radial",
            Shape::Bird,
            voronoi(100, Pattern::Radial),
        ),
        case(
            "bird slice 8",
            Shape::Bird,
            Method::Slice {
                planes: None,
                pieces: 8,
            },
        ),
        case(
            "cube slice 8",
            Shape::Cube,
            Method::Slice {
                planes: None,
                pieces: 8,
            },
        ),
    ]
}

/// One measured case.
#[derive(Debug, Clone, Serialize)]
pub struct Row {
    /// The case's name.
    pub case: &'static str,
    /// The shape's name.
    pub shape: &'static str,
    /// Fragments made (warm-up run).
    pub fragments: usize,
    /// Bonds made (warm-up run).
    pub bonds: usize,
    /// Timed runs.
    pub runs: u32,
    /// Mean ms.
    pub mean_ms: f64,
    /// Fastest run, ms.
    pub min_ms: f64,
    /// Slowest run, ms.
    pub max_ms: f64,
}

/// The `--json` report.
#[derive(Debug, Clone, Serialize)]
pub struct Report {
    /// The seed of every case.
    pub seed: u64,
    /// One row per case.
    pub rows: Vec<Row>,
}

/// A benchmark whose estimate fitted the limits, ready to run.
#[derive(Debug)]
pub struct BenchFracture {
    runs: u32,
    seed: u64,
}

impl BenchFracture {
    /// Checks the estimate of every case (`runs` timed runs and a warm-up each, at
    /// least 1 run) against the context's limits.
    pub fn prepare(runs: u32, seed: u64, ctx: &Context) -> Result<Self, LabError> {
        if runs == 0 {
            return Err(LabError::input("--runs must be at least 1"));
        }
        let bench = Self { runs, seed };
        let mut total = Estimate::default();
        for case in cases() {
            let config = bench.config(&case);
            let (model, _) = load_source(&config)?;
            let (_, e) = fracture_estimate(&model.mesh, &config);
            total.bytes = total.bytes.max(e.bytes);
            total.seconds += e.seconds * (f64::from(runs) + 1.0);
        }
        ctx.check(
            &format!(
                "--runs {runs}: {} fracture runs",
                format_count((u64::from(runs) + 1) * cases().len() as u64)
            ),
            &total,
        )?;
        Ok(bench)
    }

    fn config(&self, case: &Case) -> FractureConfig {
        FractureConfig::shape(case.shape, case.method.clone(), self.seed)
    }

    /// Times every case, with a bar unless `quiet`; `on_row` gets each row as it is
    /// measured, with the bar to print above.
    pub fn run(
        &self,
        ctx: &Context,
        quiet: bool,
        mut on_row: impl FnMut(&Row, &Bar),
    ) -> Result<Report, LabError> {
        let bar = ctx.bar(cases().len() as u64, quiet);
        let mut rows = Vec::new();
        for case in cases() {
            let config = self.config(&case);
            let (model, _) = load_source(&config)?;
            ctx.progress.check()?;
            let (warm, _, _) = fracture_timed(&model, &config)?;
            let mut times = Vec::with_capacity(self.runs as usize);
            for _ in 0..self.runs {
                ctx.progress.check()?;
                let (_, _, ms) = fracture_timed(&model, &config)?;
                times.push(ms);
            }
            bar.tick(case.name);
            let spread = Spread::of(times).ok_or_else(|| LabError::internal("no timed run"))?;
            let row = Row {
                case: case.name,
                shape: case.shape.name(),
                fragments: warm.fragments.len(),
                bonds: warm.bonds.len(),
                runs: self.runs,
                mean_ms: spread.mean,
                min_ms: spread.min,
                max_ms: spread.max,
            };
            on_row(&row, &bar);
            rows.push(row);
        }
        Ok(Report {
            seed: self.seed,
            rows,
        })
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;
    use shatter_geom::budget::Limits;

    #[test]
    fn the_cases_have_unique_names_and_cover_every_method() {
        let cases = cases();
        let mut names: Vec<&str> = cases.iter().map(|c| c.name).collect();
        names.sort();
        names.dedup();
        assert_eq!(names.len(), cases.len());
        assert!(
            cases
                .iter()
                .any(|c| matches!(c.method, Method::Tetra { .. }))
        );
        assert!(
            cases
                .iter()
                .any(|c| matches!(c.method, Method::Voronoi { .. }))
        );
        assert!(
            cases
                .iter()
                .any(|c| matches!(c.method, Method::Slice { .. }))
        );
    }

    #[test]
    fn zero_runs_and_a_tight_time_limit_are_refused_before_any_run() {
        let ctx = Context::quiet(Limits::none());
        assert_eq!(
            BenchFracture::prepare(0, 0, &ctx).unwrap_err(),
            LabError::input("--runs must be at least 1")
        );
        let tight = Context::quiet(Limits {
            memory_bytes: None,
            seconds: Some(1e-9),
            memory_source: "test",
        });
        let e = BenchFracture::prepare(5, 0, &tight).unwrap_err();
        assert!(
            e.to_string().starts_with("--runs 5: 54 fracture runs"),
            "{e}"
        );
    }
}
