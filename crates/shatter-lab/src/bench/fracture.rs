//! The fracture benchmark: the fracture methods timed on the built-in shapes.
//!
//! Cases: the bird into 100 Voronoi fragments (the comparison with Blender's Cell
//! Fracture), the same bird painted (UVs, smooth normals and colours on every corner, two
//! materials: what carrying a textured asset's attributes costs), the thesis's creation
//! case (cube + 500 random points, tetra), and a few more rows covering every method. Each case is run `runs` times after one untimed
//! warm-up; mean, min and max are reported.

use serde::Serialize;
use shatter_geom::budget::{Estimate, format_count};
use shatter_geom::fracture::{Method, Pattern, Placement};
use shatter_geom::model::{Material, Model};
use shatter_geom::shapes::Shape;
use shatter_geom::{DVec3, TriMesh};

use crate::bar::Bar;
use crate::context::Context;
use crate::error::LabError;
use crate::fracture::{FractureConfig, fracture_estimate, fracture_timed, load_source};
use crate::spread::Spread;

/// One benchmark case.
#[derive(Debug, Clone)]
pub struct Case {
    /// Its name in the table.
    pub name: &'static str,
    /// The shape fractured.
    pub shape: Shape,
    /// How.
    pub method: Method,
    /// Whether the shape is painted first ([`paint`]).
    pub painted: bool,
}

/// The cases, in the order they run.
pub fn cases() -> Vec<Case> {
    let voronoi = Method::voronoi;
    let tetra = Method::tetra;
    let case = |name, shape, method| Case {
        name,
        shape,
        method,
        painted: false,
    };
    vec![
        case(
            "bird voronoi 100",
            Shape::Bird,
            voronoi(100, Pattern::Uniform),
        ),
        Case {
            painted: true,
            ..case(
                "bird voronoi 100 painted",
                Shape::Bird,
                voronoi(100, Pattern::Uniform),
            )
        },
        case(
            "cube tetra 500 thesis",
            Shape::Cube,
            tetra(500, Placement::Thesis),
        ),
        case(
            "cube tetra 500 interior",
            Shape::Cube,
            tetra(500, Placement::Interior),
        ),
        case(
            "bird tetra 200 interior",
            Shape::Bird,
            tetra(200, Placement::Interior),
        ),
        case(
            "capsule voronoi 50",
            Shape::Capsule,
            voronoi(50, Pattern::Uniform),
        ),
        case(
            "cylinder voronoi 50",
            Shape::Cylinder,
            voronoi(50, Pattern::Uniform),
        ),
        case(
            "bird voronoi 100 radial",
            Shape::Bird,
            voronoi(100, Pattern::Radial),
        ),
        case(
            "bird slice 8",
            Shape::Bird,
            Method::Slice {
                planes: None,
                pieces: 8,
            },
        ),
        case(
            "cube slice 8",
            Shape::Cube,
            Method::Slice {
                planes: None,
                pieces: 8,
            },
        ),
    ]
}

/// One measured case.
#[derive(Debug, Clone, Serialize)]
pub struct Row {
    /// The case's name.
    pub case: &'static str,
    /// The shape's name.
    pub shape: &'static str,
    /// Fragments made (warm-up run).
    pub fragments: usize,
    /// Bonds made (warm-up run).
    pub bonds: usize,
    /// Timed runs.
    pub runs: u32,
    /// Mean ms.
    pub mean_ms: f64,
    /// Fastest run, ms.
    pub min_ms: f64,
    /// Slowest run, ms.
    pub max_ms: f64,
}

/// The `--json` report.
#[derive(Debug, Clone, Serialize)]
pub struct Report {
    /// The seed of every case.
    pub seed: u64,
    /// One row per case.
    pub rows: Vec<Row>,
}

/// A benchmark whose estimate fitted the limits, ready to run.
#[derive(Debug)]
pub struct BenchFracture {
    runs: u32,
    seed: u64,
}

impl BenchFracture {
    /// Checks the estimate of every case (`runs` timed runs and a warm-up each, at
    /// least 1 run) against the context's limits.
    pub fn prepare(runs: u32, seed: u64, ctx: &Context) -> Result<Self, LabError> {
        if runs == 0 {
            return Err(LabError::input("--runs must be at least 1"));
        }
        let bench = Self { runs, seed };
        let mut total = Estimate::default();
        for case in cases() {
            let config = bench.config(&case);
            let (model, _) = load_source(&config)?;
            let (_, e) = fracture_estimate(&model.mesh, &config);
            total.bytes = total.bytes.max(e.bytes);
            total.seconds += e.seconds * (f64::from(runs) + 1.0);
        }
        ctx.check(
            &format!(
                "--runs {runs}: {} fracture runs",
                format_count((u64::from(runs) + 1) * cases().len() as u64)
            ),
            &total,
        )?;
        Ok(bench)
    }

    fn config(&self, case: &Case) -> FractureConfig {
        FractureConfig::shape(case.shape, case.method.clone(), self.seed)
    }

