//! The runtime-fracture benchmark: how long a cut at the impact takes
//! ([`shatter_sim::runtime::cut_fragment`], the radial Voronoi cut an `on_impact` object gets
//! when it is hit), on the bird and the cube, with a given number of threads (one by
//! default: issue 16's budget is 4 ms for 50 pieces of the bird on one core). Each case is
//! also timed inside a world ([`World::cut_now`]: the cut plus the new bodies and
//! colliders).

use glam::Vec3;
use shatter_geom::DVec3;
use shatter_geom::model::Model;
use shatter_sim::runtime::{self, FractureTiming, RuntimeFracture};
use shatter_sim::{FractureParams, FractureSource, ObjectSpec, Shape, World, WorldSettings};

use crate::context::Context;
use crate::error::LabError;
use crate::spread::Spread;

/// One case: a shape and how many pieces its cut asks for.
#[derive(Debug, Clone, Copy)]
pub struct Case {
    /// Name in the report.
    pub name: &'static str,
    /// The shape cut.
    pub shape: Shape,
    /// Pieces asked for.
    pub pieces: u32,
}

/// The cases: the bird at 50 pieces (the budget's case), 20 and 100, and the cube at 50.
pub fn cases() -> Vec<Case> {
    vec![
        Case {
            name: "bird-50",
            shape: Shape::Bird,
            pieces: 50,
        },
        Case {
            name: "bird-20",
            shape: Shape::Bird,
            pieces: 20,
        },
        Case {
            name: "bird-100",
            shape: Shape::Bird,
            pieces: 100,
        },
        Case {
            name: "cube-50",
            shape: Shape::Cube,
            pieces: 50,
        },
    ]
}

/// Options of the benchmark.
#[derive(Debug, Clone, Copy)]
pub struct BenchRuntimeOptions {
    /// Timed runs per case (after one warm-up).
    pub runs: u32,
    /// Threads the cut may use (1: one core).
    pub threads: usize,
}

/// One measured case.
#[derive(Debug, Clone, serde::Serialize)]
pub struct Row {
    /// Case name.
    pub case: &'static str,
    /// Pieces asked for.
    pub pieces: u32,
    /// Fragments the cut made (small cells are merged into neighbours).
    pub fragments: usize,
    /// The cut alone (ms): mean, min, max.
    pub cut_ms: Spread,
    /// The cut in a world, with the new bodies and colliders (ms): mean, min, max.
    pub world_ms: Spread,
    /// Of `world_ms`, the part the simulation's thread pays when the cut was computed on
    /// a thread: applying it ([`shatter_sim::Stats::cut_apply_ms`]).
    pub apply_ms: Spread,
}

/// The benchmark's report.
#[derive(Debug, Clone, serde::Serialize)]
pub struct Report {
    /// Threads used.
    pub threads: usize,
    /// Runs per case.
    pub runs: u32,
    /// The budget of a 50-piece cut of the bird (ms).
    pub budget_ms: f64,
    /// One row per case.
    pub rows: Vec<Row>,
}

/// The budget of issue 16: a 50-fragment runtime fracture of the bird in 4 ms.
pub const BUDGET_MS: f64 = 4.0;

/// Where a case is hit: the shape's vertex farthest along +z (its front).
fn impact(model: &Model) -> DVec3 {
    model
        .mesh
        .positions
        .iter()
        .copied()
        .max_by(|a, b| a.z.total_cmp(&b.z).then(a.x.total_cmp(&b.x)))
        .unwrap_or(DVec3::ZERO)
}

/// An `on_impact` object of `case` in an empty world without gravity.
fn world_of(case: &Case, seed: u64) -> Result<(World, shatter_sim::ObjectId), LabError> {
    let mut world = World::new(WorldSettings {
        gravity: Vec3::ZERO,
        ground: false,
        ..WorldSettings::default()
    });
    let mut spec = ObjectSpec::from_fracture(Default::default(), Vec3::ZERO);
    spec.source = FractureSource::Shape {
        shape: case.shape,
        params: FractureParams {
            pieces: case.pieces,
            seed,
            ..FractureParams::default()
        },
    };
    spec.runtime = RuntimeFracture {
        timing: FractureTiming::OnImpact,
        ..RuntimeFracture::default()
    };
    let id = world
        .add_object(spec)
        .map_err(|e| LabError::internal(format!("{}: {e}", case.name)))?;
    Ok((world, id))
}

