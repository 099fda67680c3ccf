//! What a scene will cost before it is built: the fractures of its objects (memory and
//! time, from [`shatter_geom::budget`]), the simulation's bodies, and the time of its
//! steps; checked against [`Limits`] so that a scene that cannot run on the machine
//! (`grid = [1000, 1000, 1000]`, `dt = 1e-9`, `world.seconds = 1e9`) is refused before
//! any of it is built.
//!
//! ```
//! use shatter_geom::budget::Limits;
//! use shatter_sim::scene::Scene;
//!
//! // 2^-7 s steps (exact in f32) for 1e9 s.
//! let scene = Scene::parse("[world]\ndt = 0.0078125\nseconds = 1e9\n")?;
//! let steps = scene.steps(None, None);
//! assert_eq!(steps, 128_000_000_000);
//! let limits = Limits { memory_bytes: Some(24_000_000_000), seconds: Some(3600.0), memory_source: "test" };
//! let err = scene.check_budget(steps, &limits).unwrap_err();
//! assert!(err.to_string().starts_with("128,000,000,000 steps"), "{err}");
//! # Ok::<(), shatter_sim::SimError>(())
//! ```
//!
//! # Basis of the figures
//!
//! Measured with release builds on the project's 2-core machine (CPU time, the machine
//! shared with other builds) and rounded up. `shatter simulate` of an empty scene runs
//! 10,000 steps in 10 ms; grid scenes of 20 × 20 × 20 bricks falling and breaking took
//! 115 ms of CPU a step with clusters and 470 ms with joints (14 and 59 µs per fragment
//! and step) and peaked at 197 MB and 354 MB (24 and 43 kB per brick). Intact clusters
//! are far cheaper (`shatter bench step`: 0.7 ms a step for the 2,000-brick wall), so the
//! time is an upper bound: every fragment moving on its own.

use shatter_geom::budget::{BudgetError, Estimate, Limits, format_count, fragments_at_most};

use crate::material::MethodKind;
use crate::object::{BondModel, FractureSource, ObjectSpec};
use crate::scene::Scene;

/// Bytes per simulated fragment with clusters: its body, colliders (convex pieces in
/// `f32`), contacts and bond state, and the prepared copy of its geometry.
pub const SIM_BYTES_PER_FRAGMENT: f64 = 25_000.0;
/// Bytes per simulated fragment with joints (its joints and their solver data added).
pub const SIM_BYTES_PER_FRAGMENT_JOINTS: f64 = 45_000.0;
/// Seconds to build one fragment's body and colliders.
pub const SIM_BUILD_SECONDS_PER_FRAGMENT: f64 = 2.0e-5;
/// Seconds per step and per fragment with clusters (contacts, the solver, bond loads).
pub const SIM_SECONDS_PER_FRAGMENT_STEP: f64 = 1.5e-5;
/// Seconds per step and per fragment with joints.
pub const SIM_SECONDS_PER_FRAGMENT_STEP_JOINTS: f64 = 6.0e-5;
/// Seconds per step whatever the scene holds (the pipeline's fixed cost).
pub const SIM_SECONDS_PER_STEP: f64 = 3.0e-6;
/// Roughening the cut faces costs this many times the fracture it roughens (the bird's
/// 100 Voronoi cells: 102 ms against 29 ms, `cargo bench -p shatter-geom --bench
/// fracture -- roughen`), and its finer faces this many times the fracture's memory.
pub const ROUGHEN_SECONDS_FACTOR: f64 = 3.5;
/// See [`ROUGHEN_SECONDS_FACTOR`]: rough fragments hold 2–3× the triangles.
pub const ROUGHEN_BYTES_FACTOR: f64 = 3.0;

/// A scene's estimate, part by part.
#[derive(Debug, Clone, PartialEq)]
pub struct SceneEstimate {
    /// Per object: its key (`objects[2]`), how it is cut, its fragments and its estimate
    /// (fracture and bodies).
    pub objects: Vec<ObjectEstimate>,
    /// Fragments of all objects.
    pub fragments: f64,
    /// Steps of the run.
    pub steps: u64,
    /// Running the steps.
    pub run: Estimate,
    /// Everything: building the objects (memory kept) and running.
    pub total: Estimate,
}

