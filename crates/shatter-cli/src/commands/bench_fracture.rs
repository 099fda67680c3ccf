//! `shatter bench fracture`: time the fracture methods on the built-in shapes.
//!
//! Cases: the bird into 100 Voronoi fragments (the comparison with Blender's Cell
//! Fracture), the thesis's creation case (cube + 500 random points, tetra), and a few
//! more rows covering every method. Each case is run `--runs` times after one untimed
//! warm-up; mean, min and max are reported.

use clap::Args;
use serde::Serialize;
use shatter_geom::DVec3;
use shatter_geom::budget::{Estimate, format_count};

use crate::commands::fracture::{
    FractureConfig, MeshSource, MethodConfig, VoronoiSeeds, fracture_estimate, fracture_timed,
    load_source,
};
use crate::context::Context;
use crate::error::{CliError, ResultExt};
use shatter_geom::fracture::{Pattern, Placement};
use shatter_geom::shapes::Shape;

/// Arguments of `shatter bench fracture`.
#[derive(Debug, Args)]
pub struct BenchFractureArgs {
    /// Timed runs per case (after one warm-up run).
    #[arg(long, value_name = "R", default_value_t = 5,
          value_parser = clap::value_parser!(u32).range(1..))]
    pub runs: u32,
    /// Random seed of every case.
    #[arg(long, value_name = "S", default_value_t = 0)]
    pub seed: u64,
    /// Print one JSON object instead of a table.
    #[arg(long)]
    pub json: bool,
}

/// One benchmark case.
struct Case {
    name: &'static str,
    shape: Shape,
    method: MethodConfig,
}

fn voronoi(count: usize, pattern: Pattern) -> MethodConfig {
    MethodConfig::Voronoi {
        seeds: VoronoiSeeds::Pattern { count, pattern },
        impact: None,
    }
}

fn tetra(random_vertices: usize, placement: Placement) -> MethodConfig {
    MethodConfig::Tetra {
        random_vertices,
        skip: 0,
        center: false,
        placement,
    }
}

fn cases() -> Vec<Case> {
    vec![
        Case {
            name: "bird voronoi 100",
            shape: Shape::Bird,
            method: voronoi(100, Pattern::Uniform),
        },
        Case {
            name: "cube tetra 500 thesis",
            shape: Shape::Cube,
            method: tetra(500, Placement::Thesis),
        },
        Case {
            name: "cube tetra 500 interior",
            shape: Shape::Cube,
            method: tetra(500, Placement::Interior),
        },
        Case {
            name: "bird tetra 200 interior",
            shape: Shape::Bird,
            method: tetra(200, Placement::Interior),
        },
        Case {
            name: "capsule voronoi 50",
            shape: Shape::Capsule,
            method: voronoi(50, Pattern::Uniform),
        },
        Case {
            name: "cylinder voronoi 50",
            shape: Shape::Cylinder,
            method: voronoi(50, Pattern::Uniform),
        },
        Case {
            name: "bird voronoi 100 radial",
            shape: Shape::Bird,
            method: voronoi(100, Pattern::Radial),
        },
        Case {
            name: "bird slice 8",
            shape: Shape::Bird,
            method: MethodConfig::Slice { planes: 8 },
        },
        Case {
            name: "cube slice 8",
            shape: Shape::Cube,
            method: MethodConfig::Slice { planes: 8 },
        },
    ]
}

/// One measured case.
#[derive(Debug, Serialize)]
struct Row {
    case: &'static str,
    shape: &'static str,
    fragments: usize,
    bonds: usize,
    runs: u32,
    mean_ms: f64,
    min_ms: f64,
    max_ms: f64,
}

/// The `--json` report.
#[derive(Debug, Serialize)]
struct Report {
    seed: u64,
    rows: Vec<Row>,
}

/// Runs `shatter bench fracture`.
pub fn run(args: &BenchFractureArgs, ctx: &Context) -> Result<(), CliError> {
    let config_of = |case: &Case| FractureConfig {
        source: MeshSource::Shape(case.shape),
        scale: DVec3::ONE,
        method: case.method.clone(),
        seed: args.seed,
        strict: true,
    };
    let mut total = Estimate::default();
    for case in cases() {
        let config = config_of(&case);
        let (model, _) = load_source(&config)?;
        let (_, e) = fracture_estimate(&model.mesh, &config);
        total.bytes = total.bytes.max(e.bytes);
        total.seconds += e.seconds * (f64::from(args.runs) + 1.0);
    }
    ctx.check(
        &format!(
            "--runs {}: {} fracture runs",
            args.runs,
            format_count((u64::from(args.runs) + 1) * cases().len() as u64)
        ),
        &total,
    )?;
    let bar = ctx.bar(cases().len() as u64, args.json);
    if !args.json {
        println!(
            "{:<26} {:>9} {:>7} {:>10} {:>10} {:>10}",
            "case", "fragments", "bonds", "mean ms", "min ms", "max ms"
        );
    }
    let mut rows = Vec::new();
    for case in cases() {
        let config = config_of(&case);
        let (model, _) = load_source(&config)?;
        ctx.progress.check()?;
        let (warm, _, _) = fracture_timed(&model, &config)?;
        let mut times = Vec::with_capacity(args.runs as usize);
        for _ in 0..args.runs {
            ctx.progress.check()?;
            let (_, _, ms) = fracture_timed(&model, &config)?;
            times.push(ms);
        }
        bar.tick(case.name);
        let row = Row {
            case: case.name,
            shape: case.shape.name(),
            fragments: warm.fragments.len(),
            bonds: warm.bonds.len(),
            runs: args.runs,
            mean_ms: times.iter().sum::<f64>() / times.len() as f64,
            min_ms: times.iter().copied().fold(f64::INFINITY, f64::min),
            max_ms: times.iter().copied().fold(0.0, f64::max),
        };
        if !args.json {
            bar.println(format!(
                "{:<26} {:>9} {:>7} {:>10.3} {:>10.3} {:>10.3}",
                row.case, row.fragments, row.bonds, row.mean_ms, row.min_ms, row.max_ms
            ));
        }
        rows.push(row);
    }
    drop(bar);
    if args.json {
        let report = Report {
            seed: args.seed,
            rows,
        };
        println!(
            "{}",
            serde_json::to_string(&report).internal_err("cannot encode the report")?
        );
    }
    Ok(())
}
