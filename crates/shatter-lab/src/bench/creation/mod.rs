//! The creation benchmark: the thesis's chapter 5, reproduced.
//!
//! For each model and number of random points (0, step, 2·step, … max), the time to
//! create the breakable object with the thesis's tetra method (surface vertices + random
//! points → Delaunay → fragments → bonds), for each random point placement, over several
//! runs (each with its own seed): mean, min and max. With the simulation, the time to
//! build the object's Rapier bodies and joints (the thesis's model) is measured too, in
//! its own columns. Writes `creation.csv` (columns [`HEADER`]) and plots as PNG and SVG.

mod config;
mod output;

use std::path::PathBuf;
use std::time::Instant;

use shatter_geom::budget::{Estimate, format_count};
use shatter_geom::fracture::{Fracture, Method, Placement};
use shatter_geom::model::Model;
use shatter_geom::shapes::Shape;

pub use config::{CreationConfig, CreationOptions};
pub use output::{HEADER, plots, table, write_csv};

use crate::context::Context;
use crate::error::{LabError, ResultExt};
use crate::fracture::{FractureConfig, fracture_estimate, fracture_timed, load_source};
use crate::spread::Spread;

/// One timed creation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sample {
    /// The fracture, ms.
    pub fracture_ms: f64,
    /// Building the bodies and joints, when measured.
    pub bodies_ms: Option<f64>,
    /// Fragments made.
    pub fragments: usize,
    /// Bonds made.
    pub bonds: usize,
}

/// One row of the CSV: a model, a placement and a number of random points.
#[derive(Debug, Clone, PartialEq)]
pub struct Row {
    /// The model.
    pub model: Shape,
    /// The random points' placement.
    pub placement: Placement,
    /// Random points added to the surface vertices.
    pub random_points: usize,
    /// Timed runs.
    pub runs: usize,
    /// Mean fragments.
    pub fragments: f64,
    /// Mean bonds.
    pub bonds: f64,
    /// The fracture's time, ms.
    pub fracture: Spread,
    /// Building the bodies and joints, ms (when every run measured it).
    pub bodies: Option<Spread>,
    /// Both, ms.
    pub total: Spread,
}

impl Row {
    /// The row of some runs of a case; `None` for no runs.
    pub fn from_samples(
        model: Shape,
        placement: Placement,
        random_points: usize,
        samples: &[Sample],
    ) -> Option<Self> {
        let n = samples.len() as f64;
        let bodies = if samples.iter().all(|s| s.bodies_ms.is_some()) {
            Spread::of(samples.iter().filter_map(|s| s.bodies_ms))
        } else {
            None
        };
        Some(Self {
            model,
            placement,
            random_points,
            runs: samples.len(),
            fragments: samples.iter().map(|s| s.fragments as f64).sum::<f64>() / n,
            bonds: samples.iter().map(|s| s.bonds as f64).sum::<f64>() / n,
            fracture: Spread::of(samples.iter().map(|s| s.fracture_ms))?,
            bodies,
            total: Spread::of(
                samples
                    .iter()
                    .map(|s| s.fracture_ms + s.bodies_ms.unwrap_or(0.0)),
            )?,
        })
    }
}

/// What the benchmark measured and wrote.
#[derive(Debug, Clone, PartialEq)]
pub struct CreationResult {
    /// The validated configuration.
    pub config: CreationConfig,
    /// One row per case.
    pub rows: Vec<Row>,
    /// creation.csv.
    pub csv: PathBuf,
    /// The plots.
    pub plots: Vec<PathBuf>,
}

/// Runs every case through `create` (model, placement, random points, seed) and
/// summarises the runs; `tick` is called after each case with its description.
pub fn sweep(
    config: &CreationConfig,
    mut create: impl FnMut(Shape, Placement, usize, u64) -> Result<Sample, LabError>,
    mut tick: impl FnMut(&str),
) -> Result<Vec<Row>, LabError> {
    let mut rows = Vec::new();
    for &model in &config.models {
        for &placement in &config.placements {
            // Warm-up: page in the code and the mesh, untimed.
            create(model, placement, config.counts[0], config.seed)?;
            for &count in &config.counts {
                let samples = (0..config.runs as u64)
                    .map(|r| create(model, placement, count, config.seed.wrapping_add(r)))
                    .collect::<Result<Vec<_>, _>>()?;
                let row = Row::from_samples(model, placement, count, &samples)
                    .ok_or_else(|| LabError::internal("a case ran no run"))?;
                rows.push(row);
                tick(&format!("{model} {} {count}", Placement::name(placement)));
            }
        }
    }
    Ok(rows)
}

