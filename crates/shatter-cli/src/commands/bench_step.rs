//! `shatter bench step [--seconds T] [--json]`: the 2,000-brick wall of
//! `assets/scenes/wall.toml` hit by a projectile, mean milliseconds per step for each bond
//! model.

use clap::Args;
use shatter_geom::budget::format_count;
use shatter_geom::progress::Progress;
use shatter_sim::BondModel;
use shatter_sim::scene::budget::{bodies_estimate, run_estimate};
use shatter_sim::testing::wall_benchmark_world;

use crate::context::Context;
use crate::error::{CliError, ResultExt};

/// Fragments of the benchmark wall.
const WALL_FRAGMENTS: f64 = 2000.0;

/// Arguments of `shatter bench step`.
#[derive(Debug, Args)]
pub struct BenchStepArgs {
    /// Simulated seconds per model (the projectile hits at 0.5 s).
    #[arg(long, default_value_t = 2.0)]
    pub seconds: f64,
    /// Print one JSON object.
    #[arg(long)]
    pub json: bool,
}

/// What the benchmark measured.
#[derive(Debug, Clone, serde::Serialize)]
pub struct BenchStepReport {
    /// Fragments in the wall.
    pub fragments: usize,
    /// Steps per model.
    pub steps: u64,
    /// Mean ms per step, joints model.
    pub joints_ms_per_step: f64,
    /// Mean ms per step, clusters model.
    pub clusters_ms_per_step: f64,
    /// Worst step, joints model (ms).
    pub joints_max_ms: f64,
    /// Worst step, clusters model (ms).
    pub clusters_max_ms: f64,
    /// Bonds broken at the end, joints model.
    pub joints_bonds_broken: usize,
    /// Bonds broken at the end, clusters model.
    pub clusters_bonds_broken: usize,
}

struct Run {
    fragments: usize,
    steps: u64,
    mean_ms: f64,
    max_ms: f64,
    broken: usize,
}

/// Steps of `seconds` at the wall's step.
fn steps_of(seconds: f64) -> u64 {
    let dt = shatter_sim::WorldSettings::default().dt;
    (seconds / f64::from(dt)).round().max(1.0) as u64
}

fn measure(model: BondModel, seconds: f64, progress: &Progress) -> Result<Run, CliError> {
    progress.check()?;
    let mut world = wall_benchmark_world(model);
    let fragments = world.stats().fragments;
    let steps = steps_of(seconds);
    world.start();
    let (mut total, mut max) = (0.0f64, 0.0f64);
    world.run_steps(steps, progress, |world, _| {
        let ms = world.stats().last_step_ms;
        total += ms;
        max = max.max(ms);
        Ok::<(), CliError>(())
    })?;
    Ok(Run {
        fragments,
        steps,
        mean_ms: total / steps as f64,
        max_ms: max,
        broken: world.stats().bonds_broken,
    })
}

/// Runs `shatter bench step`.
pub fn run(args: &BenchStepArgs, ctx: &Context) -> Result<BenchStepReport, CliError> {
    if !(args.seconds.is_finite() && args.seconds > 0.0) {
        return Err(CliError::input(format!(
            "--seconds must be positive, got {}",
            args.seconds
        )));
    }
    let steps = steps_of(args.seconds);
    let joints = bodies_estimate(WALL_FRAGMENTS, BondModel::Joints)
        + run_estimate(WALL_FRAGMENTS, BondModel::Joints, steps);
    let clusters = bodies_estimate(WALL_FRAGMENTS, BondModel::Clusters)
        + run_estimate(WALL_FRAGMENTS, BondModel::Clusters, steps);
    let estimate = shatter_geom::budget::Estimate {
        bytes: joints.bytes.max(clusters.bytes),
        seconds: joints.seconds + clusters.seconds,
    }
    .with_process();
    ctx.check(
        &format!(
            "--seconds {}: 2 x {} steps of the 2,000-brick wall",
            args.seconds,
            format_count(steps)
        ),
        &estimate,
    )?;
    let bar = ctx.follow("bench step", &estimate, args.json);
    let joints = measure(BondModel::Joints, args.seconds, &ctx.progress)?;
    let clusters = measure(BondModel::Clusters, args.seconds, &ctx.progress)?;
    drop(bar);
    let report = BenchStepReport {
        fragments: clusters.fragments,
        steps: clusters.steps,
        joints_ms_per_step: joints.mean_ms,
        clusters_ms_per_step: clusters.mean_ms,
        joints_max_ms: joints.max_ms,
        clusters_max_ms: clusters.max_ms,
        joints_bonds_broken: joints.broken,
        clusters_bonds_broken: clusters.broken,
    };
    if args.json {
        let json = serde_json::to_string(&report).internal_err("cannot encode the report")?;
        println!("{json}");
    } else {
        println!(
            "wall of {} fragments, {} steps per model\n  joints:   {:.3} ms/step (max {:.3}), {} bonds broken\n  clusters: {:.3} ms/step (max {:.3}), {} bonds broken\n  clusters are {:.1}x cheaper",
            report.fragments,
            report.steps,
            report.joints_ms_per_step,
            report.joints_max_ms,
            report.joints_bonds_broken,
            report.clusters_ms_per_step,
            report.clusters_max_ms,
            report.clusters_bonds_broken,
            report.joints_ms_per_step / report.clusters_ms_per_step.max(1e-9)
        );
    }
    Ok(report)
}
