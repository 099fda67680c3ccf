//! The run recorder.

use std::path::Path;

use crate::ReportError;
use crate::export::{AnimatedNode, AnimatedScene, FragmentMesh, Pose, write_animated_glb};
use crate::table::{Cell, CsvTable};

/// Statistics of one simulation step (one row of the `--record` CSV).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct StepStats {
    /// Step number (1 for the first step).
    pub step: u64,
    /// Simulated time after the step, in seconds.
    pub time: f64,
    /// Rigid bodies in the world.
    pub bodies: usize,
    /// Fragments in the world.
    pub fragments: usize,
    /// Bonds at the start of the run.
    pub bonds_total: usize,
    /// Bonds broken so far.
    pub bonds_broken: usize,
    /// Bodies removed so far because their state diverged (NaN or runaway speed).
    pub diverged: usize,
    /// Debris bodies removed so far by the debris cap.
    pub debris_removed: usize,
    /// Wall-clock time the step took, in milliseconds.
    pub millis: f64,
    /// Conjugate-gradient iterations of the stress solver in the step.
    pub stress_iterations: usize,
    /// Wall-clock time of the step's stress pass, in milliseconds.
    pub stress_millis: f64,
}

/// Columns of [`RunRecorder::stats_table`].
pub const STATS_HEADER: [&str; 11] = [
    "step",
    "time_s",
    "bodies",
    "fragments",
    "bonds_total",
    "bonds_broken",
    "diverged",
    "debris_removed",
    "step_ms",
    "stress_iterations",
    "stress_ms",
];

/// Collects a run step by step, then writes it as CSV and animated GLB.
///
/// Nodes (fragments, projectiles) are registered with [`RunRecorder::add_node`]; at each
/// keyframe the simulation passes the poses of the nodes that exist. A node missing from
/// a keyframe is hidden at that time (not yet created, or removed).
///
/// ```
/// use shatter_report::export::{FragmentMesh, Pose};
/// use shatter_report::record::{RunRecorder, StepStats};
///
/// let mut rec = RunRecorder::new().with_keyframe_rate(30.0);
/// let cube = rec.add_mesh(FragmentMesh::new(
///     "tetra",
///     vec![[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
///     vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]],
///     [0.7, 0.7, 0.7],
/// ));
/// let node = rec.add_node("fragment_0", cube)?;
/// for step in 1..=60u64 {
///     let time = step as f64 / 60.0;
///     rec.record_stats(StepStats { step, time, ..Default::default() });
///     if rec.wants_keyframe(time) {
///         let y = 10.0 - 4.9 * (time * time) as f32;
///         rec.record_poses(time, [(node, Pose::new([0.0, y, 0.0], [0.0, 0.0, 0.0, 1.0]))])?;
///     }
/// }
/// assert_eq!(rec.keyframe_count(), 30);
/// let dir = tempfile::tempdir()?;
/// rec.write_csv(dir.path().join("run.csv"))?;
/// rec.write_glb(dir.path().join("run.glb"))?;
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug, Clone, Default)]
pub struct RunRecorder {
    stats: Vec<StepStats>,
    meshes: Vec<FragmentMesh>,
    nodes: Vec<(String, usize)>,
    times: Vec<f64>,
    /// `poses[node][sample]`; `None` where the node did not exist.
    poses: Vec<Vec<Option<Pose>>>,
    /// Minimum time between keyframes, in seconds (0: every call is a keyframe).
    keyframe_interval: f64,
}

impl RunRecorder {
    /// An empty recorder that keeps every keyframe it is given.
    pub fn new() -> Self {
        Self::default()
    }

    /// Keeps at most `per_second` keyframes per simulated second (for example 30 for a
    /// 60 Hz simulation exported at 30 fps). A non-positive rate keeps every keyframe.
    pub fn with_keyframe_rate(mut self, per_second: f64) -> Self {
        self.keyframe_interval = if per_second > 0.0 {
            1.0 / per_second
        } else {
            0.0
        };
        self
    }

