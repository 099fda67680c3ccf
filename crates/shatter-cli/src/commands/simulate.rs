//! `shatter simulate SCENE.toml [--seconds T | --steps N] [--bonds joints|clusters] [--json]
//! [--export RUN.glb [--fps F]] [--record RUN.csv]`: runs a scene headless and prints its
//! statistics and the digest of the final state; optionally writes the run as an animated
//! glTF and its per-step statistics as CSV.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use anyhow::Context as _;
use clap::Args;
use shatter_geom::TriMesh;
use shatter_report::export::{FragmentMesh, Pose as KeyPose};
use shatter_report::record::{RunRecorder, StepStats};
use shatter_sim::scene::Scene;
use shatter_sim::{BondModel, ObjectId, Pose, ProjectileSpec, World};

use crate::args::check_writable;
use crate::context::Context;
use crate::error::{CliError, ResultExt};
use crate::output;

/// Keyframes per simulated second of `--export` when `--fps` is not given.
pub const DEFAULT_FPS: f64 = 30.0;

/// Arguments of `shatter simulate`.
#[derive(Debug, Args)]
pub struct SimulateArgs {
    /// The scene file (TOML, see docs/scene-format.md).
    #[arg(value_name = "SCENE.toml")]
    pub scene: PathBuf,
    /// Simulated seconds (default: the scene's `world.seconds`).
    #[arg(long, conflicts_with = "steps")]
    pub seconds: Option<f64>,
    /// Number of fixed steps.
    #[arg(long)]
    pub steps: Option<u64>,
    /// Override every object's bond model.
    #[arg(long, value_enum)]
    pub bonds: Option<BondModel>,
    /// Print one JSON object.
    #[arg(long)]
    pub json: bool,
    /// Write the run as an animated binary glTF: one node per fragment and per
    /// projectile, keyframed (viewable in Blender or any glTF viewer).
    #[arg(long, value_name = "RUN.glb")]
    pub export: Option<PathBuf>,
    /// Keyframes per simulated second in --export (default 30; 0: one per step). The
    /// first and the last state are always keyframes.
    #[arg(long, value_name = "F", requires = "export")]
    pub fps: Option<f64>,
    /// Write per-step statistics as CSV: one row per step, with a header.
    #[arg(long, value_name = "RUN.csv")]
    pub record: Option<PathBuf>,
}

/// What `--export` wrote.
#[derive(Debug, Clone, serde::Serialize)]
pub struct ExportSummary {
    /// The GLB file.
    pub path: PathBuf,
    /// Nodes in the file (fragments + projectiles).
    pub nodes: usize,
    /// Nodes that are fragments (one per fragment of every object).
    pub fragment_nodes: usize,
    /// Nodes that are projectiles (one per projectile in flight at some keyframe).
    pub projectile_nodes: usize,
    /// Keyframes per node.
    pub keyframes: usize,
}

/// What `--record` wrote.
#[derive(Debug, Clone, serde::Serialize)]
pub struct RecordSummary {
    /// The CSV file.
    pub path: PathBuf,
    /// Rows after the header (one per step).
    pub rows: usize,
}

/// What a run measured.
#[derive(Debug, Clone, serde::Serialize)]
pub struct SimulateReport {
    /// Steps run.
    pub steps: u64,
    /// Rigid bodies at the end.
    pub bodies: usize,
    /// Fragments with a body at the end.
    pub fragments: usize,
    /// Bonds of all objects.
    pub bonds_total: usize,
    /// Broken bonds (never decreases during a run; the sum of the three causes).
    pub bonds_broken: usize,
    /// Bonds broken by a load over the break force (contacts, explosions, joints).
    pub bonds_broken_by_impact: usize,
    /// Bonds broken by the stress solver (stress over the material's limits).
    pub bonds_broken_by_stress: usize,
    /// Bonds broken when repeated weak hits wore their health to 0.
    pub bonds_broken_by_damage: usize,
    /// Mean wall-clock milliseconds per step.
    pub millis_per_step: f64,
    /// Bodies removed because they diverged.
    pub diverged: usize,
    /// Hash of the final state (hex).
    pub digest: String,
    /// The animated glTF written by `--export`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub export: Option<ExportSummary>,
    /// The statistics written by `--record`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub record: Option<RecordSummary>,
}