/// One object's share of a [`SceneEstimate`].
#[derive(Debug, Clone, PartialEq)]
pub struct ObjectEstimate {
    /// `objects[i]`.
    pub key: String,
    /// The request in words ("grid = [1000, 1000, 1000]: 1,000,000,000 bricks").
    pub what: String,
    /// Fragments expected.
    pub fragments: f64,
    /// Its bond model.
    pub bond_model: BondModel,
    /// Fracture and bodies.
    pub estimate: Estimate,
}

/// The estimate of simulating `fragments` fragments bonded by `model` for `steps`
/// steps (the fixed cost of the steps included).
pub fn run_estimate(fragments: f64, model: BondModel, steps: u64) -> Estimate {
    let per_fragment = match model {
        BondModel::Joints => SIM_SECONDS_PER_FRAGMENT_STEP_JOINTS,
        BondModel::Clusters => SIM_SECONDS_PER_FRAGMENT_STEP,
    };
    Estimate {
        bytes: 0.0,
        seconds: steps as f64 * (SIM_SECONDS_PER_STEP + fragments * per_fragment),
    }
}

/// The estimate of building (and holding) the bodies of `fragments` fragments bonded by
/// `model`.
pub fn bodies_estimate(fragments: f64, model: BondModel) -> Estimate {
    let bytes = match model {
        BondModel::Joints => SIM_BYTES_PER_FRAGMENT_JOINTS,
        BondModel::Clusters => SIM_BYTES_PER_FRAGMENT,
    };
    Estimate {
        bytes: fragments * bytes,
        seconds: fragments * SIM_BUILD_SECONDS_PER_FRAGMENT,
    }
}

/// The mesh an object is cut from: a built-in shape's own, a mesh file's once loaded (a
/// file that does not load is reported when the object is built; here there is none).
fn source_mesh(source: &FractureSource) -> Option<shatter_geom::TriMesh> {
    match source {
        FractureSource::Prebuilt(_) => None,
        FractureSource::Shape { shape, .. } => Some(shape.mesh()),
        FractureSource::MeshFile { path, .. } => shatter_geom::io::load_mesh(path).ok(),
    }
}

/// The estimate of one object: its fracture and its bodies; `world_model` is the bond
/// model of objects that do not choose one.
pub fn object_estimate(key: &str, spec: &ObjectSpec, world_model: BondModel) -> ObjectEstimate {
    let bond_model = spec.bond_model.unwrap_or(world_model);
    let params = match &spec.source {
        FractureSource::Prebuilt(f) => {
            let n = f.fragments.len() as f64;
            return ObjectEstimate {
                key: key.to_string(),
                what: format!("{key}: {} fragments", format_count(n as u64)),
                fragments: n,
                bond_model,
                estimate: bodies_estimate(n, bond_model),
            };
        }
        FractureSource::Shape { params, .. } | FractureSource::MeshFile { params, .. } => params,
    };
    let method = params.method.unwrap_or(spec.material.method);
    let mesh = source_mesh(&spec.source);
    let (vertices, triangles) = mesh.as_ref().map_or((0, 0), |m| {
        (m.positions.len() as u64, m.triangles.len() as u64)
    });
    let (what, fragments, fracture) = match method {
        MethodKind::Grid => {
            // Only a grid asks whether the mesh is a box (bricks) or not (clipped cells).
            let boxed = mesh.as_ref().is_some_and(shatter_geom::budget::is_box);
            let bricks: f64 = params.grid.iter().map(|&c| f64::from(c)).product();
            (
                format!(
                    "{key}.grid = {:?}: {} {}",
                    params.grid,
                    format_count(bricks as u64),
                    if boxed { "bricks" } else { "cells" }
                ),
                bricks,
                Estimate::grid_fracture(params.grid, triangles, boxed),
            )
        }
        MethodKind::Tetra => {
            let surface = vertices.div_ceil(u64::from(params.skip) + 1);
            let points = surface + u64::from(params.random_vertices) + u64::from(params.center);
            (
                format!(
                    "{key}.random_vertices = {}: a tetra fracture of {} points",
                    params.random_vertices,
                    format_count(points)
                ),
                fragments_at_most(points as f64 * shatter_geom::budget::TETRAHEDRA_PER_POINT),
                Estimate::tetra_fracture(points, surface),
            )
        }
        MethodKind::Voronoi => (
            format!(
                "{key}.pieces = {}: {} Voronoi cells",
                params.pieces,
                format_count(u64::from(params.pieces))
            ),
            fragments_at_most(f64::from(params.pieces)),
            Estimate::voronoi_fracture(u64::from(params.pieces), triangles),
        ),
        MethodKind::Slice => (
            format!("{key}.pieces = {}: slice planes", params.pieces),
            fragments_at_most(shatter_geom::budget::slice_pieces(u64::from(params.pieces))),
            Estimate::slice_fracture(u64::from(params.pieces), triangles),
        ),
    };
    // Precomputed voronoi, tetra and slice fractures of a rough material are roughened
    // (see `object::prepare`); grids and runtime cuts stay flat.
    let rough = method != MethodKind::Grid
        && spec.runtime.timing == crate::runtime::FractureTiming::Precomputed
        && !spec.material.roughness.is_off();
    let (what, fracture) = if rough {
        (
            format!("{what} with rough cut faces"),
            Estimate {
                bytes: fracture.bytes * ROUGHEN_BYTES_FACTOR,
                seconds: fracture.seconds * (1.0 + ROUGHEN_SECONDS_FACTOR),
            },
        )
    } else {
        (what, fracture)
    };
    ObjectEstimate {
        key: key.to_string(),
        what,
        fragments,
        bond_model,
        estimate: fracture + bodies_estimate(fragments, bond_model),
    }
}

