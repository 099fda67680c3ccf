//! Shared set-up for the behaviour tests.
#![allow(dead_code, clippy::unwrap_used)]

use glam::Vec3;
use shatter_sim::testing::box_grid_fracture;
use shatter_sim::{BondModel, ObjectId, ObjectSpec, ProjectileSpec, World, WorldSettings};

/// A 2 m × 1 m × 0.5 m wall of 8×4×2 bricks standing on the ground at z = 0.
pub fn wall_world(model: BondModel, break_force: f32) -> (World, ObjectId) {
    let mut world = World::new(WorldSettings {
        bond_model: model,
        ..WorldSettings::default()
    });
    let mut spec = ObjectSpec::from_fracture(
        box_grid_fracture([8, 4, 2], [2.0, 1.0, 0.5].into()),
        Vec3::new(0.0, 0.5, 0.0),
    );
    spec.break_force = Some(break_force);
    spec.anchored = true;
    let id = world.add_object(spec).unwrap();
    (world, id)
}

/// A 0.2 m steel ball flying at the wall's centre along −z.
pub fn shot(speed: f32) -> ProjectileSpec {
    ProjectileSpec {
        size: 0.2,
        speed,
        from: Vec3::new(0.1, 0.6, 1.5),
        to: Vec3::new(0.1, 0.6, 0.0),
        ..ProjectileSpec::default()
    }
}

/// Runs `steps` steps (starting the world) and returns the broken bond count.
pub fn run(world: &mut World, steps: usize) -> usize {
    world.start();
    for _ in 0..steps {
        world.step();
    }
    world.stats().bonds_broken
}

pub const MODELS: [BondModel; 2] = [BondModel::Joints, BondModel::Clusters];
