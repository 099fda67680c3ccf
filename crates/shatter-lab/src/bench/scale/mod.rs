//! The scale benchmark (`shatter bench scale`): brick worlds of growing size (2k, 5k, 10k
//! and 20k fragments by default) for each bond model and case ([`ScaleCase`]: a wall hit
//! by shots, an explosion in a wall, a block shattering on landing, a wall blown apart),
//! run for some simulated seconds. Per run: milliseconds per step (mean and worst),
//! bodies, fragments at rest and diverged bodies; and a plot of ms/step against
//! fragments.
//!
//! At rest: the dynamic bodies Rapier put to sleep ([`ScaleRow::sleeping_bodies`], from
//! `Stats::sleeping_bodies`), and the fragments whose pose did not change at all over
//! the last step ([`ScaleRow::still_fragments`]: on sleeping bodies, and on fixed ones
//! such as an intact anchored cluster).

mod plot;
mod worlds;

use std::path::PathBuf;
use std::time::Instant;

use shatter_geom::budget::{Estimate, format_count};
use shatter_sim::scene::budget::{bodies_estimate, run_estimate};
use shatter_sim::{BondModel, Pose};

#[doc(hidden)]
pub use worlds::build as build_world;
pub use worlds::{ScaleCase, Speedups, bricks, grid_for};

use crate::bench::step::steps_of;
use crate::context::Context;
use crate::error::{LabError, ResultExt};
use crate::names::parse_list;

/// The options of the scale benchmark, as given (named after `shatter bench scale`'s
/// flags; [`run`] validates them).
#[derive(Debug, Clone, PartialEq)]
pub struct BenchScaleOptions {
    /// About how many fragments each world has (rounded to a grid of bricks).
    pub sizes: Vec<usize>,
    /// Bond models, by name: joints, clusters.
    pub models: Vec<String>,
    /// Cases, by name: shots, explosion, landing, blast.
    pub cases: Vec<String>,
    /// Simulated seconds per run.
    pub seconds: f64,
    /// Folder for the plots (created if missing).
    pub out: PathBuf,
    /// Bricks collide as cuboids instead of their hulls
    /// ([`WorldSettings::box_colliders`](shatter_sim::WorldSettings::box_colliders)).
    pub box_colliders: bool,
    /// Joints-model fragments held within three bonds skip their contacts
    /// ([`WorldSettings::skip_held_contacts`](shatter_sim::WorldSettings::skip_held_contacts)).
    pub skip_held_contacts: bool,
    /// Enclosed bricks of cluster objects have colliders from the start
    /// ([`WorldSettings::enclosed_colliders`](shatter_sim::WorldSettings::enclosed_colliders)).
    pub enclosed_colliders: bool,
    /// Turn off the contact speed cap
    /// ([`WorldSettings::contact_speed_cap`](shatter_sim::WorldSettings::contact_speed_cap)).
    pub no_contact_speed_cap: bool,
}

/// The largest world one run may ask for (the estimate refuses what the machine cannot
/// run well before this).
pub const MAX_SIZE: usize = 10_000_000;

