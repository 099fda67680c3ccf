//! `shatter bench creation`: the thesis's chapter 5, reproduced.
//!
//! For each model and number of random points (0, step, 2·step, … max), the time to
//! create the breakable object with the thesis's tetra method (surface vertices + random
//! points → Delaunay → fragments → bonds), for each random point placement, over several
//! runs (each with its own seed): mean, min and max. With the simulation, the time to
//! build the object's Rapier bodies and joints (the thesis's model) is measured too, in
//! its own columns. Writes `creation.csv`, and plots as PNG and SVG: one per placement
//! (one line per model, as the thesis drew them) and one per model (both placements).

use std::path::{Path, PathBuf};
use std::time::Instant;

use clap::{Args, ValueEnum};
use shatter_geom::DVec3;
use shatter_geom::budget::{Estimate, format_count};
use shatter_geom::fracture::Fracture;
use shatter_geom::progress::Progress;
use shatter_report::plot::{LinePlot, Series};
use shatter_report::table::{Cell, CsvTable};

use crate::commands::fracture::{
    FractureConfig, MeshSource, MethodConfig, fracture_estimate, fracture_timed, load_source,
};
use crate::context::Context;
use crate::error::{CliError, ResultExt};
use crate::output;
use shatter_geom::fracture::Placement;
use shatter_geom::shapes::Shape;

/// Arguments of `shatter bench creation`.
#[derive(Debug, Args)]
pub struct BenchCreationArgs {
    /// Models, comma separated: cube, capsule, cylinder, sphere, torus, bird.
    #[arg(
        long,
        value_delimiter = ',',
        default_value = "cube,capsule,cylinder,bird"
    )]
    pub models: Vec<String>,
    /// Random point placements, comma separated: thesis, interior.
    #[arg(long, value_delimiter = ',', default_value = "thesis,interior")]
    pub placements: Vec<String>,
    /// Largest number of random points.
    #[arg(long, value_name = "N", default_value_t = 500)]
    pub max_points: usize,
    /// Step between two numbers of random points.
    #[arg(long, value_name = "N", default_value_t = 10)]
    pub step: usize,
    /// Timed runs per model, placement and number of points (after one warm-up).
    #[arg(long, value_name = "R", default_value_t = 5)]
    pub runs: usize,
    /// Folder for creation.csv and the plots (created if missing).
    #[arg(long, value_name = "DIR", default_value = "bench-creation")]
    pub out: PathBuf,
    /// Seed of the first run (run r uses seed + r).
    #[arg(long, value_name = "S", default_value_t = 0)]
    pub seed: u64,
    /// Time the fracture only, without building the simulation bodies and joints.
    #[arg(long)]
    pub fracture_only: bool,
}

/// The validated configuration.
#[derive(Debug, Clone, PartialEq)]
struct CreationConfig {
    models: Vec<Shape>,
    placements: Vec<Placement>,
    counts: Vec<usize>,
    runs: usize,
    out: PathBuf,
    seed: u64,
    with_bodies: bool,
}

impl CreationConfig {
    fn from_args(args: &BenchCreationArgs) -> Result<Self, CliError> {
        if args.step == 0 {
            return Err(CliError::input("--step must be at least 1"));
        }
        if args.runs == 0 {
            return Err(CliError::input("--runs must be at least 1"));
        }
        // The list of counts is built below: refuse a list that alone would not fit.
        let cases = args.max_points / args.step + 1;
        if cases > MAX_COUNTS {
            return Err(CliError::input(format!(
                "--max-points {} --step {}: {} numbers of random points; at most {} \
                 (a larger --step makes fewer)",
                args.max_points,
                args.step,
                format_count(cases as u64),
                format_count(MAX_COUNTS as u64)
            )));
        }
        let models = parse_list(&args.models, "--models", "model")?;
        let placements = parse_list(&args.placements, "--placements", "placement")?;
        Ok(Self {
            models,
            placements,
            counts: (0..=args.max_points).step_by(args.step).collect(),
            runs: args.runs,
            out: args.out.clone(),
            seed: args.seed,
            with_bodies: !args.fracture_only,
        })
    }
}

/// The most numbers of random points one run measures.
const MAX_COUNTS: usize = 1_000_000;

