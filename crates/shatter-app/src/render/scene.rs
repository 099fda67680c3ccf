//! Lights, ground, and one entity per fragment kept in step with the simulation.

use std::collections::HashMap;

use bevy::asset::RenderAssetUsages;
use bevy::image::{
    CompressedImageFormats, ImageAddressMode, ImageSampler, ImageSamplerDescriptor, ImageType,
};
use bevy::light::CascadeShadowConfigBuilder;
use bevy::prelude::*;
use shatter_geom::model::Material;

use crate::commands::ObjectId;
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

/// Entities drawing each piece, the material they share, and the materials of file
/// models (per build, object and index in the fracture's list).
#[derive(Resource, Default)]
struct PieceEntities {
    entities: HashMap<PieceKey, Entity>,
    material: Handle<StandardMaterial>,
    file_materials: HashMap<(u32, ObjectId, u32), Handle<StandardMaterial>>,
}

/// What the renderer draws, for the state line the web page reads
/// ([`crate::state_log`]).
#[derive(Resource, Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct RenderStats {
    /// Materials of file models in use that carry a base-colour texture.
    pub textured_materials: usize,
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
            .init_resource::<RenderStats>()
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

/// A file's material as Bevy draws it: its base colour, texture (decoded here; one that
/// does not decode is left out with a warning, the colour kept), metalness and roughness.
/// The fragments' vertex colours (white unless the file has colours) multiply it.
fn file_material(m: &Material, images: &mut Assets<Image>) -> StandardMaterial {
    let [r, g, b, a] = m.base_color;
    let texture = m.base_color_texture.as_ref().and_then(|t| {
        match Image::from_buffer(
            &t.image.bytes,
            ImageType::MimeType(t.image.format.mime()),
            CompressedImageFormats::NONE,
            true,
            // Repeating, as glTF's default sampler and OBJ's maps do: a file's UVs may
            // run past [0, 1] (Khronos' textured box spans 0..6).
            ImageSampler::Descriptor(ImageSamplerDescriptor {
                address_mode_u: ImageAddressMode::Repeat,
                address_mode_v: ImageAddressMode::Repeat,
                ..ImageSamplerDescriptor::linear()
            }),
            RenderAssetUsages::RENDER_WORLD,
        ) {
            Ok(image) => Some(images.add(image)),
            Err(e) => {
                warn!(
                    "material {}: texture {} does not decode ({e}); drawn in its colour",
                    m.name, t.image.name
                );
                None
            }
        }
    });
    StandardMaterial {
        base_color: Color::linear_rgba(r, g, b, a),
        base_color_texture: texture,
        metallic: m.metallic,
        perceptual_roughness: m.roughness,
        alpha_mode: if a < 1.0 {
            AlphaMode::Blend
        } else {
            AlphaMode::Opaque
        },
        ..default()
    }
}

#[allow(clippy::too_many_arguments)]
fn sync_pieces(
    mut commands: Commands,
    bridge: Res<SimBridge>,
    mut pieces: ResMut<PieceEntities>,
    mut meshes: ResMut<Assets<Mesh>>,
    mut materials: ResMut<Assets<StandardMaterial>>,
    mut images: ResMut<Assets<Image>>,
    mut transforms: Query<&mut Transform, With<PieceMarker>>,
    mut stats: ResMut<RenderStats>,
) {
    let poses = bridge.poses();
    // Whether the file materials in use changed (only then is the count recomputed).
    let mut materials_changed = false;
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
        let Some(parts) = bridge.piece_parts(pose.key) else {
            continue;
        };
        let mut drawn = Vec::with_capacity(parts.len());
        for part in parts {
            let material = match &part.material {
                None => pieces.material.clone(),
                Some((index, m)) => pieces
                    .file_materials
                    .entry((pose.key.build, pose.key.object, *index))
                    .or_insert_with(|| {
                        materials_changed = true;
                        materials.add(file_material(m, &mut images))
                    })
                    .clone(),
            };
            drawn.push((
                Mesh3d(meshes.add(to_bevy_mesh(part.mesh))),
                MeshMaterial3d(material),
            ));
        }
        let mut e = commands.spawn((transform, Visibility::Visible, PieceMarker(pose.key)));
        if drawn.len() == 1 {
            // One material (always, for built-in shapes): the piece's own entity draws it.
            e.insert(drawn.remove(0));
        } else {
            e.with_children(|parent| {
                for part in drawn {
                    parent.spawn(part);
                }
            });
        }
        pieces.entities.insert(pose.key, e.id());
    }
    pieces.entities.retain(|key, e| {
        let keep = alive.contains(key);
        if !keep {
            commands.entity(*e).despawn();
        }
        keep
    });
    // Materials of builds no piece shows any more.
    let live: std::collections::HashSet<u32> = pieces.entities.keys().map(|k| k.build).collect();
    let before = pieces.file_materials.len();
    pieces
        .file_materials
        .retain(|(build, _, _), _| live.contains(build));
    if !materials_changed && pieces.file_materials.len() == before {
        return;
    }
    let textured = pieces
        .file_materials
        .values()
        .filter(|h| {
            materials
                .get(*h)
                .is_some_and(|m| m.base_color_texture.is_some())
        })
        .count();
    stats.set_if_neq(RenderStats {
        textured_materials: textured,
    });
}
