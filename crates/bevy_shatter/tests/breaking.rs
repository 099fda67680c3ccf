//! Headless outcome tests: `MinimalPlugins` + avian + the plugin, a fixed 1/64 s step per
//! update (no wall-clock time).

#![allow(clippy::unwrap_used)]

use std::time::Duration;

use avian3d::prelude::*;
use bevy::prelude::*;
use bevy::time::TimeUpdateStrategy;
use bevy_shatter::{
    BondBroken, Breakable, BreakableError, FractureFailed, Fractured, ShatterObject, ShatterPlugin,
    ShatterSystems, Split,
};
use shatter_sim::MethodKind;

/// What arrived.
#[derive(Resource, Default)]
struct Log {
    fractured: usize,
    broken: usize,
    splits: Vec<Split>,
}

fn collect(
    mut log: ResMut<Log>,
    mut f: MessageReader<Fractured>,
    mut b: MessageReader<BondBroken>,
    mut s: MessageReader<Split>,
) {
    log.fractured += f.read().count();
    log.broken += b.read().count();
    log.splits.extend(s.read().cloned());
}

fn app() -> App {
    let mut app = App::new();
    app.add_plugins((
        MinimalPlugins,
        TransformPlugin,
        AssetPlugin::default(),
        PhysicsPlugins::default(),
        ShatterPlugin::default(),
    ))
    .init_asset::<Mesh>()
    .init_asset::<StandardMaterial>()
    .init_resource::<Log>()
    .insert_resource(TimeUpdateStrategy::ManualDuration(Duration::from_secs_f64(
        1.0 / 64.0,
    )))
    .add_systems(FixedUpdate, collect.after(ShatterSystems::Break));
    app.finish();
    app.cleanup();
    app
}

/// A 3 × 1.5 × 0.3 m wall standing on the ground at the origin, bonds of 50 kN.
fn wall(app: &mut App, breakable: Breakable, y: f32) -> Entity {
    let world = app.world_mut();
    let mesh = world
        .resource_mut::<Assets<Mesh>>()
        .add(Cuboid::new(3.0, 1.5, 0.3));
    let material = world
        .resource_mut::<Assets<StandardMaterial>>()
        .add(StandardMaterial::default());
    world
        .spawn((
            Mesh3d(mesh),
            MeshMaterial3d(material),
            Transform::from_xyz(0.0, y, 0.0),
            Breakable {
                break_force: Some(50_000.0),
                ..breakable
            },
        ))
        .id()
}

/// The game's own ground: a static box whose top is at y = 0.
fn ground(app: &mut App) {
    app.world_mut().spawn((
        RigidBody::Static,
        Collider::cuboid(40.0, 1.0, 40.0),
        Transform::from_xyz(0.0, -0.5, 0.0),
    ));
}

/// A steel ball (r = 0.15 m) flying along −z at `speed` at the wall's middle, 0.3 m in
/// front of it (close enough that a slow ball reaches the wall before it falls to the
/// ground).
fn ball(app: &mut App, speed: f32) -> Entity {
    app.world_mut()
        .spawn((
            RigidBody::Dynamic,
            Collider::sphere(0.15),
            ColliderDensity(7800.0),
            SweptCcd::default(),
            Transform::from_xyz(0.0, 0.8, 0.6),
            LinearVelocity(Vec3::new(0.0, 0.0, -speed)),
        ))
        .id()
}

/// Updates until the object is fractured (a bounded number of updates).
fn fractured(app: &mut App, object: Entity) {
    for _ in 0..2000 {
        app.update();
        if app.world().get::<ShatterObject>(object).is_some() {
            return;
        }
        std::thread::yield_now();
    }
    panic!("the wall was never fractured");
}

fn run(app: &mut App, steps: usize) {
    for _ in 0..steps {
        app.update();
    }
}

fn anchored_wall() -> Breakable {
    Breakable {
        anchored: true,
        ..Breakable::grid([6, 3, 1])
    }
}