/// One run: one case, size and bond model.
#[derive(Debug, Clone, serde::Serialize)]
pub struct ScaleRow {
    /// The case's name.
    pub case: String,
    /// The bond model's name.
    pub model: String,
    /// The size asked for (`--sizes`).
    pub requested: usize,
    /// The grid of bricks built for it.
    pub grid: [u32; 3],
    /// Fragments built.
    pub fragments: usize,
    /// Steps run.
    pub steps: u64,
    /// Milliseconds to build the world (the grid and its bodies).
    pub build_ms: f64,
    /// Mean milliseconds per step.
    pub mean_ms: f64,
    /// Worst step (ms).
    pub max_ms: f64,
    /// CPU milliseconds of the stepping thread per step, over the whole run (`None` where
    /// the thread's CPU time cannot be read): unlike the wall clock, not inflated by other
    /// processes on a busy machine (the step runs on one thread). The kernel counts it at
    /// its scheduler tick (a few ms), so it is a mean only, and rough for short runs.
    pub cpu_mean_ms: Option<f64>,
    /// Mean wall-clock milliseconds of the step's stress pass (`Stats::stress_ms`: the
    /// solves, the bonds they break and the splits that follow), over every step.
    pub stress_mean_ms: f64,
    /// Its largest.
    pub stress_max_ms: f64,
    /// Mean wall-clock milliseconds of the step's stress solves alone
    /// (`Stats::stress_solve_ms`), over every step.
    pub solve_mean_ms: f64,
    /// Its largest.
    pub solve_max_ms: f64,
    /// Mean CPU milliseconds of the stepping thread in the step's stress solves
    /// (`Stats::stress_solve_cpu_ms`), over every step (`None` where the thread's CPU time
    /// cannot be read).
    pub solve_cpu_mean_ms: Option<f64>,
    /// Its largest.
    pub solve_cpu_max_ms: Option<f64>,
    /// Rigid bodies at the end (fragments' bodies and projectiles; not the ground).
    pub bodies: usize,
    /// Dynamic bodies asleep at the end.
    pub sleeping_bodies: usize,
    /// Fragments whose pose did not change over the last step: on sleeping bodies or
    /// fixed ones.
    pub still_fragments: usize,
    /// Bodies removed because their state diverged.
    pub diverged: usize,
    /// The fastest any dynamic body moved after a step, over the whole run (m/s; linear
    /// speed, projectiles included).
    pub fastest: f32,
    /// Bodies the contact speed cap slowed over the run (`Stats::speeds_capped`).
    pub speeds_capped: usize,
    /// Bonds broken since the start.
    pub bonds_broken: usize,
}

/// What the benchmark measured.
#[derive(Debug, Clone, serde::Serialize)]
pub struct BenchScaleReport {
    /// Simulated seconds per run.
    pub seconds: f64,
    /// Steps per run.
    pub steps: u64,
    /// Whether the bricks collided as cuboids (`--box-colliders`), not as their hulls.
    pub box_colliders: bool,
    /// Whether joints-model bricks held within three bonds skipped their contacts
    /// (`--skip-held-contacts`).
    pub skip_held_contacts: bool,
    /// Whether enclosed cluster bricks had colliders from the start
    /// (`--enclosed-colliders`).
    pub enclosed_colliders: bool,
    /// Whether the contact speed cap was on (off with `--no-contact-speed-cap`).
    pub contact_speed_cap: bool,
    /// The estimate checked before the runs (s).
    pub estimated_seconds: f64,
    /// Wall-clock seconds of all runs (building included).
    pub measured_seconds: f64,
    /// One row per case, model and size, in that nesting order.
    pub rows: Vec<ScaleRow>,
    /// The plots written (PNG and SVG).
    pub plots: Vec<PathBuf>,
}

/// The validated options.
#[derive(Debug, Clone, PartialEq)]
struct ScaleConfig {
    sizes: Vec<usize>,
    models: Vec<BondModel>,
    cases: Vec<ScaleCase>,
    seconds: f64,
    steps: u64,
    box_colliders: bool,
    skip_held_contacts: bool,
    enclosed_colliders: bool,
    no_contact_speed_cap: bool,
}

impl ScaleConfig {
    fn new(o: &BenchScaleOptions) -> Result<Self, LabError> {
        if !(o.seconds.is_finite() && o.seconds > 0.0) {
            return Err(LabError::input(format!(
                "--seconds must be positive, got {}",
                o.seconds
            )));
        }
        if o.sizes.is_empty() {
            return Err(LabError::input("--sizes: give at least one size"));
        }
        for (i, &n) in o.sizes.iter().enumerate() {
            if !(1..=MAX_SIZE).contains(&n) {
                return Err(LabError::input(format!(
                    "--sizes: {n} is not in 1..={}",
                    format_count(MAX_SIZE as u64)
                )));
            }
            if o.sizes[..i].contains(&n) {
                return Err(LabError::input(format!("--sizes: {n} is repeated")));
            }
        }
        let models = parse_list(
            &o.models,
            "--models",
            "bond model",
            BondModel::ALL,
            BondModel::NAMES,
        )?;
        let cases = parse_list(
            &o.cases,
            "--cases",
            "case",
            ScaleCase::ALL,
            ScaleCase::NAMES,
        )?;
        Ok(Self {
            sizes: o.sizes.clone(),
            models,
            cases,
            seconds: o.seconds,
            steps: steps_of(o.seconds),
            box_colliders: o.box_colliders,
            skip_held_contacts: o.skip_held_contacts,
            enclosed_colliders: o.enclosed_colliders,
            no_contact_speed_cap: o.no_contact_speed_cap,
        })
    }

