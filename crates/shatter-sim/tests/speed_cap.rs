//! The contact speed cap (`WorldSettings::contact_speed_cap`): a block of bricks landing
//! on the ground shatters into a pile without bricks flung out of it.
#![allow(clippy::unwrap_used)]

mod common;

use common::{run, shot, wall_world};
use glam::Vec3;
use shatter_geom::DVec3;
use shatter_sim::BondModel;
use shatter_sim::testing::box_grid_fracture;
use shatter_sim::{ObjectSpec, World, WorldSettings};

/// Drop height of the block's bottom (m).
const HEIGHT: f32 = 4.0;

/// `bench scale`'s 2,000-brick landing: 13 × 13 × 12 bricks of 0.1 m with 2 kN bonds,
/// dropped from 4 m. Returns the fastest any body moved after a step over 2 s, and the
/// bodies the cap slowed.
fn landing(cap: bool) -> (f32, usize) {
    let mut world = World::new(WorldSettings {
        contact_speed_cap: cap,
        ..WorldSettings::default()
    });
    let mut spec = ObjectSpec::from_fracture(
        box_grid_fracture([13, 13, 12], DVec3::ONE),
        Vec3::new(0.0, HEIGHT + 0.65, 0.0),
    );
    spec.scale = Vec3::new(1.3, 1.3, 1.2);
    spec.break_force = Some(2_000.0);
    world.add_object(spec).unwrap();
    world.start();
    let mut fastest = 0.0f32;
    for _ in 0..120 {
        world.step();
        fastest = fastest.max(world.fastest_speed());
    }
    assert!(world.stats().bonds_broken > 1_000, "the block shattered");
    (fastest, world.stats().speeds_capped)
}

#[test]
fn a_landing_block_flings_no_brick_out_of_its_pile() {
    // What nothing in the fall can give a brick: twice the speed the block lands at.
    let impact = (2.0 * 9.81 * HEIGHT).sqrt();
    let (uncapped, none) = landing(false);
    assert_eq!(none, 0);
    // The case provokes the solver's fling (without the cap, 39 m/s with Rapier 0.36).
    assert!(
        uncapped > 2.0 * impact,
        "without the cap the fastest brick moved at {uncapped} m/s"
    );
    let (capped, slowed) = landing(true);
    assert!(slowed > 0, "the cap slowed no body");
    assert!(
        capped <= 2.0 * impact,
        "with the cap a brick still moved at {capped} m/s (landed at {impact})"
    );
}

/// A heavy block at 10 m/s against a row of two loose bricks that touch it and each
/// other, no gravity, three steps (Rapier passes the push on one brick per step: the far
/// brick moves at the second). Returns the momentum along x before and after, and the far
/// brick's speed at the end.
fn row(cap: bool) -> (f32, f32, f32) {
    let mut world = World::new(WorldSettings {
        contact_speed_cap: cap,
        gravity: Vec3::ZERO,
        ground: false,
        ..WorldSettings::default()
    });
    let cube = |x: f32, side: f32| {
        let mut spec =
            ObjectSpec::from_fracture(box_grid_fracture([1, 1, 1], DVec3::ONE), Vec3::X * x);
        spec.scale = Vec3::splat(side);
        spec
    };
    let mut heavy = cube(0.0, 0.5);
    heavy.material.density *= 50.0;
    let block = world.add_object(heavy).unwrap();
    let brick = cube(0.35, 0.2);
    let brick_mass = brick.material.density * 0.2f32.powi(3);
    let near = world.add_object(brick).unwrap();
    let far = world.add_object(cube(0.55, 0.2)).unwrap();
    world.start();
    world.set_object_velocity(block, Vec3::ZERO, Vec3::X * 10.0, Vec3::ZERO);
    let momentum = |world: &World| -> f32 {
        [block, near, far]
            .iter()
            .map(|&id| world.object_momentum(id, Vec3::ZERO).0.x)
            .sum()
    };
    let before = momentum(&world);
    for _ in 0..3 {
        world.step();
    }
    let speed = world.object_momentum(far, Vec3::ZERO).0.x / brick_mass;
    (before, momentum(&world), speed)
}

#[test]
fn a_push_down_a_row_of_bricks_is_not_capped_and_keeps_its_momentum() {
    let (before, free, free_speed) = row(false);
    // The block (50 times as dense) drives the bricks ahead of it at about its speed.
    assert!(
        free_speed > 5.0,
        "without the cap the far brick moved at {free_speed}"
    );
    let (_, capped, capped_speed) = row(true);
    for after in [free, capped] {
        assert!(
            (after - before).abs() <= 1e-4 * before,
            "momentum {before} before the steps, {after} after"
        );
    }
    assert!(
        (capped_speed - free_speed).abs() <= 1e-4 * free_speed,
        "the far brick moved at {capped_speed} with the cap, {free_speed} without"
    );
}

/// The joints model's wall hit by a shot at 120 m/s (a bound from what touches its bricks
/// would slow 12 of them): bonds broken, bodies capped and the final
/// state's digest.
fn joints_wall(cap: bool) -> (usize, usize, u64) {
    let (mut world, _) = wall_world(BondModel::Joints, 12_000.0);
    world.set_settings(WorldSettings {
        contact_speed_cap: cap,
        ..*world.settings()
    });
    world.fire(shot(120.0));
    let broken = run(&mut world, 45);
    (broken, world.stats().speeds_capped, world.digest())
}

#[test]
fn bodies_held_by_joints_are_left_to_them() {
    // Rapier moves a jointed wall as one within a step: a shot sets bricks far from the
    // one it hits moving at once, which a bound from what touches them would slow.
    let (free, _, free_digest) = joints_wall(false);
    let (capped, slowed, digest) = joints_wall(true);
    assert!(free > 0, "the shot broke no bond");
    assert_eq!(slowed, 0, "the cap slowed {slowed} jointed bodies");
    assert_eq!((capped, digest), (free, free_digest));
}
