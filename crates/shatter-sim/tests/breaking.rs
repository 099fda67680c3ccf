//! The engine-free break logic on small bond graphs: outcomes, no physics engine.

#![allow(clippy::unwrap_used)]

use shatter_sim::breaking::{
    BondState, BreakCause, Graph, LOAD_ATTENUATION, Loads, components, contact_share,
};
use shatter_sim::testing::box_grid_fracture;

/// A row of `n` unit cubes: bonds 0-1, 1-2, ... (the grid's bond order is checked).
fn row(n: u32) -> (shatter_geom::fracture::Fracture, Vec<Vec<u32>>, Vec<f32>) {
    let f = box_grid_fracture([n, 1, 1], [f64::from(n), 1.0, 1.0].into());
    let adjacency = Graph::adjacency_of(&f.bonds, n as usize);
    let masses = vec![1.0; n as usize];
    (f, adjacency, masses)
}

#[test]
fn a_contact_load_spreads_two_bonds_deep_halving_each_step() {
    let (f, adjacency, masses) = row(5);
    let graph = Graph {
        bonds: &f.bonds,
        adjacency: &adjacency,
        masses: &masses,
    };
    let state = BondState::new(f.bonds.len(), 1000.0, 0.0);
    let mut loads = Loads::default();
    let end = (0..5u32)
        .find(|&i| adjacency[i as usize].len() == 1)
        .unwrap();
    loads.add_contact(&graph, &state, end, 800.0, glam::Vec3::X, 0.0);
    let mut values: Vec<f32> = loads.bonds.values().copied().collect();
    values.sort_by(|a, b| b.total_cmp(a));
    assert_eq!(
        values,
        vec![
            800.0,
            800.0 * LOAD_ATTENUATION,
            800.0 * LOAD_ATTENUATION.powi(2)
        ]
    );
}

#[test]
fn a_load_over_the_strength_breaks_and_the_row_splits_in_two() {
    let (f, adjacency, masses) = row(3);
    let graph = Graph {
        bonds: &f.bonds,
        adjacency: &adjacency,
        masses: &masses,
    };
    let mut state = BondState::new(f.bonds.len(), 100.0, 0.0);
    let mut loads = Loads::default();
    loads.add_bond(0, 150.0);
    loads.add_bond(1, 50.0);
    let broken = state.apply(&graph, &loads);
    assert_eq!(broken.len(), 1);
    assert_eq!(broken[0].cause, BreakCause::Impact);
    assert_eq!(state.intact(), 1);
    let body_of = [Some(0u8); 3];
    let parts = components(&graph, &state, &body_of, 0);
    assert_eq!(parts.len(), 2);
    assert_eq!(parts.iter().map(Vec::len).sum::<usize>(), 3);
}

#[test]
fn hits_below_the_strength_wear_a_bond_out() {
    let (f, adjacency, masses) = row(2);
    let graph = Graph {
        bonds: &f.bonds,
        adjacency: &adjacency,
        masses: &masses,
    };
    let mut state = BondState::new(1, 100.0, 0.5);
    let mut loads = Loads::default();
    loads.add_bond(0, 60.0); // each hit takes 0.5 × 0.6 = 0.3 of the health
    let mut hits = 0;
    while state.intact() == 1 && hits < 10 {
        let broken = state.apply(&graph, &loads);
        hits += 1;
        if let Some(b) = broken.first() {
            assert_eq!(b.cause, BreakCause::Damage);
        }
    }
    assert_eq!(hits, 4, "1.0 − 3 × 0.3 > 0, 1.0 − 4 × 0.3 ≤ 0");
    assert_eq!(state.broken_by, [0, 0, 1]);
}

#[test]
fn loads_under_the_endurance_limit_never_wear_a_bond() {
    use shatter_sim::breaking::ENDURANCE;
    let (f, adjacency, masses) = row(2);
    let graph = Graph {
        bonds: &f.bonds,
        adjacency: &adjacency,
        masses: &masses,
    };
    let mut state = BondState::new(1, 100.0, 0.5);
    // A steady load just under the limit (an object resting on the ground), step after
    // step: no wear at all.
    let mut loads = Loads::default();
    loads.add_bond(0, 100.0 * ENDURANCE * 0.99);
    for _ in 0..10_000 {
        assert!(state.apply(&graph, &loads).is_empty());
    }
    assert_eq!(state.health[0], 1.0);
    // At the limit it wears, by wear × x.
    let mut loads = Loads::default();
    loads.add_bond(0, 100.0 * ENDURANCE);
    assert!(state.apply(&graph, &loads).is_empty());
    assert!((state.health[0] - (1.0 - 0.5 * ENDURANCE)).abs() < 1e-6);
}

#[test]
fn without_wear_sub_threshold_hits_never_break() {
    let (f, adjacency, masses) = row(2);
    let graph = Graph {
        bonds: &f.bonds,
        adjacency: &adjacency,
        masses: &masses,
    };
    let mut state = BondState::new(1, 100.0, 0.0);
    let mut loads = Loads::default();
    loads.add_bond(0, 99.0);
    for _ in 0..1000 {
        assert!(state.apply(&graph, &loads).is_empty());
    }
    assert_eq!(
        contact_share(1.0, Some(1.0)),
        0.0,
        "a lone fragment's bonds carry nothing"
    );
}
