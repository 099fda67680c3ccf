//! `shatter bench creation`: the thesis's chapter 5, reproduced (the work is
//! `shatter_lab::bench::creation`'s: the cases, the CSV columns and the plots).
//!
//! Writes `creation.csv`, and plots as PNG and SVG: one per placement (one line per
//! model, as the thesis drew them) and one per model (both placements).

use std::path::PathBuf;

use clap::Args;
use shatter_geom::fracture::Placement;
use shatter_lab::bench::creation::{self, CreationOptions, CreationResult};

use crate::context::Context;
use crate::error::CliError;

/// Arguments of `shatter bench creation`.
#[derive(Debug, Args)]
pub struct BenchCreationArgs {
    /// Models, comma separated: cube, capsule, cylinder, sphere, torus, bird.
    #[arg(
        long,
        value_delimiter = ',',
        default_value = "cube,capsule,cylinder,bird"
    )]
    pub models: Vec<String>,
    /// Random point placements, comma separated: thesis, interior.
    #[arg(long, value_delimiter = ',', default_value = "thesis,interior")]
    pub placements: Vec<String>,
    /// Largest number of random points.
    #[arg(long, value_name = "N", default_value_t = 500)]
    pub max_points: usize,
    /// Step between two numbers of random points.
    #[arg(long, value_name = "N", default_value_t = 10)]
    pub step: usize,
    /// Timed runs per model, placement and number of points (after one warm-up).
    #[arg(long, value_name = "R", default_value_t = 5)]
    pub runs: usize,
    /// Folder for creation.csv and the plots (created if missing).
    #[arg(long, value_name = "DIR", default_value = "bench-creation")]
    pub out: PathBuf,
    /// Seed of the first run (run r uses seed + r).
    #[arg(long, value_name = "S", default_value_t = 0)]
    pub seed: u64,
    /// Time the fracture only, without building the simulation bodies and joints.
    #[arg(long)]
    pub fracture_only: bool,
}

impl BenchCreationArgs {
    /// The lab's options: the flags as given (the lab validates them).
    fn options(&self) -> CreationOptions {
        CreationOptions {
            models: self.models.clone(),
            placements: self.placements.clone(),
            max_points: self.max_points,
            step: self.step,
            runs: self.runs,
            out: self.out.clone(),
            seed: self.seed,
            fracture_only: self.fracture_only,
        }
    }
}

/// Runs `shatter bench creation`.
pub fn run(args: &BenchCreationArgs, ctx: &Context) -> Result<(), CliError> {
    let result = creation::run(&args.options(), ctx)?;
    print_summary(&result);
    println!("wrote {}", result.csv.display());
    for p in &result.plots {
        println!("wrote {}", p.display());
    }
    Ok(())
}

/// A short table on stdout: per model and placement, the first, middle and last case.
fn print_summary(result: &CreationResult) {
    println!(
        "{:<9} {:<9} {:>7} {:>10} {:>10} {:>10} {:>10}",
        "model", "placement", "points", "fragments", "mean ms", "min ms", "max ms"
    );
    let counts = &result.config.counts;
    let picks = [
        counts[0],
        counts[counts.len() / 2],
        counts[counts.len() - 1],
    ];
    for r in result
        .rows
        .iter()
        .filter(|r| picks.contains(&r.random_points))
    {
        println!(
            "{:<9} {:<9} {:>7} {:>10.0} {:>10.3} {:>10.3} {:>10.3}",
            r.model.name(),
            Placement::name(r.placement),
            r.random_points,
            r.fragments,
            r.fracture.mean,
            r.fracture.min,
            r.fracture.max
        );
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;
    use clap::Parser;

    #[derive(Parser)]
    struct Cli {
        #[command(flatten)]
        bench: BenchCreationArgs,
    }

    #[test]
    fn the_defaults_reach_the_lab_as_given() {
        let cli = Cli::try_parse_from(["creation", "--fracture-only", "--step", "50"]).unwrap();
        let o = cli.bench.options();
        assert_eq!(o.models, ["cube", "capsule", "cylinder", "bird"]);
        assert_eq!(o.placements, ["thesis", "interior"]);
        assert_eq!((o.max_points, o.step, o.runs, o.seed), (500, 50, 5, 0));
        assert!(o.fracture_only);
        let config = creation::CreationConfig::new(&o).unwrap();
        assert_eq!(config.counts.len(), 11);
        assert!(!config.with_bodies);
    }
}