impl Scene {
    /// The number of steps a run lasts: `steps` when given, else `seconds` (or the
    /// scene's `world.seconds`) divided by the step, rounded (saturating at `u64::MAX`).
    pub fn steps(&self, steps: Option<u64>, seconds: Option<f64>) -> u64 {
        match steps {
            Some(n) => n,
            None => {
                let t = seconds.unwrap_or(self.seconds);
                (t / f64::from(self.settings.dt)).round() as u64
            }
        }
    }

    /// The estimate of building this scene and running it for `steps` steps (the
    /// process's own memory included).
    pub fn estimate(&self, steps: u64) -> SceneEstimate {
        let world_model = self.settings.bond_model;
        let objects: Vec<ObjectEstimate> = self
            .objects
            .iter()
            .enumerate()
            .map(|(i, o)| object_estimate(&format!("objects[{i}]"), o, world_model))
            .collect();
        let fragments: f64 =
            objects.iter().map(|o| o.fragments).sum::<f64>() + self.projectiles.len() as f64;
        let run = objects.iter().fold(
            run_estimate(self.projectiles.len() as f64, BondModel::Clusters, steps),
            |sum, o| {
                let mut e = run_estimate(o.fragments, o.bond_model, steps);
                // The steps' fixed cost is counted once.
                e.seconds -= steps as f64 * SIM_SECONDS_PER_STEP;
                sum + e
            },
        );
        let total = objects
            .iter()
            .fold(run, |sum, o| sum + o.estimate)
            .with_process();
        SceneEstimate {
            objects,
            fragments,
            steps,
            run,
            total,
        }
    }

