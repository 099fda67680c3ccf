//! One entity per piece of the [`ShatterWorld`], kept in step with it.

use std::collections::{HashMap, HashSet};

use bevy::asset::RenderAssetUsages;
use bevy::image::{
    CompressedImageFormats, ImageAddressMode, ImageSampler, ImageSamplerDescriptor, ImageType,
};
use bevy::prelude::*;
use shatter_geom::model::Material;

use super::mesh::to_bevy_mesh;
use super::{PieceKey, PieceOwner, ShatterWorld};

/// Marks the entity that draws a piece of the [`ShatterWorld`] (its `Transform` follows
/// the piece; a piece drawn with several materials has one child per material).
#[derive(Component, Debug, Clone, Copy, PartialEq, Eq)]
pub struct Piece(pub PieceKey);

/// What is drawn, for a tool's overlay or test.
#[derive(Resource, Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct RenderStats {
    /// Materials of mesh files' models in use that carry a base-colour texture.
    pub textured_materials: usize,
}

/// Entities drawing each piece, the material the coloured pieces share, and the
/// materials of file models (per build, object and index in the fracture's list).
#[derive(Resource, Default)]
pub(super) struct PieceEntities {
    entities: HashMap<PieceKey, Entity>,
    material: Handle<StandardMaterial>,
    file_materials: HashMap<(u32, PieceOwner, u32), Handle<StandardMaterial>>,
}

pub(super) fn setup(mut commands: Commands, mut materials: ResMut<Assets<StandardMaterial>>) {
    // Built-in shapes carry their colours per vertex; the material only adds shading.
    commands.insert_resource(PieceEntities {
        material: materials.add(StandardMaterial {
            base_color: Color::WHITE,
            perceptual_roughness: 0.8,
            ..default()
        }),
        ..default()
    });
}

/// A file's material as Bevy draws it: its base colour, texture (decoded here; one that
/// does not decode is left out with a warning, the colour kept), metalness and roughness.
/// The fragments' vertex colours (white unless the file has colours) multiply it.
pub fn file_material(m: &Material, images: &mut Assets<Image>) -> StandardMaterial {
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
pub(super) fn sync_pieces(
    mut commands: Commands,
    world: Res<ShatterWorld>,
    mut pieces: ResMut<PieceEntities>,
    mut meshes: ResMut<Assets<Mesh>>,
    mut materials: ResMut<Assets<StandardMaterial>>,
    mut images: ResMut<Assets<Image>>,
    mut transforms: Query<&mut Transform, With<Piece>>,
    mut stats: ResMut<RenderStats>,
) {
    let poses = world.poses();
    // Whether the file materials in use changed (only then is the count recomputed).
    let mut materials_changed = false;
    let mut alive = HashSet::with_capacity(poses.len());
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
        let Some(parts) = world.piece_parts(pose.key) else {
            continue;
        };
        let mut drawn = Vec::with_capacity(parts.len());
        for part in parts {
            let material = match &part.material {
                None => pieces.material.clone(),
                Some((index, m)) => pieces
                    .file_materials
                    .entry((pose.key.build, pose.key.owner, *index))
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
        let mut e = commands.spawn((transform, Visibility::Visible, Piece(pose.key)));
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
    let live: HashSet<u32> = pieces.entities.keys().map(|k| k.build).collect();
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
