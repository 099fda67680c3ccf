//! One case of the study: the standard cube fractured as the case says, shot at, and
//! simulated; and the estimate of every case before any runs.

use std::sync::Arc;

use shatter_geom::budget::Estimate;
use shatter_geom::fracture::{Fracture, Method, MethodKind, Pattern, Placement};
use shatter_geom::progress::Progress;
use shatter_geom::shapes::Shape;
use shatter_sim::{
    Material, ObjectId, ObjectSpec, ProjectileShape, ProjectileSpec, World, WorldSettings,
};

use super::config::{Case, StudyConfig};
use crate::error::{LabError, ResultExt};
use crate::fracture::{
    FractureConfig, builtin_shape, fracture_estimate, fracture_timed, load_source,
};

/// What one case did.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Outcome {
    /// Fragments of the cube.
    pub fragments: usize,
    /// Bonds of the cube.
    pub bonds_total: usize,
    /// Bonds broken at the end.
    pub bonds_broken: usize,
    /// Fragments no longer connected to the largest piece.
    pub released: usize,
}

/// When the shot is fired, in seconds after start (the cube has settled by then).
const SHOT_AT: f64 = 0.25;

/// Grid cells along each axis for about `pieces` bricks (a grid case is not part of the
/// method study; this keeps every method usable in a case).
fn grid_side(pieces: usize) -> u32 {
    ((pieces as f64).cbrt().round() as u32).clamp(1, 1000)
}

/// Fragments not connected through intact bonds to the largest connected piece.
pub fn released_fragments(fragments: usize, bonds: &[(u32, u32)], broken: &[bool]) -> usize {
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
        MethodKind::Tetra => Method::tetra(case.random_vertices, Placement::Interior),
        MethodKind::Voronoi => Method::voronoi(case.pieces, Pattern::Uniform),
        MethodKind::Slice => Method::Slice {
            pieces: case.planes,
            planes: None,
        },
        MethodKind::Grid => Method::Grid {
            cells: [grid_side(case.pieces); 3],
            voids: Vec::new(),
        },
    };
    FractureConfig::shape(Shape::Cube, method, case.seed)
}

/// The standard cube fractured as `case` says (through the same code path as
/// `shatter fracture`).
fn fracture_case(case: &Case) -> Result<Fracture, LabError> {
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
pub fn study_estimate(config: &StudyConfig) -> Result<(Estimate, Estimate), LabError> {
    let cube = builtin_shape(Shape::Cube)?;
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
/// middle of a face, `seconds` of simulated time. Cancelling `progress` stops it between
/// two steps.
pub fn simulate_case(case: &Case, progress: &Progress) -> Result<Outcome, LabError> {
    progress.check()?;
    let fracture = fracture_case(case)?;
    let material = Material::preset("stone")
        .ok_or_else(|| LabError::internal("the stone material preset is missing"))?;
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
    world.run_steps(case_steps(case), progress, |_, _| Ok::<(), LabError>(()))?;
    let fracture: Arc<Fracture> = world
        .object_fracture(id)
        .ok_or_else(|| LabError::internal("the standard cube vanished"))?;
    let broken = world.bond_states(id).unwrap_or_default();
    let bonds: Vec<(u32, u32)> = fracture.bonds.iter().map(|b| (b.a, b.b)).collect();
    Ok(Outcome {
        fragments: fracture.fragments.len(),
        bonds_total: bonds.len(),
        bonds_broken: broken.iter().filter(|&&b| b).count(),
        released: released_fragments(fracture.fragments.len(), &bonds, &broken),
    })
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;
    use crate::study::config::tests::options;
    use shatter_sim::BondModel;

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
    fn a_study_costs_more_with_more_runs() {
        let mut o = options();
        let config = StudyConfig::new(&o).unwrap();
        let (total, largest) = study_estimate(&config).unwrap();
        assert!(total.seconds >= largest.seconds && largest.seconds > 0.0);
        o.runs *= 2;
        let (doubled, _) = study_estimate(&StudyConfig::new(&o).unwrap()).unwrap();
        assert!((doubled.seconds - 2.0 * total.seconds).abs() < 1e-9 * doubled.seconds);
    }

    #[test]
    fn without_a_shot_a_resting_cube_keeps_its_bonds() {
        let case = Case {
            method: MethodKind::Slice,
            bond_model: BondModel::Clusters,
            break_force: 1e6,
            speed: 0.0,
            random_vertices: 0,
            pieces: 8,
            planes: 2,
            seconds: 0.1,
            seed: 1,
        };
        let o = simulate_case(&case, &Progress::none()).unwrap();
        assert!(o.fragments >= 2, "{o:?}");
        assert_eq!((o.bonds_broken, o.released), (0, 0));
        let cancelled = Progress::new();
        cancelled.cancel();
        assert_eq!(
            simulate_case(&case, &cancelled).unwrap_err(),
            LabError::Interrupted
        );
    }
}