    /// Registers a mesh; returns its index for [`RunRecorder::add_node`].
    pub fn add_mesh(&mut self, mesh: FragmentMesh) -> usize {
        self.meshes.push(mesh);
        self.meshes.len() - 1
    }

    /// Registers a node showing mesh `mesh`; returns its id for
    /// [`RunRecorder::record_poses`]. It is hidden at the keyframes already recorded.
    pub fn add_node(&mut self, name: impl Into<String>, mesh: usize) -> Result<usize, ReportError> {
        if mesh >= self.meshes.len() {
            return Err(ReportError::Scene(format!(
                "mesh {mesh} does not exist ({} meshes registered)",
                self.meshes.len()
            )));
        }
        self.nodes.push((name.into(), mesh));
        self.poses.push(vec![None; self.times.len()]);
        Ok(self.nodes.len() - 1)
    }

    /// Appends the statistics of one step.
    pub fn record_stats(&mut self, stats: StepStats) {
        self.stats.push(stats);
    }

    /// Whether a keyframe at `time` would be kept: the time can be recorded (see
    /// [`RunRecorder::can_record_at`]) and is at least one keyframe interval after the
    /// previous keyframe (the first one always is).
    pub fn wants_keyframe(&self, time: f64) -> bool {
        self.can_record_at(time)
            && match self.times.last() {
                None => true,
                // A little slack so that 60 Hz steps give exactly 30 keyframes a second.
                Some(&last) => time - last >= self.keyframe_interval * (1.0 - 1e-3),
            }
    }

    /// Whether a keyframe at `time` can be recorded at all, whatever the rate: `time` is
    /// finite, at least 0, and after the previous keyframe also once rounded to `f32`
    /// (the precision of glTF times).
    pub fn can_record_at(&self, time: f64) -> bool {
        time.is_finite()
            && time >= 0.0
            && self
                .times
                .last()
                .is_none_or(|&last| time > last && time as f32 > last as f32)
    }

    /// Time of the last keyframe recorded, if any.
    pub fn last_keyframe_time(&self) -> Option<f64> {
        self.times.last().copied()
    }

    /// Records the poses of the nodes that exist at `time`. Returns `false` (and records
    /// nothing) when the keyframe rate says to skip this time.
    ///
    /// Fails on an unknown node id or a time that cannot be recorded (see
    /// [`RunRecorder::can_record_at`]).
    pub fn record_poses(
        &mut self,
        time: f64,
        poses: impl IntoIterator<Item = (usize, Pose)>,
    ) -> Result<bool, ReportError> {
        self.check_time(time)?;
        if !self.wants_keyframe(time) {
            return Ok(false);
        }
        self.push_keyframe(time, poses)?;
        Ok(true)
    }

    /// Records the poses of the nodes that exist at `time` whatever the keyframe rate
    /// (for example the last step of a run, so that the animation ends where the run
    /// ended).
    ///
    /// Fails on an unknown node id or a time that cannot be recorded (see
    /// [`RunRecorder::can_record_at`]); nothing is recorded then.
    pub fn record_keyframe(
        &mut self,
        time: f64,
        poses: impl IntoIterator<Item = (usize, Pose)>,
    ) -> Result<(), ReportError> {
        self.check_time(time)?;
        self.push_keyframe(time, poses)
    }

    fn check_time(&self, time: f64) -> Result<(), ReportError> {
        if self.can_record_at(time) {
            return Ok(());
        }
        Err(ReportError::Scene(format!(
            "keyframe time {time} is not finite, negative or not after the previous one \
             ({:?})",
            self.times.last()
        )))
    }

    /// Appends a keyframe (the time is already checked).
    fn push_keyframe(
        &mut self,
        time: f64,
        poses: impl IntoIterator<Item = (usize, Pose)>,
    ) -> Result<(), ReportError> {
        let mut column = vec![None; self.nodes.len()];
        for (node, pose) in poses {
            let slot = column.get_mut(node).ok_or_else(|| {
                ReportError::Scene(format!(
                    "node {node} does not exist ({} nodes registered)",
                    self.nodes.len()
                ))
            })?;
            *slot = Some(pose);
        }
        self.times.push(time);
        for (track, pose) in self.poses.iter_mut().zip(column) {
            track.push(pose);
        }
        Ok(())
    }

