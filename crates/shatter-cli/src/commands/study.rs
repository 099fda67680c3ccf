//! `shatter study`: how the parameters change what one shot does to a standard object.
//!
//! The standard object is the Unity cube (1 m, stone) resting on the ground, fractured
//! into about a hundred fragments; a steel sphere is fired at the middle of one face a
//! quarter of a second after start, and the world runs for `--seconds`. Each case is run
//! with `--runs` fracture seeds. Measured: bonds broken, and fragments released (those no
//! longer connected, through intact bonds, to the largest remaining piece).
//!
//! Four studies, each against one parameter with the others at their baseline:
//! - `break-force`: the bond break force (one line per bond model);
//! - `speed`: the projectile speed (one line per bond model);
//! - `random-vertices`: the tetra method's random points (one line per bond model);
//! - `method`: tetra, voronoi and slice against the projectile speed (one line per
//!   method and bond model).
//!
//! Writes `study.csv` (one row per study, parameter value, method and bond model) and,
//! per study, a plot of bonds broken and one of fragments released, as PNG and SVG.

use std::path::{Path, PathBuf};
use std::sync::Arc;

use clap::Args;
use shatter_geom::DVec3;
use shatter_geom::budget::{Estimate, format_count};
use shatter_geom::fracture::Fracture;
use shatter_geom::progress::Progress;
use shatter_report::plot::{LinePlot, Series};
use shatter_report::table::{Cell, CsvTable};
use shatter_sim::{
    BondModel, Material, ObjectId, ObjectSpec, ProjectileShape, ProjectileSpec, World,
    WorldSettings,
};

use crate::commands::fracture::{
    FractureConfig, MeshSource, MethodConfig, VoronoiSeeds, fracture_estimate, fracture_timed,
    load_source,
};
use crate::context::Context;
use crate::error::{CliError, ResultExt};
use crate::output;
use shatter_geom::fracture::{MethodKind, Pattern, Placement};
use shatter_geom::shapes::Shape;

/// Arguments of `shatter study`.
#[derive(Debug, Args)]
pub struct StudyArgs {
    /// Folder for study.csv and the plots (created if missing).
    #[arg(long, value_name = "DIR", default_value = "study")]
    pub out: PathBuf,
    /// Studies to run, comma separated: break-force, speed, random-vertices, method.
    #[arg(
        long,
        value_delimiter = ',',
        default_value = "break-force,speed,random-vertices,method"
    )]
    pub studies: Vec<String>,
    /// Bond models, comma separated: joints, clusters.
    #[arg(long, value_delimiter = ',', default_value = "joints,clusters")]
    pub bonds: Vec<String>,
    /// Simulated seconds per case.
    #[arg(long, value_name = "T", default_value_t = 2.0)]
    pub seconds: f64,
    /// Runs (fracture seeds) per case.
    #[arg(long, value_name = "R", default_value_t = 3)]
    pub runs: usize,
    /// Seed of the first run (run r uses seed + r).
    #[arg(long, value_name = "S", default_value_t = 1)]
    pub seed: u64,
    /// Baseline break force of a bond, in newtons.
    #[arg(long, value_name = "F", default_value_t = 20_000.0)]
    pub break_force: f64,
    /// Baseline projectile speed, in m/s.
    #[arg(long, value_name = "V", default_value_t = 30.0)]
    pub speed: f64,
    /// Baseline random vertices of the tetra method.
    #[arg(long, value_name = "N", default_value_t = 20)]
    pub random_vertices: usize,
    /// Cells of the voronoi method.
    #[arg(long, value_name = "K", default_value_t = 100)]
    pub pieces: usize,
    /// Planes of the slice method.
    #[arg(long, value_name = "K", default_value_t = 7)]
    pub planes: usize,
    /// Break forces of the break-force study.
    #[arg(
        long,
        value_delimiter = ',',
        default_value = "2500,5000,7500,10000,15000,20000,30000,40000,60000,80000"
    )]
    pub break_forces: Vec<f64>,
    /// Projectile speeds of the speed and method studies.
    #[arg(
        long,
        value_delimiter = ',',
        default_value = "0,5,10,15,20,30,40,50,60"
    )]
    pub speeds: Vec<f64>,
    /// Random vertices of the random-vertices study.
    #[arg(long, value_delimiter = ',', default_value = "0,10,20,40,60,80,100")]
    pub vertex_counts: Vec<usize>,
}

