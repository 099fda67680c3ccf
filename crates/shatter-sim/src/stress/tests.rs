//! Unit tests of the stress solver: hanging chains, columns, cantilevers, equilibrium,
//! islands and settling.

use glam::DVec3;

use super::*;
use crate::testing::box_grid_fracture;

const G: DVec3 = DVec3::new(0.0, -9.81, 0.0);

fn solved(graph: &BondGraph, broken: &[bool]) -> (StressSolver, SolveReport) {
    let mut solver = StressSolver::new(graph, SolverSettings::default());
    let report = solver.solve(graph, broken, G, &[]);
    (solver, report)
}

/// A vertical column of `n` 0.2 m blocks (fragment 0 at the bottom).
fn column(n: u32, density: f64, anchored: impl Fn(u32) -> bool) -> BondGraph {
    let f = box_grid_fracture([1, n, 1], DVec3::new(0.2, 0.2 * n as f64, 0.2));
    BondGraph::from_fracture(&f, density, anchored).unwrap()
}

#[test]
fn the_bond_nearest_the_anchor_of_a_hanging_chain_carries_the_whole_weight() {
    let n = 6;
    let graph = column(n, 2000.0, |f| f == n - 1);
    let broken = vec![false; graph.bonds().len()];
    let (solver, report) = solved(&graph, &broken);
    assert!(report.converged, "{report:?}");
    let block = graph.nodes()[0].mass * 9.81;
    let area = graph.bonds()[0].area;
    // Bond k joins blocks k and k+1 and holds the k+1 blocks below it.
    for k in 0..(n - 1) {
        let s = solver.stress(k);
        let expected = (k + 1) as f64 * block / area;
        assert!(
            (s.tension - expected).abs() <= 1e-4 * expected,
            "bond {k}: tension {} expected {expected}",
            s.tension
        );
        assert_eq!(s.compression, 0.0, "bond {k} is pulled, not pressed");
        assert!(s.shear <= 1e-6 * expected, "bond {k} shear {}", s.shear);
    }
    let top = solver.stress(n - 2).tension;
    assert!((top - (n - 1) as f64 * block / area).abs() <= 1e-4 * top);
}

#[test]
fn a_column_on_its_anchor_is_compressed_not_pulled() {
    let n = 5;
    let graph = column(n, 2400.0, |f| f == 0);
    let broken = vec![false; graph.bonds().len()];
    let (solver, report) = solved(&graph, &broken);
    assert!(report.converged);
    let block = graph.nodes()[0].mass * 9.81;
    let area = graph.bonds()[0].area;
    for k in 0..(n - 1) {
        let s = solver.stress(k);
        // Bond k (between blocks k and k+1) holds up the n − k − 1 blocks above it.
        let expected = (n - k - 1) as f64 * block / area;
        assert!(
            (s.compression - expected).abs() <= 1e-4 * expected,
            "bond {k}: compression {} expected {expected}",
            s.compression
        );
        assert_eq!(s.tension, 0.0, "bond {k} must not be in tension");
    }
}

#[test]
fn a_cantilever_root_takes_the_beam_theory_bending_stress() {
    // 3 m × 0.3 m × 0.3 m beam of 10 × 3 × 3 cells, its first column of cells anchored.
    let (l, h) = (3.0, 0.3);
    let f = box_grid_fracture([10, 3, 3], DVec3::new(l, h, h));
    let graph = BondGraph::from_fracture(&f, 2500.0, |i| i % 10 == 0).unwrap();
    let broken = vec![false; graph.bonds().len()];
    let (solver, report) = solved(&graph, &broken);
    assert!(report.converged, "{report:?}");
    // Root section at x = −1.2 (between cell columns 0 and 1): it holds 2.7 m of beam.
    let weight = 2500.0 * 9.81 * h * h * 2.7;
    let moment = weight * 2.7 / 2.0;
    let beam = moment * (h / 2.0) / (h * h * h * h / 12.0);
    let mut top = 0.0f64;
    let mut shear_force = 0.0;
    for (b, bond) in graph.bonds().iter().enumerate() {
        if bond.normal.x > 0.5 && (bond.centroid.x + 1.2).abs() < 1e-9 {
            top = top.max(solver.stress(b as u32).tension);
            shear_force += solver.bond_load(b as u32).0.y;
        }
    }
    assert!(
        (top - beam).abs() <= 0.1 * beam,
        "root tension {top} Pa, beam theory {beam} Pa"
    );
    // The section carries the weight beyond it as shear (force balance).
    assert!(
        (shear_force.abs() - weight).abs() <= 1e-3 * weight,
        "root shear {shear_force} N, weight {weight} N"
    );
}

#[test]
fn the_anchors_carry_the_whole_weight_of_a_wall() {
    // A 2 m × 1.5 m wall of 8 × 6 × 2 bricks on its bottom row.
    let f = box_grid_fracture([8, 6, 2], DVec3::new(2.0, 1.5, 0.4));
    let graph = BondGraph::from_fracture(&f, 2000.0, |i| (i / 8) % 6 == 0).unwrap();
    let broken = vec![false; graph.bonds().len()];
    let (solver, report) = solved(&graph, &broken);
    assert!(report.converged);
    let anchored = graph.anchored();
    let free_weight: f64 = graph
        .nodes()
        .iter()
        .zip(anchored)
        .filter(|(_, a)| !**a)
        .map(|(n, _)| n.mass * 9.81)
        .sum();
    // Forces the bonds from anchored to free bricks pass down (normals point up).
    let mut total = DVec3::ZERO;
    for (b, bond) in graph.bonds().iter().enumerate() {
        if anchored[bond.a as usize] != anchored[bond.b as usize] {
            total += solver.bond_load(b as u32).0;
        }
    }
    assert!(
        (total - DVec3::new(0.0, -free_weight, 0.0)).length() <= 1e-4 * free_weight,
        "anchor bonds carry {total}, the free bricks weigh {free_weight} N"
    );
}

