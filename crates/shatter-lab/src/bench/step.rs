//! The step benchmark: the 2,000-brick wall of `assets/scenes/wall.toml` hit by a
//! projectile, mean milliseconds per step for each bond model.

use shatter_geom::budget::{Estimate, format_count};
use shatter_geom::progress::Progress;
use shatter_sim::BondModel;
use shatter_sim::scene::budget::{bodies_estimate, run_estimate};
use shatter_sim::testing::wall_benchmark_world;

use crate::context::Context;
use crate::error::LabError;

/// Fragments of the benchmark wall.
const WALL_FRAGMENTS: f64 = 2000.0;

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

/// One bond model's run of the wall.
struct Run {
    fragments: usize,
    steps: u64,
    mean_ms: f64,
    max_ms: f64,
    broken: usize,
}

/// Steps of `seconds` at the wall's step.
pub fn steps_of(seconds: f64) -> u64 {
    let dt = shatter_sim::WorldSettings::default().dt;
    (seconds / f64::from(dt)).round().max(1.0) as u64
}

fn measure(model: BondModel, seconds: f64, progress: &Progress) -> Result<Run, LabError> {
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
        Ok::<(), LabError>(())
    })?;
    Ok(Run {
        fragments,
        steps,
        mean_ms: total / steps as f64,
        max_ms: max,
        broken: world.stats().bonds_broken,
    })
}

/// The estimate of both bond models' runs of `seconds`.
fn estimate(seconds: f64) -> Estimate {
    let steps = steps_of(seconds);
    let joints = bodies_estimate(WALL_FRAGMENTS, BondModel::Joints)
        + run_estimate(WALL_FRAGMENTS, BondModel::Joints, steps);
    let clusters = bodies_estimate(WALL_FRAGMENTS, BondModel::Clusters)
        + run_estimate(WALL_FRAGMENTS, BondModel::Clusters, steps);
    Estimate {
        bytes: joints.bytes.max(clusters.bytes),
        seconds: joints.seconds + clusters.seconds,
    }
    .with_process()
}

/// Runs the wall for `seconds` (positive) with each bond model, after checking the
/// estimate against the context's limits; a bar follows the steps unless `quiet`.
pub fn run(seconds: f64, ctx: &Context, quiet: bool) -> Result<BenchStepReport, LabError> {
    if !(seconds.is_finite() && seconds > 0.0) {
        return Err(LabError::input(format!(
            "--seconds must be positive, got {seconds}"
        )));
    }
    let estimate = estimate(seconds);
    ctx.check(
        &format!(
            "--seconds {seconds}: 2 x {} steps of the 2,000-brick wall",
            format_count(steps_of(seconds))
        ),
        &estimate,
    )?;
    let bar = ctx.follow("bench step", &estimate, quiet);
    let joints = measure(BondModel::Joints, seconds, &ctx.progress)?;
    let clusters = measure(BondModel::Clusters, seconds, &ctx.progress)?;
    drop(bar);
    Ok(BenchStepReport {
        fragments: clusters.fragments,
        steps: clusters.steps,
        joints_ms_per_step: joints.mean_ms,
        clusters_ms_per_step: clusters.mean_ms,
        joints_max_ms: joints.max_ms,
        clusters_max_ms: clusters.max_ms,
        joints_bonds_broken: joints.broken,
        clusters_bonds_broken: clusters.broken,
    })
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;
    use shatter_geom::budget::Limits;

    #[test]
    fn steps_round_to_the_world_step_and_are_at_least_one() {
        let dt = f64::from(shatter_sim::WorldSettings::default().dt);
        assert_eq!(steps_of(100.0 * dt), 100);
        assert_eq!(steps_of(1e-9), 1);
        assert!(estimate(2.0).seconds > estimate(1.0).seconds);
    }

    #[test]
    fn bad_seconds_are_refused_before_any_world_is_built() {
        let ctx = Context::quiet(Limits::none());
        for s in [0.0, -1.0, f64::NAN] {
            let e = run(s, &ctx, true).unwrap_err();
            assert!(
                e.to_string().starts_with("--seconds must be positive"),
                "{e}"
            );
        }
    }
}