/// One of the four studies.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Study {
    BreakForce,
    Speed,
    RandomVertices,
    Method,
}

impl Study {
    const ALL: [Study; 4] = [
        Study::BreakForce,
        Study::Speed,
        Study::RandomVertices,
        Study::Method,
    ];

    fn name(self) -> &'static str {
        match self {
            Self::BreakForce => "break-force",
            Self::Speed => "speed",
            Self::RandomVertices => "random-vertices",
            Self::Method => "method",
        }
    }

    /// The parameter on the horizontal axis, with its unit.
    fn x_label(self) -> &'static str {
        match self {
            Self::BreakForce => "break force [N]",
            Self::Speed | Self::Method => "projectile speed [m/s]",
            Self::RandomVertices => "random vertices",
        }
    }
}

/// The fracture methods the method study compares.
const STUDY_METHODS: [MethodKind; 3] = [MethodKind::Tetra, MethodKind::Voronoi, MethodKind::Slice];

/// Grid cells along each axis for about `pieces` bricks (a grid case is not part of the
/// method study; this keeps every method usable in a case).
fn grid_side(pieces: usize) -> u32 {
    ((pieces as f64).cbrt().round() as u32).clamp(1, 1000)
}

/// One simulated case.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Case {
    method: MethodKind,
    bond_model: BondModel,
    break_force: f64,
    speed: f64,
    random_vertices: usize,
    pieces: usize,
    planes: usize,
    seconds: f64,
    seed: u64,
}

/// What one case did.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
struct Outcome {
    fragments: usize,
    bonds_total: usize,
    bonds_broken: usize,
    released: usize,
}

/// The validated configuration.
#[derive(Debug, Clone, PartialEq)]
struct StudyConfig {
    studies: Vec<Study>,
    bond_models: Vec<BondModel>,
    baseline: Case,
    runs: usize,
    break_forces: Vec<f64>,
    speeds: Vec<f64>,
    vertex_counts: Vec<usize>,
    out: PathBuf,
}

impl StudyConfig {
    fn from_args(a: &StudyArgs) -> Result<Self, CliError> {
        let mut studies = Vec::new();
        for name in a.studies.iter().map(|s| s.trim()).filter(|s| !s.is_empty()) {
            let study = Study::ALL
                .into_iter()
                .find(|s| s.name() == name)
                .ok_or_else(|| {
                    CliError::input(format!(
                        "--studies: unknown study '{name}' (expected break-force, speed, \
                         random-vertices or method)"
                    ))
                })?;
            if !studies.contains(&study) {
                studies.push(study);
            }
        }
        let mut bond_models = Vec::new();
        for name in a.bonds.iter().map(|s| s.trim()).filter(|s| !s.is_empty()) {
            let model: BondModel = name
                .parse()
                .map_err(|e| CliError::input(format!("--bonds: {e}")))?;
            if !bond_models.contains(&model) {
                bond_models.push(model);
            }
        }
        if studies.is_empty() || bond_models.is_empty() {
            return Err(CliError::input(
                "--studies and --bonds each need at least one value",
            ));
        }
        if !(a.seconds.is_finite() && a.seconds > 0.0) {
            return Err(CliError::input(format!(
                "--seconds must be a positive number, got {}",
                a.seconds
            )));
        }
        if a.runs == 0 {
            return Err(CliError::input("--runs must be at least 1"));
        }
        if a.pieces == 0 || a.planes == 0 {
            return Err(CliError::input("--pieces and --planes must be at least 1"));
        }
        positive("--break-force", [a.break_force], false)?;
        positive("--speed", [a.speed], true)?;
        positive("--break-forces", a.break_forces.iter().copied(), false)?;
        positive("--speeds", a.speeds.iter().copied(), true)?;
        for (flag, empty) in [
            ("--break-forces", a.break_forces.is_empty()),
            ("--speeds", a.speeds.is_empty()),
            ("--vertex-counts", a.vertex_counts.is_empty()),
        ] {
            if empty {
                return Err(CliError::input(format!("{flag} needs at least one value")));
            }
        }
        Ok(Self {
            studies,
            bond_models: bond_models.clone(),
            baseline: Case {
                method: MethodKind::Tetra,
                bond_model: bond_models[0],
                break_force: a.break_force,
                speed: a.speed,
                random_vertices: a.random_vertices,
                pieces: a.pieces,
                planes: a.planes,
                seconds: a.seconds,
                seed: a.seed,
            },
            runs: a.runs,
            break_forces: a.break_forces.clone(),
            speeds: a.speeds.clone(),
            vertex_counts: a.vertex_counts.clone(),
            out: a.out.clone(),
        })
    }

