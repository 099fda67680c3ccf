//! Runtime fracture in the plugin (`Breakable::runtime`), headless: `MinimalPlugins` +
//! avian + the plugin, a fixed 1/64 s step per update. The object is a stone boulder (an
//! icosphere of radius 0.5 m resting on the ground at the origin), hit by a steel ball.

#![allow(clippy::unwrap_used)]

use std::time::Duration;

use avian3d::prelude::*;
use bevy::prelude::*;
use bevy::time::TimeUpdateStrategy;
use bevy_shatter::{Breakable, RuntimeFractured, ShatterObject, ShatterPlugin, ShatterSystems};
use shatter_sim::runtime::{FractureTiming, RuntimeFracture};

/// What arrived.
#[derive(Resource, Default)]
struct Log {
    cuts: Vec<RuntimeFractured>,
}

fn collect(mut log: ResMut<Log>, mut cut: MessageReader<RuntimeFractured>) {
    log.cuts.extend(cut.read().cloned());
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

/// The game's own ground: a static box whose top is at y = 0.
fn ground(app: &mut App) {
    app.world_mut().spawn((
        RigidBody::Static,
        Collider::cuboid(40.0, 1.0, 40.0),
        Transform::from_xyz(0.0, -0.5, 0.0),
    ));
}

/// An `on_impact` boulder: radius 0.5 m, resting on the ground, 40 cells at the first
/// cut, bonds of 100 kN (so a hit cuts it from 100 kN · dt ≈ 1560 N·s, unless `runtime`
/// says otherwise; its weight gives the ground about 190 N·s a step, and its first
/// contact with the ground about 950 N·s).
fn boulder(app: &mut App, anchored: bool, runtime: RuntimeFracture) -> Entity {
    let world = app.world_mut();
    let mesh = Sphere::new(0.5).mesh().ico(2).unwrap();
    // Its lowest vertex on the ground, so it does not land with a hit.
    let Some(bevy::mesh::VertexAttributeValues::Float32x3(positions)) =
        mesh.attribute(Mesh::ATTRIBUTE_POSITION)
    else {
        panic!("an icosphere without positions");
    };
    let lowest = positions.iter().map(|p| p[1]).fold(f32::MAX, f32::min);
    let mesh = world.resource_mut::<Assets<Mesh>>().add(mesh);
    let material = world
        .resource_mut::<Assets<StandardMaterial>>()
        .add(StandardMaterial::default());
    world
        .spawn((
            Mesh3d(mesh),
            MeshMaterial3d(material),
            Transform::from_xyz(0.0, -lowest, 0.0),
            Breakable {
                pieces: 40,
                seed: 3,
                break_force: Some(100_000.0),
                anchored,
                runtime: RuntimeFracture {
                    timing: FractureTiming::OnImpact,
                    ..runtime
                },
                ..Breakable::default()
            },
        ))
        .id()
}

/// A steel ball (r = 0.15 m, about 110 kg) flying along −z at `speed` at the middle of
/// `boulder`, 0.35 m in front of it.
fn ball(app: &mut App, boulder: Entity, speed: f32) -> Entity {
    let y = app.world().get::<Transform>(boulder).unwrap().translation.y;
    app.world_mut()
        .spawn((
            RigidBody::Dynamic,
            Collider::sphere(0.15),
            ColliderDensity(7800.0),
            SweptCcd::default(),
            Transform::from_xyz(0.0, y, 1.0),
            LinearVelocity(Vec3::new(0.0, 0.0, -speed)),
        ))
        .id()
}

/// Updates until the object has its record (a bounded number of updates).
fn spawned(app: &mut App, object: Entity) {
    for _ in 0..2000 {
        app.update();
        if app.world().get::<ShatterObject>(object).is_some() {
            return;
        }
        std::thread::yield_now();
    }
    panic!("the boulder was never spawned");
}

fn run(app: &mut App, steps: usize) {
    for _ in 0..steps {
        app.update();
    }
}

/// Every object record: (entity, record).
fn objects(app: &mut App) -> Vec<(Entity, ShatterObject)> {
    let world = app.world_mut();
    let mut q = world.query::<(Entity, &ShatterObject)>();
    q.iter(world).map(|(e, o)| (e, o.clone())).collect()
}

/// Updates until the first runtime cut (at most `steps` updates); the cut's message.
fn first_cut(app: &mut App, steps: usize) -> RuntimeFractured {
    for _ in 0..steps {
        app.update();
        if let Some(cut) = app.world().resource::<Log>().cuts.first() {
            return cut.clone();
        }
    }
    panic!("no runtime cut in {steps} steps");
}

const THRESHOLD_FROM_STRENGTH: RuntimeFracture = RuntimeFracture {
    timing: FractureTiming::OnImpact,
    impulse: None,
    depth: 1,
    min_size: 0.1,
};

#[test]
fn an_on_impact_object_stays_one_whole_body_while_nothing_hits_it() {
    for anchored in [false, true] {
        let mut app = app();
        ground(&mut app);
        let b = boulder(&mut app, anchored, THRESHOLD_FROM_STRENGTH);
        spawned(&mut app, b);
        let start = app.world().get::<ShatterObject>(b).unwrap().clone();
        assert_eq!(start.fracture.fragments.len(), 1, "not one whole fragment");
        assert_eq!(start.fracture.bonds.len(), 0);
        assert_eq!(start.level, 0);
        assert_eq!(start.parent, None);
        let body = start.body_of[0].expect("the whole fragment has a body");
        let kind = *app.world().get::<RigidBody>(body).unwrap();
        assert_eq!(
            kind.is_dynamic(),
            !anchored,
            "anchored {anchored}: {kind:?}"
        );
        run(&mut app, 120);
        let all = objects(&mut app);
        assert_eq!(all.len(), 1, "anchored {anchored}: an object appeared");
        let end = &all[0].1;
        assert_eq!(end.body_of, vec![Some(body)], "anchored {anchored}");
        assert!(app.world().resource::<Log>().cuts.is_empty());
        // Resting on the ground, not fallen through it.
        let y = app.world().get::<Transform>(body).unwrap().translation.y;
        assert!(
            (0.45..0.51).contains(&y),
            "anchored {anchored}: centre at {y}"
        );
    }
}

#[test]
fn a_fast_ball_cuts_it_into_fragments_crowding_at_the_impact() {
    let mut app = app();
    ground(&mut app);
    let b = boulder(&mut app, true, THRESHOLD_FROM_STRENGTH);
    spawned(&mut app, b);
    let old_body = app.world().get::<ShatterObject>(b).unwrap().body_of[0].unwrap();
    ball(&mut app, b, 40.0);
    let cut = first_cut(&mut app, 30);
    assert_eq!(cut.parent, b);
    assert_eq!(cut.fragment, 0);
    assert_eq!(cut.level, 1);
    let parent = app.world().get::<ShatterObject>(b).unwrap().clone();
    assert_eq!(parent.body_of, vec![None], "the intact body is still held");
    assert!(
        app.world().get_entity(old_body).is_err(),
        "the intact body was not despawned"
    );
    let child = app
        .world()
        .get::<ShatterObject>(cut.object)
        .unwrap()
        .clone();
    let n = child.fracture.fragments.len();
    assert_eq!(n, cut.fragments);
    assert!(n >= 20, "only {n} fragments");
    assert_eq!((child.level, child.parent), (1, Some(b)));
    assert!(
        !child.fracture.bonds.is_empty(),
        "the fragments are not bonded"
    );
    assert_eq!(child.bodies(), 1, "the cut is not one body");
    // The volume is the boulder's.
    let v0 = parent.fracture.fragments[0].volume;
    let v1: f64 = child.fracture.fragments.iter().map(|f| f.volume).sum();
    assert!((v1 - v0).abs() < 1e-6 * v0, "{v1} vs {v0}");
    // The ball hit the middle of the boulder's +z side: (0, 0, 0.5) in its frame.
    let impact = glam::DVec3::new(0.0, 0.0, 0.5);
    let (near, far): (Vec<_>, Vec<_>) = child
        .fracture
        .fragments
        .iter()
        .partition(|f| f.centroid.distance(impact) < 0.5);
    let mean = |v: &[&shatter_geom::fracture::Fragment]| {
        v.iter().map(|f| f.volume).sum::<f64>() / v.len().max(1) as f64
    };
    eprintln!(
        "{n} fragments: {} near the impact ({} m³ on average), {} far ({} m³)",
        near.len(),
        mean(&near),
        far.len(),
        mean(&far)
    );
    assert!(
        near.len() > far.len(),
        "{} near, {} far",
        near.len(),
        far.len()
    );
    assert!(mean(&near) < mean(&far), "near cells are not smaller");
    // The hit loads the new bonds: cells around the impact come loose.
    run(&mut app, 20);
    let child = app.world().get::<ShatterObject>(cut.object).unwrap();
    assert!(child.state.bonds_broken > 0, "no bond of the cut broke");
    assert!(child.bodies() > 1, "nothing came loose");
}

/// Σ m·v over the plugin's bodies (each body's mass: its fragments' masses).
#[derive(Resource, Default)]
struct Momentum {
    before: Vec3,
    /// (before, after, objects after) at the step of the cut.
    at_cut: Option<(Vec3, Vec3, usize)>,
}

fn momentum(objects: &Query<&ShatterObject>, velocities: &Query<&LinearVelocity>) -> Vec3 {
    let mut p = Vec3::ZERO;
    for object in objects {
        for (f, body) in object.body_of.iter().enumerate() {
            if let Some(v) = body.and_then(|b| velocities.get(b).ok()) {
                p += object.masses[f] * v.0;
            }
        }
    }
    p
}

fn before_break(
    mut m: ResMut<Momentum>,
    objects: Query<&ShatterObject>,
    velocities: Query<&LinearVelocity>,
) {
    m.before = momentum(&objects, &velocities);
}

fn after_break(
    mut m: ResMut<Momentum>,
    mut cuts: MessageReader<RuntimeFractured>,
    objects: Query<&ShatterObject>,
    velocities: Query<&LinearVelocity>,
) {
    if cuts.read().count() > 0 && m.at_cut.is_none() {
        let after = momentum(&objects, &velocities);
        m.at_cut = Some((m.before, after, objects.iter().count()));
    }
}

#[test]
fn a_cut_keeps_the_objects_momentum() {
    let mut app = app();
    app.init_resource::<Momentum>().add_systems(
        FixedUpdate,
        (
            before_break.before(ShatterSystems::Break),
            after_break.after(ShatterSystems::Break),
        ),
    );
    ground(&mut app);
    // A free boulder: the ball sets it moving, and the cut must keep that motion.
    let b = boulder(&mut app, false, THRESHOLD_FROM_STRENGTH);
    spawned(&mut app, b);
    ball(&mut app, b, 40.0);
    let cut = first_cut(&mut app, 30);
    let (before, after, objects) = app.world().resource::<Momentum>().at_cut.unwrap();
    eprintln!("momentum before the cut {before}, after {after} ({objects} objects)");
    assert_eq!(objects, 2, "the new object was not there after the cut");
    // The ball's hit (about 4000 N·s) had set the boulder moving along −z.
    assert!(before.z < -1000.0, "the boulder was not moving: {before}");
    let error = (after - before).length() / before.length();
    assert!(error < 1e-4, "relative error {error}: {before} → {after}");
    let child = app.world().get::<ShatterObject>(cut.object).unwrap();
    let body = child.body_of.iter().flatten().next().unwrap();
    let rb = app.world().get::<RigidBody>(*body).unwrap();
    assert!(rb.is_dynamic(), "the cut of a free body is not free");
}

#[test]
fn a_slow_ball_cuts_nothing() {
    let mut app = app();
    ground(&mut app);
    let b = boulder(&mut app, true, THRESHOLD_FROM_STRENGTH);
    spawned(&mut app, b);
    let ball = ball(&mut app, b, 1.0);
    run(&mut app, 120);
    assert!(app.world().resource::<Log>().cuts.is_empty(), "it was cut");
    let all = objects(&mut app);
    assert_eq!(all.len(), 1);
    assert_eq!(all[0].1.fracture.fragments.len(), 1);
    assert!(all[0].1.body_of[0].is_some());
    // The ball reached the boulder: it was stopped in front of it, not flying on.
    let z = app.world().get::<Transform>(ball).unwrap().translation.z;
    let vz = app.world().get::<LinearVelocity>(ball).unwrap().0.z;
    assert!(vz > -0.9 && z > 0.5, "the slow ball missed: z {z}, vz {vz}");
}

/// The levels of every object record after a fast ball and `steps` updates.
fn levels_after_hit(depth: u32, steps: usize) -> (Vec<(Entity, ShatterObject)>, Log) {
    let mut app = app();
    ground(&mut app);
    // Loose fragments are cut again by anything harder than 30 N·s (a 20 kg cell
    // landing at 1.5 m/s), whatever their size.
    let b = boulder(
        &mut app,
        true,
        RuntimeFracture {
            impulse: Some(30.0),
            depth,
            min_size: 0.0,
            ..THRESHOLD_FROM_STRENGTH
        },
    );
    spawned(&mut app, b);
    ball(&mut app, b, 40.0);
    run(&mut app, steps);
    let all = objects(&mut app);
    let log = std::mem::take(&mut *app.world_mut().resource_mut::<Log>());
    (all, log)
}

#[test]
fn loose_fragments_are_cut_again_only_above_depth_one() {
    let (deep, deep_log) = levels_after_hit(2, 120);
    let (shallow, shallow_log) = levels_after_hit(1, 120);
    let levels = |all: &[(Entity, ShatterObject)]| {
        let mut l: Vec<u32> = all.iter().map(|(_, o)| o.level).collect();
        l.sort();
        l
    };
    eprintln!(
        "depth 2: levels {:?}; depth 1: levels {:?}",
        levels(&deep),
        levels(&shallow)
    );
    // depth 1: the boulder is cut once; its loose fragments are not cut again.
    assert_eq!(levels(&shallow), vec![0, 1], "depth 1");
    assert_eq!(shallow_log.cuts.len(), 1);
    let (_, first) = shallow.iter().find(|(_, o)| o.level == 1).unwrap();
    assert!(
        first.bodies() > 1,
        "no loose fragment at depth 1: the test shows nothing"
    );
    // depth 2: loose level-1 fragments hit again are cut (level 2), never deeper.
    let level2: Vec<&RuntimeFractured> = deep_log.cuts.iter().filter(|c| c.level == 2).collect();
    assert!(!level2.is_empty(), "no fragment was cut again at depth 2");
    assert!(deep_log.cuts.iter().all(|c| c.level <= 2));
    assert_eq!(deep_log.cuts.iter().filter(|c| c.level == 1).count(), 1);
    for cut in level2 {
        let (_, parent) = deep.iter().find(|(e, _)| *e == cut.parent).unwrap();
        assert_eq!(parent.level, 1);
        // The fragment it was cut from was loose and has gone.
        assert_eq!(parent.body_of[cut.fragment as usize], None);
        let (_, child) = deep.iter().find(|(e, _)| *e == cut.object).unwrap();
        assert_eq!(child.level, 2);
        assert!(child.fracture.fragments.len() >= 2);
    }
}