/// Times one creation: the fracture and, when asked, building the simulation object
/// with the thesis's bond model (a body per fragment, a fixed joint per bond).
fn create_once(
    model: &Model,
    config: &FractureConfig,
    with_bodies: bool,
) -> Result<Sample, LabError> {
    let (fracture, _warnings, fracture_ms) = fracture_timed(model, config)?;
    let (fragments, bonds) = (fracture.fragments.len(), fracture.bonds.len());
    let bodies_ms = if with_bodies {
        Some(build_bodies_ms(fracture)?)
    } else {
        None
    };
    Ok(Sample {
        fracture_ms,
        bodies_ms,
        fragments,
        bonds,
    })
}

/// Time to add the fractured object to an empty world with the joint bond model.
fn build_bodies_ms(fracture: Fracture) -> Result<f64, LabError> {
    use shatter_sim::{BondModel, ObjectSpec, World, WorldSettings};
    let mut world = World::new(WorldSettings {
        bond_model: BondModel::Joints,
        ..WorldSettings::default()
    });
    let spec = ObjectSpec::from_fracture(fracture, [0.0, 10.0, 0.0].into());
    let start = Instant::now();
    world
        .add_object(spec)
        .internal_err("building the simulation object")?;
    Ok(start.elapsed().as_secs_f64() * 1e3)
}

/// The estimate of the whole benchmark (every case, the warm-ups and every run); its
/// memory is the largest case's.
pub fn creation_estimate(config: &CreationConfig, meshes: &[(Shape, Model)]) -> Estimate {
    let mut total = Estimate::default();
    for (model, loaded) in meshes {
        let mesh = &loaded.mesh;
        for &placement in &config.placements {
            let runs = |count: usize, n: f64| {
                let (_, e) = fracture_estimate(mesh, &fracture_config(*model, placement, count, 0));
                let fragments = shatter_geom::budget::fragments_at_most(
                    (mesh.positions.len() + count) as f64
                        * shatter_geom::budget::TETRAHEDRA_PER_POINT,
                );
                let bodies = if config.with_bodies {
                    shatter_sim::scene::budget::bodies_estimate(
                        fragments,
                        shatter_sim::BondModel::Joints,
                    )
                } else {
                    Estimate::default()
                };
                let one = e + bodies;
                Estimate {
                    bytes: one.bytes,
                    seconds: one.seconds * n,
                }
            };
            let mut add = |e: Estimate| {
                total.bytes = total.bytes.max(e.bytes);
                total.seconds += e.seconds;
            };
            add(runs(config.counts[0], 1.0));
            for &count in &config.counts {
                add(runs(count, config.runs as f64));
            }
        }
    }
    total
}

/// The tetra fracture of a built-in shape with `random_vertices` random points.
fn fracture_config(
    model: Shape,
    placement: Placement,
    random_vertices: usize,
    seed: u64,
) -> FractureConfig {
    FractureConfig::shape(model, Method::tetra(random_vertices, placement), seed)
}