    /// Every case of `study`: (line name, x value, case without its seed).
    fn cases(&self, study: Study) -> Vec<(String, f64, Case)> {
        let mut cases = Vec::new();
        for &model in &self.bond_models {
            let base = Case {
                bond_model: model,
                ..self.baseline
            };
            let line = model.name().to_string();
            match study {
                Study::BreakForce => {
                    for &f in &self.break_forces {
                        cases.push((
                            line.clone(),
                            f,
                            Case {
                                break_force: f,
                                ..base
                            },
                        ));
                    }
                }
                Study::Speed => {
                    for &v in &self.speeds {
                        cases.push((line.clone(), v, Case { speed: v, ..base }));
                    }
                }
                Study::RandomVertices => {
                    for &n in &self.vertex_counts {
                        let case = Case {
                            random_vertices: n,
                            ..base
                        };
                        cases.push((line.clone(), n as f64, case));
                    }
                }
                Study::Method => {
                    for method in STUDY_METHODS {
                        let line = format!("{} ({})", method.name(), model.name());
                        for &v in &self.speeds {
                            let case = Case {
                                method,
                                speed: v,
                                ..base
                            };
                            cases.push((line.clone(), v, case));
                        }
                    }
                }
            }
        }
        cases
    }
}

/// Checks that every value is a finite number ≥ 0 (or > 0) that the simulation's `f32`
/// holds: break forces and speeds are `f32` in the simulation.
fn positive(
    flag: &str,
    values: impl IntoIterator<Item = f64>,
    zero_ok: bool,
) -> Result<(), CliError> {
    for v in values {
        if !v.is_finite() || v < 0.0 || (!zero_ok && v == 0.0) {
            let bound = if zero_ok { ">= 0" } else { "> 0" };
            return Err(CliError::input(format!(
                "{flag}: {v} is not a finite number {bound}"
            )));
        }
        shatter_sim::scene::values::narrow_to_f32(v)
            .map_err(|e| CliError::input(format!("{flag}: {e}")))?;
    }
    Ok(())
}

/// Mean, min and max of counts over the runs of a case.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Spread {
    mean: f64,
    min: f64,
    max: f64,
}

impl Spread {
    fn of(values: &[usize]) -> Self {
        let min = values.iter().copied().min().unwrap_or(0) as f64;
        let max = values.iter().copied().max().unwrap_or(0) as f64;
        let mean = values.iter().sum::<usize>() as f64 / values.len().max(1) as f64;
        Self { mean, min, max }
    }
}

/// One row of study.csv.
#[derive(Debug, Clone, PartialEq)]
struct Row {
    study: Study,
    line: String,
    value: f64,
    case: Case,
    runs: usize,
    fragments: Spread,
    bonds_total: Spread,
    bonds_broken: Spread,
    released: Spread,
}

/// Runs every case of every study through `simulate`; `tick` after each case.
fn sweep(
    config: &StudyConfig,
    mut simulate: impl FnMut(&Case) -> Result<Outcome, CliError>,
    mut tick: impl FnMut(&str),
) -> Result<Vec<Row>, CliError> {
    let mut rows = Vec::new();
    for &study in &config.studies {
        for (line, value, case) in config.cases(study) {
            let outcomes = (0..config.runs as u64)
                .map(|r| {
                    simulate(&Case {
                        seed: config.baseline.seed.wrapping_add(r),
                        ..case
                    })
                })
                .collect::<Result<Vec<_>, _>>()?;
            let pick =
                |f: fn(&Outcome) -> usize| Spread::of(&outcomes.iter().map(f).collect::<Vec<_>>());
            rows.push(Row {
                study,
                line: line.clone(),
                value,
                case,
                runs: outcomes.len(),
                fragments: pick(|o| o.fragments),
                bonds_total: pick(|o| o.bonds_total),
                bonds_broken: pick(|o| o.bonds_broken),
                released: pick(|o| o.released),
            });
            tick(&format!("{} {line} {value}", study.name()));
        }
    }
    Ok(rows)
}