/// Parses a comma-separated list of clap value names, refusing unknown and repeated
/// names and an empty list.
fn parse_list<T: ValueEnum + PartialEq>(
    names: &[String],
    flag: &str,
    what: &str,
) -> Result<Vec<T>, CliError> {
    let mut values: Vec<T> = Vec::new();
    for name in names.iter().map(|n| n.trim()).filter(|n| !n.is_empty()) {
        let Ok(value) = T::from_str(name, true) else {
            let known: Vec<String> = T::value_variants()
                .iter()
                .filter_map(|v| v.to_possible_value().map(|p| p.get_name().to_string()))
                .collect();
            return Err(CliError::input(format!(
                "{flag}: unknown {what} '{name}' (expected one of: {})",
                known.join(", ")
            )));
        };
        if values.contains(&value) {
            return Err(CliError::input(format!(
                "{flag}: {what} '{name}' is repeated"
            )));
        }
        values.push(value);
    }
    if values.is_empty() {
        return Err(CliError::input(format!("{flag}: give at least one {what}")));
    }
    Ok(values)
}

/// One timed creation.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Sample {
    fracture_ms: f64,
    /// Building the bodies and joints, when measured.
    bodies_ms: Option<f64>,
    fragments: usize,
    bonds: usize,
}

/// Mean, min and max of some times.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Summary {
    mean: f64,
    min: f64,
    max: f64,
}

impl Summary {
    /// `None` for no values.
    fn of(values: impl IntoIterator<Item = f64>) -> Option<Self> {
        let values: Vec<f64> = values.into_iter().collect();
        if values.is_empty() {
            return None;
        }
        let (min, max) = values
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &v| {
                (lo.min(v), hi.max(v))
            });
        Some(Self {
            mean: values.iter().sum::<f64>() / values.len() as f64,
            min,
            max,
        })
    }
}

/// One row of the CSV: a model, a placement and a number of random points.
#[derive(Debug, Clone, PartialEq)]
struct Row {
    model: Shape,
    placement: Placement,
    random_points: usize,
    runs: usize,
    fragments: f64,
    bonds: f64,
    fracture: Summary,
    bodies: Option<Summary>,
    total: Summary,
}

impl Row {
    fn from_samples(
        model: Shape,
        placement: Placement,
        random_points: usize,
        samples: &[Sample],
    ) -> Option<Self> {
        let n = samples.len() as f64;
        let bodies = if samples.iter().all(|s| s.bodies_ms.is_some()) {
            Summary::of(samples.iter().filter_map(|s| s.bodies_ms))
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
            fracture: Summary::of(samples.iter().map(|s| s.fracture_ms))?,
            bodies,
            total: Summary::of(
                samples
                    .iter()
                    .map(|s| s.fracture_ms + s.bodies_ms.unwrap_or(0.0)),
            )?,
        })
    }
}

/// Runs every case through `create` (model, placement, random points, seed) and
/// summarises the runs; `tick` is called after each case with its description.
fn sweep(
    config: &CreationConfig,
    mut create: impl FnMut(Shape, Placement, usize, u64) -> Result<Sample, CliError>,
    mut tick: impl FnMut(&str),
) -> Result<Vec<Row>, CliError> {
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
                    .ok_or_else(|| CliError::internal("a case ran no run"))?;
                rows.push(row);
                tick(&format!("{model} {} {count}", Placement::name(placement)));
            }
        }
    }
    Ok(rows)
}

const HEADER: [&str; 15] = [
    "model",
    "placement",
    "random_points",
    "runs",
    "fragments",
    "bonds",
    "fracture_mean_ms",
    "fracture_min_ms",
    "fracture_max_ms",
    "bodies_mean_ms",
    "bodies_min_ms",
    "bodies_max_ms",
    "total_mean_ms",
    "total_min_ms",
    "total_max_ms",
];

fn table(rows: &[Row]) -> Result<CsvTable, CliError> {
    let mut t = CsvTable::new(HEADER);
    for r in rows {
        let bodies = match r.bodies {
            Some(b) => [Cell::from(b.mean), Cell::from(b.min), Cell::from(b.max)],
            None => [Cell::from(""), Cell::from(""), Cell::from("")],
        };
        let cells = [
            Cell::from(r.model.name()),
            Cell::from(Placement::name(r.placement)),
            Cell::from(r.random_points),
            Cell::from(r.runs),
            Cell::from(r.fragments),
            Cell::from(r.bonds),
            Cell::from(r.fracture.mean),
            Cell::from(r.fracture.min),
            Cell::from(r.fracture.max),
        ]
        .into_iter()
        .chain(bodies)
        .chain([
            Cell::from(r.total.mean),
            Cell::from(r.total.min),
            Cell::from(r.total.max),
        ]);
        t.push_row(cells)
            .internal_err("building the creation table")?;
    }
    Ok(t)
}

