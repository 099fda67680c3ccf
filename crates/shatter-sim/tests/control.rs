//! Reset, lifetime, determinism and the NaN guard, for both bond models.
#![allow(clippy::unwrap_used, missing_docs)]

mod common;
use common::*;
use glam::Vec3;
use shatter_sim::{
    BondModel, FractureParams, FractureSource, MethodKind, ObjectId, ObjectSpec, Shape, SimEvent,
    World, WorldSettings,
};

fn poses(world: &World, id: ObjectId) -> Vec<(u32, [u32; 7])> {
    world
        .fragment_poses(id)
        .into_iter()
        .map(|(f, p)| {
            let t = p.translation.to_array().map(f32::to_bits);
            let r = p.rotation.to_array().map(f32::to_bits);
            (f, [t[0], t[1], t[2], r[0], r[1], r[2], r[3]])
        })
        .collect()
}

#[test]
fn reset_restores_the_initial_state_exactly() {
    for model in MODELS {
        let (mut world, id) = wall_world(model, 5_000.0);
        let initial = poses(&world, id);
        let digest = world.digest();
        world.fire(shot(40.0));
        run(&mut world, 40);
        assert!(world.stats().bonds_broken > 0);
        assert_ne!(poses(&world, id), initial);
        world.reset();
        assert_eq!(poses(&world, id), initial, "{model:?}");
        assert_eq!(world.digest(), digest, "{model:?}");
        assert_eq!(world.stats().bonds_broken, 0);
        assert!(world.projectiles().is_empty());
    }
}

#[test]
fn lifetime_removes_objects() {
    for model in MODELS {
        let (mut world, id) = wall_world(model, 50_000.0);
        let mut spec = world.object_spec(id).unwrap().clone();
        spec.last = Some(0.5);
        world.edit_object(id, spec).unwrap();
        run(&mut world, 20);
        assert!(world.object_alive(id));
        run(&mut world, 15);
        assert!(
            !world.object_alive(id),
            "{model:?}: object outlived its 0.5 s"
        );
        assert_eq!(world.stats().fragments, 0);
        assert!(world.take_events().contains(&SimEvent::Expired(id.0)));
        world.reset();
        assert!(world.object_alive(id), "reset brings the object back");
    }
}

#[test]
fn two_runs_give_the_same_digest() {
    for model in MODELS {
        let digest = || {
            let (mut world, _) = wall_world(model, 5_000.0);
            world.schedule_projectile(0.1, shot(40.0));
            run(&mut world, 50);
            (world.digest(), world.stats().bonds_broken)
        };
        let (a, broken) = digest();
        assert!(broken > 0);
        assert_eq!(a, digest().0, "{model:?}");
    }
}

#[test]
fn a_diverging_body_is_removed_and_reported() {
    for model in MODELS {
        let (mut world, id) = wall_world(model, 5_000.0);
        let mut spec = world.object_spec(id).unwrap().clone();
        spec.anchored = false;
        world.edit_object(id, spec).unwrap();
        world.set_object_velocity(id, Vec3::ZERO, Vec3::new(f32::NAN, 0.0, 0.0), Vec3::ZERO);
        run(&mut world, 2);
        let events = world.take_events();
        assert!(
            events
                .iter()
                .any(|e| matches!(e, SimEvent::Diverged { object: Some(o), .. } if *o == id.0)),
            "{model:?}: {events:?}"
        );
        assert!(world.stats().diverged > 0);
        for (_, p) in world.fragment_poses(id) {
            assert!(p.translation.is_finite() && p.rotation.is_finite());
        }
    }
}

#[test]
fn the_debris_cap_removes_loose_fragments_beyond_it() {
    for model in MODELS {
        let (mut world, id) = wall_world(model, 5_000.0);
        let mut settings = *world.settings();
        settings.max_debris = Some(3);
        world.set_settings(settings);
        world.fire(shot(60.0));
        run(&mut world, 40);
        let s = world.stats();
        assert!(s.debris_removed > 0, "{model:?}: nothing was capped");
        // Every removed body took at least one fragment with it.
        assert!(s.fragments + s.debris_removed <= 64, "{model:?}");
        assert!(world.fragment_poses(id).len() < 64, "{model:?}");
    }
}

/// A cube of `pieces` Voronoi cells with bonds that break at a touch, its bottom `height`
/// above the ground at `x`.
fn loose_cube(world: &mut World, x: f32, height: f32, pieces: u32) -> ObjectId {
    let mut spec = ObjectSpec::from_fracture(Default::default(), Vec3::new(x, height + 0.5, 0.0));
    spec.source = FractureSource::Shape {
        shape: Shape::Cube,
        params: FractureParams {
            method: Some(MethodKind::Voronoi),
            pieces,
            seed: 7,
            ..FractureParams::default()
        },
    };
    spec.break_force = Some(0.01);
    world.add_object(spec).unwrap()
}