/// Runs every case `options.runs` times (after a warm-up) on `options.threads` threads.
pub fn run(options: BenchRuntimeOptions, ctx: &Context, quiet: bool) -> Result<Report, LabError> {
    if options.runs == 0 {
        return Err(LabError::input("--runs must be at least 1"));
    }
    if options.threads == 0 || options.threads > 1024 {
        return Err(LabError::input(format!(
            "--threads must be 1..=1024, got {}",
            options.threads
        )));
    }
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(options.threads)
        .build()
        .map_err(|e| {
            LabError::internal(format!("cannot start {} threads: {e}", options.threads))
        })?;
    let bar = ctx.bar(cases().len() as u64, quiet);
    let mut rows = Vec::new();
    for case in cases() {
        let whole = runtime::whole(&Model::from_mesh(case.shape.mesh()))
            .map_err(|e| LabError::internal(format!("{}: {e}", case.name)))?;
        let at = impact(&runtime::fragment_model(&whole, 0));
        let cut = |seed: u64| {
            runtime::cut_fragment(&whole, 0, at, case.pieces, seed)
                .map_err(|e| LabError::internal(format!("{}: {e}", case.name)))
        };
        let warm = pool.install(|| cut(0))?;
        let (mut cut_ms, mut world_ms, mut apply_ms) = (Vec::new(), Vec::new(), Vec::new());
        for i in 0..u64::from(options.runs) {
            ctx.progress.check()?;
            let t = web_time::Instant::now();
            pool.install(|| cut(i + 1))?;
            cut_ms.push(t.elapsed().as_secs_f64() * 1e3);
            let (mut world, id) = world_of(&case, i + 1)?;
            let t = web_time::Instant::now();
            pool.install(|| world.cut_now(id, 0, at.as_vec3()))
                .map_err(|e| LabError::internal(format!("{}: {e}", case.name)))?;
            world_ms.push(t.elapsed().as_secs_f64() * 1e3);
            apply_ms.push(world.stats().cut_apply_ms);
        }
        bar.tick(case.name);
        let spread = |v: Vec<f64>| Spread::of(v).ok_or_else(|| LabError::internal("no timed run"));
        rows.push(Row {
            case: case.name,
            pieces: case.pieces,
            fragments: warm.fragments.len(),
            cut_ms: spread(cut_ms)?,
            world_ms: spread(world_ms)?,
            apply_ms: spread(apply_ms)?,
        });
    }
    Ok(Report {
        threads: options.threads,
        runs: options.runs,
        budget_ms: BUDGET_MS,
        rows,
    })
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;
    use shatter_geom::budget::Limits;

    fn ctx() -> Context {
        Context::quiet(Limits {
            memory_bytes: None,
            seconds: None,
            memory_source: "test",
        })
    }

    #[test]
    fn zero_runs_and_zero_threads_are_input_errors() {
        for options in [
            BenchRuntimeOptions {
                runs: 0,
                threads: 1,
            },
            BenchRuntimeOptions {
                runs: 1,
                threads: 0,
            },
        ] {
            assert!(matches!(
                run(options, &ctx(), true),
                Err(LabError::Input(_))
            ));
        }
    }

    #[test]
    fn the_impact_is_on_the_front_of_the_shape() {
        let model = Model::from_mesh(Shape::Cube.mesh());
        assert!((impact(&model).z - 0.5).abs() < 1e-12);
    }

    #[test]
    fn a_case_in_a_world_is_one_intact_body() {
        let (world, id) = world_of(&cases()[3], 1).unwrap();
        assert_eq!(world.object_bodies(id).len(), 1);
        assert_eq!(world.stats().fragments, 1);
    }
}