/// Which time a plot shows.
#[derive(Debug, Clone, Copy)]
enum Measure {
    Fracture,
    Total,
}

impl Measure {
    fn of(self, row: &Row) -> Summary {
        match self {
            Self::Fracture => row.fracture,
            Self::Total => row.total,
        }
    }
}

fn series(name: &str, rows: &[&Row], measure: Measure) -> Series {
    let points = rows
        .iter()
        .map(|r| (r.random_points as f64, measure.of(r).mean))
        .collect();
    let band = rows
        .iter()
        .map(|r| {
            let s = measure.of(r);
            (r.random_points as f64, s.min, s.max)
        })
        .collect();
    Series::new(name, points).with_band(band)
}

/// Writes `stem.png` and `stem.svg` in `dir`; returns their paths.
fn write_plot(
    dir: &Path,
    stem: &str,
    series: &[Series],
    title: &str,
    progress: &Progress,
) -> Result<[PathBuf; 2], CliError> {
    let plot = LinePlot::new(series, title, "random points", "time to create [ms]");
    let png = dir.join(format!("{stem}.png"));
    let svg = dir.join(format!("{stem}.svg"));
    output::via_temp_path(&png, progress, |temp| {
        plot.write_png(temp).internal_err("writing a plot")
    })?;
    output::via_temp_path(&svg, progress, |temp| {
        plot.write_svg(temp).internal_err("writing a plot")
    })?;
    Ok([png, svg])
}

fn plots(
    config: &CreationConfig,
    rows: &[Row],
    progress: &Progress,
) -> Result<Vec<PathBuf>, CliError> {
    let mut written = Vec::new();
    let select = |m: Shape, p: Placement| -> Vec<&Row> {
        rows.iter()
            .filter(|r| r.model == m && r.placement == p)
            .collect()
    };
    let mut measures = vec![(Measure::Fracture, "creation", "fracture")];
    if config.with_bodies {
        measures.push((
            Measure::Total,
            "creation_total",
            "fracture + bodies and joints",
        ));
    }
    for &(measure, prefix, what) in &measures {
        for &p in &config.placements {
            let lines: Vec<Series> = config
                .models
                .iter()
                .map(|&m| series(m.name(), &select(m, p), measure))
                .collect();
            let title = format!(
                "Creation time ({what}), {} placement, mean of {} runs (band: min–max)",
                Placement::name(p),
                config.runs
            );
            written.extend(write_plot(
                &config.out,
                &format!("{prefix}_{}", Placement::name(p)),
                &lines,
                &title,
                progress,
            )?);
        }
    }
    for &m in &config.models {
        let lines: Vec<Series> = config
            .placements
            .iter()
            .map(|&p| series(Placement::name(p), &select(m, p), Measure::Fracture))
            .collect();
        let title = format!(
            "Creation time of the {m} (fracture), mean of {} runs",
            config.runs
        );
        written.extend(write_plot(
            &config.out,
            &format!("creation_{m}"),
            &lines,
            &title,
            progress,
        )?);
    }
    Ok(written)
}