#[test]
fn islands_without_an_anchor_carry_nothing() {
    let n = 4;
    let graph = column(n, 2000.0, |f| f == n - 1);
    // Break the middle bond: blocks 0 and 1 hang from nothing.
    let mut broken = vec![false; graph.bonds().len()];
    broken[1] = true;
    let (solver, _) = solved(&graph, &broken);
    assert!(!solver.is_supported(0) && !solver.is_supported(1));
    assert!(solver.is_supported(2) && solver.is_supported(3));
    assert_eq!(solver.stress(0), BondStress::default());
    // The top bond now holds one block only.
    let block = graph.nodes()[0].mass * 9.81 / graph.bonds()[0].area;
    assert!((solver.stress(2).tension - block).abs() <= 1e-4 * block);
}

#[test]
fn settled_islands_are_skipped_until_something_changes() {
    let graph = column(4, 2000.0, |f| f == 0);
    let mut broken = vec![false; graph.bonds().len()];
    let mut solver = StressSolver::new(&graph, SolverSettings::default());
    let first = solver.solve(&graph, &broken, G, &[]);
    assert_eq!((first.islands_solved, first.islands_skipped), (1, 0));
    let resting = solver.stress(2).compression;
    let again = solver.solve(&graph, &broken, G, &[]);
    assert_eq!((again.islands_solved, again.islands_skipped), (0, 1));
    assert_eq!(again.iterations, 0);
    // A push on the top block is a load for that solve only...
    let push = [(3, DVec3::new(0.0, -5000.0, 0.0))];
    let pushed = solver.solve(&graph, &broken, G, &push);
    assert_eq!(pushed.islands_solved, 1);
    // (the top bond is pressed harder: the push minus the top block's share of the
    // island's inertia)
    let with_push = solver.stress(2).compression;
    assert!(with_push > resting * 1.5, "{with_push} vs {resting}");
    // ... then the island is solved once more without it, and settles.
    let back = solver.solve(&graph, &broken, G, &[]);
    assert_eq!(back.islands_solved, 1);
    assert!((solver.stress(2).compression - resting).abs() <= 1e-4 * resting);
    assert_eq!(solver.solve(&graph, &broken, G, &[]).islands_solved, 0);
    broken[2] = true;
    assert_eq!(solver.solve(&graph, &broken, G, &[]).islands_solved, 1);
}

#[test]
fn a_hit_is_balanced_by_inertia_not_carried_to_the_anchors() {
    // A 10-block column; a sideways push on its top block.
    let graph = column(10, 2000.0, |f| f == 0);
    let broken = vec![false; graph.bonds().len()];
    let mut solver = StressSolver::new(&graph, SolverSettings::default());
    let push = DVec3::new(20_000.0, 0.0, 0.0);
    let report = solver.solve(&graph, &broken, DVec3::ZERO, &[(9, push)]);
    assert!(report.converged);
    // The bond under the pushed block shears with over half the push; the base bond with
    // (almost) none: the column's inertia takes the push.
    let (top, _) = solver.bond_load(8);
    let (base, base_moment) = solver.bond_load(0);
    assert!(top.x.abs() > 0.5 * push.x, "top shear force {top}");
    assert!(base.length() < 0.05 * push.x, "base force {base}");
    assert!(
        base_moment.length() < 0.05 * push.x * 0.2,
        "base moment {base_moment}"
    );
}

#[test]
fn overloaded_names_the_limit_passed() {
    let graph = column(3, 2000.0, |f| f == 2);
    let broken = vec![false; graph.bonds().len()];
    let (solver, _) = solved(&graph, &broken);
    let t = solver.stress(1).tension;
    let weak = StressLimits {
        compression: 1e9,
        tension: t * 0.9,
        shear: 1e9,
    };
    assert_eq!(solver.overloaded(&weak), vec![(1, Failure::Tension)]);
    let strong = StressLimits {
        tension: t * 1.1,
        ..weak
    };
    assert!(solver.overloaded(&strong).is_empty());
}

#[test]
fn bad_graphs_are_refused_with_the_bad_part_named() {
    let node = Node {
        mass: 1.0,
        centroid: DVec3::ZERO,
    };
    let bond = GraphBond {
        a: 0,
        b: 5,
        area: 1.0,
        centroid: DVec3::ZERO,
        normal: DVec3::X,
    };
    let e = BondGraph::new(vec![node, node], vec![bond], vec![false, false]).unwrap_err();
    assert!(e.to_string().contains("bond 0"), "{e}");
    let e = BondGraph::new(vec![node], vec![], vec![]).unwrap_err();
    assert!(e.to_string().contains("anchor"), "{e}");
    let nan = Node {
        mass: f64::NAN,
        ..node
    };
    let e = BondGraph::new(vec![nan], vec![], vec![false]).unwrap_err();
    assert!(e.to_string().contains("node 0"), "{e}");
}
