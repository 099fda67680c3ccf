//! What the study writes: `study.csv` (its schema is [`HEADER`]) and, per study, a plot of
//! bonds broken and one of fragments released, as PNG and SVG.

use std::path::PathBuf;

use shatter_geom::progress::Progress;
use shatter_report::plot::{LinePlot, Series};
use shatter_report::table::{Cell, CsvTable};

use super::config::{Case, Study, StudyConfig};
use crate::error::{LabError, ResultExt};
use crate::output;
use crate::spread::Spread;

/// One row of study.csv: a study, a line (bond model, or method and bond model) and a
/// parameter value, over the case's runs.
#[derive(Debug, Clone, PartialEq)]
pub struct Row {
    /// The study.
    pub study: Study,
    /// The line of the plot the row is a point of.
    pub line: String,
    /// The study's parameter.
    pub value: f64,
    /// The case (with the first run's seed).
    pub case: Case,
    /// Runs averaged.
    pub runs: usize,
    /// Fragments of the cube.
    pub fragments: Spread,
    /// Bonds of the cube.
    pub bonds_total: Spread,
    /// Bonds broken.
    pub bonds_broken: Spread,
    /// Fragments released.
    pub released: Spread,
}

/// The columns of study.csv.
pub const HEADER: [&str; 21] = [
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

/// The rows as study.csv's table.
pub fn table(rows: &[Row]) -> Result<CsvTable, LabError> {
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
) -> Result<Vec<PathBuf>, LabError> {
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
            written.extend(output::write_plot(&plot, &base, progress)?);
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

/// Writes study.csv and the plots into the configuration's folder; returns their paths,
/// the CSV first.
pub fn write_outputs(
    config: &StudyConfig,
    rows: &[Row],
    progress: &Progress,
) -> Result<Vec<PathBuf>, LabError> {
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