    /// Refuses the scene when an object alone, all of them, or the run does not fit
    /// `limits`; the error names the key ("objects[0].grid = [1000, 1000, 1000]:
    /// 1,000,000,000 bricks need about 5.5 TB; ..."). Nothing is built.
    pub fn check_budget(&self, steps: u64, limits: &Limits) -> Result<SceneEstimate, BudgetError> {
        let estimate = self.estimate(steps);
        let memory_only = Limits {
            seconds: None,
            ..*limits
        };
        for o in &estimate.objects {
            memory_only.check(&o.what, &o.estimate)?;
        }
        memory_only.check(
            &format!(
                "the scene's {} objects ({} fragments)",
                estimate.objects.len(),
                format_count(estimate.fragments as u64)
            ),
            &estimate.total,
        )?;
        let dt = self.settings.dt;
        limits.check(
            &format!(
                "{} steps of {} s with {} fragments",
                format_count(steps),
                dt,
                format_count(estimate.fragments as u64)
            ),
            &estimate.total,
        )?;
        Ok(estimate)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn limits() -> Limits {
        Limits {
            memory_bytes: Some(24_000_000_000),
            seconds: Some(3600.0),
            memory_source: "test",
        }
    }

    fn refusal(toml: &str, steps: Option<u64>) -> String {
        let scene = Scene::parse(toml).unwrap();
        let steps = scene.steps(steps, None);
        scene
            .check_budget(steps, &limits())
            .unwrap_err()
            .to_string()
    }

    #[test]
    fn a_huge_grid_is_refused_naming_the_key() {
        let e = refusal(
            "[[objects]]\nmethod = \"grid\"\ngrid = [1000, 1000, 1000]\n",
            Some(1),
        );
        assert!(
            e.starts_with("objects[0].grid = [1000, 1000, 1000]: 1,000,000,000 bricks need about"),
            "{e}"
        );
        assert!(e.contains("this machine has 24 GB"), "{e}");
    }

    #[test]
    fn huge_counts_are_refused_for_memory() {
        let e = refusal(
            "[[objects]]\nmethod = \"voronoi\"\npieces = 10000000\n",
            Some(1),
        );
        assert!(
            e.starts_with(
                "objects[0].pieces = 10000000: 10,000,000 Voronoi cells with rough cut faces need"
            ),
            "{e}"
        );
        let e = refusal(
            "[[objects]]\nmethod = \"tetra\"\nrandom_vertices = 10000000\n",
            Some(1),
        );
        assert!(
            e.starts_with(
                "objects[0].random_vertices = 10000000: a tetra fracture of 10,000,024 points with rough cut faces need"
            ),
            "{e}"
        );
    }

    #[test]
    fn tiny_steps_and_long_runs_are_refused_for_time() {
        let e = refusal("[world]\ndt = 1e-9\n", None);
        // dt is an f32: 1e-9 is 9.99999972e-10, so the 3 s are 3,000,000,085 steps.
        assert!(
            e.starts_with("3,000,000,085 steps of 0.000000001 s with 0 fragments would take about"),
            "{e}"
        );
        assert!(e.ends_with("; the limit is 1 hour"), "{e}");
        let e = refusal("[world]\nseconds = 1e9\n", None);
        // 1e9 s at 1/60 s (an f32: 0.016666668) are 59,999,996,871 steps.
        assert!(
            e.starts_with("59,999,996,871 steps of 0.016666668 s"),
            "{e}"
        );
        assert!(e.contains("days"), "{e}");
    }

    #[test]
    fn the_shipped_scenes_fit() {
        let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/../../assets/scenes");
        for name in ["default", "wall", "bird", "explosion", "thesis_joints"] {
            let path = std::path::Path::new(dir).join(format!("{name}.toml"));
            let scene = Scene::load(&path).unwrap();
            let steps = scene.steps(None, None);
            let e = scene.check_budget(steps, &limits());
            assert!(e.is_ok(), "{name}: {e:?}");
        }
    }

    #[test]
    fn rough_cut_faces_are_in_the_estimate() {
        let object = |extra: &str| {
            let text = format!("[[objects]]\nmaterial = \"stone\"\npieces = 50\n{extra}\n");
            Scene::parse(&text).unwrap().estimate(1).objects.remove(0)
        };
        let (rough, flat) = (object(""), object("roughness = 0"));
        assert!(rough.what.contains("rough cut faces"), "{}", rough.what);
        assert!(!flat.what.contains("rough"), "{}", flat.what);
        assert!(rough.estimate.seconds > 1.5 * flat.estimate.seconds);
        assert!(rough.estimate.bytes > flat.estimate.bytes);
        // A grid stays square, and so costs the same either way.
        let grid = |extra: &str| object(&format!("method = \"grid\"\n{extra}")).estimate;
        assert_eq!(grid(""), grid("roughness = 0"));
    }

    #[test]
    fn the_estimate_grows_with_the_steps_and_the_objects() {
        let scene = Scene::parse("[[objects]]\nmethod = \"grid\"\ngrid = [10, 10, 10]\n").unwrap();
        let a = scene.estimate(100);
        let b = scene.estimate(200);
        assert_eq!(a.fragments, 1000.0);
        assert!(b.run.seconds > a.run.seconds && b.total.seconds > a.total.seconds);
        assert_eq!(a.total.bytes, b.total.bytes);
    }
}
