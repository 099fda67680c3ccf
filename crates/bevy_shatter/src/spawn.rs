//! Fragment entities: one rigid body holding every fragment (a compound collider, the
//! cluster bond model), each fragment a child entity with its meshes and collider.

use avian3d::prelude::*;
use bevy::prelude::*;
use shatter_geom::fracture::Fracture;
use shatter_sim::breaking::{BondState, Graph};

use crate::bonds::{ShatterBody, ShatterObject};
use crate::breakable::Outcome;
use crate::{Breakable, convert};

/// A fragment of a fractured object: a child of its body entity, with the surface mesh,
/// the entity's own material and a collider; its interior (cut) faces are a child entity
/// with the interior material.
#[derive(Component, Debug, Clone, Copy, PartialEq, Eq)]
pub struct Fragment {
    /// The object (the former [`Breakable`] entity).
    pub object: Entity,
    /// The fragment's index in the fracture.
    pub index: u32,
}

/// The collider of a fragment: the convex hulls of its pieces (object frame).
fn fragment_collider(pieces: &[Vec<glam::DVec3>]) -> Option<Collider> {
    let hulls: Vec<Collider> = pieces
        .iter()
        .filter_map(|p| {
            Collider::convex_hull(p.iter().map(|v| convert::to_bevy(v.as_vec3())).collect())
        })
        .collect();
    match hulls.len() {
        0 => None,
        1 => hulls.into_iter().next(),
        _ => Some(Collider::compound(
            hulls
                .into_iter()
                .map(|c| (Vec3::ZERO, Quat::IDENTITY, c))
                .collect(),
        )),
    }
}

/// Replaces `object`'s mesh by the fragments of `fracture`: one body at `pose`.
#[allow(clippy::too_many_arguments)]
pub(crate) fn spawn_fragments(
    commands: &mut Commands,
    meshes: &mut Assets<Mesh>,
    object: Entity,
    breakable: &Breakable,
    outcome: Outcome,
    pose: Transform,
    surface: Handle<StandardMaterial>,
    interior: Handle<StandardMaterial>,
) {
    let m = &breakable.material;
    let fracture = outcome.fracture;
    let n = fracture.fragments.len();
    let masses: Vec<f32> = fracture
        .fragments
        .iter()
        .map(|f| (f.volume * f64::from(m.density)) as f32)
        .collect();
    let adjacency = Graph::adjacency_of(&fracture.bonds, n);
    let anchored = match &outcome.anchors {
        // A pre-fractured asset's own anchors (`shatter fracture --anchor`) hold it.
        Some(list) => {
            let mut flags = vec![false; n];
            for &f in list {
                if let Some(flag) = flags.get_mut(f as usize) {
                    *flag = true;
                }
            }
            flags
        }
        None => anchored_fragments(&fracture, breakable.anchored),
    };
    let strength = breakable
        .break_force
        .or(outcome.strength)
        .unwrap_or(breakable.material.strength);
    let body_type = if anchored.iter().any(|&a| a) {
        RigidBody::Static
    } else {
        RigidBody::Dynamic
    };
    let body = commands
        .spawn((
            body_type,
            Transform::from_translation(pose.translation).with_rotation(pose.rotation),
            Visibility::default(),
            ShatterBody { object },
            Name::new("shatter body"),
        ))
        .id();
    let mut body_of = vec![None; n];
    let mut entities = vec![Entity::PLACEHOLDER; n];
    for (i, frag) in fracture.fragments.iter().enumerate() {
        let Some(collider) = fragment_collider(&frag.convex_pieces) else {
            continue;
        };
        let mut e = commands.spawn((
            Fragment {
                object,
                index: i as u32,
            },
            collider,
            ColliderDensity(m.density),
            Friction::new(m.friction),
            Restitution::new(m.restitution),
            Transform::IDENTITY,
            Visibility::default(),
            ChildOf(body),
        ));
        let corners = &frag.corners;
        if let Some(mesh) = convert::bevy_mesh(&frag.mesh, corners, true, |t| !frag.interior[t]) {
            e.insert((Mesh3d(meshes.add(mesh)), MeshMaterial3d(surface.clone())));
        }
        let id = e.id();
        if let Some(mesh) = convert::bevy_mesh(&frag.mesh, corners, false, |t| frag.interior[t]) {
            commands.spawn((
                Mesh3d(meshes.add(mesh)),
                MeshMaterial3d(interior.clone()),
                Transform::IDENTITY,
                Visibility::default(),
                ChildOf(id),
            ));
        }
        body_of[i] = Some(body);
        entities[i] = id;
    }
    let bonds = fracture.bonds.len();
    commands
        .entity(object)
        .remove::<(Mesh3d, MeshMaterial3d<StandardMaterial>)>()
        .insert(ShatterObject {
            fracture,
            masses,
            adjacency,
            state: BondState::new(bonds, strength, m.wear),
            body_of,
            fragments: entities,
            anchored,
        });
}

/// With `anchored`, the fragments at the bottom of the object (their lowest point within
/// 1 % of the object's height of its lowest point) are fixed to the world.
fn anchored_fragments(fracture: &Fracture, anchored: bool) -> Vec<bool> {
    let low = |f: &shatter_geom::fracture::Fragment| {
        f.mesh
            .positions
            .iter()
            .map(|p| p.y)
            .fold(f64::MAX, f64::min)
    };
    let high = |f: &shatter_geom::fracture::Fragment| {
        f.mesh
            .positions
            .iter()
            .map(|p| p.y)
            .fold(f64::MIN, f64::max)
    };
    let bottom = fracture.fragments.iter().map(low).fold(f64::MAX, f64::min);
    let top = fracture.fragments.iter().map(high).fold(f64::MIN, f64::max);
    let tolerance = 0.01 * (top - bottom).max(0.0);
    fracture
        .fragments
        .iter()
        .map(|f| anchored && low(f) <= bottom + tolerance)
        .collect()
}
