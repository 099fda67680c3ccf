//! shatter's own world in Bevy ([`bevy_shatter::world`]), headless: the plugin steps it
//! in the world's fixed steps, keeps one entity per piece where the simulation has it,
//! sends the world's events as messages, and replaces the entities on a rebuild.
#![allow(clippy::unwrap_used)]

use bevy::prelude::*;
use bevy::time::TimeUpdateStrategy;
use bevy_shatter::world::{Piece, PieceOwner, ShatterWorld, ShatterWorldPlugin, WorldEvent};
use shatter_sim::scene::Scene;
use shatter_sim::{ProjectileSpec, SimEvent};

/// A 4×3×1 anchored brick wall, weak enough for one shot to break.
const WALL: &str = r#"
[[objects]]
shape = "cube"
method = "grid"
grid = [4, 3, 1]
scale = [2.0, 1.5, 0.3]
position = [0.0, 0.75, 0.0]
anchored = true
break_force = 200.0
"#;

fn app(scene: &str) -> App {
    let world = Scene::parse(scene).unwrap().build(None).unwrap();
    let mut app = App::new();
    app.add_plugins((MinimalPlugins, AssetPlugin::default(), ShatterWorldPlugin))
        .init_asset::<Mesh>()
        .init_asset::<StandardMaterial>()
        .init_asset::<Image>()
        // Every frame is one 60 Hz step of the world.
        .insert_resource(TimeUpdateStrategy::ManualDuration(
            std::time::Duration::from_secs_f64(1.0 / 60.0),
        ))
        .insert_resource(ShatterWorld::new(world))
        .init_resource::<Seen>()
        .add_systems(
            Update,
            collect.after(bevy_shatter::world::ShatterWorldSystems::Step),
        );
    app
}

#[derive(Resource, Default)]
struct Seen(Vec<SimEvent>);

fn collect(mut events: MessageReader<WorldEvent>, mut seen: ResMut<Seen>) {
    seen.0.extend(events.read().map(|e| e.0.clone()));
}

fn pieces(app: &mut App) -> Vec<(Piece, Transform)> {
    let mut q = app.world_mut().query::<(&Piece, &Transform)>();
    let mut out: Vec<_> = q.iter(app.world()).map(|(p, t)| (*p, *t)).collect();
    out.sort_by_key(|(p, _)| p.0);
    out
}

#[test]
fn every_piece_has_an_entity_where_the_world_has_it() {
    let mut app = app(WALL);
    app.update();
    let drawn = pieces(&mut app);
    assert_eq!(drawn.len(), 12, "one entity per brick");
    let world = app.world().resource::<ShatterWorld>();
    let mut poses = world.poses();
    poses.sort_by_key(|p| p.key);
    for ((piece, t), pose) in drawn.iter().zip(&poses) {
        assert_eq!(piece.0, pose.key);
        assert_eq!(t.translation, pose.translation);
        // Each has a mesh of its fragment (flat-shaded: 3 vertices per triangle).
        let parts = world.piece_parts(pose.key).unwrap();
        assert_eq!(parts.len(), 1);
        assert_eq!(parts[0].mesh.positions.len() % 3, 0);
    }
}

#[test]
fn a_shot_breaks_bonds_the_events_arrive_and_the_pieces_move() {
    let mut app = app(WALL);
    app.update();
    let before = pieces(&mut app);
    {
        let mut world = app.world_mut().resource_mut::<ShatterWorld>();
        world.start();
        world
            .fire(ProjectileSpec {
                speed: 40.0,
                from: glam::Vec3::new(0.2, 0.9, 5.0),
                to: glam::Vec3::new(0.2, 0.9, 0.0),
                ..ProjectileSpec::default()
            })
            .unwrap();
    }
    for _ in 0..40 {
        app.update();
    }
    let world = app.world().resource::<ShatterWorld>();
    let stats = world.stats();
    assert!(stats.bonds_broken > 0, "{stats:?}");
    assert!(stats.running && stats.time > 0.5, "{stats:?}");
    let seen = &app.world().resource::<Seen>().0;
    let broken: usize = seen
        .iter()
        .map(|e| match e {
            SimEvent::BondsBroken { count, .. } => *count,
            _ => 0,
        })
        .sum();
    assert_eq!(broken, stats.bonds_broken, "every broken bond was sent");
    assert!(seen.iter().any(|e| matches!(e, SimEvent::Split { .. })));
    let after = pieces(&mut app);
    // The projectile is drawn too, and some bricks moved.
    assert!(
        after
            .iter()
            .any(|(p, _)| matches!(p.0.owner, PieceOwner::Projectile(_)))
    );
    let moved = before
        .iter()
        .filter(|(p, t)| {
            after
                .iter()
                .find(|(q, _)| q == p)
                .is_some_and(|(_, u)| u.translation.distance(t.translation) > 0.01)
        })
        .count();
    assert!(moved > 0, "no brick moved");
}

#[test]
fn a_reset_replaces_the_pieces_and_puts_them_back() {
    let mut app = app(WALL);
    app.update();
    let before = pieces(&mut app);
    app.world_mut().resource_mut::<ShatterWorld>().start();
    for _ in 0..10 {
        app.update();
    }
    app.world_mut().resource_mut::<ShatterWorld>().reset();
    app.update();
    let after = pieces(&mut app);
    assert_eq!(after.len(), before.len());
    for ((p, t), (q, u)) in before.iter().zip(&after) {
        assert_ne!(p.0.build, q.0.build, "a new build's entities");
        assert_eq!((p.0.owner, p.0.fragment), (q.0.owner, q.0.fragment));
        assert_eq!(t.translation, u.translation);
    }
    let stats = app.world().resource::<ShatterWorld>().stats();
    assert!(!stats.running && stats.time == 0.0);
}
