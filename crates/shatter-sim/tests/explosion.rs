//! Explosions break the bonds inside their radius and none far outside.
#![allow(clippy::unwrap_used, missing_docs)]

mod common;
use common::*;
use glam::Vec3;
use shatter_sim::ExplosionSpec;

#[test]
fn an_explosion_breaks_bonds_inside_its_radius_and_none_far_outside() {
    for model in MODELS {
        // The joints model carries the wall's weight and its jelly-like ringing in every
        // joint, so it needs a larger margin between break force and static load.
        let (break_force, power) = match model {
            shatter_sim::BondModel::Joints => (40_000.0, 12_000.0),
            shatter_sim::BondModel::Clusters => (20_000.0, 1_000.0),
        };
        let (mut world, id) = wall_world(model, break_force);
        let centre = Vec3::new(-1.0, 1.0, 0.3);
        let radius = 0.6;
        let fracture = world.object_fracture(id).unwrap();
        let pose = world.fragment_pose(id, 0).unwrap();
        world.start();
        world.step();
        world.explode(ExplosionSpec {
            position: centre,
            radius,
            power,
        });
        for _ in 0..3 {
            world.step();
        }
        let states = world.bond_states(id).unwrap();
        let (mut inside, mut far) = (0, 0);
        for (bond, broken) in fracture.bonds.iter().zip(&states) {
            let d = (pose.transform_point(bond.centroid.as_vec3()) - centre).length();
            if *broken && d < radius {
                inside += 1;
            }
            if *broken && d > 2.5 * radius {
                far += 1;
            }
        }
        assert!(inside > 0, "{model:?}: nothing broke inside the radius");
        assert_eq!(far, 0, "{model:?}: {far} bonds broke far outside");
    }
}

#[test]
fn an_explosion_throws_no_body_faster_than_the_launch_limit() {
    for model in MODELS {
        let (mut world, _) = wall_world(model, 20_000.0);
        let limit = 50.0;
        let mut settings = *world.settings();
        settings.max_launch_speed = limit;
        world.set_settings(settings);
        world.start();
        world.step();
        // A blast that would throw a 30 kg brick at tens of km/s: past `max_speed`, where
        // the body would count as diverged.
        world.explode(ExplosionSpec {
            position: Vec3::new(0.0, 0.5, 0.3),
            radius: 1.0,
            power: 2_000_000.0,
        });
        let mut fastest = 0.0f32;
        for _ in 0..3 {
            world.step();
            fastest = fastest.max(world.fastest_speed());
        }
        let s = world.stats();
        assert_eq!(s.diverged, 0, "{model:?}: {} bodies diverged", s.diverged);
        assert!(s.bonds_broken > 0, "{model:?}: nothing broke");
        // Gravity adds at most 3 steps × 9.81 m/s² × dt; contacts and joints only take
        // from the blast's push.
        assert!(
            fastest <= limit + 0.5,
            "{model:?}: fastest body at {fastest} m/s, limit {limit}"
        );
        if model == shatter_sim::BondModel::Clusters {
            // Loose bricks fly at the limit (the joints still hold theirs back a little).
            assert!(fastest > limit * 0.9, "{model:?}: fastest at {fastest} m/s");
        }
    }
}