/// Fragments not connected through intact bonds to the largest connected piece.
fn released_fragments(fragments: usize, bonds: &[(u32, u32)], broken: &[bool]) -> usize {
    let mut parent: Vec<usize> = (0..fragments).collect();
    fn find(parent: &mut [usize], mut i: usize) -> usize {
        while parent[i] != i {
            parent[i] = parent[parent[i]];
            i = parent[i];
        }
        i
    }
    for (k, &(a, b)) in bonds.iter().enumerate() {
        if broken.get(k).copied().unwrap_or(false) {
            continue;
        }
        let (a, b) = (a as usize, b as usize);
        if a >= fragments || b >= fragments {
            continue;
        }
        let (ra, rb) = (find(&mut parent, a), find(&mut parent, b));
        if ra != rb {
            parent[ra] = rb;
        }
    }
    let mut size = vec![0usize; fragments];
    for i in 0..fragments {
        let r = find(&mut parent, i);
        size[r] += 1;
    }
    fragments - size.into_iter().max().unwrap_or(0)
}

/// The fracture configuration of `case`: the standard cube cut by its method.
fn case_config(case: &Case) -> FractureConfig {
    let method = match case.method {
        MethodKind::Tetra => MethodConfig::Tetra {
            random_vertices: case.random_vertices,
            skip: 0,
            center: false,
            placement: Placement::Interior,
        },
        MethodKind::Voronoi => MethodConfig::Voronoi {
            seeds: VoronoiSeeds::Pattern {
                count: case.pieces,
                pattern: Pattern::Uniform,
            },
            impact: None,
        },
        MethodKind::Slice => MethodConfig::Slice {
            planes: case.planes,
        },
        MethodKind::Grid => MethodConfig::Grid {
            cells: [grid_side(case.pieces); 3],
        },
    };
    FractureConfig {
        source: MeshSource::Shape(Shape::Cube),
        scale: DVec3::ONE,
        method,
        seed: case.seed,
        strict: true,
    }
}

/// The standard cube fractured as `case` says (through the same code path as
/// `shatter fracture`).
fn fracture_case(case: &Case) -> Result<Fracture, CliError> {
    let config = case_config(case);
    let (model, _) = load_source(&config)?;
    let (fracture, _, _) = fracture_timed(&model, &config)?;
    Ok(fracture)
}

/// Steps of a case.
fn case_steps(case: &Case) -> u64 {
    (case.seconds / f64::from(WorldSettings::default().dt)).ceil() as u64
}

/// The estimate of the whole study (every case, every run), and of its largest case.
fn study_estimate(config: &StudyConfig) -> Result<(Estimate, Estimate), CliError> {
    let cube = library_cube()?;
    let (mut total, mut largest) = (Estimate::default(), Estimate::default());
    for &study in &config.studies {
        for (_, _, case) in config.cases(study) {
            let (_, fracture) = fracture_estimate(&cube, &case_config(&case));
            let fragments = fracture_fragments(&case);
            let one = fracture
                + shatter_sim::scene::budget::bodies_estimate(fragments, case.bond_model)
                + shatter_sim::scene::budget::run_estimate(
                    fragments,
                    case.bond_model,
                    case_steps(&case),
                );
            largest.bytes = largest.bytes.max(one.bytes);
            largest.seconds = largest.seconds.max(one.seconds);
            total.seconds += one.seconds * config.runs as f64;
        }
    }
    total.bytes = largest.bytes;
    Ok((total, largest))
}

fn library_cube() -> Result<shatter_geom::TriMesh, CliError> {
    crate::library::builtin_shape(Shape::Cube)
}

/// Fragments a case is expected to make.
fn fracture_fragments(case: &Case) -> f64 {
    use shatter_geom::budget::{TETRAHEDRA_PER_POINT, fragments_at_most, slice_pieces};
    fragments_at_most(match case.method {
        // The cube's 8 corners (24 split vertices weld to 8) and the random points.
        MethodKind::Tetra => (8 + case.random_vertices) as f64 * TETRAHEDRA_PER_POINT,
        MethodKind::Voronoi => case.pieces as f64,
        MethodKind::Slice => slice_pieces(case.planes as u64),
        MethodKind::Grid => f64::from(grid_side(case.pieces)).powi(3),
    })
}

