//! `shatter bench step [--seconds T] [--json]`: the 2,000-brick wall of
//! `assets/scenes/wall.toml` hit by a projectile, mean milliseconds per step for each bond
//! model (measured by `shatter_lab::bench::step`).

use clap::Args;
use shatter_lab::bench::step::{self, BenchStepReport};

use crate::context::Context;
use crate::error::{CliError, ResultExt};

/// Arguments of `shatter bench step`.
#[derive(Debug, Args)]
pub struct BenchStepArgs {
    /// Simulated seconds per model (the projectile hits at 0.5 s).
    #[arg(long, default_value_t = 2.0)]
    pub seconds: f64,
    /// Print one JSON object.
    #[arg(long)]
    pub json: bool,
}

/// Runs `shatter bench step`.
pub fn run(args: &BenchStepArgs, ctx: &Context) -> Result<BenchStepReport, CliError> {
    let report = step::run(args.seconds, ctx, args.json)?;
    if args.json {
        let json = serde_json::to_string(&report).internal_err("cannot encode the report")?;
        println!("{json}");
    } else {
        println!(
            "wall of {} fragments, {} steps per model\n  joints:   {:.3} ms/step (max {:.3}), {} bonds broken\n  clusters: {:.3} ms/step (max {:.3}), {} bonds broken\n  clusters are {:.1}x cheaper",
            report.fragments,
            report.steps,
            report.joints_ms_per_step,
            report.joints_max_ms,
            report.joints_bonds_broken,
            report.clusters_ms_per_step,
            report.clusters_max_ms,
            report.clusters_bonds_broken,
            report.joints_ms_per_step / report.clusters_ms_per_step.max(1e-9)
        );
    }
    Ok(report)
}
