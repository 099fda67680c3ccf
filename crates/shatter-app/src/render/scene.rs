//! Lights, ground, and one entity per fragment kept in step with the simulation.

use std::collections::HashMap;

use bevy::light::CascadeShadowConfigBuilder;
use bevy::prelude::*;

use crate::render::fragment_mesh::to_bevy_mesh;
use crate::sim_bridge::{PieceKey, SimBridge};

/// Draws the simulation: sun with shadows, ground, flat-shaded fragments.
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

/// Entities drawing each piece, and the material they share.
#[derive(Resource, Default)]
struct PieceEntities {
    entities: HashMap<PieceKey, Entity>,
    material: Handle<StandardMaterial>,
}

/// Marks an entity drawing a fragment.
#[derive(Component, Debug, Clone, Copy)]
pub struct PieceMarker(pub PieceKey);

impl Plugin for SceneRenderPlugin {
    fn build(&self, app: &mut App) {
        let half = self.ground_half_size;
        app.insert_resource(ClearColor(Color::srgb(0.62, 0.72, 0.84)))
            .insert_resource(GlobalAmbientLight {
                color: Color::WHITE,
                brightness: 350.0,
                ..default()
            })
            .init_resource::<PieceEntities>()
            .add_systems(
                Startup,
                move |commands: Commands,
                      meshes: ResMut<Assets<Mesh>>,
                      materials: ResMut<Assets<StandardMaterial>>,
                      pieces: ResMut<PieceEntities>| {
                    setup_world(commands, meshes, materials, pieces, half)
                },
            )
            .add_systems(PostUpdate, sync_pieces.before(TransformSystems::Propagate));
    }
}

fn setup_world(
    mut commands: Commands,
    mut meshes: ResMut<Assets<Mesh>>,
    mut materials: ResMut<Assets<StandardMaterial>>,
    mut pieces: ResMut<PieceEntities>,
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
    // Fragments carry their colours per vertex; the material only adds shading.
    pieces.material = materials.add(StandardMaterial {
        base_color: Color::WHITE,
        perceptual_roughness: 0.8,
        ..default()
    });
}

fn sync_pieces(
    mut commands: Commands,
    bridge: Res<SimBridge>,
    mut pieces: ResMut<PieceEntities>,
    mut meshes: ResMut<Assets<Mesh>>,
    mut transforms: Query<&mut Transform, With<PieceMarker>>,
) {
    let poses = bridge.poses();
    let mut alive = std::collections::HashSet::with_capacity(poses.len());
    for pose in poses {
        alive.insert(pose.key);
        let transform = Transform::from_translation(pose.translation).with_rotation(pose.rotation);
        if let Some(&e) = pieces.entities.get(&pose.key) {
            if let Ok(mut t) = transforms.get_mut(e)
                && *t != transform
            {
                *t = transform;
            }
            continue;
        }
        let Some(flat) = bridge.piece_mesh(pose.key) else {
            continue;
        };
        let mesh = meshes.add(to_bevy_mesh(flat));
        let material = pieces.material.clone();
        let e = commands
            .spawn((
                Mesh3d(mesh),
                MeshMaterial3d(material),
                transform,
                PieceMarker(pose.key),
            ))
            .id();
        pieces.entities.insert(pose.key, e);
    }
    pieces.entities.retain(|key, e| {
        let keep = alive.contains(key);
        if !keep {
            commands.entity(*e).despawn();
        }
        keep
    });
}