    /// Times every case, with a bar unless `quiet`; `on_row` gets each row as it is
    /// measured, with the bar to print above.
    pub fn run(
        &self,
        ctx: &Context,
        quiet: bool,
        mut on_row: impl FnMut(&Row, &Bar),
    ) -> Result<Report, LabError> {
        let bar = ctx.bar(cases().len() as u64, quiet);
        let mut rows = Vec::new();
        for case in cases() {
            let config = self.config(&case);
            let (mut model, _) = load_source(&config)?;
            if case.painted {
                paint(&mut model);
            }
            ctx.progress.check()?;
            let (warm, _, _) = fracture_timed(&model, &config)?;
            let mut times = Vec::with_capacity(self.runs as usize);
            for _ in 0..self.runs {
                ctx.progress.check()?;
                let (_, _, ms) = fracture_timed(&model, &config)?;
                times.push(ms);
            }
            bar.tick(case.name);
            let spread = Spread::of(times).ok_or_else(|| LabError::internal("no timed run"))?;
            let row = Row {
                case: case.name,
                shape: case.shape.name(),
                fragments: warm.fragments.len(),
                bonds: warm.bonds.len(),
                runs: self.runs,
                mean_ms: spread.mean,
                min_ms: spread.min,
                max_ms: spread.max,
            };
            on_row(&row, &bar);
            rows.push(row);
        }
        Ok(Report {
            seed: self.seed,
            rows,
        })
    }
}

/// Gives `model` what a textured asset carries on every corner, from its positions: UVs
/// (a spherical projection about the bounding box's centre), smooth normals (each
/// vertex's area-weighted mean of its triangles' normals) and colours (the position in
/// the bounding box as RGB), and two materials (the triangles whose centroid has x < the
/// centre's, and the others).
pub fn paint(model: &mut Model) {
    let mesh = &model.mesh;
    let Some((lo, hi)) = mesh.bounds() else {
        return;
    };
    let centre = (lo + hi) * 0.5;
    let size = (hi - lo).max(DVec3::splat(f64::MIN_POSITIVE));
    let mut normal = vec![DVec3::ZERO; mesh.positions.len()];
    for t in &mesh.triangles {
        let [a, b, c] = t.map(|i| mesh.positions[i as usize]);
        let n = (b - a).cross(c - a);
        for &i in t {
            normal[i as usize] += n;
        }
    }
    // One value per corner, from its vertex.
    fn per_vertex<T: Copy>(mesh: &TriMesh, f: impl Fn(usize) -> T) -> Vec<[T; 3]> {
        mesh.triangles
            .iter()
            .map(|t| t.map(|i| f(i as usize)))
            .collect()
    }
    let uv = per_vertex(mesh, |i| {
        let d = (mesh.positions[i] - centre).normalize_or_zero();
        let u = 0.5 + d.z.atan2(d.x) / std::f64::consts::TAU;
        let v = 0.5 - d.y.clamp(-1.0, 1.0).asin() / std::f64::consts::PI;
        [u as f32, v as f32]
    });
    let smooth = per_vertex(mesh, |i| normal[i].normalize_or_zero().as_vec3().to_array());
    let color = per_vertex(mesh, |i| {
        let q = ((mesh.positions[i] - lo) / size).as_vec3();
        [q.x, q.y, q.z, 1.0]
    });
    model.corners.uv = Some(uv);
    model.corners.normal = Some(smooth);
    model.corners.color = Some(color);
    model.material = mesh
        .triangles
        .iter()
        .map(|t| {
            let x: f64 = t.iter().map(|&i| mesh.positions[i as usize].x).sum();
            u32::from(x / 3.0 >= centre.x)
        })
        .collect();
    model.materials = vec![Material::named("left"), Material::named("right")];
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;
    use shatter_geom::budget::Limits;

    #[test]
    fn the_cases_have_unique_names_and_cover_every_method() {
        let cases = cases();
        let mut names: Vec<&str> = cases.iter().map(|c| c.name).collect();
        names.sort();
        names.dedup();
        assert_eq!(names.len(), cases.len());
        assert!(
            cases
                .iter()
                .any(|c| matches!(c.method, Method::Tetra { .. }))
        );
        assert!(
            cases
                .iter()
                .any(|c| matches!(c.method, Method::Voronoi { .. }))
        );
        assert!(
            cases
                .iter()
                .any(|c| matches!(c.method, Method::Slice { .. }))
        );
    }

    #[test]
    fn a_painted_bird_is_a_valid_model_whose_fragments_carry_every_attribute() {
        let mut model = Model::from_mesh(Shape::Bird.mesh());
        paint(&mut model);
        assert_eq!(model.check(), Ok(()));
        let uv = model.corners.uv.as_ref().unwrap();
        let normal = model.corners.normal.as_ref().unwrap();
        assert!(
            uv.iter()
                .flatten()
                .all(|c| (0.0..=1.0).contains(&c[0]) && (0.0..=1.0).contains(&c[1]))
        );
        assert!(normal.iter().flatten().all(|n| {
            let l = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
            (l - 1.0).abs() < 1e-5
        }));
        // Both materials are used: the bird spans both sides of its centre.
        assert!(model.material.contains(&0) && model.material.contains(&1));
        let params = shatter_geom::fracture::FractureParams {
            method: Method::voronoi(12, Pattern::Uniform),
            seed: 1,
        };
        let result = shatter_geom::fracture::fracture_model(&model, &params).unwrap();
        let names: Vec<&str> = result.materials.iter().map(|m| m.name.as_str()).collect();
        assert_eq!(names, ["left", "right", "interior"]);
        for f in &result.fragments {
            assert!(
                f.corners.uv.is_some() && f.corners.normal.is_some() && f.corners.color.is_some()
            );
        }
    }

    #[test]
    fn zero_runs_and_a_tight_time_limit_are_refused_before_any_run() {
        let ctx = Context::quiet(Limits::none());
        assert_eq!(
            BenchFracture::prepare(0, 0, &ctx).unwrap_err(),
            LabError::input("--runs must be at least 1")
        );
        let tight = Context::quiet(Limits {
            memory_bytes: None,
            seconds: Some(1e-9),
            memory_source: "test",
        });
        let e = BenchFracture::prepare(5, 0, &tight).unwrap_err();
        assert!(
            e.to_string().starts_with("--runs 5: 60 fracture runs"),
            "{e}"
        );
    }
}
