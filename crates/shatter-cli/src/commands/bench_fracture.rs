//! `shatter bench fracture`: time the fracture methods on the built-in shapes (the cases
//! and the timing are `shatter_lab::bench::fracture`'s).
//!
//! Each case is run `--runs` times after one untimed warm-up; mean, min and max are
//! reported, as a table or one JSON object.

use clap::Args;
use shatter_lab::bench::fracture::{BenchFracture, Row};

use crate::context::Context;
use crate::error::{CliError, ResultExt};

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

fn row_line(row: &Row) -> String {
    format!(
        "{:<26} {:>9} {:>7} {:>10.3} {:>10.3} {:>10.3}",
        row.case, row.fragments, row.bonds, row.mean_ms, row.min_ms, row.max_ms
    )
}

/// Runs `shatter bench fracture`.
pub fn run(args: &BenchFractureArgs, ctx: &Context) -> Result<(), CliError> {
    let bench = BenchFracture::prepare(args.runs, args.seed, ctx)?;
    if !args.json {
        println!(
            "{:<26} {:>9} {:>7} {:>10} {:>10} {:>10}",
            "case", "fragments", "bonds", "mean ms", "min ms", "max ms"
        );
    }
    let report = bench.run(ctx, args.json, |row, bar| {
        if !args.json {
            bar.println(row_line(row));
        }
    })?;
    if args.json {
        println!(
            "{}",
            serde_json::to_string(&report).internal_err("cannot encode the report")?
        );
    }
    Ok(())
}
