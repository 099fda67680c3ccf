//! The stress benchmark: the stress solver on a 20,097-bond graph (a 10 m × 10.2 m ×
//! 0.6 m stone wall of 50 × 51 × 3 blocks anchored on its bottom row), one core: a cold
//! solve, a settled (skipped) solve, the warm re-solve after a hit and the one after it,
//! and the re-solve after a bond breaks. Milliseconds are means over the runs. The same
//! cases are then run as the World runs them ([`WorldPass`]): the hierarchy built before
//! the first solve, as when an object is created, and every solve held to the World's
//! default budgets, each case solved step after step until it converges; the mean
//! milliseconds per solve over all of them is what a step pays.

use std::time::Instant;

use shatter_geom::DVec3;
use shatter_sim::stress::{BondGraph, Preconditioner, SolverSettings, StressSolver};
use shatter_sim::testing::box_grid_fracture;
use shatter_sim::{DEFAULT_STRESS_BUDGET, DEFAULT_STRESS_SPRING_BUDGET};

use crate::bench::scale::thread_cpu_ns;
use crate::context::Context;
use crate::error::{LabError, ResultExt};

/// The benchmark's options.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BenchStressOptions {
    /// Times to repeat the measurement (fresh solver each time), 1..=1000.
    pub runs: usize,
    /// Most conjugate-gradient iterations per solve.
    pub max_iterations: usize,
    /// Relative residual at which a solve has converged, in (0, 1).
    pub tolerance: f64,
    /// The conjugate gradients' preconditioner.
    pub preconditioner: Preconditioner,
    /// Most iterations per solve, over all islands (time-slicing; `None`: no limit).
    /// With a budget each case is solved again and again, as steps would, until it
    /// converges; its milliseconds are then per solve.
    pub budget: Option<usize>,
    /// Most springs visited per solve (see `SolverSettings::spring_budget`; `None`: no
    /// limit), time-slicing as `budget` does.
    pub spring_budget: Option<usize>,
}

/// One kind of solve: mean milliseconds and iterations.
#[derive(Debug, Clone, Copy, Default, serde::Serialize)]
pub struct Timing {
    /// Mean wall-clock milliseconds of one solve.
    pub ms: f64,
    /// Largest wall-clock milliseconds of one solve.
    pub max_ms: f64,
    /// Solves (steps) until it converged: 1 without a budget.
    pub solves: f64,
    /// Mean conjugate-gradient iterations, summed over its solves.
    pub iterations: f64,
    /// Whether every run converged.
    pub converged: bool,
    /// Largest relative residual left.
    pub residual: f64,
    /// Mean CPU milliseconds of the thread per solve (`None` where it cannot be read):
    /// unlike `ms`, not inflated when other processes share the core.
    pub cpu_ms: Option<f64>,
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
    /// The same cases as the World runs them.
    pub world: WorldPass,
}

/// The cases run as the World runs an object: its islands and hierarchy prepared when
/// it is created ([`StressSolver::prepare`]), every solve held to the World's default
/// budgets ([`DEFAULT_STRESS_BUDGET`] iterations, [`DEFAULT_STRESS_SPRING_BUDGET`]
/// springs), each case solved again, step after step, until it converges.
#[derive(Debug, Clone, Copy, Default, serde::Serialize)]
pub struct WorldPass {
    /// Iterations per solve.
    pub budget: usize,
    /// Springs visited per solve.
    pub spring_budget: usize,
    /// Milliseconds to prepare the islands and the hierarchy (mean over the runs).
    pub build_ms: f64,
    /// From rest.
    pub cold: Timing,
    /// The 50 kN hit.
    pub hit: Timing,
    /// After the hit.
    pub after_hit: Timing,
    /// After one base bond breaks.
    pub bond_broken: Timing,
    /// Mean milliseconds per solve over every solve of the four cases: what a step pays
    /// for this object's stresses while it has something to solve (a settled one pays
    /// nothing).
    pub per_solve_ms: f64,
    /// Largest milliseconds of one solve.
    pub max_solve_ms: f64,
    /// Mean CPU milliseconds of the thread per solve over every solve of the four cases
    /// (`None` where it cannot be read).
    pub per_solve_cpu_ms: Option<f64>,
    /// Solves in all (mean over the runs).
    pub solves: f64,
}