/// Times one creation: the fracture and, when asked, building the simulation object
/// with the thesis's bond model (a body per fragment, a fixed joint per bond).
fn create_once(
    mesh: &shatter_geom::model::Model,
    config: &FractureConfig,
    with_bodies: bool,
) -> Result<Sample, CliError> {
    let (fracture, _warnings, fracture_ms) = fracture_timed(mesh, config)?;
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
fn build_bodies_ms(fracture: Fracture) -> Result<f64, CliError> {
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
fn creation_estimate(
    config: &CreationConfig,
    meshes: &[(Shape, shatter_geom::model::Model)],
) -> Estimate {
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

/// Runs `shatter bench creation`.
pub fn run(args: &BenchCreationArgs, ctx: &Context) -> Result<(), CliError> {
    let config = CreationConfig::from_args(args)?;

    let mut meshes = Vec::new();
    for &model in &config.models {
        let fracture_config = fracture_config(model, Placement::Thesis, 0, 0);
        let (mesh, _) = load_source(&fracture_config)?;
        meshes.push((model, mesh));
    }
    let cases = config.models.len() * config.placements.len() * config.counts.len();
    ctx.check(
        &format!(
            "{} cases of {} runs (up to --max-points {} random points)",
            format_count(cases as u64),
            config.runs,
            args.max_points
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
                .ok_or_else(|| CliError::internal(format!("model {model} was not loaded")))?;
            create_once(
                mesh,
                &fracture_config(model, placement, count, seed),
                config.with_bodies,
            )
        },
        |case| bar.tick(case),
    )?;
    drop(bar);

    let csv = config.out.join("creation.csv");
    let table = table(&rows)?;
    output::via_temp_path(&csv, &ctx.progress, |temp| {
        table
            .write(temp)
            .input_err(format!("cannot write '{}'", csv.display()))
    })?;
    let written = plots(&config, &rows, &ctx.progress)?;

    print_summary(&config, &rows);
    println!("wrote {}", csv.display());
    for p in written {
        println!("wrote {}", p.display());
    }
    Ok(())
}

fn fracture_config(
    model: Shape,
    placement: Placement,
    random_vertices: usize,
    seed: u64,
) -> FractureConfig {
    FractureConfig {
        source: MeshSource::Shape(model),
        scale: DVec3::ONE,
        method: MethodConfig::Tetra {
            random_vertices,
            skip: 0,
            center: false,
            placement,
        },
        seed,
        strict: true,
    }
}

/// A short table on stdout: per model and placement, the first, middle and last case.
fn print_summary(config: &CreationConfig, rows: &[Row]) {
    println!(
        "{:<9} {:<9} {:>7} {:>10} {:>10} {:>10} {:>10}",
        "model", "placement", "points", "fragments", "mean ms", "min ms", "max ms"
    );
    let picks = [
        config.counts[0],
        config.counts[config.counts.len() / 2],
        config.counts[config.counts.len() - 1],
    ];
    for r in rows.iter().filter(|r| picks.contains(&r.random_points)) {
        println!(
            "{:<9} {:<9} {:>7} {:>10.0} {:>10.3} {:>10.3} {:>10.3}",
            r.model.name(),
            Placement::name(r.placement),
            r.random_points,
            r.fragments,
            r.fracture.mean,
            r.fracture.min,
            r.fracture.max
        );
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;

    fn args() -> BenchCreationArgs {
        BenchCreationArgs {
            models: vec!["cube".into(), "bird".into()],
            placements: vec!["thesis".into(), "interior".into()],
            max_points: 25,
            step: 10,
            runs: 3,
            out: PathBuf::from("out"),
            seed: 7,
            fracture_only: false,
        }
    }

    #[test]
    fn counts_run_from_zero_by_step_up_to_the_maximum() {
        let c = CreationConfig::from_args(&args()).unwrap();
        assert_eq!(c.counts, vec![0, 10, 20]);
        assert_eq!(c.models, vec![Shape::Cube, Shape::Bird]);
        assert_eq!(c.placements, vec![Placement::Thesis, Placement::Interior]);
    }

    #[test]
    fn zero_step_zero_runs_and_bad_names_are_input_errors() {
        type Change = fn(&mut BenchCreationArgs);
        let cases: [(Change, &str); 5] = [
            (|a| a.step = 0, "--step must be at least 1"),
            (|a| a.runs = 0, "--runs must be at least 1"),
            (
                |a| a.models = vec!["cube".into(), "teapot".into()],
                "--models: unknown model 'teapot' (expected one of: cube,",
            ),
            (
                |a| a.placements = vec!["outside".into()],
                "--placements: unknown placement 'outside'",
            ),
            (
                |a| a.models = vec!["cube".into(), "cube".into()],
                "is repeated",
            ),
        ];
        for (change, message) in cases {
            let mut a = args();
            change(&mut a);
            let e = CreationConfig::from_args(&a).unwrap_err();
            assert_eq!(e.exit_code(), 2);
            assert!(e.to_string().contains(message), "{e}");
        }
    }

    #[test]
    fn summary_is_mean_min_max() {
        let s = Summary::of([2.0, 1.0, 6.0]).unwrap();
        assert_eq!((s.mean, s.min, s.max), (3.0, 1.0, 6.0));
        assert!(Summary::of([]).is_none());
    }

    #[test]
    fn the_sweep_runs_every_case_runs_times_and_summarises_it() {
        let config = CreationConfig::from_args(&args()).unwrap();
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
            Summary {
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
        let config = CreationConfig::from_args(&args()).unwrap();
        let e = sweep(
            &config,
            |_, _, n, _| {
                if n == 20 {
                    Err(CliError::input("boom at 20"))
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
        let mut config = CreationConfig::from_args(&args()).unwrap();
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
    }
}
