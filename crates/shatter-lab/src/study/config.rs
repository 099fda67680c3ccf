//! The study's options, validated into the cases it runs.

use std::path::PathBuf;

use shatter_geom::fracture::MethodKind;
use shatter_sim::BondModel;

use crate::error::LabError;

/// One of the four studies.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Study {
    /// The bond break force (one line per bond model).
    BreakForce,
    /// The projectile speed (one line per bond model).
    Speed,
    /// The tetra method's random points (one line per bond model).
    RandomVertices,
    /// Tetra, voronoi and slice against the projectile speed (one line per method and
    /// bond model).
    Method,
}

impl Study {
    /// Every study, in the order they run.
    pub const ALL: [Study; 4] = [
        Study::BreakForce,
        Study::Speed,
        Study::RandomVertices,
        Study::Method,
    ];

    /// The study's name, as `--studies` takes it.
    pub fn name(self) -> &'static str {
        match self {
            Self::BreakForce => "break-force",
            Self::Speed => "speed",
            Self::RandomVertices => "random-vertices",
            Self::Method => "method",
        }
    }

    /// The parameter on the horizontal axis, with its unit.
    pub fn x_label(self) -> &'static str {
        match self {
            Self::BreakForce => "break force [N]",
            Self::Speed | Self::Method => "projectile speed [m/s]",
            Self::RandomVertices => "random vertices",
        }
    }
}

/// The fracture methods the method study compares.
const STUDY_METHODS: [MethodKind; 3] = [MethodKind::Tetra, MethodKind::Voronoi, MethodKind::Slice];

/// The options of a study, as given (named after `shatter study`'s flags).
#[derive(Debug, Clone, PartialEq)]
pub struct StudyOptions {
    /// Folder for study.csv and the plots (created if missing).
    pub out: PathBuf,
    /// Studies to run, by name: break-force, speed, random-vertices, method.
    pub studies: Vec<String>,
    /// Bond models, by name: joints, clusters.
    pub bonds: Vec<String>,
    /// Simulated seconds per case.
    pub seconds: f64,
    /// Runs (fracture seeds) per case.
    pub runs: usize,
    /// Seed of the first run (run r uses seed + r).
    pub seed: u64,
    /// Baseline break force of a bond, in newtons.
    pub break_force: f64,
    /// Baseline projectile speed, in m/s.
    pub speed: f64,
    /// Baseline random vertices of the tetra method.
    pub random_vertices: usize,
    /// Cells of the voronoi method.
    pub pieces: usize,
    /// Planes of the slice method.
    pub planes: usize,
    /// Break forces of the break-force study.
    pub break_forces: Vec<f64>,
    /// Projectile speeds of the speed and method studies.
    pub speeds: Vec<f64>,
    /// Random vertices of the random-vertices study.
    pub vertex_counts: Vec<usize>,
}

/// One simulated case.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Case {
    /// How the cube is fractured.
    pub method: MethodKind,
    /// How its fragments hold together.
    pub bond_model: BondModel,
    /// Break force of a bond, N.
    pub break_force: f64,
    /// Projectile speed, m/s (0: no shot).
    pub speed: f64,
    /// Random vertices of the tetra method.
    pub random_vertices: usize,
    /// Cells of the voronoi method.
    pub pieces: usize,
    /// Planes of the slice method.
    pub planes: usize,
    /// Simulated seconds.
    pub seconds: f64,
    /// Fracture seed.
    pub seed: u64,
}

/// The validated configuration.
#[derive(Debug, Clone, PartialEq)]
pub struct StudyConfig {
    /// The studies, in order, each once.
    pub studies: Vec<Study>,
    /// The bond models, in order, each once.
    pub bond_models: Vec<BondModel>,
    /// Every parameter at its baseline (the first bond model, tetra).
    pub baseline: Case,
    /// Runs per case.
    pub runs: usize,
    /// Break forces of the break-force study.
    pub break_forces: Vec<f64>,
    /// Speeds of the speed and method studies.
    pub speeds: Vec<f64>,
    /// Random vertices of the random-vertices study.
    pub vertex_counts: Vec<usize>,
    /// The output folder.
    pub out: PathBuf,
}

impl StudyConfig {
    /// Validates the options; every error is bad input naming the flag.
    pub fn new(a: &StudyOptions) -> Result<Self, LabError> {
        let mut studies = Vec::new();
        for name in a.studies.iter().map(|s| s.trim()).filter(|s| !s.is_empty()) {
            let study = Study::ALL
                .into_iter()
                .find(|s| s.name() == name)
                .ok_or_else(|| {
                    LabError::input(format!(
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
                .map_err(|e| LabError::input(format!("--bonds: {e}")))?;
            if !bond_models.contains(&model) {
                bond_models.push(model);
            }
        }
        if studies.is_empty() || bond_models.is_empty() {
            return Err(LabError::input(
                "--studies and --bonds each need at least one value",
            ));
        }
        if !(a.seconds.is_finite() && a.seconds > 0.0) {
            return Err(LabError::input(format!(
                "--seconds must be a positive number, got {}",
                a.seconds
            )));
        }
        if a.runs == 0 {
            return Err(LabError::input("--runs must be at least 1"));
        }
        if a.pieces == 0 || a.planes == 0 {
            return Err(LabError::input("--pieces and --planes must be at least 1"));
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
                return Err(LabError::input(format!("{flag} needs at least one value")));
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
    pub fn cases(&self, study: Study) -> Vec<(String, f64, Case)> {
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
                        let case = Case {
                            break_force: f,
                            ..base
                        };
                        cases.push((line.clone(), f, case));
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

    /// The number of cases of every study.
    pub fn case_count(&self) -> usize {
        self.studies.iter().map(|&s| self.cases(s).len()).sum()
    }
}

/// Checks that every value is a finite number ≥ 0 (or > 0) that the simulation's `f32`
/// holds: break forces and speeds are `f32` in the simulation.
fn positive(
    flag: &str,
    values: impl IntoIterator<Item = f64>,
    zero_ok: bool,
) -> Result<(), LabError> {
    for v in values {
        if !v.is_finite() || v < 0.0 || (!zero_ok && v == 0.0) {
            let bound = if zero_ok { ">= 0" } else { "> 0" };
            return Err(LabError::input(format!(
                "{flag}: {v} is not a finite number {bound}"
            )));
        }
        shatter_sim::scene::values::narrow_to_f32(v)
            .map_err(|e| LabError::input(format!("{flag}: {e}")))?;
    }
    Ok(())
}

#[cfg(test)]
pub(crate) mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;

    pub(crate) fn options() -> StudyOptions {
        StudyOptions {
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
    fn bad_options_are_input_errors_naming_the_flag() {
        type Change = fn(&mut StudyOptions);
        let cases: [(Change, &str); 7] = [
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
            (|a| a.speed = 1e300, "--speed: "),
        ];
        for (change, message) in cases {
            let mut a = options();
            change(&mut a);
            let e = StudyConfig::new(&a).unwrap_err();
            assert!(matches!(e, LabError::Input(_)), "{e:?}");
            assert!(e.to_string().contains(message), "{e}");
        }
    }

    #[test]
    fn each_study_varies_only_its_parameter() {
        let c = StudyConfig::new(&options()).unwrap();
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
        assert_eq!(c.case_count(), 6 + 18);
    }
}