/// The benchmark graph.
pub fn graph() -> Result<BondGraph, LabError> {
    let fracture = box_grid_fracture([50, 51, 3], DVec3::new(10.0, 10.2, 0.6));
    // Fragment i is at cell (x, y, z) with i = x + 50·(y + 51·z): row y = 0 is anchored.
    BondGraph::from_fracture(&fracture, 2600.0, |i| (i / 50) % 51 == 0)
        .internal_err("the benchmark graph is valid")
}

/// Most solves a budgeted case is given to converge.
const MAX_SOLVES: usize = 100_000;

/// Solves once (or, with a budget, until converged: `forces` in the first solve only,
/// the solver keeps them until they are judged).
fn timed(
    solver: &mut StressSolver,
    graph: &BondGraph,
    broken: &[bool],
    forces: &[(u32, DVec3)],
) -> Timing {
    let g = DVec3::new(0.0, -9.81, 0.0);
    let sliced = solver.settings().budget.is_some();
    let mut t = Timing::default();
    let mut total = 0.0;
    let cpu_start = thread_cpu_ns();
    loop {
        let first = t.solves == 0.0;
        let t0 = Instant::now();
        let report = solver.solve(graph, broken, g, if first { forces } else { &[] });
        let ms = t0.elapsed().as_secs_f64() * 1e3;
        total += ms;
        t.max_ms = t.max_ms.max(ms);
        t.solves += 1.0;
        t.iterations += report.iterations as f64;
        t.converged = report.converged;
        t.residual = report.residual;
        if !sliced || report.converged || t.solves as usize >= MAX_SOLVES {
            break;
        }
    }
    t.ms = total / t.solves;
    t.cpu_ms = cpu_start
        .zip(thread_cpu_ns())
        .map(|(a, b)| b.saturating_sub(a) as f64 / 1e6 / t.solves);
    t
}

fn mean(samples: &[Timing]) -> Timing {
    let n = samples.len().max(1) as f64;
    let avg = |f: fn(&Timing) -> f64| samples.iter().map(f).sum::<f64>() / n;
    Timing {
        ms: avg(|t| t.ms),
        max_ms: samples.iter().map(|t| t.max_ms).fold(0.0, f64::max),
        solves: avg(|t| t.solves),
        iterations: avg(|t| t.iterations),
        converged: samples.iter().all(|t| t.converged),
        residual: samples.iter().map(|t| t.residual).fold(0.0, f64::max),
        cpu_ms: samples
            .iter()
            .map(|t| t.cpu_ms)
            .sum::<Option<f64>>()
            .map(|sum| sum / n),
    }
}