    /// Number of keyframes recorded.
    pub fn keyframe_count(&self) -> usize {
        self.times.len()
    }

    /// Number of nodes registered.
    pub fn node_count(&self) -> usize {
        self.nodes.len()
    }

    /// The statistics recorded so far.
    pub fn stats(&self) -> &[StepStats] {
        &self.stats
    }

    /// The statistics as a table with the columns [`STATS_HEADER`].
    pub fn stats_table(&self) -> CsvTable {
        let mut table = CsvTable::new(STATS_HEADER);
        for s in &self.stats {
            table
                .push_row([
                    Cell::from(s.step),
                    Cell::from(s.time),
                    Cell::from(s.bodies),
                    Cell::from(s.fragments),
                    Cell::from(s.bonds_total),
                    Cell::from(s.bonds_broken),
                    Cell::from(s.diverged),
                    Cell::from(s.debris_removed),
                    Cell::from(s.millis),
                    Cell::from(s.stress_iterations),
                    Cell::from(s.stress_millis),
                ])
                .expect("every row has one cell per STATS_HEADER column");
        }
        table
    }

    /// Writes the per-step statistics as CSV.
    pub fn write_csv(&self, path: impl AsRef<Path>) -> Result<(), ReportError> {
        self.stats_table().write(path)
    }

    /// The recorded run as an animated scene. A node is hidden, at its nearest known
    /// pose, at the keyframes where it did not exist.
    pub fn to_scene(&self) -> AnimatedScene {
        let nodes = self
            .nodes
            .iter()
            .zip(&self.poses)
            .map(|((name, mesh), track)| {
                let first = track
                    .iter()
                    .flatten()
                    .next()
                    .copied()
                    .unwrap_or(Pose::IDENTITY);
                let mut current = first;
                let mut poses = Vec::with_capacity(track.len());
                let mut visible = Vec::with_capacity(track.len());
                for pose in track {
                    if let Some(p) = pose {
                        current = *p;
                    }
                    poses.push(current);
                    visible.push(pose.is_some());
                }
                if visible.iter().all(|&v| v) {
                    visible.clear();
                }
                AnimatedNode {
                    name: name.clone(),
                    mesh: *mesh,
                    poses,
                    visible,
                }
            })
            .collect();
        AnimatedScene {
            times: self.times.iter().map(|&t| t as f32).collect(),
            meshes: self.meshes.clone(),
            nodes,
        }
    }