/// The validated output files.
#[derive(Debug, Clone, PartialEq)]
struct Outputs {
    export: Option<PathBuf>,
    fps: f64,
    record: Option<PathBuf>,
}

impl Outputs {
    /// Checks the output flags before any work: `--export` ends in `.glb`, `--fps` is a
    /// number ≥ 0, every output can be written, and no two of the scene and the outputs
    /// are the same file.
    fn from_args(args: &SimulateArgs) -> anyhow::Result<Self> {
        let fps = args.fps.unwrap_or(DEFAULT_FPS);
        if !(fps.is_finite() && fps >= 0.0) {
            anyhow::bail!("--fps must be a non-negative number, got {fps}");
        }
        if let Some(path) = &args.export {
            let glb = path
                .extension()
                .and_then(|e| e.to_str())
                .is_some_and(|e| e.eq_ignore_ascii_case("glb"));
            if !glb {
                anyhow::bail!(
                    "{}: unknown export format; --export writes binary glTF, use a .glb file \
                     name",
                    path.display()
                );
            }
        }
        let named = [("--export", &args.export), ("--record", &args.record)];
        for (flag, path) in named {
            let Some(path) = path else { continue };
            if same_file(path, &args.scene) {
                anyhow::bail!("{}: {flag} would overwrite the scene file", path.display());
            }
            check_writable(path).map_err(|e| anyhow::anyhow!("{e}"))?;
        }
        if let (Some(a), Some(b)) = (&args.export, &args.record)
            && same_file(a, b)
        {
            anyhow::bail!("{}: --export and --record name the same file", a.display());
        }
        Ok(Self {
            export: args.export.clone(),
            fps,
            record: args.record.clone(),
        })
    }
}

/// Whether two paths name the same file (compared through their canonical parent
/// folders, so the files need not exist).
fn same_file(a: &Path, b: &Path) -> bool {
    fn canonical(p: &Path) -> Option<PathBuf> {
        if let Ok(c) = p.canonicalize() {
            return Some(c);
        }
        let parent = match p.parent() {
            Some(d) if !d.as_os_str().is_empty() => d,
            _ => Path::new("."),
        };
        Some(parent.canonicalize().ok()?.join(p.file_name()?))
    }
    a == b || matches!((canonical(a), canonical(b)), (Some(x), Some(y)) if x == y)
}

