//! `shatter tetrahedralize`: the 3D Delaunay tetrahedralization of a point file or of
//! random points.

use std::io::Write;
use std::path::PathBuf;
use std::time::Instant;

use clap::{ArgGroup, Args};
use serde::Serialize;
use shatter_geom::delaunay::{self, Tetrahedralization};

use crate::args::{Distribution, check_writable};
use crate::error::{CliError, ResultExt};
use crate::library;
use crate::points_file::read_points_file;

/// Arguments of `shatter tetrahedralize`.
#[derive(Debug, Args)]
#[command(group(ArgGroup::new("source").required(true).args(["input", "random"])))]
pub struct TetrahedralizeArgs {
    /// Points file: one `x y z` per line, `#` comments allowed.
    #[arg(long, value_name = "POINTS.xyz")]
    pub input: Option<PathBuf>,
    /// Tetrahedralize N random points instead of a file.
    #[arg(long, value_name = "N")]
    pub random: Option<usize>,
    /// Distribution of the random points.
    #[arg(long, value_enum, default_value_t = Distribution::Uniform)]
    pub distribution: Distribution,
    /// Seed of the random points.
    #[arg(long, value_name = "S", default_value_t = 0)]
    pub seed: u64,
    /// Write the tetrahedra here, one `a b c d` per line (0-based input indices).
    #[arg(long, value_name = "TETS.txt")]
    pub out: Option<PathBuf>,
    /// Print one JSON object with the counts and the time.
    #[arg(long)]
    pub json: bool,
}

/// Where the points come from, validated.
enum PointSource {
    File(PathBuf),
    Random {
        n: usize,
        distribution: Distribution,
        seed: u64,
    },
}

/// The validated configuration.
struct Config {
    source: PointSource,
    out: Option<PathBuf>,
    json: bool,
}

impl TetrahedralizeArgs {
    fn validate(&self) -> Result<Config, CliError> {
        let source = match (&self.input, self.random) {
            (Some(path), None) => PointSource::File(path.clone()),
            (None, Some(n)) if n < 4 => {
                return Err(CliError::input(format!(
                    "--random {n}: a tetrahedralization needs at least 4 points"
                )));
            }
            (None, Some(n)) => PointSource::Random {
                n,
                distribution: self.distribution,
                seed: self.seed,
            },
            // clap's argument group makes exactly one of the two present.
            _ => return Err(CliError::input("give either --input or --random")),
        };
        let out = self.out.as_deref().map(check_writable).transpose()?;
        Ok(Config {
            source,
            out,
            json: self.json,
        })
    }
}

/// The `--json` report.
#[derive(Debug, Serialize)]
struct Report {
    points: usize,
    unique_points: usize,
    duplicates: usize,
    tetrahedra: usize,
    millis: f64,
}

/// Runs `shatter tetrahedralize`.
pub fn run(args: &TetrahedralizeArgs) -> Result<(), CliError> {
    let config = args.validate()?;
    let (points, source_name) = match &config.source {
        PointSource::File(path) => (
            read_points_file(path).map_err(CliError::input)?,
            path.display().to_string(),
        ),
        PointSource::Random {
            n,
            distribution,
            seed,
        } => (
            library::random_points(*distribution, *n, *seed)?,
            format!("{n} random {} points", distribution.as_str()),
        ),
    };

    let start = Instant::now();
    let tets = delaunay::tetrahedralize(&points).input_err(&source_name)?;
    let millis = start.elapsed().as_secs_f64() * 1e3;

    if let Some(out) = &config.out {
        write_tets(out, &tets)?;
    }
    let report = Report {
        points: points.len(),
        unique_points: tets.unique_points,
        duplicates: points.len() - tets.unique_points,
        tetrahedra: tets.len(),
        millis,
    };
    if config.json {
        println!(
            "{}",
            serde_json::to_string(&report).internal_err("cannot encode the report")?
        );
    } else {
        print_summary(&report, config.out.as_deref());
    }
    Ok(())
}

fn print_summary(report: &Report, out: Option<&std::path::Path>) {
    println!(
        "{} points ({} unique, {} duplicates) -> {} tetrahedra in {:.3} ms",
        report.points, report.unique_points, report.duplicates, report.tetrahedra, report.millis
    );
    if let Some(out) = out {
        println!("wrote {}", out.display());
    }
}

/// Writes one tetrahedron per line, indices into the input as given; a duplicate point
/// is always written as its first occurrence.
fn write_tets(path: &std::path::Path, tets: &Tetrahedralization) -> Result<(), CliError> {
    let write = || -> std::io::Result<()> {
        let file = std::fs::File::create(path)?;
        let mut w = std::io::BufWriter::new(file);
        for t in tets.tetrahedra() {
            let [a, b, c, d] = t.map(|i| first_occurrence(tets, i));
            writeln!(w, "{a} {b} {c} {d}")?;
        }
        w.flush()
    };
    write().map_err(|e| CliError::input(format!("{}: cannot write: {e}", path.display())))
}

fn first_occurrence(tets: &Tetrahedralization, i: u32) -> u32 {
    tets.representative.get(i as usize).copied().unwrap_or(i)
}
