//! The scale benchmark's plots: milliseconds per step against fragments, one line per
//! case and bond model; `scale_mean_ms` (the mean step), `scale_max_ms` (the worst) and
//! `scale_cpu_ms` (the stepping thread's CPU per step, where it was measured).

use std::path::{Path, PathBuf};

use shatter_geom::progress::Progress;
use shatter_report::plot::{LinePlot, Series};

use super::{ScaleCase, ScaleRow};
use crate::error::LabError;
use crate::output;

/// What a plot shows of a row (`None`: not measured; the row is left out).
type Measure = fn(&ScaleRow) -> Option<f64>;

/// The lines of one measure: per case (in `cases`' order) and bond model (in the rows'
/// order), its rows' `(fragments, measure)`.
pub fn lines(rows: &[ScaleRow], cases: &[ScaleCase], measure: Measure) -> Vec<Series> {
    let mut series = Vec::new();
    for case in cases {
        let mut models: Vec<&str> = Vec::new();
        for r in rows.iter().filter(|r| r.case == case.name()) {
            if !models.contains(&r.model.as_str()) {
                models.push(&r.model);
            }
        }
        for model in models {
            let points = rows
                .iter()
                .filter(|r| r.case == case.name() && r.model == model)
                .filter_map(|r| Some((r.fragments as f64, measure(r)?)))
                .collect::<Vec<_>>();
            if !points.is_empty() {
                series.push(Series::new(format!("{case}, {model}"), points));
            }
        }
    }
    series
}

/// Writes both plots (PNG and SVG) into `dir`; returns their paths.
pub fn write(
    dir: &Path,
    rows: &[ScaleRow],
    cases: &[ScaleCase],
    progress: &Progress,
) -> Result<Vec<PathBuf>, LabError> {
    let steps = rows.first().map_or(0, |r| r.steps);
    // (file stem, what the title says, the y axis, the measure)
    let measures: [(&str, &str, &str, Measure); 3] = [
        ("scale_mean_ms", "mean", "mean step [ms]", |r| {
            Some(r.mean_ms)
        }),
        ("scale_max_ms", "worst", "worst step [ms]", |r| {
            Some(r.max_ms)
        }),
        ("scale_cpu_ms", "mean CPU", "CPU per step [ms]", |r| {
            r.cpu_mean_ms
        }),
    ];
    let mut written = Vec::new();
    for (stem, what, y_label, measure) in measures {
        let series = lines(rows, cases, measure);
        if series.is_empty() {
            continue;
        }
        let title = format!("Step time against fragments ({what} of {steps} steps)");
        let plot = LinePlot::new(&series, &title, "fragments", y_label);
        written.extend(output::write_plot(&plot, &dir.join(stem), progress)?);
    }
    Ok(written)
}