/// Runs `shatter simulate`. Every error is the scene's or a flag's fault (bad input,
/// exit code 2); output paths are checked before the scene is even loaded, and the
/// scene's estimate before anything is built. Ctrl-C stops it between two steps
/// (exit code 130) without writing any output.
pub fn run(args: &SimulateArgs, ctx: &Context) -> Result<SimulateReport, CliError> {
    let outputs = Outputs::from_args(args).map_err(CliError::Input)?;
    if let Some(t) = args.seconds
        && !(t.is_finite() && t >= 0.0)
    {
        return Err(CliError::input(format!(
            "--seconds must be a non-negative number, got {t}"
        )));
    }
    let scene_name = args.scene.display().to_string();
    let scene =
        Scene::load(&args.scene).map_err(|e| CliError::input(format!("{scene_name}: {e}")))?;
    let steps = scene.steps(args.steps, args.seconds);
    let estimate = scene
        .check_budget(steps, &ctx.limits)
        .map_err(|e| ctx.refusal(&format!("{scene_name}: {e}")))?;
    ctx.progress.check()?;
    let mut world = scene
        .build(args.bonds)
        .map_err(|e| CliError::input(format!("{scene_name}: {e}")))?;
    ctx.progress.check()?;
    world.start();
    let mut run_export = outputs
        .export
        .as_ref()
        .map(|_| RunExport::new(&world, outputs.fps))
        .transpose()
        .map_err(CliError::Input)?;
    let mut stats_log = outputs.record.as_ref().map(|_| RunRecorder::new());
    let mut total_ms = 0.0;
    let bar = ctx.follow("simulating", &estimate.run, args.json);
    world.run_steps(steps, &ctx.progress, |world, done| {
        let stats = world.stats();
        total_ms += stats.last_step_ms;
        if let Some(log) = &mut stats_log {
            log.record_stats(StepStats {
                step: stats.steps,
                time: stats.time,
                bodies: stats.bodies,
                fragments: stats.fragments,
                bonds_total: stats.bonds_total,
                bonds_broken: stats.bonds_broken,
                diverged: stats.diverged,
                debris_removed: stats.debris_removed,
                millis: stats.last_step_ms,
            });
        }
        if let Some(export) = &mut run_export {
            export
                .observe(world, done == steps)
                .map_err(CliError::Input)?;
        }
        Ok::<(), CliError>(())
    })?;
    drop(bar);
    let stats = world.stats();
    let mut report = SimulateReport {
        steps: stats.steps,
        bodies: stats.bodies,
        fragments: stats.fragments,
        bonds_total: stats.bonds_total,
        bonds_broken: stats.bonds_broken,
        bonds_broken_by_impact: stats.bonds_broken_by_impact,
        bonds_broken_by_stress: stats.bonds_broken_by_stress,
        bonds_broken_by_damage: stats.bonds_broken_by_damage,
        millis_per_step: if steps > 0 {
            total_ms / steps as f64
        } else {
            0.0
        },
        diverged: stats.diverged,
        digest: format!("{:016x}", world.digest()),
        export: None,
        record: None,
    };
    if let (Some(export), Some(path)) = (run_export, &outputs.export) {
        report.export = Some(output::via_temp_path(path, &ctx.progress, |temp| {
            export.write(temp, path).map_err(CliError::Input)
        })?);
    }
    if let (Some(log), Some(path)) = (stats_log, &outputs.record) {
        output::via_temp_path(path, &ctx.progress, |temp| {
            log.write_csv(temp)
                .with_context(|| format!("cannot write --record {}", path.display()))
                .map_err(CliError::Input)
        })?;
        report.record = Some(RecordSummary {
            path: path.clone(),
            rows: log.stats().len(),
        });
    }
    if args.json {
        let json = serde_json::to_string(&report).internal_err("cannot encode the report")?;
        println!("{json}");
    } else {
        println!(
            "steps {}  bodies {}  fragments {}  bonds {}/{} broken ({} impact, {} stress, {} damage)  {:.3} ms/step  diverged {}  digest {}",
            report.steps,
            report.bodies,
            report.fragments,
            report.bonds_broken,
            report.bonds_total,
            report.bonds_broken_by_impact,
            report.bonds_broken_by_stress,
            report.bonds_broken_by_damage,
            report.millis_per_step,
            report.diverged,
            report.digest
        );
        if let Some(e) = &report.export {
            let plural =
                |n: usize, word: &str| format!("{n} {word}{}", if n == 1 { "" } else { "s" });
            println!(
                "wrote {} ({}: {}, {}; {})",
                e.path.display(),
                plural(e.nodes, "node"),
                plural(e.fragment_nodes, "fragment"),
                plural(e.projectile_nodes, "projectile"),
                plural(e.keyframes, "keyframe")
            );
        }
        if let Some(r) = &report.record {
            println!("wrote {} ({} steps)", r.path.display(), r.rows);
        }
    }
    Ok(report)
}

/// The animated export of a run: a node per fragment of every object (registered at
/// the start) and per projectile (registered at the first keyframe it is in flight).
struct RunExport {
    recorder: RunRecorder,
    /// Per object: its id and the node of each fragment, in fragment order.
    objects: Vec<(ObjectId, Vec<usize>)>,
    /// Per projectile seen in flight, by firing order ([`shatter_sim::ProjectileView::index`]): its
    /// node.
    projectiles: BTreeMap<usize, usize>,
    fragment_nodes: usize,
}

