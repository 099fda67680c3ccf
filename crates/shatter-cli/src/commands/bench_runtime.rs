//! `shatter bench runtime [--runs R] [--threads N] [--json]`: the time of a runtime cut at
//! the impact (`shatter_lab::bench::runtime`), on the bird and the cube, against the
//! budget of 4 ms for 50 pieces of the bird on one core.

use clap::Args;
use shatter_lab::bench::runtime::{self, BenchRuntimeOptions};

use crate::context::Context;
use crate::error::{CliError, ResultExt};

/// Arguments of `shatter bench runtime`.
#[derive(Debug, Args)]
pub struct BenchRuntimeArgs {
    /// Timed runs per case (after one warm-up run).
    #[arg(long, value_name = "R", default_value_t = 10,
          value_parser = clap::value_parser!(u32).range(1..))]
    pub runs: u32,
    /// Threads a cut may use (1: one core, as the budget is stated).
    #[arg(long, value_name = "N", default_value_t = 1,
          value_parser = clap::value_parser!(u32).range(1..=1024))]
    pub threads: u32,
    /// Print one JSON object instead of a table.
    #[arg(long)]
    pub json: bool,
}

/// Runs `shatter bench runtime`.
pub fn run(args: &BenchRuntimeArgs, ctx: &Context) -> Result<(), CliError> {
    let options = BenchRuntimeOptions {
        runs: args.runs,
        threads: args.threads as usize,
    };
    let report = runtime::run(options, ctx, args.json)?;
    if args.json {
        println!(
            "{}",
            serde_json::to_string(&report).internal_err("cannot encode the report")?
        );
        return Ok(());
    }
    println!(
        "runtime cut at the impact, {} thread(s), {} runs (budget: {} ms for bird-50)",
        report.threads, report.runs, report.budget_ms
    );
    println!(
        "{:<10} {:>6} {:>9} {:>12} {:>12} {:>14} {:>14}",
        "case", "pieces", "fragments", "cut mean ms", "cut min ms", "in world ms", "apply ms"
    );
    for row in &report.rows {
        println!(
            "{:<10} {:>6} {:>9} {:>12.3} {:>12.3} {:>14.3} {:>14.3}",
            row.case,
            row.pieces,
            row.fragments,
            row.cut_ms.mean,
            row.cut_ms.min,
            row.world_ms.mean,
            row.apply_ms.mean
        );
    }
    Ok(())
}
