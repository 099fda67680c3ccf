//! A minimal game with bevy_shatter: a brick wall stands on the game's own ground; a left
//! click shoots a steel ball from the camera towards the cursor. The wall is fractured
//! into bricks at spawn (on a background task), its bottom row fixed to the world; a hard
//! enough hit breaks bonds and the wall falls apart into bodies of the game's avian
//! physics. The camera, the light and the ground are the game's; the plugin adds none.
//! Run with `cargo run -p bevy_shatter --example breakable_wall --features window`.
//!
//! With `BREAKABLE_WALL_SHOT=out.png` it plays itself instead: one ball at the wall's
//! middle after a second, a screenshot a second and a half later, then it quits (how
//! the example is looked at under Xvfb).

use avian3d::prelude::*;
use bevy::prelude::*;
use bevy::render::view::screenshot::{Screenshot, save_to_disk};
use bevy_shatter::{BondBroken, Breakable, ShatterPlugin};

fn main() {
    let mut app = App::new();
    app.add_plugins((
        DefaultPlugins,
        PhysicsPlugins::default(),
        ShatterPlugin::default(),
    ))
    .add_systems(Startup, setup)
    .add_systems(Update, (shoot, report));
    if let Some(path) = std::env::var_os("BREAKABLE_WALL_SHOT") {
        app.insert_resource(AutoShot {
            path: path.into(),
            frame: 0,
        })
        .add_systems(Update, auto_shot);
    }
    app.run();
}

/// The self-playing mode's state.
#[derive(Resource)]
struct AutoShot {
    path: std::path::PathBuf,
    frame: u32,
}

/// Fires one ball at the wall at frame 60 (a second at 60 fps), screenshots at frame
/// 150, quits once the file is written.
fn auto_shot(
    mut commands: Commands,
    mut shot: ResMut<AutoShot>,
    mut meshes: ResMut<Assets<Mesh>>,
    mut materials: ResMut<Assets<StandardMaterial>>,
    mut exit: MessageWriter<AppExit>,
) {
    shot.frame += 1;
    match shot.frame {
        60 => {
            let from = Vec3::new(0.0, 2.0, 8.0);
            let to = Vec3::new(0.0, 0.9, 0.0);
            spawn_ball(
                &mut commands,
                &mut meshes,
                &mut materials,
                from,
                (to - from).normalize(),
            );
        }
        150 => {
            commands
                .spawn(Screenshot::primary_window())
                .observe(save_to_disk(shot.path.clone()));
        }
        f if f > 150 && shot.path.is_file() || f > 2000 => {
            exit.write(AppExit::Success);
        }
        _ => {}
    }
}

fn setup(
    mut commands: Commands,
    mut meshes: ResMut<Assets<Mesh>>,
    mut materials: ResMut<Assets<StandardMaterial>>,
) {
    commands.spawn((
        Camera3d::default(),
        Transform::from_xyz(0.0, 2.0, 8.0).looking_at(Vec3::new(0.0, 1.0, 0.0), Vec3::Y),
    ));
    commands.spawn((
        DirectionalLight {
            illuminance: 8000.0,
            shadow_maps_enabled: true,
            ..default()
        },
        Transform::from_xyz(4.0, 8.0, 4.0).looking_at(Vec3::ZERO, Vec3::Y),
    ));
    commands.spawn((
        RigidBody::Static,
        Collider::cuboid(40.0, 1.0, 40.0),
        Mesh3d(meshes.add(Cuboid::new(40.0, 1.0, 40.0))),
        MeshMaterial3d(materials.add(Color::srgb(0.3, 0.5, 0.3))),
        Transform::from_xyz(0.0, -0.5, 0.0),
    ));
    commands.spawn((
        Mesh3d(meshes.add(Cuboid::new(3.0, 1.5, 0.3))),
        MeshMaterial3d(materials.add(Color::srgb(0.7, 0.3, 0.2))),
        Transform::from_xyz(0.0, 0.75, 0.0),
        Breakable {
            anchored: true,
            break_force: Some(50_000.0),
            ..Breakable::grid([6, 3, 1])
        },
    ));
}

/// A left click fires a ball along the cursor's ray.
fn shoot(
    mut commands: Commands,
    buttons: Res<ButtonInput<MouseButton>>,
    windows: Query<&Window>,
    cameras: Query<(&Camera, &GlobalTransform)>,
    mut meshes: ResMut<Assets<Mesh>>,
    mut materials: ResMut<Assets<StandardMaterial>>,
) {
    if !buttons.just_pressed(MouseButton::Left) {
        return;
    }
    let (Ok(window), Ok((camera, at))) = (windows.single(), cameras.single()) else {
        return;
    };
    let Some(ray) = window
        .cursor_position()
        .and_then(|c| camera.viewport_to_world(at, c).ok())
    else {
        return;
    };
    spawn_ball(
        &mut commands,
        &mut meshes,
        &mut materials,
        ray.origin,
        *ray.direction,
    );
}

/// A steel ball at `from`, flying along `dir` (unit) at 40 m/s.
fn spawn_ball(
    commands: &mut Commands,
    meshes: &mut Assets<Mesh>,
    materials: &mut Assets<StandardMaterial>,
    from: Vec3,
    dir: Vec3,
) {
    commands.spawn((
        RigidBody::Dynamic,
        Collider::sphere(0.15),
        ColliderDensity(7800.0),
        SweptCcd::default(),
        Mesh3d(meshes.add(Sphere::new(0.15))),
        MeshMaterial3d(materials.add(Color::srgb(0.8, 0.8, 0.85))),
        Transform::from_translation(from),
        LinearVelocity(dir * 40.0),
    ));
}

fn report(mut broken: MessageReader<BondBroken>) {
    let n = broken.read().count();
    if n > 0 {
        info!("{n} bonds broke");
    }
}