impl RunExport {
    /// Registers every fragment of every object of `world` and records the initial
    /// keyframe (time 0).
    fn new(world: &World, fps: f64) -> anyhow::Result<Self> {
        let mut recorder = RunRecorder::new().with_keyframe_rate(fps);
        let mut objects = Vec::new();
        let mut fragment_nodes = 0;
        for id in world.object_ids() {
            let Some(fracture) = world.object_fracture(id) else {
                continue;
            };
            let colour = world.object_color(id).unwrap_or([0.8; 3]);
            let name = world
                .object_spec(id)
                .map(|s| s.name.trim().to_string())
                .filter(|n| !n.is_empty())
                .unwrap_or_else(|| format!("object_{}", id.0));
            let mut nodes = Vec::with_capacity(fracture.fragments.len());
            for (f, fragment) in fracture.fragments.iter().enumerate() {
                let mut mesh =
                    fragment_mesh(format!("{name}/fragment_{f}"), &fragment.mesh, colour);
                if fragment.interior.len() == fragment.mesh.triangles.len() {
                    mesh.interior = fragment.interior.clone();
                }
                let m = recorder.add_mesh(mesh);
                nodes.push(recorder.add_node(format!("{name}/fragment_{f}"), m)?);
            }
            fragment_nodes += nodes.len();
            objects.push((id, nodes));
        }
        let mut export = Self {
            recorder,
            objects,
            projectiles: BTreeMap::new(),
            fragment_nodes,
        };
        export.observe(world, false)?;
        Ok(export)
    }

    /// Records a keyframe of every fragment and projectile when the rate asks for one,
    /// or when `last` (the final state). A projectile that flies only between two
    /// keyframes gets no node.
    fn observe(&mut self, world: &World, last: bool) -> anyhow::Result<()> {
        let time = world.stats().time;
        let keyframe =
            self.recorder.wants_keyframe(time) || (last && self.recorder.can_record_at(time));
        if !keyframe {
            return Ok(());
        }
        let mut poses = self.track_projectiles(world)?;
        for (id, nodes) in &self.objects {
            for (f, pose) in world.fragment_poses(*id) {
                if let Some(&node) = nodes.get(f as usize) {
                    poses.push((node, key_pose(&pose)));
                }
            }
        }
        self.recorder
            .record_keyframe(time, poses)
            .context("recording the --export animation")
    }

    /// The poses of the projectiles in flight; one seen for the first time gets its
    /// node (named after its firing order).
    fn track_projectiles(&mut self, world: &World) -> anyhow::Result<Vec<(usize, KeyPose)>> {
        let mut poses = Vec::new();
        for view in world.projectiles() {
            let node = match self.projectiles.get(&view.index) {
                Some(&node) => node,
                None => {
                    let name = format!("projectile_{}", view.index);
                    let mesh = self
                        .recorder
                        .add_mesh(projectile_mesh(name.clone(), view.spec));
                    let node = self.recorder.add_node(name, mesh)?;
                    self.projectiles.insert(view.index, node);
                    node
                }
            };
            poses.push((node, key_pose(&view.pose)));
        }
        Ok(poses)
    }

    /// Writes the GLB file to `temp`, for `path`.
    fn write(self, temp: &Path, path: &Path) -> anyhow::Result<ExportSummary> {
        self.recorder
            .write_glb(temp)
            .with_context(|| format!("cannot write --export {}", path.display()))?;
        Ok(ExportSummary {
            path: path.to_path_buf(),
            nodes: self.recorder.node_count(),
            fragment_nodes: self.fragment_nodes,
            projectile_nodes: self.projectiles.len(),
            keyframes: self.recorder.keyframe_count(),
        })
    }
}

fn key_pose(p: &Pose) -> KeyPose {
    KeyPose::new(p.translation.to_array(), p.rotation.to_array())
}

/// A mesh for the export, in `f32`.
fn fragment_mesh(name: String, mesh: &TriMesh, colour: [f32; 3]) -> FragmentMesh {
    FragmentMesh::new(
        name,
        mesh.positions
            .iter()
            .map(|p| p.as_vec3().to_array())
            .collect(),
        mesh.triangles.clone(),
        colour,
    )
}

