//! The creation benchmark's options, validated.

use std::path::PathBuf;

use shatter_geom::budget::format_count;
use shatter_geom::fracture::Placement;
use shatter_geom::shapes::Shape;

use crate::error::LabError;
use crate::names::parse_list;

/// The options of the creation benchmark, as given (named after `shatter bench
/// creation`'s flags).
#[derive(Debug, Clone, PartialEq)]
pub struct CreationOptions {
    /// Models, by name: cube, capsule, cylinder, sphere, torus, bird.
    pub models: Vec<String>,
    /// Random point placements, by name: thesis, interior.
    pub placements: Vec<String>,
    /// Largest number of random points.
    pub max_points: usize,
    /// Step between two numbers of random points.
    pub step: usize,
    /// Timed runs per model, placement and number of points (after one warm-up).
    pub runs: usize,
    /// Folder for creation.csv and the plots (created if missing).
    pub out: PathBuf,
    /// Seed of the first run (run r uses seed + r).
    pub seed: u64,
    /// Time the fracture only, without building the simulation bodies and joints.
    pub fracture_only: bool,
}

/// The validated configuration.
#[derive(Debug, Clone, PartialEq)]
pub struct CreationConfig {
    /// The models, in order.
    pub models: Vec<Shape>,
    /// The placements, in order.
    pub placements: Vec<Placement>,
    /// The numbers of random points: 0, step, 2·step, … up to the maximum.
    pub counts: Vec<usize>,
    /// Timed runs per case.
    pub runs: usize,
    /// The output folder.
    pub out: PathBuf,
    /// Seed of the first run.
    pub seed: u64,
    /// Whether building the simulation bodies and joints is timed too.
    pub with_bodies: bool,
}

/// The most numbers of random points one run measures.
const MAX_COUNTS: usize = 1_000_000;

impl CreationConfig {
    /// Validates the options; every error is bad input naming the flag.
    pub fn new(args: &CreationOptions) -> Result<Self, LabError> {
        if args.step == 0 {
            return Err(LabError::input("--step must be at least 1"));
        }
        if args.runs == 0 {
            return Err(LabError::input("--runs must be at least 1"));
        }
        // The list of counts is built below: refuse a list that alone would not fit.
        let cases = args.max_points / args.step + 1;
        if cases > MAX_COUNTS {
            return Err(LabError::input(format!(
                "--max-points {} --step {}: {} numbers of random points; at most {} \
                 (a larger --step makes fewer)",
                args.max_points,
                args.step,
                format_count(cases as u64),
                format_count(MAX_COUNTS as u64)
            )));
        }
        let models = parse_list(&args.models, "--models", "model", Shape::ALL, Shape::NAMES)?;
        let placements = parse_list(
            &args.placements,
            "--placements",
            "placement",
            Placement::ALL,
            Placement::NAMES,
        )?;
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

    /// Cases measured: models × placements × numbers of points.
    pub fn case_count(&self) -> usize {
        self.models.len() * self.placements.len() * self.counts.len()
    }
}

#[cfg(test)]
pub(crate) mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;

    pub(crate) fn options() -> CreationOptions {
        CreationOptions {
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
        let c = CreationConfig::new(&options()).unwrap();
        assert_eq!(c.counts, vec![0, 10, 20]);
        assert_eq!(c.models, vec![Shape::Cube, Shape::Bird]);
        assert_eq!(c.placements, vec![Placement::Thesis, Placement::Interior]);
        assert_eq!(c.case_count(), 2 * 2 * 3);
    }

    #[test]
    fn zero_step_zero_runs_and_bad_names_are_input_errors() {
        type Change = fn(&mut CreationOptions);
        let cases: [(Change, &str); 6] = [
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
            (
                |a| (a.max_points, a.step) = (10_000_000, 1),
                "10,000,001 numbers of random points; at most 1,000,000",
            ),
        ];
        for (change, message) in cases {
            let mut a = options();
            change(&mut a);
            let e = CreationConfig::new(&a).unwrap_err();
            assert!(matches!(e, LabError::Input(_)), "{e:?}");
            assert!(e.to_string().contains(message), "{e}");
        }
    }
}
