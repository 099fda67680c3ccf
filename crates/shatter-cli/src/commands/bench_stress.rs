//! `shatter bench stress [--runs N] [--json]`: the stress solver on a 20,097-bond graph
//! (a 10 m × 10.2 m × 0.6 m stone wall of 50 × 51 × 3 blocks anchored on its bottom
//! row), one core, measured by `shatter_lab::bench::stress`: a cold solve, a settled
//! (skipped) solve, the warm re-solve after a hit and the one after it, and the re-solve
//! after a bond breaks. Milliseconds are means over the runs.

use clap::Args;
use shatter_lab::bench::stress::{self, BenchStressOptions, BenchStressReport};
use shatter_sim::stress::{Preconditioner, SolverSettings};

use crate::context::Context;
use crate::error::{CliError, ResultExt};

/// Arguments of `shatter bench stress`.
#[derive(Debug, Args)]
pub struct BenchStressArgs {
    /// Times to repeat the measurement (fresh solver each time).
    #[arg(long, default_value_t = 5)]
    pub runs: usize,
    /// Most conjugate-gradient iterations per solve.
    #[arg(long, default_value_t = SolverSettings::default().max_iterations)]
    pub max_iterations: usize,
    /// Relative residual at which a solve has converged.
    #[arg(long, default_value_t = SolverSettings::default().tolerance)]
    pub tolerance: f64,
    /// The conjugate gradients' preconditioner: multigrid or block-jacobi.
    #[arg(long, default_value_t = SolverSettings::default().preconditioner)]
    pub preconditioner: Preconditioner,
    /// Most iterations per solve (time-slicing): each case is then solved again, as the
    /// steps of a game would, until it converges, and its milliseconds are per solve.
    #[arg(long)]
    pub budget: Option<usize>,
    /// Print one JSON object.
    #[arg(long)]
    pub json: bool,
}

/// Runs `shatter bench stress`.
pub fn run(args: &BenchStressArgs, ctx: &Context) -> Result<BenchStressReport, CliError> {
    let options = BenchStressOptions {
        runs: args.runs,
        max_iterations: args.max_iterations,
        tolerance: args.tolerance,
        preconditioner: args.preconditioner,
        budget: args.budget,
    };
    let report = stress::run(&options, ctx)?;
    if args.json {
        let json = serde_json::to_string(&report).internal_err("cannot encode the report")?;
        println!("{json}");
    } else {
        println!(
            "stress solver ({}), {} nodes, {} bonds, mean of {} runs, one core{}",
            report.preconditioner,
            report.nodes,
            report.bonds,
            report.runs,
            match args.budget {
                Some(b) => format!(", at most {b} iterations per solve"),
                None => String::new(),
            }
        );
        for (name, t) in [
            ("cold solve", report.cold),
            ("settled (skipped)", report.settled),
            ("hit, warm", report.hit),
            ("after the hit", report.after_hit),
            ("a bond broken", report.bond_broken),
        ] {
            let sliced = if args.budget.is_some() {
                format!(" per solve (max {:.3}), {:.0} solves,", t.max_ms, t.solves)
            } else {
                String::new()
            };
            println!(
                "  {name:<18} {:>9.3} ms{sliced}  {:>6.0} iterations  residual {:.1e}{}",
                t.ms,
                t.iterations,
                t.residual,
                if t.converged { "" } else { "  (not converged)" }
            );
        }
        println!("  {:.4} ms per iteration", report.ms_per_iteration);
    }
    Ok(report)
}
