//! Tests of hierarchies built a slice at a time: the same hierarchy as one built at once,
//! no slice over its budget by more than a row, an island split off a larger one solved
//! at once on that one's hierarchy (restricted to its nodes, exactly) or on block Jacobi,
//! and the stresses of a solver that built everything at once in the end.

use glam::DVec3;

use super::local::{Dof, LocalSprings};
use super::multigrid::real::F32;
use super::multigrid::{Build, Multigrid};
use super::slicing_tests::{G, difference, until_converged, wall};
use super::solver::springs;
use super::*;

/// The free nodes' springs and positions of a wall (all of its bonds).
pub(super) fn wall_springs(graph: &BondGraph) -> (LocalSprings, Vec<DVec3>) {
    let all_springs = springs(graph, &SolverSettings::default());
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
    let pos = free
        .iter()
        .map(|&v| graph.nodes()[v as usize].centroid)
        .collect();
    (springs, pos)
}

#[test]
fn a_hierarchy_built_in_slices_is_the_one_built_at_once_and_no_slice_passes_its_budget_by_more_than_a_row()
 {
    for graph in [wall(14, 10, 2), wall(5, 4, 1)] {
        let (springs, pos) = wall_springs(&graph);
        let whole = Multigrid::<F32>::new(&springs, &pos);
        let r: Vec<Dof> = (0..springs.n)
            .map(|i| {
                let s = (i % 7) as f64 - 3.0;
                (DVec3::new(s, -2.0 * s, 0.5), DVec3::new(0.1, s, -0.2))
            })
            .collect();
        let expected = whole.apply_alloc(&r);
        for budget in [1, 50, 3_000] {
            let mut build = Build::<F32>::new(&springs, &pos);
            let mut slices = 0;
            while !build.done() {
                let done = build.advance(budget);
                assert!(done <= budget + build.largest_step(), "{done} for {budget}");
                slices += 1;
            }
            // The largest row is small next to the whole build.
            assert!(build.largest_step() * 20 <= build.spent());
            if budget < 100 {
                assert!(slices > 50, "{slices} slices of {budget}");
            }
            let sliced = build.finish();
            assert_eq!(sliced.depth(), whole.depth());
            assert_eq!(sliced.apply_alloc(&r), expected, "budget {budget}");
        }
    }
}

/// The bonds of a wall of `nx` columns between columns `x − 1` and `x`, its anchored row
/// included: breaking them splits the wall in two islands.
fn cut_at(graph: &BondGraph, nx: u32, x: u32) -> Vec<bool> {
    let column = |v: u32| v % nx;
    graph
        .bonds()
        .iter()
        .map(|b| {
            let (ca, cb) = (column(b.a), column(b.b));
            ca.min(cb) == x - 1 && ca.max(cb) == x
        })
        .collect()
}

#[test]
fn a_hierarchy_restricted_to_some_rows_is_the_whole_one_on_vectors_zero_elsewhere() {
    let (springs, pos) = wall_springs(&wall(12, 9, 2));
    let mg = Multigrid::<F32>::new(&springs, &pos);
    let rows: Vec<u32> = (0..springs.n as u32).filter(|i| i % 3 != 1).collect();
    let r: Vec<Dof> = rows
        .iter()
        .map(|&i| {
            let s = f64::from(i % 5) - 2.0;
            (DVec3::new(s, 1.0, -s), DVec3::new(0.3, -s, 0.5))
        })
        .collect();
    let mut spread = vec![(DVec3::ZERO, DVec3::ZERO); springs.n];
    for (&i, v) in rows.iter().zip(&r) {
        spread[i as usize] = *v;
    }
    let whole = mg.apply_alloc(&spread);
    let mut rs = r.clone();
    rs.push((DVec3::ZERO, DVec3::ZERO));
    let mut z = rs.clone();
    mg.apply_rows(&rows, &rs, &mut z, &mut Default::default());
    for (k, &i) in rows.iter().enumerate() {
        assert_eq!(z[k], whole[i as usize], "row {i}");
    }
}

