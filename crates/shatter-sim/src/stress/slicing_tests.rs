//! Tests of what a solve costs: settled islands and the solve after a hit cost nothing,
//! the spring budget bounds every solve, the `f32` preconditioner is the `f64` one within
//! its precision, and a bond broken inside an island is taken off its hierarchy in place
//! with the answer of a rebuild.

use glam::DVec3;

use super::local::{Dof, LocalSprings};
use super::multigrid::Multigrid;
use super::multigrid::real::{F32, F64};
use super::solver::springs;
use super::*;
use crate::testing::box_grid_fracture;

pub(super) const G: DVec3 = DVec3::new(0.0, -9.81, 0.0);

/// A wall of `nx × ny × nz` blocks of 0.2 m, its bottom row anchored.
pub(super) fn wall(nx: u32, ny: u32, nz: u32) -> BondGraph {
    let f = box_grid_fracture(
        [nx, ny, nz],
        DVec3::new(0.2 * nx as f64, 0.2 * ny as f64, 0.2 * nz as f64),
    );
    BondGraph::from_fracture(&f, 2400.0, |i| (i / nx).is_multiple_of(ny)).unwrap()
}

/// The largest difference of two solvers' stresses over every bond, and the peak stress
/// of the first.
pub(super) fn difference(graph: &BondGraph, a: &StressSolver, b: &StressSolver) -> (f64, f64) {
    let (mut worst, mut peak) = (0.0f64, 0.0f64);
    for k in 0..graph.bonds().len() as u32 {
        let (x, y) = (a.stress(k), b.stress(k));
        peak = peak.max(x.tension).max(x.compression).max(x.shear);
        worst = worst
            .max((x.tension - y.tension).abs())
            .max((x.compression - y.compression).abs())
            .max((x.shear - y.shear).abs());
    }
    (worst, peak)
}

/// Solves until converged (at most 1,000 solves), `forces` in the first solve only;
/// returns the reports.
pub(super) fn until_converged(
    solver: &mut StressSolver,
    graph: &BondGraph,
    broken: &[bool],
    forces: &[(u32, DVec3)],
) -> Vec<SolveReport> {
    let mut reports = Vec::new();
    for k in 0..1000 {
        let r = solver.solve(graph, broken, G, if k == 0 { forces } else { &[] });
        reports.push(r);
        if r.converged {
            return reports;
        }
    }
    panic!("never converged: {:?}", reports.last());
}

#[test]
fn a_settled_island_and_the_solve_after_a_hit_cost_no_iteration() {
    let graph = wall(12, 10, 2);
    let broken = vec![false; graph.bonds().len()];
    let mut solver = StressSolver::new(&graph, SolverSettings::default());
    assert!(solver.solve(&graph, &broken, G, &[]).converged);
    for _ in 0..3 {
        let r = solver.solve(&graph, &broken, G, &[]);
        assert_eq!(
            (r.islands_skipped, r.iterations, r.springs),
            (1, 0, 0),
            "{r:?}"
        );
    }
    let resting: Vec<BondStress> = (0..graph.bonds().len() as u32)
        .map(|b| solver.stress(b))
        .collect();
    let hit = solver.solve(
        &graph,
        &broken,
        G,
        &[(12 * 8 + 5, DVec3::new(0.0, 0.0, -4e5))],
    );
    assert!(hit.converged && hit.iterations > 0, "{hit:?}");
    // The hit gone, the island is back at its gravity solution without iterating.
    let after = solver.solve(&graph, &broken, G, &[]);
    assert_eq!(
        (after.islands_solved, after.iterations),
        (1, 0),
        "{after:?}"
    );
    for (b, s) in resting.iter().enumerate() {
        assert_eq!(solver.stress(b as u32), *s, "bond {b}");
    }
    assert_eq!(solver.solve(&graph, &broken, G, &[]).islands_skipped, 1);
}

