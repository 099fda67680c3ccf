//! `shatter bench stress [--runs N] [--json]`: the stress solver on a 20,097-bond graph
//! (a 10 m × 10.2 m × 0.6 m stone wall of 50 × 51 × 3 blocks anchored on its bottom
//! row), one core, measured by `shatter_lab::bench::stress`: a cold solve, a settled
//! (skipped) solve, the warm re-solve after a hit and the one after it, and the re-solve
//! after a bond breaks; then the same cases as the World runs them, with the mean
//! milliseconds per solve (per step). Milliseconds are means over the runs.

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
    /// Most springs visited per solve (each iteration and each start of a solve visits
    /// every bond once), time-slicing as --budget does.
    #[arg(long)]
    pub spring_budget: Option<usize>,
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
        spring_budget: args.spring_budget,
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
            match (args.budget, args.spring_budget) {
                (Some(b), Some(s)) => format!(", at most {b} iterations and {s} springs per solve"),
                (Some(b), None) => format!(", at most {b} iterations per solve"),
                (None, Some(s)) => format!(", at most {s} springs per solve"),
                (None, None) => String::new(),
            }
        );
        for (name, t) in [
            ("cold solve", report.cold),
            ("settled (skipped)", report.settled),
            ("hit, warm", report.hit),
            ("after the hit", report.after_hit),
            ("a bond broken", report.bond_broken),
        ] {
            let sliced = if args.budget.is_some() || args.spring_budget.is_some() {
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
        let w = &report.world;
        println!(
            "as the World runs it (hierarchy built with the object, at most {} iterations and {} springs per solve):",
            w.budget, w.spring_budget
        );
        println!(
            "  hierarchy built    {:>9.3} ms, before the first solve",
            w.build_ms
        );
        for (name, t) in [
            ("cold solve", w.cold),
            ("hit, warm", w.hit),
            ("after the hit", w.after_hit),
            ("a bond broken", w.bond_broken),
        ] {
            println!(
                "  {name:<18} {:>9.3} ms per solve (max {:.3}), {:>4.0} solves, {:>4.0} iterations{}",
                t.ms,
                t.max_ms,
                t.solves,
                t.iterations,
                if t.converged { "" } else { "  (not converged)" }
            );
        }
        println!(
            "  per solve          {:>9.3} ms mean over {:.0} solves, max {:.3} ms; CPU {}",
            w.per_solve_ms,
            w.solves,
            w.max_solve_ms,
            match w.per_solve_cpu_ms {
                Some(ms) => format!("{ms:.3} ms"),
                None => "-".to_string(),
            }
        );
    }
    Ok(report)
}