/// Runs the benchmark: validates the options, checks the estimate against the context's
/// limits, times every case with a progress bar, and writes creation.csv and the plots
/// into `options.out` (created if missing).
pub fn run(options: &CreationOptions, ctx: &Context) -> Result<CreationResult, LabError> {
    let config = CreationConfig::new(options)?;
    let mut meshes = Vec::new();
    for &model in &config.models {
        let (mesh, _) = load_source(&fracture_config(model, Placement::Thesis, 0, 0))?;
        meshes.push((model, mesh));
    }
    let cases = config.case_count();
    ctx.check(
        &format!(
            "{} cases of {} runs (up to --max-points {} random points)",
            format_count(cases as u64),
            config.runs,
            options.max_points
        ),
        &creation_estimate(&config, &meshes),
    )?;
    std::fs::create_dir_all(&config.out)
        .input_err(format!("cannot create '{}'", config.out.display()))?;

    let bar = ctx.bar(cases as u64, false);
    let rows = sweep(
        &config,
        |model, placement, count, seed| {
            ctx.progress.check()?;
            let mesh = meshes
                .iter()
                .find(|(m, _)| *m == model)
                .map(|(_, mesh)| mesh)
                .ok_or_else(|| LabError::internal(format!("model {model} was not loaded")))?;
            create_once(
                mesh,
                &fracture_config(model, placement, count, seed),
                config.with_bodies,
            )
        },
        |case| bar.tick(case),
    )?;
    drop(bar);
    let csv = write_csv(&config, &rows, &ctx.progress)?;
    let plots = plots(&config, &rows, &ctx.progress)?;
    Ok(CreationResult {
        config,
        rows,
        csv,
        plots,
    })
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;
    use config::tests::options;
    use shatter_geom::progress::Progress;

    #[test]
    fn the_sweep_runs_every_case_runs_times_and_summarises_it() {
        let config = CreationConfig::new(&options()).unwrap();
        let mut calls = Vec::new();
        let mut ticks = 0;
        let rows = sweep(
            &config,
            |m, p, n, seed| {
                calls.push((m, p, n, seed));
                // A time that depends on the seed, so that min < mean < max.
                Ok(Sample {
                    fracture_ms: n as f64 + seed as f64,
                    bodies_ms: Some(1.0),
                    fragments: n * 2,
                    bonds: n * 3,
                })
            },
            |_| ticks += 1,
        )
        .unwrap();
        // 2 models × 2 placements × (1 warm-up + 3 counts × 3 runs).
        assert_eq!(calls.len(), 2 * 2 * (1 + 3 * 3));
        assert_eq!(rows.len(), 2 * 2 * 3);
        assert_eq!(ticks, rows.len());
        let r = &rows[1];
        assert_eq!(
            (r.model, r.placement, r.random_points),
            (Shape::Cube, Placement::Thesis, 10)
        );
        // Seeds 7, 8, 9.
        assert_eq!(
            r.fracture,
            Spread {
                mean: 18.0,
                min: 17.0,
                max: 19.0
            }
        );
        assert_eq!(r.total.mean, 19.0);
        assert_eq!(r.fragments, 20.0);

        let t = table(&rows).unwrap();
        assert_eq!(t.header()[0], "model");
        assert_eq!(t.rows().len(), rows.len());
        assert_eq!(t.rows()[1][0].0, "cube");
        assert_eq!(t.rows()[1][2].0, "10");
        assert_eq!(t.rows()[1][6].0, "18");
    }

    #[test]
    fn a_failing_creation_stops_the_sweep_with_its_error() {
        let config = CreationConfig::new(&options()).unwrap();
        let e = sweep(
            &config,
            |_, _, n, _| {
                if n == 20 {
                    Err(LabError::input("boom at 20"))
                } else {
                    Ok(Sample {
                        fracture_ms: 1.0,
                        bodies_ms: None,
                        fragments: 1,
                        bonds: 0,
                    })
                }
            },
            |_| {},
        )
        .unwrap_err();
        assert_eq!(e.to_string(), "boom at 20");
    }

    #[test]
    fn plots_are_written_per_placement_and_per_model() {
        let dir = tempfile::tempdir().unwrap();
        let mut config = CreationConfig::new(&options()).unwrap();
        config.out = dir.path().to_path_buf();
        let rows = sweep(
            &config,
            |_, _, n, s| {
                Ok(Sample {
                    fracture_ms: n as f64 + s as f64,
                    bodies_ms: Some(0.5),
                    fragments: n,
                    bonds: n,
                })
            },
            |_| {},
        )
        .unwrap();
        let written = plots(&config, &rows, &Progress::none()).unwrap();
        // fracture + total per placement, and one per model; PNG and SVG each.
        assert_eq!(written.len(), 2 * (2 * 2 + 2));
        for name in [
            "creation_thesis.png",
            "creation_total_interior.svg",
            "creation_bird.png",
        ] {
            assert!(dir.path().join(name).is_file(), "{name} missing");
        }
        let csv = write_csv(&config, &rows, &Progress::none()).unwrap();
        let text = std::fs::read_to_string(csv).unwrap();
        assert_eq!(text.lines().next().unwrap(), HEADER.join(","));
    }

    #[test]
    fn one_creation_times_the_fracture_and_the_bodies() {
        let config = fracture_config(Shape::Cube, Placement::Interior, 5, 1);
        let (model, _) = load_source(&config).unwrap();
        let s = create_once(&model, &config, true).unwrap();
        assert!(s.fragments > 1 && s.bonds > 0, "{s:?}");
        assert!(s.bodies_ms.is_some_and(|ms| ms >= 0.0));
        assert_eq!(create_once(&model, &config, false).unwrap().bodies_ms, None);
    }
}
