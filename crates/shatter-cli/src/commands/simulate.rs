//! `shatter simulate SCENE.toml [--seconds T | --steps N] [--bonds joints|clusters] [--json]`:
//! runs a scene headless and prints its statistics and the digest of the final state.

use std::path::PathBuf;

use anyhow::Context;
use clap::{Args, ValueEnum};
use shatter_sim::BondModel;
use shatter_sim::scene::Scene;

/// Bond model on the command line.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum BondsArg {
    /// One body per fragment, a breakable fixed joint per bond (the thesis).
    Joints,
    /// Connected fragments as one body, a breakable bond graph.
    Clusters,
}

impl From<BondsArg> for BondModel {
    fn from(b: BondsArg) -> BondModel {
        match b {
            BondsArg::Joints => BondModel::Joints,
            BondsArg::Clusters => BondModel::Clusters,
        }
    }
}

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
    pub bonds: Option<BondsArg>,
    /// Print one JSON object.
    #[arg(long)]
    pub json: bool,
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
    /// Broken bonds.
    pub bonds_broken: usize,
    /// Mean wall-clock milliseconds per step.
    pub millis_per_step: f64,
    /// Bodies removed because they diverged.
    pub diverged: usize,
    /// Hash of the final state (hex).
    pub digest: String,
}

/// Runs `shatter simulate`. Every error is the scene's fault (bad input, exit code 2).
pub fn run(args: &SimulateArgs) -> anyhow::Result<SimulateReport> {
    let scene = Scene::load(&args.scene).with_context(|| args.scene.display().to_string())?;
    let mut world = scene
        .build(args.bonds.map(BondModel::from))
        .with_context(|| args.scene.display().to_string())?;
    let steps = match (args.steps, args.seconds) {
        (Some(n), _) => n,
        (None, Some(t)) if t.is_finite() && t >= 0.0 => {
            (t / world.settings().dt as f64).round() as u64
        }
        (None, Some(t)) => anyhow::bail!("--seconds must be a non-negative number, got {t}"),
        (None, None) => (scene.seconds / world.settings().dt as f64).round() as u64,
    };
    world.start();
    let mut total_ms = 0.0;
    for _ in 0..steps {
        world.step();
        total_ms += world.stats().last_step_ms;
    }
    let stats = world.stats();
    let report = SimulateReport {
        steps: stats.steps,
        bodies: stats.bodies,
        fragments: stats.fragments,
        bonds_total: stats.bonds_total,
        bonds_broken: stats.bonds_broken,
        millis_per_step: if steps > 0 {
            total_ms / steps as f64
        } else {
            0.0
        },
        diverged: stats.diverged,
        digest: format!("{:016x}", world.digest()),
    };
    if args.json {
        println!("{}", serde_json::to_string(&report)?);
    } else {
        println!(
            "steps {}  bodies {}  fragments {}  bonds {}/{} broken  {:.3} ms/step  diverged {}  digest {}",
            report.steps,
            report.bodies,
            report.fragments,
            report.bonds_broken,
            report.bonds_total,
            report.millis_per_step,
            report.diverged,
            report.digest
        );
    }
    Ok(report)
}