/// Simulates one case: the standard cube (stone, resting on the ground), one shot at the
/// middle of a face, `seconds` of simulated time. Ctrl-C (`progress`) stops it between
/// two steps.
fn simulate_case(case: &Case, progress: &Progress) -> Result<Outcome, CliError> {
    progress.check()?;
    let fracture = fracture_case(case)?;
    let material = Material::preset("stone")
        .ok_or_else(|| CliError::internal("the stone material preset is missing"))?;
    let spec = ObjectSpec {
        name: "standard cube".to_string(),
        material,
        break_force: Some(case.break_force as f32),
        bond_model: Some(case.bond_model),
        ..ObjectSpec::from_fracture(fracture, [0.0, 0.5, 0.0].into())
    };
    let mut world = World::new(WorldSettings {
        bond_model: case.bond_model,
        ..WorldSettings::default()
    });
    let id: ObjectId = world
        .add_object(spec)
        .internal_err(format!("building the standard cube ({case:?})"))?;
    if case.speed > 0.0 {
        world.schedule_projectile(
            SHOT_AT,
            ProjectileSpec {
                shape: ProjectileShape::Sphere,
                size: 0.2,
                density: 7800.0,
                speed: case.speed as f32,
                last: None,
                from: [0.0, 0.5, 3.0].into(),
                to: [0.0, 0.5, 0.0].into(),
                ..ProjectileSpec::default()
            },
        );
    }
    world.start();
    world.run_steps(case_steps(case), progress, |_, _| Ok::<(), CliError>(()))?;
    let fracture: Arc<Fracture> = world
        .object_fracture(id)
        .ok_or_else(|| CliError::internal("the standard cube vanished"))?;
    let broken = world.bond_states(id).unwrap_or_default();
    let bonds: Vec<(u32, u32)> = fracture.bonds.iter().map(|b| (b.a, b.b)).collect();
    Ok(Outcome {
        fragments: fracture.fragments.len(),
        bonds_total: bonds.len(),
        bonds_broken: broken.iter().filter(|&&b| b).count(),
        released: released_fragments(fracture.fragments.len(), &bonds, &broken),
    })
}

/// When the shot is fired, in seconds after start (the cube has settled by then).
const SHOT_AT: f64 = 0.25;

const HEADER: [&str; 21] = [
    "study",
    "line",
    "value",
    "method",
    "bond_model",
    "break_force_n",
    "speed_m_s",
    "random_vertices",
    "pieces",
    "planes",
    "seconds",
    "runs",
    "fragments",
    "bonds_total",
    "bonds_broken_mean",
    "bonds_broken_min",
    "bonds_broken_max",
    "released_mean",
    "released_min",
    "released_max",
    "bonds_broken_fraction",
];

fn table(rows: &[Row]) -> Result<CsvTable, CliError> {
    let mut t = CsvTable::new(HEADER);
    for r in rows {
        let c = &r.case;
        let fraction = if r.bonds_total.mean > 0.0 {
            r.bonds_broken.mean / r.bonds_total.mean
        } else {
            0.0
        };
        t.push_row([
            Cell::from(r.study.name()),
            Cell::from(&r.line),
            Cell::from(r.value),
            Cell::from(c.method.name()),
            Cell::from(c.bond_model.name()),
            Cell::from(c.break_force),
            Cell::from(c.speed),
            Cell::from(c.random_vertices),
            Cell::from(c.pieces),
            Cell::from(c.planes),
            Cell::from(c.seconds),
            Cell::from(r.runs),
            Cell::from(r.fragments.mean),
            Cell::from(r.bonds_total.mean),
            Cell::from(r.bonds_broken.mean),
            Cell::from(r.bonds_broken.min),
            Cell::from(r.bonds_broken.max),
            Cell::from(r.released.mean),
            Cell::from(r.released.min),
            Cell::from(r.released.max),
            Cell::from(fraction),
        ])
        .internal_err("building the study table")?;
    }
    Ok(t)
}

/// Reads one measured quantity off a row.
type Metric = fn(&Row) -> Spread;

