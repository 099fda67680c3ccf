//! `shatter simulate SCENE.toml [--seconds T | --steps N] [--bonds joints|clusters] [--json]
//! [--export RUN.glb [--fps F]] [--record RUN.csv]`: runs a scene headless and prints its
//! statistics and the digest of the final state; optionally writes the run as an animated
//! glTF and its per-step statistics as CSV.

use std::path::{Path, PathBuf};

use clap::Args;
use shatter_lab::simulate::{self, DEFAULT_FPS, RunOutputs, SimulateReport};
use shatter_sim::BondModel;
use shatter_sim::scene::Scene;

use crate::args::check_writable;
use crate::context::Context;
use crate::error::{CliError, ResultExt};

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

impl SimulateArgs {
    /// Checks the output flags before any work: `--export` ends in `.glb`, `--fps` is a
    /// number ≥ 0, every output can be written, and no two of the scene and the outputs
    /// are the same file.
    fn outputs(&self) -> anyhow::Result<RunOutputs> {
        let args = self;
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
        Ok(RunOutputs {
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
    let outputs = args.outputs().map_err(CliError::Input)?;
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
    let report = simulate::run(&mut world, steps, &outputs, &estimate.run, ctx, args.json)?;
    if args.json {
        let json = serde_json::to_string(&report).internal_err("cannot encode the report")?;
        println!("{json}");
    } else {
        println!(
            "steps {}  bodies {}  fragments {}  bonds {}/{} broken ({} impact, {} stress, {} damage)  {} worn (lowest health {:.2})  runtime cuts {} (depth {})  {:.3} ms/step  diverged {}  digest {}",
            report.steps,
            report.bodies,
            report.fragments,
            report.bonds_broken,
            report.bonds_total,
            report.bonds_broken_by_impact,
            report.bonds_broken_by_stress,
            report.bonds_broken_by_damage,
            report.bonds_damaged,
            report.min_bond_health,
            report.runtime_fractures,
            report.max_depth,
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

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;

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
        let ok = args(dir.path()).outputs().unwrap();
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
            let e = a.outputs().unwrap_err();
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
}