#[test]
fn an_island_split_off_a_wall_builds_its_hierarchy_a_slice_per_solve_and_ends_with_the_stresses_of_a_rebuild()
 {
    let (nx, ny, nz) = (14, 10, 2);
    let graph = wall(nx, ny, nz);
    let budget = 500;
    let settings = SolverSettings {
        tolerance: 1e-9,
        build_budget: Some(budget),
        ..SolverSettings::default()
    };
    let mut solver = StressSolver::new(&graph, settings);
    let intact = vec![false; graph.bonds().len()];
    assert_eq!(solver.prepare(&graph, &intact), 1, "built with the object");
    until_converged(&mut solver, &graph, &intact, &[]);
    // Cut after the fourth column: the left part has 4 of 14 columns, under half of the
    // wall's hierarchy, and gets its own; the right part keeps the wall's.
    let broken = cut_at(&graph, nx, 4);
    let reports = until_converged(&mut solver, &graph, &broken, &[]);
    // What building the left part's hierarchy at once costs, and its largest row.
    let island = graph
        .islands(&broken)
        .into_iter()
        .find(|i| i.nodes.contains(&(nx * ny)))
        .expect("the left part");
    let all = springs(&graph, &settings);
    let mut local = vec![u32::MAX; graph.nodes().len()];
    let mut free = Vec::new();
    for &v in &island.nodes {
        if !graph.anchored()[v as usize] {
            local[v as usize] = free.len() as u32;
            free.push(v);
        }
    }
    let left = LocalSprings::new(&all, &island.bonds, &local, free.len());
    let pos: Vec<DVec3> = free
        .iter()
        .map(|&v| graph.nodes()[v as usize].centroid)
        .collect();
    let mut whole = Build::<F32>::new(&left, &pos);
    whole.advance(1);
    while !whole.done() {
        whole.advance(1);
    }
    let (total, row) = (whole.spent(), whole.largest_step());
    assert!(
        total > 20 * budget,
        "a whole build, {total}, is many slices"
    );
    // No solve did more than its budget and one row; the hierarchy was built over many
    // solves, and completed once.
    for r in &reports {
        assert!(
            r.build_work <= budget + row,
            "{} > {budget} + {row}",
            r.build_work
        );
    }
    assert_eq!(reports[0].hierarchies_built, 0);
    let built: usize = reports.iter().map(|r| r.hierarchies_built).sum();
    let work: usize = reports.iter().map(|r| r.build_work).sum();
    if built == 0 {
        // Converged on the wall's hierarchy before its own was done: go on until it is.
        let mut more = 0;
        let mut work = work;
        while more == 0 {
            let r = solver.solve(&graph, &broken, G, &[]);
            assert!(r.build_work <= budget + row);
            work += r.build_work;
            more = r.hierarchies_built;
        }
        assert_eq!(work, total);
    } else {
        assert_eq!((built, work), (1, total));
    }
    // The same stresses as a solver that built the two parts' hierarchies at once.
    let mut fresh = StressSolver::new(
        &graph,
        SolverSettings {
            build_budget: None,
            ..settings
        },
    );
    until_converged(&mut fresh, &graph, &broken, &[]);
    let (worst, peak) = difference(&graph, &solver, &fresh);
    assert!(worst <= 1e-6 * peak, "{worst:e} of {peak:e}");
}