/// Per study: a plot of bonds broken and one of fragments released (PNG and SVG).
fn plots(
    config: &StudyConfig,
    rows: &[Row],
    progress: &Progress,
) -> Result<Vec<PathBuf>, CliError> {
    let mut written = Vec::new();
    for &study in &config.studies {
        let study_rows: Vec<&Row> = rows.iter().filter(|r| r.study == study).collect();
        let mut lines: Vec<String> = Vec::new();
        for r in &study_rows {
            if !lines.contains(&r.line) {
                lines.push(r.line.clone());
            }
        }
        let metrics: [(&str, &str, Metric); 2] = [
            ("bonds", "bonds broken", |r| r.bonds_broken),
            ("released", "fragments released", |r| r.released),
        ];
        for (stem, label, metric) in metrics {
            let series: Vec<Series> = lines
                .iter()
                .map(|line| {
                    let of_line: Vec<&&Row> =
                        study_rows.iter().filter(|r| &r.line == line).collect();
                    let points = of_line.iter().map(|r| (r.value, metric(r).mean)).collect();
                    let band = of_line
                        .iter()
                        .map(|r| (r.value, metric(r).min, metric(r).max))
                        .collect();
                    Series::new(line.as_str(), points).with_band(band)
                })
                .collect();
            let title = format!(
                "{} against {} (mean of {} seeds, band: min–max)",
                capitalised(label),
                study.x_label(),
                config.runs
            );
            let plot = LinePlot::new(&series, &title, study.x_label(), label);
            let base = config
                .out
                .join(format!("study_{}_{stem}", study.name().replace('-', "_")));
            for (path, svg) in [
                (base.with_extension("png"), false),
                (base.with_extension("svg"), true),
            ] {
                output::via_temp_path(&path, progress, |temp| {
                    if svg {
                        plot.write_svg(temp)
                    } else {
                        plot.write_png(temp)
                    }
                    .internal_err("writing a study plot")
                })?;
                written.push(path);
            }
        }
    }
    Ok(written)
}

fn capitalised(s: &str) -> String {
    let mut chars = s.chars();
    chars
        .next()
        .map(|c| c.to_uppercase().chain(chars).collect())
        .unwrap_or_default()
}

fn write_outputs(
    config: &StudyConfig,
    rows: &[Row],
    progress: &Progress,
) -> Result<Vec<PathBuf>, CliError> {
    let csv: PathBuf = config.out.join("study.csv");
    let table = table(rows)?;
    output::via_temp_path(&csv, progress, |temp| {
        table
            .write(temp)
            .input_err(format!("cannot write '{}'", csv.display()))
    })?;
    let mut written = vec![csv];
    written.extend(plots(config, rows, progress)?);
    Ok(written)
}

/// Runs `shatter study`.
pub fn run(args: &StudyArgs, ctx: &Context) -> Result<(), CliError> {
    let config = StudyConfig::from_args(args)?;
    let cases: usize = config.studies.iter().map(|&s| config.cases(s).len()).sum();
    let (total, _) = study_estimate(&config)?;
    ctx.check(
        &format!(
            "{} cases of {} runs ({} simulated seconds each)",
            format_count(cases as u64),
            config.runs,
            config.baseline.seconds
        ),
        &total,
    )?;
    ensure_dir(&config.out)?;
    let bar = ctx.bar(cases as u64, false);
    let rows = sweep(
        &config,
        |case| simulate_case(case, &ctx.progress),
        |case| bar.tick(case),
    )?;
    drop(bar);
    let written = write_outputs(&config, &rows, &ctx.progress)?;
    println!(
        "{:<16} {:<20} {:>9} {:>10} {:>13} {:>9}",
        "study", "line", "value", "fragments", "bonds broken", "released"
    );
    for r in &rows {
        println!(
            "{:<16} {:<20} {:>9} {:>10.0} {:>13.1} {:>9.1}",
            r.study.name(),
            r.line,
            r.value,
            r.fragments.mean,
            r.bonds_broken.mean,
            r.released.mean
        );
    }
    for p in written {
        println!("wrote {}", p.display());
    }
    Ok(())
}

