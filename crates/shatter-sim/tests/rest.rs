//! Clusters carry what hits them, not their own weight: a block at rest holds together,
//! the same block dropped from a height breaks on landing.
#![allow(clippy::unwrap_used, missing_docs)]

use shatter_sim::scene::Scene;

fn block_at(height: f32) -> shatter_sim::World {
    let text = format!(
        "[[objects]]\nshape = \"cube\"\nmethod = \"grid\"\ngrid = [8, 8, 8]\n\
         material = \"concrete\"\nposition = [0.0, {height}, 0.0]\nscale = [2.0, 2.0, 2.0]\n"
    );
    let mut world = Scene::parse(&text).unwrap().build(None).unwrap();
    world.start();
    world
}

#[test]
fn a_block_resting_on_the_ground_keeps_its_bonds() {
    // 2 m of concrete (19 t) standing on the ground: its weight is far above the bonds'
    // strength, but weight alone must not break them.
    let mut world = block_at(1.0);
    for _ in 0..120 {
        world.step();
    }
    assert_eq!(world.stats().bonds_broken, 0, "{:?}", world.stats());
    assert_eq!(world.stats().bodies, 1);
}

#[test]
fn the_same_block_dropped_from_twenty_metres_breaks() {
    let mut world = block_at(21.0);
    for _ in 0..180 {
        world.step();
    }
    assert!(world.stats().bonds_broken > 0, "{:?}", world.stats());
}

#[test]
fn a_block_at_rest_on_the_ground_falls_asleep_and_a_falling_one_is_awake() {
    use shatter_sim::testing::box_grid_fracture;
    use shatter_sim::{ObjectSpec, World, WorldSettings};
    let mut world = World::new(WorldSettings::default());
    let block = box_grid_fracture([1, 1, 1], [0.5, 0.5, 0.5].into());
    world
        .add_object(ObjectSpec::from_fracture(block, [0.0, 2.0, 0.0].into()))
        .unwrap();
    world.start();
    for _ in 0..10 {
        world.step();
    }
    assert_eq!(world.stats().sleeping_bodies, 0, "falling");
    for _ in 0..600 {
        world.step();
    }
    assert_eq!(world.stats().sleeping_bodies, 1, "{:?}", world.stats());
}