#[test]
fn an_island_with_no_hierarchy_to_use_is_solved_on_block_jacobi_while_its_own_is_built() {
    let graph = wall(8, 6, 2);
    let settings = SolverSettings {
        tolerance: 1e-9,
        build_budget: Some(500),
        ..SolverSettings::default()
    };
    // No `prepare`: the first solve finds no hierarchy.
    let mut solver = StressSolver::new(&graph, settings);
    let intact = vec![false; graph.bonds().len()];
    let first = solver.solve(&graph, &intact, G, &[]);
    assert_eq!(first.hierarchies_built, 0);
    assert!(first.converged, "block Jacobi converges on a small wall");
    let mut fresh = StressSolver::new(
        &graph,
        SolverSettings {
            build_budget: None,
            ..settings
        },
    );
    until_converged(&mut fresh, &graph, &intact, &[]);
    let (worst, peak) = difference(&graph, &solver, &fresh);
    assert!(worst <= 1e-6 * peak, "{worst:e} of {peak:e}");
    // Its hierarchy comes later, and then a hit is solved on it.
    let mut built = 0;
    for _ in 0..10_000 {
        built += solver.solve(&graph, &intact, G, &[]).hierarchies_built;
        if built > 0 {
            break;
        }
    }
    assert_eq!(built, 1);
    let hit = [(20, DVec3::new(0.0, 0.0, -5e4))];
    let a = until_converged(&mut solver, &graph, &intact, &hit);
    let b = until_converged(&mut fresh, &graph, &intact, &hit);
    let iterations = |r: &[SolveReport]| r.iter().map(|r| r.iterations).sum::<usize>();
    assert_eq!(iterations(&a), iterations(&b));
}

#[test]
fn a_brick_knocked_out_of_a_wall_is_dropped_from_its_island_in_place_with_the_answer_of_a_rebuild()
{
    let (nx, ny, nz) = (12, 9, 2);
    let graph = wall(nx, ny, nz);
    let settings = SolverSettings {
        tolerance: 1e-9,
        build_budget: Some(500),
        ..SolverSettings::default()
    };
    let mut solver = StressSolver::new(&graph, settings);
    let mut broken = vec![false; graph.bonds().len()];
    solver.prepare(&graph, &broken);
    until_converged(&mut solver, &graph, &broken, &[]);
    // A brick of the front layer in the middle of the wall, and a pair of bonded bricks
    // at the top corner: every bond to the rest breaks.
    let brick = 6 + nx * 4;
    let (corner, below) = (nx * ny - 1, nx * ny - 1 - nx);
    let pieces = [vec![brick], vec![corner, below]];
    for piece in &pieces {
        for (b, bond) in graph.bonds().iter().enumerate() {
            if piece.contains(&bond.a) != piece.contains(&bond.b) {
                broken[b] = true;
            }
        }
    }
    let reports = until_converged(&mut solver, &graph, &broken, &[]);
    assert!(!reports[0].rebuilt, "the pieces are dropped in place");
    for &v in pieces.iter().flatten() {
        assert!(!solver.is_supported(v), "node {v} left its island");
    }
    // The bond between the two corner bricks is intact but carries nothing.
    let inside = graph
        .bonds()
        .iter()
        .position(|b| (b.a, b.b) == (below, corner))
        .expect("the corner bond") as u32;
    assert_eq!(solver.stress(inside), BondStress::default());
    let mut fresh = StressSolver::new(&graph, settings);
    until_converged(&mut fresh, &graph, &broken, &[]);
    let (worst, peak) = difference(&graph, &solver, &fresh);
    assert!(worst <= 1e-6 * peak, "{worst:e} of {peak:e}");
    // The dropped pair's own bond breaks too (it was taken off with the pair, and is not
    // taken off again), then the wall is cut in two anchored parts: a rebuild, and again
    // the answer of a fresh solver.
    broken[inside as usize] = true;
    until_converged(&mut solver, &graph, &broken, &[]);
    let cut: Vec<bool> = cut_at(&graph, nx, 6)
        .iter()
        .zip(&broken)
        .map(|(c, b)| *c || *b)
        .collect();
    let reports = until_converged(&mut solver, &graph, &cut, &[]);
    assert!(reports[0].rebuilt);
    let mut fresh = StressSolver::new(&graph, settings);
    until_converged(&mut fresh, &graph, &cut, &[]);
    let (worst, peak) = difference(&graph, &solver, &fresh);
    assert!(worst <= 1e-6 * peak, "{worst:e} of {peak:e}");
}