/// Checks the options and runs the benchmark.
pub fn run(options: &BenchStressOptions, ctx: &Context) -> Result<BenchStressReport, LabError> {
    let o = options;
    if !(o.tolerance.is_finite() && o.tolerance > 0.0 && o.tolerance < 1.0) {
        return Err(LabError::input(format!(
            "--tolerance must be in (0, 1), got {}",
            o.tolerance
        )));
    }
    if o.budget == Some(0) {
        return Err(LabError::input("--budget must be at least 1 iteration"));
    }
    if o.spring_budget == Some(0) {
        return Err(LabError::input("--spring-budget must be at least 1 spring"));
    }
    if o.runs == 0 || o.runs > 1000 {
        return Err(LabError::input(format!(
            "--runs must be in 1..=1000, got {}",
            o.runs
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
        .ok_or_else(|| LabError::internal("the benchmark graph has no base bond"))?;
    let mut samples: [Vec<Timing>; 5] = Default::default();
    let mut world: [Vec<Timing>; 4] = Default::default();
    let mut build_ms = 0.0;
    for _ in 0..o.runs {
        ctx.progress.check()?;
        let settings = SolverSettings {
            max_iterations: o.max_iterations,
            tolerance: o.tolerance,
            preconditioner: o.preconditioner,
            budget: o.budget,
            spring_budget: o.spring_budget,
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
        // As the World runs it.
        let mut solver = StressSolver::new(
            &graph,
            SolverSettings {
                budget: Some(DEFAULT_STRESS_BUDGET),
                spring_budget: Some(DEFAULT_STRESS_SPRING_BUDGET),
                ..settings
            },
        );
        let mut broken = vec![false; bonds];
        let t0 = Instant::now();
        solver.prepare(&graph, &broken);
        build_ms += t0.elapsed().as_secs_f64() * 1e3 / o.runs as f64;
        world[0].push(timed(&mut solver, &graph, &broken, &[]));
        world[1].push(timed(&mut solver, &graph, &broken, &hit));
        world[2].push(timed(&mut solver, &graph, &broken, &[]));
        broken[base_bond] = true;
        world[3].push(timed(&mut solver, &graph, &broken, &[]));
    }
    let [cold, settled, hit, after_hit, bond_broken] = samples.map(|s| mean(&s));
    let cases = world.map(|s| mean(&s));
    let solves: f64 = cases.iter().map(|t| t.solves).sum();
    let total: f64 = cases.iter().map(|t| t.ms * t.solves).sum();
    let world = WorldPass {
        budget: DEFAULT_STRESS_BUDGET,
        spring_budget: DEFAULT_STRESS_SPRING_BUDGET,
        build_ms,
        cold: cases[0],
        hit: cases[1],
        after_hit: cases[2],
        bond_broken: cases[3],
        per_solve_ms: total / solves.max(1.0),
        per_solve_cpu_ms: cases
            .iter()
            .map(|t| t.cpu_ms.map(|c| c * t.solves))
            .sum::<Option<f64>>()
            .map(|sum| sum / solves.max(1.0)),
        max_solve_ms: cases.iter().map(|t| t.max_ms).fold(0.0, f64::max),
        solves,
    };
    Ok(BenchStressReport {
        nodes: graph.nodes().len(),
        bonds,
        runs: o.runs,
        preconditioner: o.preconditioner.to_string(),
        cold,
        settled,
        hit,
        after_hit,
        bond_broken,
        ms_per_iteration: cold.ms * cold.solves / cold.iterations.max(1.0),
        world,
    })
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;
    use shatter_geom::budget::Limits;

    fn options() -> BenchStressOptions {
        BenchStressOptions {
            runs: 1,
            max_iterations: SolverSettings::default().max_iterations,
            tolerance: SolverSettings::default().tolerance,
            preconditioner: Preconditioner::default(),
            budget: None,
            spring_budget: None,
        }
    }

    #[test]
    fn bad_tolerance_and_runs_are_input_errors() {
        let ctx = Context::quiet(Limits::none());
        for (change, message) in [
            (
                (|o: &mut BenchStressOptions| o.tolerance = 2.0) as fn(&mut _),
                "--tolerance must be in (0, 1), got 2",
            ),
            (|o| o.runs = 0, "--runs must be in 1..=1000, got 0"),
            (
                |o| o.budget = Some(0),
                "--budget must be at least 1 iteration",
            ),
            (
                |o| o.spring_budget = Some(0),
                "--spring-budget must be at least 1 spring",
            ),
        ] {
            let mut o = options();
            change(&mut o);
            assert_eq!(run(&o, &ctx).unwrap_err(), LabError::input(message));
        }
    }

    #[test]
    fn the_mean_of_timings_averages_and_keeps_the_worst() {
        let t = |ms, converged, residual| Timing {
            ms,
            max_ms: ms * 2.0,
            solves: ms,
            iterations: ms * 10.0,
            converged,
            residual,
            cpu_ms: Some(ms),
        };
        let m = mean(&[t(1.0, true, 1e-9), t(3.0, false, 1e-6)]);
        assert_eq!((m.ms, m.iterations, m.solves), (2.0, 20.0, 2.0));
        assert_eq!(m.max_ms, 6.0);
        assert!(!m.converged);
        assert_eq!(m.residual, 1e-6);
    }

    #[test]
    fn the_graph_is_the_50_by_51_by_3_wall() {
        let g = graph().unwrap();
        assert_eq!(g.nodes().len(), 50 * 51 * 3);
        assert_eq!(g.bonds().len(), 20_097);
    }
}
