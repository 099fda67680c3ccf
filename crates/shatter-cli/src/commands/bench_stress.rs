//! `shatter bench stress [--runs N] [--json]`: the stress solver on a 20,097-bond graph
//! (a 10 m × 10.2 m × 0.6 m stone wall of 50 × 51 × 3 blocks anchored on its bottom
//! row), one core: a cold solve, a settled (skipped) solve, the warm re-solve after a hit
//! and the one after it, and the re-solve after a bond breaks. Milliseconds are means over
//! the runs.

use clap::Args;
use shatter_geom::DVec3;
use shatter_sim::stress::{BondGraph, Preconditioner, SolverSettings, StressSolver};
use shatter_sim::testing::box_grid_fracture;
use std::time::Instant;

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
    /// Print one JSON object.
    #[arg(long)]
    pub json: bool,
}

/// One kind of solve: mean milliseconds and iterations.
#[derive(Debug, Clone, Copy, Default, serde::Serialize)]
pub struct Timing {
    /// Mean wall-clock milliseconds.
    pub ms: f64,
    /// Mean conjugate-gradient iterations.
    pub iterations: f64,
    /// Whether every run converged.
    pub converged: bool,
    /// Largest relative residual left.
    pub residual: f64,
}

/// What the benchmark measured.
#[derive(Debug, Clone, serde::Serialize)]
pub struct BenchStressReport {
    /// Nodes of the graph.
    pub nodes: usize,
    /// Bonds of the graph.
    pub bonds: usize,
    /// Runs averaged.
    pub runs: usize,
    /// The preconditioner used.
    pub preconditioner: String,
    /// Solve from rest (zero warm start) to the tolerance.
    pub cold: Timing,
    /// A solve with nothing changed: the island is settled and skipped.
    pub settled: Timing,
    /// Warm re-solve with a 50 kN hit on one block at mid-height.
    pub hit: Timing,
    /// The solve after the hit (back to gravity only).
    pub after_hit: Timing,
    /// Warm re-solve after one bond at the base breaks (islands rebuilt).
    pub bond_broken: Timing,
    /// Milliseconds per iteration (cold solve).
    pub ms_per_iteration: f64,
}

/// The benchmark graph.
pub fn graph() -> Result<BondGraph, CliError> {
    let fracture = box_grid_fracture([50, 51, 3], DVec3::new(10.0, 10.2, 0.6));
    // Fragment i is at cell (x, y, z) with i = x + 50·(y + 51·z): row y = 0 is anchored.
    BondGraph::from_fracture(&fracture, 2600.0, |i| (i / 50) % 51 == 0)
        .internal_err("the benchmark graph is valid")
}

fn timed(
    solver: &mut StressSolver,
    graph: &BondGraph,
    broken: &[bool],
    forces: &[(u32, DVec3)],
) -> Timing {
    let g = DVec3::new(0.0, -9.81, 0.0);
    let t0 = Instant::now();
    let report = solver.solve(graph, broken, g, forces);
    Timing {
        ms: t0.elapsed().as_secs_f64() * 1e3,
        iterations: report.iterations as f64,
        converged: report.converged,
        residual: report.residual,
    }
}

fn mean(samples: &[Timing]) -> Timing {
    let n = samples.len().max(1) as f64;
    Timing {
        ms: samples.iter().map(|t| t.ms).sum::<f64>() / n,
        iterations: samples.iter().map(|t| t.iterations).sum::<f64>() / n,
        converged: samples.iter().all(|t| t.converged),
        residual: samples.iter().map(|t| t.residual).fold(0.0, f64::max),
    }
}

/// Runs `shatter bench stress`.
pub fn run(args: &BenchStressArgs, ctx: &Context) -> Result<BenchStressReport, CliError> {
    if !(args.tolerance.is_finite() && args.tolerance > 0.0 && args.tolerance < 1.0) {
        return Err(CliError::input(format!(
            "--tolerance must be in (0, 1), got {}",
            args.tolerance
        )));
    }
    if args.runs == 0 || args.runs > 1000 {
        return Err(CliError::input(format!(
            "--runs must be in 1..=1000, got {}",
            args.runs
        )));
    }
    let graph = graph()?;
    let bonds = graph.bonds().len();
    // A block at mid-height in the middle of the front layer, and a base bond under it.
    let hit_node = 25 + 50 * 25;
    let base_bond = graph
        .bonds()
        .iter()
        .position(|b| b.a == 25 && b.b == 25 + 50)
        .ok_or_else(|| CliError::internal("the benchmark graph has no base bond"))?;
    let mut samples: [Vec<Timing>; 5] = Default::default();
    for _ in 0..args.runs {
        ctx.progress.check()?;
        let settings = SolverSettings {
            max_iterations: args.max_iterations,
            tolerance: args.tolerance,
            preconditioner: args.preconditioner,
            ..SolverSettings::default()
        };
        let mut solver = StressSolver::new(&graph, settings);
        let mut broken = vec![false; bonds];
        samples[0].push(timed(&mut solver, &graph, &broken, &[]));
        samples[1].push(timed(&mut solver, &graph, &broken, &[]));
        let hit = [(hit_node, DVec3::new(0.0, 0.0, -50_000.0))];
        samples[2].push(timed(&mut solver, &graph, &broken, &hit));
        samples[3].push(timed(&mut solver, &graph, &broken, &[]));
        broken[base_bond] = true;
        samples[4].push(timed(&mut solver, &graph, &broken, &[]));
    }
    let [cold, settled, hit, after_hit, bond_broken] = samples.map(|s| mean(&s));
    let report = BenchStressReport {
        nodes: graph.nodes().len(),
        bonds,
        runs: args.runs,
        preconditioner: args.preconditioner.to_string(),
        cold,
        settled,
        hit,
        after_hit,
        bond_broken,
        ms_per_iteration: cold.ms / cold.iterations.max(1.0),
    };
    if args.json {
        let json = serde_json::to_string(&report).internal_err("cannot encode the report")?;
        println!("{json}");
    } else {
        println!(
            "stress solver ({}), {} nodes, {} bonds, mean of {} runs, one core",
            report.preconditioner, report.nodes, report.bonds, report.runs
        );
        for (name, t) in [
            ("cold solve", report.cold),
            ("settled (skipped)", report.settled),
            ("hit, warm", report.hit),
            ("after the hit", report.after_hit),
            ("a bond broken", report.bond_broken),
        ] {
            println!(
                "  {name:<18} {:>9.3} ms  {:>6.0} iterations  residual {:.1e}{}",
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
