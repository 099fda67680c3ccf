//! The `shatter` command line.
//!
//! Every command lives in its own module under `commands/` with a clap `Args` struct and
//! a `run(&Args, &Context) -> Result<(), CliError>` function. Exit codes: 0 success, 1
//! internal failure, 2 bad input or a request too big for the machine, 130 Ctrl-C (see
//! [`error`]).

mod args;
mod commands;
mod context;
mod error;
mod interrupt;
mod points_file;

use std::process::ExitCode;

/// mimalloc instead of the system allocator: the fracture cuts make many small,
/// short-lived vectors, which glibc's malloc served at about a tenth of the run time.
#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

use clap::{Parser, Subcommand};

use crate::commands::{
    batch, bench_creation, bench_delaunay, bench_fracture, bench_runtime, bench_scale, bench_step,
    bench_stress, fracture, inspect, shape, simulate, study, tetrahedralize,
};
use crate::context::Context;
use crate::error::CliError;

/// shatter: fracture simulation — tetrahedralize, fracture, simulate, benchmark.
#[derive(Debug, Parser)]
#[command(name = "shatter", version, about, long_about = None)]
struct Cli {
    #[command(subcommand)]
    command: Command,
    /// Run requests that the estimate says need more than 80% of this machine's memory
    /// or more than an hour (see docs/cli.md, "Resource limits").
    #[arg(long, global = true)]
    no_limits: bool,
}

/// The commands, one variant each.
#[derive(Debug, Subcommand)]
enum Command {
    /// 3D Delaunay tetrahedralization of a point file or of random points.
    Tetrahedralize(tetrahedralize::TetrahedralizeArgs),
    /// Export a built-in shape (cube, capsule, cylinder, sphere, torus, bird).
    Shape(shape::ShapeArgs),
    /// Fracture a mesh into bonded fragments (tetra, voronoi, slice or grid).
    Fracture(fracture::FractureArgs),
    /// What a mesh file holds (shells, holes, volume, materials, UV sets) without fracturing.
    Inspect(inspect::InspectArgs),
    /// Run a scene headless and print its statistics and final-state digest.
    Simulate(simulate::SimulateArgs),
    /// The influence of the parameters on a shot at a standard object (CSV and plots).
    Study(study::StudyArgs),
    /// Benchmarks.
    #[command(subcommand)]
    Bench(BenchCommand),
}

/// The benchmarks, one variant each.
#[derive(Debug, Subcommand)]
enum BenchCommand {
    /// Time the Delaunay tetrahedralization of random points.
    Delaunay(bench_delaunay::BenchDelaunayArgs),
    /// Time the fracture methods on the built-in shapes.
    Fracture(bench_fracture::BenchFractureArgs),
    /// Time one simulation step of the 2,000-fragment wall for each bond model.
    Step(bench_step::BenchStepArgs),
    /// Runtime fracture: a cut at the impact on the bird and the cube, on one core by
    /// default.
    Runtime(bench_runtime::BenchRuntimeArgs),
    /// Step time against the number of fragments (2k to 20k bricks by default) for both
    /// bond models: a wall hit by shots, an explosion in a wall, a block landing, a wall
    /// blown apart.
    Scale(bench_scale::BenchScaleArgs),
    /// Time the stress solver on a 20,000-bond graph.
    Stress(bench_stress::BenchStressArgs),
    /// The thesis's creation time against random points, with CSV and plots.
    Creation(bench_creation::BenchCreationArgs),
}

fn run(command: &Command, ctx: &Context) -> Result<(), CliError> {
    match command {
        Command::Tetrahedralize(a) => tetrahedralize::run(a, ctx),
        Command::Shape(a) => shape::run(a, ctx),
        Command::Fracture(a) if a.is_batch() => batch::run(a, ctx),
        Command::Fracture(a) => fracture::run(a, ctx),
        Command::Inspect(a) => inspect::run(a),
        Command::Simulate(a) => simulate::run(a, ctx).map(|_| ()),
        Command::Bench(BenchCommand::Delaunay(a)) => {
            // Each size is checked before any is measured (bench_delaunay.rs measures; the
            // processes it starts per size were checked here).
            if !a.in_process {
                for &n in &a.sizes {
                    tetrahedralize::check_points(ctx, &format!("--sizes {n}"), n as u64)?;
                }
            }
            bench_delaunay::run(a)
        }
        Command::Bench(BenchCommand::Fracture(a)) => bench_fracture::run(a, ctx),
        Command::Bench(BenchCommand::Step(a)) => bench_step::run(a, ctx).map(|_| ()),
        Command::Bench(BenchCommand::Runtime(a)) => bench_runtime::run(a, ctx),
        Command::Bench(BenchCommand::Scale(a)) => bench_scale::run(a, ctx).map(|_| ()),
        Command::Bench(BenchCommand::Stress(a)) => bench_stress::run(a, ctx).map(|_| ()),
        Command::Bench(BenchCommand::Creation(a)) => bench_creation::run(a, ctx),
        Command::Study(a) => study::run(a, ctx),
    }
}

fn main() -> ExitCode {
    // clap prints usage errors itself and exits with code 2.
    let cli = Cli::parse();
    // Each pool thread kept on one processor, before anything uses the pool (see
    // `shatter_lab::threads`; SHATTER_PIN_THREADS=0 turns it off).
    if let Err(e) = shatter_lab::threads::pin_global_pool() {
        let e = CliError::from(e);
        eprintln!("error: {e}");
        return ExitCode::from(e.exit_code());
    }
    // A panic is a bug in shatter, never the user's fault: report it as an internal error
    // (exit code 1) with a one-line message instead of a backtrace dump.
    std::panic::set_hook(Box::new(|info| {
        eprintln!("error: internal error (a bug in shatter, please report it): {info}");
    }));
    let ctx = context::new(cli.no_limits);
    match std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| run(&cli.command, &ctx))) {
        Ok(Ok(())) => ExitCode::SUCCESS,
        Ok(Err(e)) => {
            // After Ctrl-C, whatever failed failed because of it (a child process that
            // was interrupted too, a write cut short).
            let e = if ctx.progress.is_cancelled() {
                CliError::Interrupted
            } else {
                e
            };
            eprintln!("error: {e}");
            ExitCode::from(e.exit_code())
        }
        Err(_) => ExitCode::from(error::EXIT_INTERNAL),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::CommandFactory;

    #[test]
    fn the_command_line_definition_is_consistent() {
        Cli::command().debug_assert();
    }

    /// Regression: `--sizes` was declared as `Vec<usize>` with a parser returning a whole
    /// `Vec`, and clap panicked ("Mismatch between definition and access of `sizes`") on
    /// every `bench delaunay` run.
    #[test]
    fn bench_delaunay_sizes_list_parses_without_a_clap_panic() {
        let cli = Cli::try_parse_from(["shatter", "bench", "delaunay", "--sizes", "10,200"])
            .expect("valid arguments");
        let Command::Bench(BenchCommand::Delaunay(args)) = cli.command else {
            panic!("parsed as another command");
        };
        assert_eq!(args.sizes, vec![10, 200]);
        let cli = Cli::try_parse_from(["shatter", "bench", "delaunay"]).expect("defaults");
        let Command::Bench(BenchCommand::Delaunay(args)) = cli.command else {
            panic!("parsed as another command");
        };
        assert_eq!(args.sizes, vec![1000, 10_000, 100_000, 1_000_000]);
    }
}
