//! `shatter study`: how the parameters change what one shot does to a standard object
//! (the work is `shatter_lab::study`'s: the cases, the CSV columns and the plots).
//!
//! Writes `study.csv` (one row per study, parameter value, method and bond model) and,
//! per study, a plot of bonds broken and one of fragments released, as PNG and SVG.

use std::path::PathBuf;

use clap::Args;
use shatter_lab::study::{self, StudyOptions};

use crate::context::Context;
use crate::error::CliError;

/// Arguments of `shatter study`.
#[derive(Debug, Args)]
pub struct StudyArgs {
    /// Folder for study.csv and the plots (created if missing).
    #[arg(long, value_name = "DIR", default_value = "study")]
    pub out: PathBuf,
    /// Studies to run, comma separated: break-force, speed, random-vertices, method.
    #[arg(
        long,
        value_delimiter = ',',
        default_value = "break-force,speed,random-vertices,method"
    )]
    pub studies: Vec<String>,
    /// Bond models, comma separated: joints, clusters.
    #[arg(long, value_delimiter = ',', default_value = "joints,clusters")]
    pub bonds: Vec<String>,
    /// Simulated seconds per case.
    #[arg(long, value_name = "T", default_value_t = 2.0)]
    pub seconds: f64,
    /// Runs (fracture seeds) per case.
    #[arg(long, value_name = "R", default_value_t = 3)]
    pub runs: usize,
    /// Seed of the first run (run r uses seed + r).
    #[arg(long, value_name = "S", default_value_t = 1)]
    pub seed: u64,
    /// Baseline break force of a bond, in newtons.
    #[arg(long, value_name = "F", default_value_t = 20_000.0)]
    pub break_force: f64,
    /// Baseline projectile speed, in m/s.
    #[arg(long, value_name = "V", default_value_t = 30.0)]
    pub speed: f64,
    /// Baseline random vertices of the tetra method.
    #[arg(long, value_name = "N", default_value_t = 20)]
    pub random_vertices: usize,
    /// Cells of the voronoi method.
    #[arg(long, value_name = "K", default_value_t = 100)]
    pub pieces: usize,
    /// Planes of the slice method.
    #[arg(long, value_name = "K", default_value_t = 7)]
    pub planes: usize,
    /// Break forces of the break-force study.
    #[arg(
        long,
        value_delimiter = ',',
        default_value = "2500,5000,7500,10000,15000,20000,30000,40000,60000,80000"
    )]
    pub break_forces: Vec<f64>,
    /// Projectile speeds of the speed and method studies.
    #[arg(
        long,
        value_delimiter = ',',
        default_value = "0,5,10,15,20,30,40,50,60"
    )]
    pub speeds: Vec<f64>,
    /// Random vertices of the random-vertices study.
    #[arg(long, value_delimiter = ',', default_value = "0,10,20,40,60,80,100")]
    pub vertex_counts: Vec<usize>,
}

impl StudyArgs {
    /// The lab's options: the flags as given (the lab validates them).
    fn options(&self) -> StudyOptions {
        StudyOptions {
            out: self.out.clone(),
            studies: self.studies.clone(),
            bonds: self.bonds.clone(),
            seconds: self.seconds,
            runs: self.runs,
            seed: self.seed,
            break_force: self.break_force,
            speed: self.speed,
            random_vertices: self.random_vertices,
            pieces: self.pieces,
            planes: self.planes,
            break_forces: self.break_forces.clone(),
            speeds: self.speeds.clone(),
            vertex_counts: self.vertex_counts.clone(),
        }
    }
}

/// Runs `shatter study`.
pub fn run(args: &StudyArgs, ctx: &Context) -> Result<(), CliError> {
    let result = study::run(&args.options(), ctx)?;
    println!(
        "{:<16} {:<20} {:>9} {:>10} {:>13} {:>9}",
        "study", "line", "value", "fragments", "bonds broken", "released"
    );
    for r in &result.rows {
        println!(
            "{:<16} {:<20} {:>9} {:>10.0} {:>13.1} {:>9.1}",
            r.study.name(),
            r.line,
            r.value,
            r.fragments.mean,
            r.bonds_broken.mean,
            r.released.mean
        );
    }
    for p in result.written {
        println!("wrote {}", p.display());
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;
    use clap::Parser;

    #[derive(Parser)]
    struct Cli {
        #[command(flatten)]
        study: StudyArgs,
    }

    #[test]
    fn the_defaults_reach_the_lab_as_given() {
        let cli = Cli::try_parse_from(["study", "--runs", "2", "--speeds", "0,5"]).unwrap();
        let o = cli.study.options();
        assert_eq!(
            o.studies,
            ["break-force", "speed", "random-vertices", "method"]
        );
        assert_eq!(o.bonds, ["joints", "clusters"]);
        assert_eq!((o.runs, o.seed, o.pieces, o.planes), (2, 1, 100, 7));
        assert_eq!(o.speeds, [0.0, 5.0]);
        assert_eq!(o.out, PathBuf::from("study"));
        let config = study::StudyConfig::new(&o).unwrap();
        assert_eq!(config.case_count(), 2 * (10 + 2 + 7 + 3 * 2));
    }
}