#[test]
fn the_debris_cap_removes_the_smallest_settled_pieces_first() {
    let mut world = World::new(WorldSettings {
        bond_model: BondModel::Clusters,
        max_debris: None,
        ..WorldSettings::default()
    });
    // One cube falls apart on the ground at once and settles; another falls from 60 m
    // and shatters about 3.5 s later, when the first one's pieces are asleep.
    let settled = loose_cube(&mut world, -3.0, 0.0, 12);
    let falling = loose_cube(&mut world, 3.0, 60.0, 12);
    world.start();
    for _ in 0..190 {
        world.step();
    }
    let asleep = world.stats().sleeping_bodies;
    let first = world.fragment_poses(settled).len();
    assert!(asleep >= first, "{asleep} asleep of {first}");
    // Now a cap that leaves room for two of the falling cube's pieces.
    let cap = first + 2;
    let mut settings = *world.settings();
    settings.max_debris = Some(cap);
    // (set_settings resets the world: run the same again under the cap.)
    world.set_settings(settings);
    world.start();
    for _ in 0..300 {
        world.step();
    }
    let removed = world.stats().debris_removed;
    assert!(removed > 0, "nothing was capped");
    // (The falling cube's intact part, one body with several fragments, is not debris.)
    let fracture = world.object_fracture(settled).unwrap();
    let kept: Vec<u32> = world
        .fragment_poses(settled)
        .iter()
        .map(|(f, _)| *f)
        .collect();
    let volume = |f: u32| fracture.fragments[f as usize].volume;
    let gone: Vec<u32> = (0..fracture.fragments.len() as u32)
        .filter(|f| !kept.contains(f))
        .collect();
    assert!(!gone.is_empty(), "no settled piece was removed");
    let largest_gone = gone.iter().map(|&f| volume(f)).fold(0.0, f64::max);
    let smallest_kept = kept
        .iter()
        .map(|&f| volume(f))
        .fold(f64::INFINITY, f64::min);
    assert!(
        largest_gone <= smallest_kept,
        "removed a settled piece of {largest_gone} m³ before one of {smallest_kept} m³"
    );
    // The falling cube's pieces were moving when the cap took the settled ones.
    assert_eq!(
        world.fragment_poses(falling).len(),
        12,
        "moving pieces went before settled ones"
    );
}

#[test]
fn a_ray_finds_the_object_and_the_point_under_it() {
    for model in MODELS {
        let (mut world, id) = wall_world(model, 5_000.0);
        // Before start (the app clicks on objects while stopped) and after some steps.
        for _ in 0..2 {
            let (hit, point) = world
                .ray_cast(Vec3::new(0.3, 0.5, 5.0), Vec3::new(0.0, 0.0, -1.0))
                .unwrap();
            assert_eq!(hit, id);
            assert!((point.z - 0.25).abs() < 0.02, "{model:?}: hit at {point}");
            run(&mut world, 5);
        }
        assert!(
            world
                .ray_cast(Vec3::new(5.0, 0.5, 5.0), Vec3::new(0.0, 0.0, -1.0))
                .is_none()
        );
    }
}

#[test]
fn pause_holds_and_edit_and_delete_act_on_one_object() {
    for model in MODELS {
        let (mut world, id) = wall_world(model, 5_000.0);
        world.start();
        world.step();
        world.pause();
        assert!(!world.step(), "a paused world does not step");
        assert_eq!(world.stats().steps, 1);
        world.resume();
        assert!(world.step());
        let mut spec = world.object_spec(id).unwrap().clone();
        spec.position.x += 3.0;
        spec.color = [1.0, 0.0, 0.0];
        world.edit_object(id, spec).unwrap();
        assert_eq!(world.object_color(id), Some([1.0, 0.0, 0.0]));
        assert!(
            world
                .ray_cast(Vec3::new(3.3, 0.5, 5.0), Vec3::NEG_Z)
                .is_some()
        );
        let mut bad = world.object_spec(id).unwrap().clone();
        bad.scale = Vec3::new(1.0, -1.0, 1.0);
        assert!(world.edit_object(id, bad).is_err());
        assert_eq!(
            world.object_color(id),
            Some([1.0, 0.0, 0.0]),
            "a bad edit changes nothing"
        );
        world.delete_object(id).unwrap();
        assert_eq!(world.stats().fragments, 0);
        assert!(world.object_ids().is_empty());
        world.reset();
        assert!(
            world.object_ids().is_empty(),
            "a deleted object stays deleted"
        );
    }
}
