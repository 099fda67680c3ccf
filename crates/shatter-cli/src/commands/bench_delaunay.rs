//! `shatter bench delaunay`: time the tetrahedralization of random point sets (each size
//! measured by `shatter_lab::bench::delaunay`, in a fresh process of its own when there
//! are several).

use clap::Args;
use shatter_lab::bench::delaunay::{self, Report, Row};
use shatter_lab::memory;

use crate::args::{Distribution, parse_size};
use crate::error::{CliError, ResultExt};

/// Arguments of `shatter bench delaunay`.
#[derive(Debug, Args)]
pub struct BenchDelaunayArgs {
    /// Comma-separated numbers of points.
    #[arg(long, value_name = "N,N,...", value_parser = parse_size, value_delimiter = ',',
          default_value = "1000,10000,100000,1000000")]
    pub sizes: Vec<usize>,
    /// Distribution of the random points.
    #[arg(long, value_enum, default_value_t = Distribution::Uniform)]
    pub distribution: Distribution,
    /// Seed of the random points.
    #[arg(long, value_name = "S", default_value_t = 0)]
    pub seed: u64,
    /// Print one JSON object instead of a table.
    #[arg(long)]
    pub json: bool,
    /// Measure every size in this process (by default each of several sizes gets a fresh
    /// process, so that one size's freed memory does not hide the next one's peak).
    #[arg(long, hide = true)]
    pub in_process: bool,
}

/// Runs `shatter bench delaunay`.
///
/// With several sizes, each is measured in a fresh `shatter` process: memory the allocator
/// keeps after one size's result is dropped would otherwise be reused by the next size
/// without raising the resident set, and that size's peak would read too low.
pub fn run(args: &BenchDelaunayArgs) -> Result<(), CliError> {
    // clap's parser guarantees a non-empty list of positive sizes.
    let mut rows = Vec::with_capacity(args.sizes.len());
    let mut per_row_peak = true;
    let mut process_peak_rss_bytes = None;
    if !args.json {
        println!(
            "{:>10} {:>10} {:>12} {:>11} {:>14} {:>12} {:>12}",
            "points", "unique", "tetrahedra", "ms", "points/s", "bytes/point", "result B/pt"
        );
    }
    let alone = args.sizes.len() > 1 && !args.in_process;
    for &n in &args.sizes {
        let row = if alone {
            let child = measure_in_child(args, n)?;
            per_row_peak &= child.per_row_peak;
            process_peak_rss_bytes = process_peak_rss_bytes.max(child.process_peak_rss_bytes);
            child.rows.into_iter().next().ok_or_else(|| {
                CliError::internal(format!("the process measuring {n} points gave no row"))
            })?
        } else {
            let (row, reset) = measure(args, n)?;
            per_row_peak &= reset;
            row
        };
        if !args.json {
            print_row(&row);
        }
        rows.push(row);
    }
    let report = Report {
        distribution: args.distribution.as_str().to_string(),
        seed: args.seed,
        rows,
        process_peak_rss_bytes: if alone {
            process_peak_rss_bytes
        } else {
            memory::peak_rss_bytes()
        },
        per_row_peak,
    };
    if args.json {
        println!(
            "{}",
            serde_json::to_string(&report).internal_err("cannot encode the report")?
        );
    } else {
        let scope = if per_row_peak {
            "bytes/point: peak RSS during the tetrahedralization above the RSS before it"
        } else {
            "bytes/point: process-wide peak RSS (the peak could not be reset per size)"
        };
        println!("{scope}");
    }
    Ok(())
}

/// Times and measures one size in this process; also says whether the peak was reset
/// for it.
fn measure(args: &BenchDelaunayArgs, n: usize) -> Result<(Row, bool), CliError> {
    Ok(delaunay::measure(
        args.distribution.sampling(),
        n,
        args.seed,
    )?)
}

/// Measures one size in a fresh `shatter bench delaunay --in-process` and reads its report.
fn measure_in_child(args: &BenchDelaunayArgs, n: usize) -> Result<Report, CliError> {
    let exe = std::env::current_exe().internal_err("cannot find the shatter executable")?;
    let output = std::process::Command::new(&exe)
        .args(["bench", "delaunay", "--in-process", "--json", "--sizes"])
        .arg(n.to_string())
        .args(["--distribution", args.distribution.as_str()])
        .args(["--seed", &args.seed.to_string()])
        .output()
        .internal_err(format!("cannot run {}", exe.display()))?;
    if !output.status.success() {
        // The child printed `error: ...`; pass its message on with its kind of exit.
        let stderr = String::from_utf8_lossy(&output.stderr);
        let message = stderr.trim().trim_start_matches("error: ");
        return Err(match output.status.code() {
            Some(2) => CliError::input(message),
            _ => CliError::internal(format!("measuring {n} points failed: {message}")),
        });
    }
    serde_json::from_slice(&output.stdout).internal_err(format!(
        "cannot read the report of the process measuring {n} points"
    ))
}

fn print_row(row: &Row) {
    println!(
        "{:>10} {:>10} {:>12} {:>11.3} {:>14.0} {:>12} {:>12.1}",
        row.points,
        row.unique_points,
        row.tetrahedra,
        row.millis,
        row.points_per_second,
        row.peak_bytes_per_point
            .map_or_else(|| "n/a".to_string(), |b| format!("{b:.1}")),
        row.result_bytes_per_point
    );
}