    /// The world settings the options change (`--box-colliders`, `--skip-held-contacts`,
    /// `--enclosed-colliders`, `--no-contact-speed-cap`).
    fn settings(&self) -> worlds::Speedups {
        worlds::Speedups {
            box_colliders: self.box_colliders,
            skip_held_contacts: self.skip_held_contacts,
            enclosed_colliders: self.enclosed_colliders,
            no_contact_speed_cap: self.no_contact_speed_cap,
        }
    }

    /// Every run, in the report's order.
    fn runs(&self) -> impl Iterator<Item = (ScaleCase, BondModel, usize)> + '_ {
        self.cases.iter().flat_map(move |&c| {
            self.models
                .iter()
                .flat_map(move |&m| self.sizes.iter().map(move |&n| (c, m, n)))
        })
    }

    /// The estimate of one run (building and stepping its world).
    fn run_estimate(&self, case: ScaleCase, model: BondModel, n: usize) -> Estimate {
        let fragments = bricks(grid_for(case, n)) as f64;
        bodies_estimate(fragments, model) + run_estimate(fragments, model, self.steps)
    }

    /// All runs: the largest world's memory (one world at a time), every run's time; and
    /// the joints model's share of the time.
    fn estimate(&self) -> (Estimate, f64) {
        let mut total = Estimate::default();
        let mut joints = 0.0;
        for (case, model, n) in self.runs() {
            let e = self.run_estimate(case, model, n);
            total.bytes = total.bytes.max(e.bytes);
            total.seconds += e.seconds;
            if model == BondModel::Joints {
                joints += e.seconds;
            }
        }
        (total.with_process(), joints)
    }

    /// The request in words, for the refusal.
    fn describe(&self, joints_seconds: f64) -> String {
        let runs = self.runs().count();
        let largest = self.sizes.iter().max().copied().unwrap_or(0);
        let mut what = format!(
            "{runs} runs of {} steps (up to {} fragments)",
            format_count(self.steps),
            format_count(largest as u64)
        );
        if self.models.contains(&BondModel::Joints) {
            what.push_str(&format!(
                ", the joints model about {:.0} s of it (--models clusters leaves it out)",
                joints_seconds
            ));
        }
        what
    }
}

/// CPU time of the calling thread in nanoseconds (`CLOCK_THREAD_CPUTIME_ID`), `None`
/// where it cannot be read.
#[cfg(unix)]
pub fn thread_cpu_ns() -> Option<u64> {
    use rustix::time::{ClockId, clock_gettime};
    let t = clock_gettime(ClockId::ThreadCPUTime);
    u64::try_from(t.tv_sec)
        .ok()?
        .checked_mul(1_000_000_000)?
        .checked_add(u64::try_from(t.tv_nsec).ok()?)
}

/// CPU time of the calling thread: not read on this platform.
#[cfg(not(unix))]
pub fn thread_cpu_ns() -> Option<u64> {
    None
}

/// Fragments with a body in both lists whose pose is the same in both.
fn unchanged(before: &[(u32, Pose)], after: &[(u32, Pose)]) -> usize {
    let mut i = 0;
    let mut count = 0;
    for (f, pose) in after {
        while i < before.len() && before[i].0 < *f {
            i += 1;
        }
        if let Some((g, old)) = before.get(i)
            && g == f
            && old.translation == pose.translation
            && old.rotation == pose.rotation
        {
            count += 1;
        }
    }
    count
}

