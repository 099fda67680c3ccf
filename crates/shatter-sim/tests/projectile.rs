//! Projectiles against a wall, for both bond models.
#![allow(clippy::unwrap_used, missing_docs)]

mod common;
use common::*;
use shatter_sim::BondModel;

/// (break force, fast speed) per model: the joints model carries the wall's weight in its
/// joints, so it needs a higher break force to stand.
fn params(model: BondModel) -> (f32, f32) {
    match model {
        BondModel::Joints => (12_000.0, 60.0),
        BondModel::Clusters => (20_000.0, 40.0),
    }
}

#[test]
fn a_fast_projectile_breaks_bonds_and_a_slow_one_none() {
    for model in MODELS {
        let (bf, fast) = params(model);
        let (mut world, _) = wall_world(model, bf);
        world.fire(shot(fast));
        let broken_fast = run(&mut world, 45);
        let (mut world, _) = wall_world(model, bf);
        world.fire(shot(1.0));
        let broken_slow = run(&mut world, 45);
        assert!(broken_fast > 0, "{model:?}: fast shot broke nothing");
        assert_eq!(broken_slow, 0, "{model:?}: slow shot broke bonds");
    }
}

#[test]
fn a_higher_break_force_raises_the_threshold() {
    for model in MODELS {
        let (bf, fast) = params(model);
        let (mut world, _) = wall_world(model, bf);
        world.fire(shot(fast));
        let weak = run(&mut world, 45);
        let (mut world, _) = wall_world(model, bf * 10.0);
        world.fire(shot(fast));
        let strong = run(&mut world, 45);
        assert!(weak > 0, "{model:?}: weak wall did not break");
        assert_eq!(
            strong, 0,
            "{model:?}: a 10x stronger wall broke ({strong} bonds)"
        );
    }
}
