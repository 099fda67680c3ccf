//! `shatter bench scale [--sizes N,..] [--models M,..] [--cases C,..] [--seconds T]
//! [--out DIR] [--box-colliders] [--skip-held-contacts] [--enclosed-colliders]
//! [--no-contact-speed-cap] [--json]`: brick worlds of growing size for each bond model and case (a
//! wall hit by shots, an explosion in a wall, a block shattering on landing), ms per
//! step (mean and worst), bodies, fragments at rest and diverged bodies, and plots of
//! ms/step against fragments (measured by `shatter_lab::bench::scale`).

use std::path::PathBuf;

use clap::Args;
use shatter_lab::bench::scale::{self, BenchScaleOptions, BenchScaleReport};

use crate::args::parse_size;
use crate::context::Context;
use crate::error::{CliError, ResultExt};

/// Arguments of `shatter bench scale`.
#[derive(Debug, Args)]
pub struct BenchScaleArgs {
    /// About how many fragments each world has, comma separated (rounded to a grid).
    #[arg(long, value_name = "N,N,...", value_parser = parse_size, value_delimiter = ',',
          default_value = "2000,5000,10000,20000")]
    pub sizes: Vec<usize>,
    /// Bond models, comma separated: joints, clusters (joints is the slow one).
    #[arg(long, value_delimiter = ',', default_value = "joints,clusters")]
    pub models: Vec<String>,
    /// Cases, comma separated: shots, explosion, landing, blast.
    #[arg(
        long,
        value_delimiter = ',',
        default_value = "shots,explosion,landing,blast"
    )]
    pub cases: Vec<String>,
    /// Simulated seconds per run (the block lands at about 0.9 s).
    #[arg(long, value_name = "T", default_value_t = 2.0)]
    pub seconds: f64,
    /// Folder for the plots (created if missing).
    #[arg(long, value_name = "DIR", default_value = "bench-scale")]
    pub out: PathBuf,
    /// Bricks collide as cuboids instead of their hulls (the scene key `box_colliders`):
    /// faster, with other contacts (see docs/scene-format.md).
    #[arg(long)]
    pub box_colliders: bool,
    /// Joints-model bricks held within three bonds skip their contacts (the scene key
    /// `skip_held_contacts`): faster, fewer bonds break (see docs/scene-format.md).
    #[arg(long)]
    pub skip_held_contacts: bool,
    /// Enclosed cluster bricks (a block's interior) have colliders from the start (the
    /// scene key `enclosed_colliders`): slower, as before it existed (see
    /// docs/scene-format.md).
    #[arg(long)]
    pub enclosed_colliders: bool,
    /// Turn off the contact speed cap (the scene key `contact_speed_cap`): bodies leave a
    /// step as fast as Rapier's solver makes them (see docs/scene-format.md).
    #[arg(long)]
    pub no_contact_speed_cap: bool,
    /// Print one JSON object instead of a table.
    #[arg(long)]
    pub json: bool,
}

impl BenchScaleArgs {
    /// The lab's options: the flags as given (the lab validates them).
    fn options(&self) -> BenchScaleOptions {
        BenchScaleOptions {
            sizes: self.sizes.clone(),
            models: self.models.clone(),
            cases: self.cases.clone(),
            seconds: self.seconds,
            out: self.out.clone(),
            box_colliders: self.box_colliders,
            skip_held_contacts: self.skip_held_contacts,
            enclosed_colliders: self.enclosed_colliders,
            no_contact_speed_cap: self.no_contact_speed_cap,
        }
    }
}

/// Runs `shatter bench scale`.
pub fn run(args: &BenchScaleArgs, ctx: &Context) -> Result<BenchScaleReport, CliError> {
    let report = scale::run(&args.options(), ctx, args.json)?;
    if args.json {
        let json = serde_json::to_string(&report).internal_err("cannot encode the report")?;
        println!("{json}");
        return Ok(report);
    }
    println!(
        "{} steps of {} s per run ({:.0} s measured, {:.0} s estimated)",
        report.steps, report.seconds, report.measured_seconds, report.estimated_seconds
    );
    println!(
        "{:<9} {:<8} {:>9} {:>14} {:>9} {:>9} {:>9} {:>9} {:>9} {:>10} {:>8} {:>9} {:>9} {:>9} {:>7} {:>7} {:>7} {:>8} {:>8} {:>7} {:>7}",
        "case",
        "model",
        "fragments",
        "grid",
        "build ms",
        "mean ms",
        "max ms",
        "cpu ms",
        "stress ms",
        "stress max",
        "solve ms",
        "solve max",
        "solve cpu",
        "cpu max",
        "bodies",
        "asleep",
        "still",
        "diverged",
        "fastest",
        "capped",
        "broken"
    );
    for r in &report.rows {
        println!(
            "{:<9} {:<8} {:>9} {:>14} {:>9.1} {:>9.3} {:>9.3} {:>9} {:>9.3} {:>10.3} {:>8.3} {:>9.3} {:>9} {:>9} {:>7} {:>7} {:>7} {:>8} {:>8.1} {:>7} {:>7}",
            r.case,
            r.model,
            r.fragments,
            format!("{}x{}x{}", r.grid[0], r.grid[1], r.grid[2]),
            r.build_ms,
            r.mean_ms,
            r.max_ms,
            cpu(r.cpu_mean_ms),
            r.stress_mean_ms,
            r.stress_max_ms,
            r.solve_mean_ms,
            r.solve_max_ms,
            cpu(r.solve_cpu_mean_ms),
            cpu(r.solve_cpu_max_ms),
            r.bodies,
            r.sleeping_bodies,
            r.still_fragments,
            r.diverged,
            r.fastest,
            r.speeds_capped,
            r.bonds_broken
        );
    }
    println!(
        "ms: wall clock per step; cpu ms: the stepping thread's CPU per step over the run; stress ms: the step's stress pass (solves, breaks, splits); solve ms: its solves alone; solve cpu, cpu max: the solves' CPU per step, mean and largest"
    );
    println!(
        "asleep: dynamic bodies Rapier put to sleep; still: fragments whose pose did not change over the last step (sleeping or fixed); fastest: the fastest body after any step (m/s); capped: bodies the contact speed cap slowed"
    );
    for p in &report.plots {
        println!("wrote {}", p.display());
    }
    Ok(report)
}

/// A CPU figure for the table, `-` where it could not be measured.
fn cpu(ms: Option<f64>) -> String {
    ms.map_or_else(|| "-".to_string(), |v| format!("{v:.3}"))
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;
    use clap::Parser;

    #[derive(Parser)]
    struct Cli {
        #[command(flatten)]
        bench: BenchScaleArgs,
    }

    #[test]
    fn the_defaults_are_the_issue_s_sizes_models_and_cases_and_the_blast() {
        let o = Cli::try_parse_from(["scale"]).unwrap().bench.options();
        assert_eq!(o.sizes, [2000, 5000, 10_000, 20_000]);
        assert_eq!(o.models, ["joints", "clusters"]);
        assert_eq!(o.cases, ["shots", "explosion", "landing", "blast"]);
        assert!(!o.box_colliders && !o.skip_held_contacts && !o.enclosed_colliders);
        assert_eq!(o.seconds, 2.0);
        assert_eq!(o.out, PathBuf::from("bench-scale"));
    }
}
