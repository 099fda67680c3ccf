//! `shatter tetrahedralize`: the 3D Delaunay tetrahedralization of a point file or of
//! random points.

use std::path::PathBuf;
use std::time::Instant;

use clap::{ArgGroup, Args};
use serde::Serialize;
use shatter_geom::budget::{Estimate, format_count};
use shatter_geom::delaunay::{self, Tetrahedralization};

use crate::args::{Distribution, check_writable};
use crate::context::Context;
use crate::error::{CliError, ResultExt};
use crate::points_file::read_points_file;
use shatter_lab::fracture::EstimateReport;
use shatter_lab::{memory, output};

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
    /// What the resource check estimated before the work.
    estimate: EstimateReport,
    /// The process's peak resident set at the end (Linux only).
    peak_rss_bytes: Option<u64>,
}

/// Refuses a tetrahedralization of `points` points that would not fit the limits;
/// `flag` names the request ("--random 3000000000"). Returns the estimate.
pub fn check_points(ctx: &Context, flag: &str, points: u64) -> Result<Estimate, CliError> {
    let estimate = Estimate::delaunay(points).with_process();
    ctx.check(
        &format!("{flag}: {} points", format_count(points)),
        &estimate,
    )?;
    Ok(estimate)
}

/// Refuses to read a points file whose text alone would not fit the limits (before it
/// is read): the text, and a point for every 6 bytes (the shortest line, `0 0 0\n`).
pub fn check_points_file(
    ctx: &Context,
    flag: &str,
    path: &std::path::Path,
) -> Result<(), CliError> {
    let Ok(meta) = std::fs::metadata(path) else {
        // The read reports the missing file.
        return Ok(());
    };
    let bytes = meta.len() as f64;
    let estimate = Estimate {
        bytes: bytes + bytes / 6.0 * shatter_geom::budget::POINT_BYTES,
        seconds: 0.0,
    };
    Ok(ctx.check(
        &format!(
            "{flag} {}: reading its {} bytes",
            path.display(),
            format_count(meta.len())
        ),
        &estimate,
    )?)
}

/// Runs `shatter tetrahedralize`.
pub fn run(args: &TetrahedralizeArgs, ctx: &Context) -> Result<(), CliError> {
    let config = args.validate()?;
    let (points, source_name, estimate) = match &config.source {
        PointSource::File(path) => {
            check_points_file(ctx, "--input", path)?;
            let points = read_points_file(path).map_err(CliError::input)?;
            let flag = format!("--input {}", path.display());
            let estimate = check_points(ctx, &flag, points.len() as u64)?;
            (points, path.display().to_string(), estimate)
        }
        PointSource::Random {
            n,
            distribution,
            seed,
        } => {
            let estimate = check_points(ctx, &format!("--random {n}"), *n as u64)?;
            (
                shatter_geom::sampling::sample(distribution.sampling(), *n, *seed),
                format!("{n} random {} points", distribution.as_str()),
                estimate,
            )
        }
    };
    ctx.progress.check()?;

    let bar = ctx.follow(
        &format!(
            "tetrahedralizing {} points",
            format_count(points.len() as u64)
        ),
        &estimate,
        config.json,
    );
    let start = Instant::now();
    let tets = delaunay::tetrahedralize(&points).input_err(&source_name)?;
    let millis = start.elapsed().as_secs_f64() * 1e3;
    drop(bar);
    ctx.progress.check()?;

    if let Some(out) = &config.out {
        write_tets(out, &tets, ctx)?;
    }
    let report = Report {
        points: points.len(),
        unique_points: tets.unique_points,
        duplicates: points.len() - tets.unique_points,
        tetrahedra: tets.len(),
        millis,
        estimate: estimate.into(),
        peak_rss_bytes: memory::peak_rss_bytes(),
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
/// Written through a temporary file: an interrupted run leaves no partial file.
fn write_tets(
    path: &std::path::Path,
    tets: &Tetrahedralization,
    ctx: &Context,
) -> Result<(), CliError> {
    Ok(output::write_file(path, &ctx.progress, |w| {
        for (k, t) in tets.tetrahedra().enumerate() {
            if k % 65_536 == 0 && ctx.progress.is_cancelled() {
                return Err(std::io::Error::other("interrupted"));
            }
            let [a, b, c, d] = t.map(|i| first_occurrence(tets, i));
            writeln!(w, "{a} {b} {c} {d}")?;
        }
        w.flush()
    })?)
}

fn first_occurrence(tets: &Tetrahedralization, i: u32) -> u32 {
    tets.representative.get(i as usize).copied().unwrap_or(i)
}