#[test]
fn the_spring_budget_bounds_every_solve_and_the_sliced_solve_ends_where_the_whole_one_does() {
    let graph = wall(12, 10, 2);
    let bonds = graph.bonds().len();
    let broken = vec![false; bonds];
    let hit = [(12 * 8 + 5, DVec3::new(0.0, 0.0, -4e5))];
    let mut whole = StressSolver::new(&graph, SolverSettings::default());
    whole.solve(&graph, &broken, G, &[]);
    let once = whole.solve(&graph, &broken, G, &hit);
    // One start or iteration of this island per solve.
    let mut sliced = StressSolver::new(
        &graph,
        SolverSettings {
            spring_budget: Some(bonds),
            ..SolverSettings::default()
        },
    );
    let cold = until_converged(&mut sliced, &graph, &broken, &[]);
    let reports = until_converged(&mut sliced, &graph, &broken, &hit);
    for r in cold.iter().chain(&reports) {
        assert!(r.springs <= bonds, "{r:?}");
    }
    // Its start, then its iterations, one per solve.
    assert_eq!(reports.len(), once.iterations + 1);
    let (worst, peak) = difference(&graph, &whole, &sliced);
    assert!(worst <= 1e-9 * peak, "{worst:e} of {peak:e}");
}

#[test]
fn an_island_dearer_than_the_spring_budget_waits_for_the_springs_saved_and_ends_where_the_whole_solve_does()
 {
    let graph = wall(12, 10, 2);
    let bonds = graph.bonds().len();
    let broken = vec![false; bonds];
    let hit = [(12 * 8 + 5, DVec3::new(0.0, 0.0, -4e5))];
    let mut whole = StressSolver::new(&graph, SolverSettings::default());
    whole.solve(&graph, &broken, G, &[]);
    let once = whole.solve(&graph, &broken, G, &hit);
    // A unit every two or three solves.
    let budget = bonds * 2 / 5;
    let mut sliced = StressSolver::new(
        &graph,
        SolverSettings {
            spring_budget: Some(budget),
            ..SolverSettings::default()
        },
    );
    until_converged(&mut sliced, &graph, &broken, &[]);
    let reports = until_converged(&mut sliced, &graph, &broken, &hit);
    let mut visited = 0;
    for (k, r) in reports.iter().enumerate() {
        assert!(r.springs == 0 || r.springs == bonds, "{r:?}");
        visited += r.springs;
        // On average never over the budget (the first solve had nothing saved).
        assert!(
            visited <= budget * (k + 1),
            "{visited} after {} solves",
            k + 1
        );
    }
    let units = once.iterations + 1;
    assert_eq!(visited, units * bonds);
    assert!(reports.len() >= units * 5 / 2, "{} solves", reports.len());
    let (worst, peak) = difference(&graph, &whole, &sliced);
    assert!(worst <= 1e-9 * peak, "{worst:e} of {peak:e}");
}

#[test]
fn the_f32_preconditioner_is_the_f64_one_within_its_precision() {
    let graph = wall(14, 10, 2);
    let all_springs = springs(&graph, &SolverSettings::default());
    let mut local = vec![u32::MAX; graph.nodes().len()];
    let mut free = Vec::new();
    for (v, &anchored) in graph.anchored().iter().enumerate() {
        if !anchored {
            local[v] = free.len() as u32;
            free.push(v as u32);
        }
    }
    let all: Vec<u32> = (0..all_springs.len() as u32).collect();
    let springs = LocalSprings::new(&all_springs, &all, &local, free.len());
    let pos: Vec<DVec3> = free
        .iter()
        .map(|&v| graph.nodes()[v as usize].centroid)
        .collect();
    let single = Multigrid::<F32>::new(&springs, &pos);
    let double = Multigrid::<F64>::new(&springs, &pos);
    // A smooth residual and a rough one.
    for rough in [false, true] {
        let r: Vec<Dof> = (0..free.len())
            .map(|i| {
                let s = if rough { (i % 7) as f64 - 3.0 } else { 1.0 };
                (DVec3::new(s, -2.0 * s, 0.5), DVec3::new(0.1, s, -0.2))
            })
            .collect();
        let (a, b) = (single.apply_alloc(&r), double.apply_alloc(&r));
        let norm = |v: &[Dof]| {
            v.iter()
                .map(|(u, t)| u.length_squared() + t.length_squared())
                .sum::<f64>()
                .sqrt()
        };
        let diff: Vec<Dof> = a
            .iter()
            .zip(&b)
            .map(|(x, y)| (x.0 - y.0, x.1 - y.1))
            .collect();
        assert!(
            norm(&diff) <= 1e-4 * norm(&b),
            "rough {rough}: {:e} of {:e}",
            norm(&diff),
            norm(&b)
        );
    }
}