fn ensure_dir(dir: &Path) -> Result<(), CliError> {
    std::fs::create_dir_all(dir).input_err(format!("cannot create '{}'", dir.display()))
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;

    fn args() -> StudyArgs {
        StudyArgs {
            out: PathBuf::from("out"),
            studies: vec!["speed".into(), "method".into()],
            bonds: vec!["joints".into(), "clusters".into()],
            seconds: 1.0,
            runs: 2,
            seed: 5,
            break_force: 1000.0,
            speed: 20.0,
            random_vertices: 10,
            pieces: 50,
            planes: 5,
            break_forces: vec![100.0, 200.0],
            speeds: vec![0.0, 10.0, 20.0],
            vertex_counts: vec![0, 10],
        }
    }

    #[test]
    fn bad_flags_are_input_errors_naming_the_flag() {
        type Change = fn(&mut StudyArgs);
        let cases: [(Change, &str); 6] = [
            (
                |a| a.studies = vec!["colour".into()],
                "--studies: unknown study 'colour'",
            ),
            (
                |a| a.bonds = vec!["glue".into()],
                "--bonds: unknown bond model `glue` (expected one of: clusters, joints)",
            ),
            (|a| a.runs = 0, "--runs must be at least 1"),
            (|a| a.seconds = -1.0, "--seconds must be a positive number"),
            (
                |a| a.break_forces = vec![10.0, 0.0],
                "--break-forces: 0 is not",
            ),
            (|a| a.speeds = vec![f64::NAN], "--speeds: NaN is not"),
        ];
        for (change, message) in cases {
            let mut a = args();
            change(&mut a);
            let e = StudyConfig::from_args(&a).unwrap_err();
            assert_eq!(e.exit_code(), 2);
            assert!(e.to_string().contains(message), "{e}");
        }
    }

    #[test]
    fn each_study_varies_only_its_parameter() {
        let c = StudyConfig::from_args(&args()).unwrap();
        let speed = c.cases(Study::Speed);
        assert_eq!(speed.len(), 2 * 3);
        for (line, x, case) in &speed {
            assert_eq!(case.speed, *x);
            assert_eq!(case.break_force, 1000.0);
            assert_eq!(case.method, MethodKind::Tetra);
            assert_eq!(line, case.bond_model.name());
        }
        let method = c.cases(Study::Method);
        assert_eq!(method.len(), 2 * 3 * 3);
        assert!(method.iter().any(|(l, _, c)| l == "voronoi (clusters)"
            && c.method == MethodKind::Voronoi
            && c.bond_model == BondModel::Clusters));
    }

    #[test]
    fn released_counts_fragments_cut_off_from_the_largest_piece() {
        // A chain 0-1-2-3 and a lone pair 4-5.
        let bonds = [(0, 1), (1, 2), (2, 3), (4, 5)];
        assert_eq!(released_fragments(6, &bonds, &[false; 4]), 2);
        // Breaking 1-2 leaves pieces {0,1}, {2,3}, {4,5}: 4 fragments off the largest.
        assert_eq!(
            released_fragments(6, &bonds, &[false, true, false, false]),
            4
        );
        // Everything broken: 5 of 6 released.
        assert_eq!(released_fragments(6, &bonds, &[true; 4]), 5);
        assert_eq!(released_fragments(0, &[], &[]), 0);
    }

    #[test]
    fn the_sweep_averages_the_runs_and_writes_csv_and_plots() {
        let dir = tempfile::tempdir().unwrap();
        let mut a = args();
        a.out = dir.path().to_path_buf();
        let config = StudyConfig::from_args(&a).unwrap();
        let mut seeds = Vec::new();
        let rows = sweep(
            &config,
            |case| {
                seeds.push(case.seed);
                // Faster shots break more; seed 6 breaks two more than seed 5.
                let broken = case.speed as usize + 2 * (case.seed as usize - 5);
                Ok(Outcome {
                    fragments: 100,
                    bonds_total: 200,
                    bonds_broken: broken,
                    released: broken / 2,
                })
            },
            |_| {},
        )
        .unwrap();
        assert_eq!(rows.len(), 6 + 18);
        assert!(seeds.iter().all(|&s| s == 5 || s == 6));
        let r = rows
            .iter()
            .find(|r| r.study == Study::Speed && r.value == 10.0)
            .unwrap();
        assert_eq!(
            r.bonds_broken,
            Spread {
                mean: 11.0,
                min: 10.0,
                max: 12.0
            }
        );

        let written = write_outputs(&config, &rows, &Progress::none()).unwrap();
        // CSV + 2 studies × 2 metrics × 2 formats.
        assert_eq!(written.len(), 1 + 8);
        let csv = std::fs::read_to_string(dir.path().join("study.csv")).unwrap();
        assert!(csv.starts_with("study,line,value,"));
        assert_eq!(csv.lines().count(), 1 + rows.len());
        assert!(dir.path().join("study_method_released.svg").is_file());
    }
}
