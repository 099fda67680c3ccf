//! The stage around the simulation: sky colour, sun with shadows, ambient light and the
//! ground. The fragments themselves are bevy_shatter's
//! ([`ShatterWorldPlugin`](bevy_shatter::world::ShatterWorldPlugin)).

use bevy::light::CascadeShadowConfigBuilder;
use bevy::prelude::*;

/// Lights the scene and lays the ground.
#[derive(Debug, Clone)]
pub struct SceneRenderPlugin {
    /// Half the edge of the square ground, in m.
    pub ground_half_size: f32,
}

impl Default for SceneRenderPlugin {
    fn default() -> Self {
        Self {
            ground_half_size: 60.0,
        }
    }
}

impl Plugin for SceneRenderPlugin {
    fn build(&self, app: &mut App) {
        let half = self.ground_half_size;
        app.insert_resource(ClearColor(Color::srgb(0.62, 0.72, 0.84)))
            .insert_resource(GlobalAmbientLight {
                color: Color::WHITE,
                brightness: 350.0,
                ..default()
            })
            .add_systems(
                Startup,
                move |commands: Commands,
                      meshes: ResMut<Assets<Mesh>>,
                      materials: ResMut<Assets<StandardMaterial>>| {
                    setup_world(commands, meshes, materials, half)
                },
            );
    }
}

fn setup_world(
    mut commands: Commands,
    mut meshes: ResMut<Assets<Mesh>>,
    mut materials: ResMut<Assets<StandardMaterial>>,
    half: f32,
) {
    commands.spawn((
        DirectionalLight {
            illuminance: 9_000.0,
            shadow_maps_enabled: true,
            ..default()
        },
        Transform::from_xyz(12.0, 20.0, 9.0).looking_at(Vec3::ZERO, Vec3::Y),
        CascadeShadowConfigBuilder {
            num_cascades: 2,
            first_cascade_far_bound: 25.0,
            maximum_distance: 90.0,
            ..default()
        }
        .build(),
    ));
    commands.spawn((
        Mesh3d(meshes.add(Plane3d::default().mesh().size(2.0 * half, 2.0 * half))),
        MeshMaterial3d(materials.add(StandardMaterial {
            base_color: Color::srgb(0.42, 0.47, 0.40),
            perceptual_roughness: 0.95,
            ..default()
        })),
        Transform::IDENTITY,
    ));
}