#[test]
fn an_updated_hierarchy_is_the_galerkin_hierarchy_of_the_springs_left() {
    let graph = wall(12, 9, 2);
    let all_springs = springs(&graph, &SolverSettings::default());
    let mut local = vec![u32::MAX; graph.nodes().len()];
    let mut free = Vec::new();
    for (v, &anchored) in graph.anchored().iter().enumerate() {
        if !anchored {
            local[v] = free.len() as u32;
            free.push(v as u32);
        }
    }
    let all: Vec<u32> = (0..all_springs.len() as u32).collect();
    let springs = LocalSprings::new(&all_springs, &all, &local, free.len());
    let pos: Vec<DVec3> = free
        .iter()
        .map(|&v| graph.nodes()[v as usize].centroid)
        .collect();
    let mut mg = Multigrid::<F64>::new(&springs, &pos);
    // Every fifth spring broken, a base one among them.
    let gone: Vec<usize> = (0..springs.springs.len()).step_by(5).collect();
    mg.remove_springs(&gone.iter().map(|&k| springs.springs[k]).collect::<Vec<_>>());
    let mut left = springs.clone();
    for &k in &gone {
        let s = &mut left.springs[k];
        (s.ks, s.dn, s.kb, s.dt) = (0.0, 0.0, 0.0, 0.0);
    }
    let x: Vec<Dof> = (0..free.len())
        .map(|i| {
            let s = (i * 37 % 11) as f64 - 5.0;
            (DVec3::new(s, 1.0, -s), DVec3::new(0.2, -s, 1.0))
        })
        .collect();
    let close = |a: &[Dof], b: &[Dof], rel: f64| {
        let (mut d, mut n) = (0.0, 0.0);
        for (p, q) in a.iter().zip(b) {
            d += (p.0 - q.0).length_squared() + (p.1 - q.1).length_squared();
            n += q.0.length_squared() + q.1.length_squared();
        }
        d.sqrt() <= rel * n.sqrt()
    };
    let mut xs = x.clone();
    xs.push((DVec3::ZERO, DVec3::ZERO));
    let mut kx = xs.clone();
    left.times(&xs, &mut kx);
    kx.pop();
    assert!(close(&mg.times(0, &x), &kx, 1e-12));
    for l in 0..mg.depth() - 1 {
        let xc: Vec<Dof> = (0..mg.level_len(l + 1))
            .map(|i| {
                (
                    DVec3::new(1.0, i as f64, -2.0),
                    DVec3::new(0.5, 0.0, i as f64),
                )
            })
            .collect();
        let fine = mg.times(l, &mg.prolong(l, &xc));
        assert!(
            close(&mg.times(l + 1, &xc), &mg.restrict(l, &fine), 1e-9),
            "level {}",
            l + 1
        );
    }
}

#[test]
fn a_bond_broken_inside_an_island_is_taken_off_in_place_with_the_answer_of_a_rebuild() {
    let graph = wall(20, 12, 2);
    let bonds = graph.bonds().len();
    let mut broken = vec![false; bonds];
    let mut solver = StressSolver::new(&graph, SolverSettings::default());
    assert_eq!(solver.prepare(&graph, &broken), 1);
    let first = solver.solve(&graph, &broken, G, &[]);
    assert!(first.converged && first.hierarchies_built == 0, "{first:?}");
    // Bonds well inside the wall, each with a way around it: the island stays whole.
    for k in (0..bonds).filter(|k| k % 17 == 3) {
        let b = graph.bonds()[k];
        let row = |v: u32| (v / 20) % 12;
        if row(b.a) >= 3 && row(b.b) >= 3 {
            broken[k] = true;
        }
    }
    let kept = solver.solve(&graph, &broken, G, &[]);
    assert!(
        kept.converged && kept.hierarchies_built == 0 && kept.islands_solved == 1,
        "{kept:?}"
    );
    let mut fresh = StressSolver::new(&graph, SolverSettings::default());
    let rebuilt = fresh.solve(&graph, &broken, G, &[]);
    assert_eq!(rebuilt.hierarchies_built, 1);
    let (worst, peak) = difference(&graph, &fresh, &solver);
    assert!(worst <= 1e-3 * peak, "{worst:e} of {peak:e}");
    // The warm start and the updated hierarchy need no more iterations than a cold
    // solve with a fresh one.
    assert!(
        kept.iterations <= rebuilt.iterations,
        "{kept:?} {rebuilt:?}"
    );
    for (k, &b) in broken.iter().enumerate() {
        if b {
            assert_eq!(solver.stress(k as u32), BondStress::default());
        }
    }
}