#[test]
fn a_fast_ball_breaks_bonds_and_a_slow_one_does_not() {
    let mut outcomes = Vec::new();
    for speed in [40.0, 1.0] {
        let mut app = app();
        ground(&mut app);
        let w = wall(&mut app, anchored_wall(), 0.75);
        fractured(&mut app, w);
        let b = ball(&mut app, speed);
        run(&mut app, 90);
        let broken = app
            .world()
            .get::<ShatterObject>(w)
            .unwrap()
            .state
            .bonds_broken;
        let z = app.world().get::<Transform>(b).unwrap().translation.z;
        let v = app.world().get::<LinearVelocity>(b).unwrap().0.z;
        assert_eq!(app.world().resource::<Log>().broken, broken);
        outcomes.push((speed, broken, z, v));
    }
    eprintln!("(speed, bonds broken, ball z, ball vz): {outcomes:?}");
    let (_, fast_broken, _, _) = outcomes[0];
    let (_, slow_broken, slow_z, slow_v) = outcomes[1];
    assert!(fast_broken > 0, "the fast ball broke nothing: {outcomes:?}");
    // The slow ball reached the wall (it was stopped or bounced: it did not fly on at
    // 1 m/s, and it is in front of the wall) and broke nothing.
    assert!(
        slow_v > -0.9 && slow_z > 0.0,
        "the slow ball missed: {outcomes:?}"
    );
    assert_eq!(slow_broken, 0, "the slow ball broke bonds: {outcomes:?}");
}

#[test]
fn a_split_message_arrives_with_the_new_bodies() {
    let mut app = app();
    ground(&mut app);
    let w = wall(&mut app, anchored_wall(), 0.75);
    fractured(&mut app, w);
    assert_eq!(app.world().resource::<Log>().fractured, 1);
    ball(&mut app, 40.0);
    run(&mut app, 60);
    let log = app.world().resource::<Log>();
    assert!(!log.splits.is_empty(), "no Split message");
    let split = &log.splits[0];
    assert_eq!(split.object, w);
    assert!(split.parts.len() >= 2 && split.bodies.len() == split.parts.len());
    let object = app.world().get::<ShatterObject>(w).unwrap();
    assert!(object.bodies() >= 2, "the wall is still one body");
    // The new bodies exist and every fragment of the split is still held by a body
    // (later splits may have moved it on to a newer one).
    for body in &split.bodies {
        assert!(app.world().get_entity(*body).is_ok(), "body {body} missing");
    }
    for &f in split.parts.iter().flatten() {
        assert!(
            object.body_of[f as usize].is_some(),
            "fragment {f} lost its body"
        );
    }
}

/// World-space centroid of every fragment.
fn fragment_centres(app: &mut App, object: Entity) -> Vec<Vec3> {
    let obj = app.world().get::<ShatterObject>(object).unwrap().clone();
    obj.fragments
        .iter()
        .zip(&obj.fracture.fragments)
        .map(|(e, f)| {
            let t = app
                .world()
                .get::<ChildOf>(*e)
                .and_then(|c| app.world().get::<Transform>(c.parent()))
                .copied()
                .unwrap_or_default();
            t.transform_point(f.centroid.as_vec3().to_array().into())
        })
        .collect()
}

#[test]
fn a_game_owned_ground_stops_falling_debris() {
    let mut app = app();
    ground(&mut app);
    // An unanchored wall of weak bonds dropped from 4 m: it lands and breaks up.
    let w = wall(
        &mut app,
        Breakable {
            break_force: Some(2_000.0),
            ..Breakable::grid([6, 3, 1])
        },
        4.0,
    );
    fractured(&mut app, w);
    let start = fragment_centres(&mut app, w);
    run(&mut app, 240);
    let end = fragment_centres(&mut app, w);
    let drop = start
        .iter()
        .zip(&end)
        .map(|(a, b)| a.y - b.y)
        .fold(0.0f32, f32::max);
    assert!(drop > 2.0, "the wall did not fall: {drop}");
    let lowest = end.iter().map(|c| c.y).fold(f32::MAX, f32::min);
    let object = app.world().get::<ShatterObject>(w).unwrap();
    eprintln!(
        "drop {drop} m, lowest centroid {lowest} m, {} bonds broken, {} bodies",
        object.state.bonds_broken,
        object.bodies()
    );
    // Cells are 0.5 × 0.5 × 0.3 m: a centroid at rest on the ground is ≥ 0.15 m up.
    assert!(
        lowest > 0.1,
        "debris sank into the ground: lowest centroid {lowest}"
    );
}

