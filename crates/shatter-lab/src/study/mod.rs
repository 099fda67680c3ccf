//! The thesis study: how the parameters change what one shot does to a standard object.
//!
//! The standard object is the Unity cube (1 m, stone) resting on the ground, fractured
//! into about a hundred fragments; a steel sphere is fired at the middle of one face a
//! quarter of a second after start, and the world runs for `seconds`. Each case is run
//! with `runs` fracture seeds. Measured: bonds broken, and fragments released (those no
//! longer connected, through intact bonds, to the largest remaining piece).
//!
//! Four studies ([`Study`]), each against one parameter with the others at their
//! baseline: the break force, the projectile speed, the tetra method's random vertices
//! (one line per bond model each), and the methods against the speed (one line per method
//! and bond model).
//!
//! Writes `study.csv` (one row per study, parameter value, method and bond model; columns
//! [`HEADER`]) and, per study, a plot of bonds broken and one of fragments released, as PNG
//! and SVG.

mod case;
mod config;
mod output;

use std::path::PathBuf;

use shatter_geom::budget::format_count;

pub use case::{Outcome, released_fragments, simulate_case, study_estimate};
pub use config::{Case, Study, StudyConfig, StudyOptions};
pub use output::{HEADER, Row, table, write_outputs};

use crate::context::Context;
use crate::error::{LabError, ResultExt};
use crate::spread::Spread;

/// What a study measured and wrote.
#[derive(Debug, Clone, PartialEq)]
pub struct StudyResult {
    /// One row per case, in the order they ran.
    pub rows: Vec<Row>,
    /// The files written: study.csv, then the plots.
    pub written: Vec<PathBuf>,
}

/// Runs every case of every study through `simulate`; `tick` after each case.
pub fn sweep(
    config: &StudyConfig,
    mut simulate: impl FnMut(&Case) -> Result<Outcome, LabError>,
    mut tick: impl FnMut(&str),
) -> Result<Vec<Row>, LabError> {
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
            let pick = |f: fn(&Outcome) -> usize| {
                Spread::of_counts(&outcomes.iter().map(f).collect::<Vec<_>>())
            };
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

/// Runs a study: validates the options, checks the estimate of every case against the
/// context's limits, runs every case with a progress bar, and writes study.csv and the
/// plots into `options.out` (created if missing).
pub fn run(options: &StudyOptions, ctx: &Context) -> Result<StudyResult, LabError> {
    let config = StudyConfig::new(options)?;
    let cases = config.case_count();
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
    std::fs::create_dir_all(&config.out)
        .input_err(format!("cannot create '{}'", config.out.display()))?;
    let bar = ctx.bar(cases as u64, false);
    let rows = sweep(
        &config,
        |case| simulate_case(case, &ctx.progress),
        |case| bar.tick(case),
    )?;
    drop(bar);
    let written = write_outputs(&config, &rows, &ctx.progress)?;
    Ok(StudyResult { rows, written })
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;
    use config::tests::options;
    use shatter_geom::progress::Progress;

    #[test]
    fn the_sweep_averages_the_runs_and_writes_csv_and_plots() {
        let dir = tempfile::tempdir().unwrap();
        let mut a = options();
        a.out = dir.path().to_path_buf();
        let config = StudyConfig::new(&a).unwrap();
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
        assert_eq!(csv.lines().next().unwrap(), HEADER.join(","));
        assert_eq!(csv.lines().count(), 1 + rows.len());
        assert!(dir.path().join("study_method_released.svg").is_file());
    }

    #[test]
    fn a_failing_case_stops_the_sweep_with_its_error() {
        let config = StudyConfig::new(&options()).unwrap();
        let e = sweep(&config, |_| Err(LabError::input("boom")), |_| {}).unwrap_err();
        assert_eq!(e, LabError::input("boom"));
    }
}
