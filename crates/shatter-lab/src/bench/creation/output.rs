//! What the creation benchmark writes: `creation.csv` (its schema is [`HEADER`]) and plots
//! as PNG and SVG, one per placement (one line per model, as the thesis drew them) and one
//! per model (both placements).

use std::path::{Path, PathBuf};

use shatter_geom::fracture::Placement;
use shatter_geom::progress::Progress;
use shatter_geom::shapes::Shape;
use shatter_report::plot::{LinePlot, Series};
use shatter_report::table::{Cell, CsvTable};

use super::{CreationConfig, Row};
use crate::error::{LabError, ResultExt};
use crate::output;
use crate::spread::Spread;

/// The columns of creation.csv (the bodies' columns are empty with `fracture_only`).
pub const HEADER: [&str; 15] = [
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

/// The rows as creation.csv's table.
pub fn table(rows: &[Row]) -> Result<CsvTable, LabError> {
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

/// Writes creation.csv into the configuration's folder; returns its path.
pub fn write_csv(
    config: &CreationConfig,
    rows: &[Row],
    progress: &Progress,
) -> Result<PathBuf, LabError> {
    let csv = config.out.join("creation.csv");
    let table = table(rows)?;
    output::via_temp_path(&csv, progress, |temp| {
        table
            .write(temp)
            .input_err(format!("cannot write '{}'", csv.display()))
    })?;
    Ok(csv)
}

/// Which time a plot shows.
#[derive(Debug, Clone, Copy)]
enum Measure {
    Fracture,
    Total,
}

impl Measure {
    fn of(self, row: &Row) -> Spread {
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
) -> Result<[PathBuf; 2], LabError> {
    let plot = LinePlot::new(series, title, "random points", "time to create [ms]");
    output::write_plot(&plot, &dir.join(stem), progress)
}

/// Writes the plots into the configuration's folder; returns their paths.
pub fn plots(
    config: &CreationConfig,
    rows: &[Row],
    progress: &Progress,
) -> Result<Vec<PathBuf>, LabError> {
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