#[test]
fn two_runs_with_the_same_seed_end_in_the_same_state() {
    let run_once = || {
        let mut app = app();
        ground(&mut app);
        let w = wall(
            &mut app,
            Breakable {
                method: MethodKind::Voronoi,
                pieces: 12,
                seed: 7,
                anchored: true,
                ..Breakable::default()
            },
            0.75,
        );
        fractured(&mut app, w);
        ball(&mut app, 40.0);
        run(&mut app, 60);
        let broken = app
            .world()
            .get::<ShatterObject>(w)
            .unwrap()
            .state
            .broken
            .clone();
        (fragment_centres(&mut app, w), broken)
    };
    let (a, broken_a) = run_once();
    let (b, broken_b) = run_once();
    assert_eq!(a.len(), b.len());
    assert_eq!(broken_a, broken_b);
    assert_eq!(a, b, "the same seed gave different end states");
}

#[test]
fn bad_input_is_reported_as_a_message_not_a_panic() {
    let mut app = app();
    app.init_resource::<Failures>().add_systems(
        FixedUpdate,
        |mut r: MessageReader<FractureFailed>, mut log: ResMut<Failures>| {
            log.0.extend(r.read().map(|m| m.error.clone()));
        },
    );
    // No mesh at all, and a joints-model wall (not simulated by the plugin yet).
    app.world_mut()
        .spawn((Transform::default(), Breakable::default()));
    wall(
        &mut app,
        Breakable {
            bond_model: shatter_sim::BondModel::Joints,
            ..Breakable::grid([2, 1, 1])
        },
        0.75,
    );
    run(&mut app, 200);
    let failures = &app.world().resource::<Failures>().0;
    assert!(failures.contains(&BreakableError::NoMesh), "{failures:?}");
    assert!(
        failures
            .iter()
            .any(|e| matches!(e, BreakableError::Unsupported(_))),
        "{failures:?}"
    );
    assert_eq!(app.world().resource::<Log>().fractured, 0);
}

#[derive(Resource, Default)]
struct Failures(Vec<BreakableError>);

/// A textured wall's fragments keep its texture mapping: the surface faces carry the
/// wall's own UVs (a Bevy cuboid maps each face onto [0, 1]²), so the entity's material
/// draws the debris as it drew the wall; cut faces get generated UVs too.
#[test]
fn fragments_keep_the_meshs_uvs_for_the_entitys_material() {
    let mut app = app();
    let object = wall(
        &mut app,
        Breakable {
            method: MethodKind::Voronoi,
            pieces: 12,
            ..Breakable::default()
        },
        0.75,
    );
    fractured(&mut app, object);
    let world = app.world_mut();
    let mut q = world.query::<(&Mesh3d, Option<&bevy_shatter::Fragment>)>();
    let handles: Vec<(Handle<Mesh>, bool)> = q
        .iter(world)
        .map(|(m, f)| (m.0.clone(), f.is_some()))
        .collect();
    let meshes = world.resource::<Assets<Mesh>>();
    let (mut surface, mut spread) = (0, Vec::new());
    for (handle, is_surface) in handles {
        let mesh = meshes.get(&handle).unwrap();
        let n = mesh.attribute(Mesh::ATTRIBUTE_POSITION).unwrap().len();
        let Some(bevy::mesh::VertexAttributeValues::Float32x2(uv)) =
            mesh.attribute(Mesh::ATTRIBUTE_UV_0)
        else {
            panic!("a fragment mesh without UVs");
        };
        assert_eq!(uv.len(), n);
        assert!(uv.iter().flatten().all(|x| x.is_finite()));
        if is_surface {
            surface += 1;
            assert!(
                uv.iter()
                    .flatten()
                    .all(|x| (-1e-4..=1.0 + 1e-4).contains(x)),
                "a surface UV outside the cuboid's [0, 1]"
            );
            spread.extend(uv.iter().map(|p| p[0]));
        }
    }
    assert!(surface >= 8, "{surface} surface meshes");
    let (lo, hi) = spread
        .iter()
        .fold((f32::MAX, f32::MIN), |(a, b), &x| (a.min(x), b.max(x)));
    assert!(hi - lo > 0.9, "the UVs cover the texture: {lo}..{hi}");
}