    /// Writes the recorded run as an animated GLB.
    pub fn write_glb(&self, path: impl AsRef<Path>) -> Result<(), ReportError> {
        write_animated_glb(path, &self.to_scene())
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;

    fn tetra() -> FragmentMesh {
        FragmentMesh::new(
            "t",
            vec![[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
            vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]],
            [0.5; 3],
        )
    }

    fn at(y: f32) -> Pose {
        Pose::new([0.0, y, 0.0], [0.0, 0.0, 0.0, 1.0])
    }

    #[test]
    fn a_node_added_late_is_hidden_before_and_one_removed_is_hidden_after() {
        let mut rec = RunRecorder::new();
        let m = rec.add_mesh(tetra());
        let a = rec.add_node("a", m).unwrap();
        rec.record_poses(0.0, [(a, at(1.0))]).unwrap();
        let b = rec.add_node("b", m).unwrap();
        rec.record_poses(0.1, [(a, at(2.0)), (b, at(5.0))]).unwrap();
        rec.record_poses(0.2, [(b, at(6.0))]).unwrap();
        let scene = rec.to_scene();
        scene.validate().unwrap();
        assert_eq!(scene.nodes[0].visible, vec![true, true, false]);
        assert_eq!(scene.nodes[0].poses[2], at(2.0));
        assert_eq!(scene.nodes[1].visible, vec![false, true, true]);
        assert_eq!(scene.nodes[1].poses[0], at(5.0));
    }

    #[test]
    fn the_keyframe_rate_halves_60_hz_steps() {
        let mut rec = RunRecorder::new().with_keyframe_rate(30.0);
        let m = rec.add_mesh(tetra());
        let a = rec.add_node("a", m).unwrap();
        let mut kept = 0;
        for step in 0..120 {
            if rec
                .record_poses(step as f64 / 60.0, [(a, at(0.0))])
                .unwrap()
            {
                kept += 1;
            }
        }
        assert_eq!(kept, 60);
        assert_eq!(rec.keyframe_count(), 60);
    }

    #[test]
    fn unknown_nodes_and_meshes_and_backward_times_are_refused() {
        let mut rec = RunRecorder::new();
        assert!(rec.add_node("x", 0).is_err());
        let m = rec.add_mesh(tetra());
        let a = rec.add_node("a", m).unwrap();
        assert!(rec.record_poses(0.0, [(a + 1, at(0.0))]).is_err());
        assert_eq!(rec.keyframe_count(), 0);
        rec.record_poses(0.5, [(a, at(0.0))]).unwrap();
        assert!(rec.record_poses(0.25, [(a, at(0.0))]).is_err());
    }

    #[test]
    fn stats_rows_follow_the_header() {
        let mut rec = RunRecorder::new();
        rec.record_stats(StepStats {
            step: 1,
            time: 1.0 / 60.0,
            bodies: 3,
            fragments: 10,
            bonds_total: 20,
            bonds_broken: 2,
            diverged: 1,
            debris_removed: 4,
            millis: 0.5,
            stress_iterations: 7,
            stress_millis: 0.25,
        });
        let csv = rec.stats_table().to_csv_string().unwrap();
        let mut lines = csv.lines();
        assert_eq!(lines.next().unwrap(), STATS_HEADER.join(","));
        let row: Vec<&str> = lines.next().unwrap().split(',').collect();
        assert_eq!(row[0], "1");
        assert_eq!(row[2], "3");
        assert_eq!(row[5], "2");
        assert_eq!(row[6], "1");
        assert_eq!(row[7], "4");
        assert_eq!(row[8], "0.5");
        assert_eq!(row[9], "7");
        assert_eq!(row[10], "0.25");
        assert_eq!(row[1].parse::<f64>().unwrap(), 1.0 / 60.0);
    }

    #[test]
    fn a_forced_keyframe_ignores_the_rate_but_not_the_order() {
        let mut rec = RunRecorder::new().with_keyframe_rate(10.0);
        let m = rec.add_mesh(tetra());
        let a = rec.add_node("a", m).unwrap();
        assert!(rec.record_poses(0.0, [(a, at(0.0))]).unwrap());
        // 0.05 s is closer than the 0.1 s interval: skipped by the rate...
        assert!(!rec.record_poses(0.05, [(a, at(1.0))]).unwrap());
        assert_eq!(rec.keyframe_count(), 1);
        // ... but kept when forced.
        rec.record_keyframe(0.05, [(a, at(1.0))]).unwrap();
        assert_eq!(rec.keyframe_count(), 2);
        assert_eq!(rec.last_keyframe_time(), Some(0.05));
        assert!(rec.record_keyframe(0.05, [(a, at(1.0))]).is_err());
        assert!(rec.record_keyframe(0.06, [(a + 1, at(1.0))]).is_err());
        assert_eq!(rec.keyframe_count(), 2);
    }

    #[test]
    fn times_equal_once_rounded_to_f32_cannot_be_recorded() {
        let mut rec = RunRecorder::new();
        let m = rec.add_mesh(tetra());
        let a = rec.add_node("a", m).unwrap();
        rec.record_keyframe(1000.0, [(a, at(0.0))]).unwrap();
        let next = 1000.0 + 1e-6;
        assert_eq!(next as f32, 1000.0f32);
        assert!(!rec.can_record_at(next));
        assert!(!rec.wants_keyframe(next));
        assert!(rec.record_poses(next, [(a, at(0.0))]).is_err());
        assert!(!rec.can_record_at(f64::NAN));
        assert!(rec.can_record_at(1000.5));
    }
}