/// The projectile's shape as a mesh in its body's frame, sized like its collider.
fn projectile_mesh(name: String, spec: &ProjectileSpec) -> FragmentMesh {
    fragment_mesh(name, &spec.shape.mesh(spec.size), spec.color)
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;
    use shatter_geom::DVec3;
    use shatter_sim::ProjectileShape;

    fn args(dir: &Path) -> SimulateArgs {
        SimulateArgs {
            scene: dir.join("scene.toml"),
            seconds: None,
            steps: Some(1),
            bonds: None,
            json: false,
            export: Some(dir.join("run.glb")),
            fps: None,
            record: Some(dir.join("run.csv")),
        }
    }

    #[test]
    fn outputs_default_to_30_fps_and_refuse_bad_values() {
        let dir = tempfile::tempdir().unwrap();
        let ok = Outputs::from_args(&args(dir.path())).unwrap();
        assert_eq!(ok.fps, DEFAULT_FPS);
        type Change = fn(&mut SimulateArgs, &Path);
        let cases: [(Change, &str); 6] = [
            (
                |a, _| a.fps = Some(-1.0),
                "--fps must be a non-negative number",
            ),
            (
                |a, _| a.fps = Some(f64::NAN),
                "--fps must be a non-negative number",
            ),
            (
                |a, d| a.export = Some(d.join("run.gltf")),
                "use a .glb file name",
            ),
            (
                |a, d| a.export = Some(d.join("none/run.glb")),
                "does not exist",
            ),
            (
                |a, d| a.record = Some(d.join("run.glb")),
                "name the same file",
            ),
            (
                |a, d| a.record = Some(d.join("scene.toml")),
                "overwrite the scene",
            ),
        ];
        for (change, message) in cases {
            let mut a = args(dir.path());
            change(&mut a, dir.path());
            let e = Outputs::from_args(&a).unwrap_err();
            assert!(e.to_string().contains(message), "{e}");
        }
    }

    #[test]
    fn same_file_sees_through_dot_segments() {
        let dir = tempfile::tempdir().unwrap();
        let a = dir.path().join("x.csv");
        let b = dir.path().join(".").join("x.csv");
        assert!(same_file(&a, &b));
        assert!(!same_file(&a, &dir.path().join("y.csv")));
    }

    #[test]
    fn projectile_meshes_have_the_collider_size() {
        let spec = |shape| ProjectileSpec {
            shape,
            size: 0.4,
            ..ProjectileSpec::default()
        };
        let extent = |m: &FragmentMesh| {
            let mut lo = [f32::INFINITY; 3];
            let mut hi = [f32::NEG_INFINITY; 3];
            for p in &m.positions {
                for k in 0..3 {
                    lo[k] = lo[k].min(p[k]);
                    hi[k] = hi[k].max(p[k]);
                }
            }
            [0, 1, 2].map(|k| hi[k] - lo[k])
        };
        // The round shapes are polygons: their width across flats is a little smaller.
        let close = |a: [f32; 3], b: [f32; 3]| (0..3).all(|k| (a[k] - b[k]).abs() < 5e-3);
        let cube = projectile_mesh("c".into(), &spec(ProjectileShape::Cube));
        assert!(close(extent(&cube), [0.4; 3]), "{:?}", extent(&cube));
        let capsule = projectile_mesh("c".into(), &spec(ProjectileShape::Capsule));
        assert!(
            close(extent(&capsule), [0.2, 0.4, 0.2]),
            "{:?}",
            extent(&capsule)
        );
        let cylinder = projectile_mesh("c".into(), &spec(ProjectileShape::Cylinder));
        assert!(
            close(extent(&cylinder), [0.4, 0.4, 0.4]),
            "{:?}",
            extent(&cylinder)
        );
        let custom = ProjectileShape::Custom(vec![DVec3::ZERO, DVec3::new(1.0, 2.0, 0.5)]);
        let custom = projectile_mesh("c".into(), &spec(custom));
        assert!(
            close(extent(&custom), [0.4, 0.8, 0.2]),
            "{:?}",
            extent(&custom)
        );
    }
}
