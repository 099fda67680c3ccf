//! Running a built scene headless: the steps, and what is recorded along the way — the
//! per-step statistics (`--record RUN.csv`) and the animated glTF (`--export RUN.glb`,
//! [`RunExport`]) — and the report of the run ([`SimulateReport`]).

mod export;
mod report;

use std::path::PathBuf;

use shatter_geom::budget::Estimate;
use shatter_report::record::{RunRecorder, StepStats};
use shatter_sim::World;

pub use export::{ExportSummary, RunExport};
pub use report::{RecordSummary, SimulateReport};

use crate::context::Context;
use crate::error::{LabError, ResultExt};
use crate::output;

/// Keyframes per simulated second of the export when no rate is given.
pub const DEFAULT_FPS: f64 = 30.0;

/// What to record of a run, validated (the paths can be written, the rate is ≥ 0).
#[derive(Debug, Clone, PartialEq)]
pub struct RunOutputs {
    /// Write the run as an animated binary glTF here.
    pub export: Option<PathBuf>,
    /// Keyframes per simulated second of the export (0: one per step).
    pub fps: f64,
    /// Write the per-step statistics as CSV here.
    pub record: Option<PathBuf>,
}

/// One row of `--record`'s CSV from the world's statistics after a step.
fn step_stats(world: &World) -> StepStats {
    let stats = world.stats();
    StepStats {
        step: stats.steps,
        time: stats.time,
        bodies: stats.bodies,
        fragments: stats.fragments,
        bonds_total: stats.bonds_total,
        bonds_broken: stats.bonds_broken,
        diverged: stats.diverged,
        debris_removed: stats.debris_removed,
        millis: stats.last_step_ms,
        stress_iterations: stats.stress_iterations,
        stress_millis: stats.stress_ms,
    }
}

/// Starts `world` and runs `steps` steps, recording what `outputs` asks for; a bar
/// follows the steps (for a run estimated at `estimate`) unless `quiet`. Cancelling the
/// context's progress stops it between two steps without writing any output. The
/// outputs are written through temporary files once the run is complete.
pub fn run(
    world: &mut World,
    steps: u64,
    outputs: &RunOutputs,
    estimate: &Estimate,
    ctx: &Context,
    quiet: bool,
) -> Result<SimulateReport, LabError> {
    world.start();
    let mut run_export = outputs
        .export
        .as_ref()
        .map(|_| RunExport::new(world, outputs.fps))
        .transpose()?;
    let mut stats_log = outputs.record.as_ref().map(|_| RunRecorder::new());
    let mut total_ms = 0.0;
    let bar = ctx.follow("simulating", estimate, quiet);
    world.run_steps(steps, &ctx.progress, |world, done| {
        total_ms += world.stats().last_step_ms;
        if let Some(log) = &mut stats_log {
            log.record_stats(step_stats(world));
        }
        if let Some(export) = &mut run_export {
            export.observe(world, done == steps)?;
        }
        Ok::<(), LabError>(())
    })?;
    drop(bar);
    let mut report = SimulateReport::new(world, steps, total_ms);
    if let (Some(export), Some(path)) = (run_export, &outputs.export) {
        report.export = Some(output::via_temp_path(path, &ctx.progress, |temp| {
            export.write(temp, path)
        })?);
    }
    if let (Some(log), Some(path)) = (stats_log, &outputs.record) {
        output::via_temp_path(path, &ctx.progress, |temp| {
            log.write_csv(temp)
                .input_err(format!("cannot write --record {}", path.display()))
        })?;
        report.record = Some(RecordSummary {
            path: path.clone(),
            rows: log.stats().len(),
        });
    }
    Ok(report)
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;
    use shatter_geom::budget::Limits;
    use shatter_sim::{BondModel, ObjectSpec, WorldSettings};

    fn world() -> World {
        let mut world = World::new(WorldSettings::default());
        let fracture = shatter_sim::testing::box_grid_fracture([2, 1, 1], [1.0, 0.5, 0.5].into());
        let spec = ObjectSpec {
            name: "pair".into(),
            bond_model: Some(BondModel::Clusters),
            ..ObjectSpec::from_fracture(fracture, [0.0, 1.0, 0.0].into())
        };
        world.add_object(spec).unwrap();
        world
    }

    #[test]
    fn a_run_records_a_row_per_step_and_keyframes_at_the_rate() {
        let dir = tempfile::tempdir().unwrap();
        let outputs = RunOutputs {
            export: Some(dir.path().join("run.glb")),
            fps: 0.0,
            record: Some(dir.path().join("run.csv")),
        };
        let ctx = Context::quiet(Limits::none());
        let mut w = world();
        let report = run(&mut w, 5, &outputs, &Estimate::default(), &ctx, true).unwrap();
        assert_eq!(report.steps, 5);
        assert_eq!(report.digest.len(), 16);
        let record = report.record.as_ref().unwrap();
        assert_eq!(record.rows, 5);
        let csv = std::fs::read_to_string(&record.path).unwrap();
        assert_eq!(csv.lines().count(), 1 + 5);
        let export = report.export.as_ref().unwrap();
        // fps 0: the initial state and one keyframe per step.
        assert_eq!((export.fragment_nodes, export.keyframes), (2, 6));
        assert!(export.path.is_file());
    }

    #[test]
    fn a_cancelled_run_writes_nothing() {
        let dir = tempfile::tempdir().unwrap();
        let outputs = RunOutputs {
            export: None,
            fps: DEFAULT_FPS,
            record: Some(dir.path().join("run.csv")),
        };
        let ctx = Context::quiet(Limits::none());
        ctx.progress.cancel();
        let e = run(&mut world(), 3, &outputs, &Estimate::default(), &ctx, true).unwrap_err();
        assert_eq!(e, LabError::Interrupted);
        assert!(!dir.path().join("run.csv").exists());
    }
}