/// Builds and runs one world.
fn measure(
    config: &ScaleConfig,
    case: ScaleCase,
    model: BondModel,
    n: usize,
    ctx: &Context,
) -> Result<ScaleRow, LabError> {
    ctx.progress.check()?;
    let t0 = Instant::now();
    let (mut world, id) = worlds::build(case, n, model, config.seconds, config.settings())?;
    let build_ms = t0.elapsed().as_secs_f64() * 1e3;
    world.start();
    let steps = config.steps;
    let (mut total, mut max) = (0.0f64, 0.0f64);
    let (mut stress_total, mut stress_max) = (0.0f64, 0.0f64);
    let (mut solve_total, mut solve_max) = (0.0f64, 0.0f64);
    let (mut solve_cpu_total, mut solve_cpu_max) = (0.0f64, 0.0f64);
    let mut solve_cpu_read = true;
    world.set_cpu_clock(Some(thread_cpu_ns));
    let mut before = if steps == 1 {
        world.fragment_poses(id)
    } else {
        Vec::new()
    };
    let mut fastest = 0.0f32;
    let cpu_start = thread_cpu_ns();
    world.run_steps(steps, &ctx.progress, |world, done| {
        fastest = fastest.max(world.fastest_speed());
        let ms = world.stats().last_step_ms;
        total += ms;
        max = max.max(ms);
        let stress = world.stats().stress_ms;
        stress_total += stress;
        stress_max = stress_max.max(stress);
        let solve = world.stats().stress_solve_ms;
        solve_total += solve;
        solve_max = solve_max.max(solve);
        match world.stats().stress_solve_cpu_ms {
            Some(cpu) => {
                solve_cpu_total += cpu;
                solve_cpu_max = solve_cpu_max.max(cpu);
            }
            None => solve_cpu_read = false,
        }
        if done + 1 == steps {
            before = world.fragment_poses(id);
        }
        Ok::<(), LabError>(())
    })?;
    let cpu_mean_ms = cpu_start
        .zip(thread_cpu_ns())
        .map(|(a, b)| b.saturating_sub(a) as f64 / 1e6 / steps as f64);
    let stats = world.stats();
    Ok(ScaleRow {
        case: case.name().to_string(),
        model: model.name().to_string(),
        requested: n,
        grid: grid_for(case, n),
        fragments: bricks(grid_for(case, n)),
        steps,
        build_ms,
        mean_ms: total / steps as f64,
        max_ms: max,
        cpu_mean_ms,
        stress_mean_ms: stress_total / steps as f64,
        stress_max_ms: stress_max,
        solve_mean_ms: solve_total / steps as f64,
        solve_max_ms: solve_max,
        solve_cpu_mean_ms: (solve_cpu_read && thread_cpu_ns().is_some())
            .then(|| solve_cpu_total / steps as f64),
        solve_cpu_max_ms: (solve_cpu_read && thread_cpu_ns().is_some()).then_some(solve_cpu_max),
        bodies: stats.bodies,
        sleeping_bodies: stats.sleeping_bodies,
        still_fragments: unchanged(&before, &world.fragment_poses(id)),
        diverged: stats.diverged,
        fastest,
        speeds_capped: stats.speeds_capped,
        bonds_broken: stats.bonds_broken,
    })
}

/// Validates the options, checks the estimate against the context's limits, runs every
/// case, model and size (a bar follows the steps unless `quiet`) and writes the plots
/// into `options.out`.
pub fn run(
    options: &BenchScaleOptions,
    ctx: &Context,
    quiet: bool,
) -> Result<BenchScaleReport, LabError> {
    let config = ScaleConfig::new(options)?;
    let (estimate, joints) = config.estimate();
    ctx.check(&config.describe(joints), &estimate)?;
    std::fs::create_dir_all(&options.out)
        .input_err(format!("cannot create '{}'", options.out.display()))?;
    let bar = ctx.follow("bench scale", &estimate, quiet);
    let t0 = Instant::now();
    let mut rows = Vec::new();
    for (case, model, n) in config.runs() {
        rows.push(measure(&config, case, model, n, ctx)?);
    }
    let measured_seconds = t0.elapsed().as_secs_f64();
    drop(bar);
    let plots = plot::write(&options.out, &rows, &config.cases, &ctx.progress)?;
    Ok(BenchScaleReport {
        seconds: config.seconds,
        steps: config.steps,
        box_colliders: config.box_colliders,
        skip_held_contacts: config.skip_held_contacts,
        enclosed_colliders: config.enclosed_colliders,
        contact_speed_cap: !config.no_contact_speed_cap,
        estimated_seconds: estimate.seconds,
        measured_seconds,
        rows,
        plots,
    })
}

#[cfg(test)]
mod tests;
