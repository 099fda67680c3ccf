//! Fragment entities: one rigid body holding every fragment (a compound collider, the
//! cluster bond model), each fragment a child entity with its meshes and collider.

use avian3d::prelude::*;
use bevy::prelude::*;
use shatter_geom::fracture::Fracture;
use shatter_sim::breaking::{BondState, Graph};

use shatter_sim::runtime::FractureTiming;

use crate::breakable::{FractureTask, Outcome};
use crate::components::{Cuttable, Fragment, ShatterBody, ShatterObject};
use crate::{Breakable, FractureFailed, Fractured, ShatterSettings, convert};
use bevy::tasks::{block_on, poll_once};

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

/// Whether triangle `t` of fragment `f` is a cut face: marked interior by the fracture,
/// or carrying the `interior` material (a fragment cut again at runtime keeps its
/// earlier cut faces as "surface" of the new cut, but their material says what they are).
fn is_interior(fracture: &Fracture, f: &shatter_geom::fracture::Fragment, t: usize) -> bool {
    f.interior.get(t).copied().unwrap_or(false)
        || f.material
            .get(t)
            .and_then(|&m| fracture.materials.get(m as usize))
            .is_some_and(|m| m.name == "interior")
}

/// Replaces `object`'s mesh by the fragments of `fracture`: one body at `pose`, which is
/// returned. An object that may be cut at runtime also gets its [`Cuttable`] record.
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
) -> Entity {
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
        let cut = |t| is_interior(&fracture, frag, t);
        if let Some(mesh) = convert::bevy_mesh(&frag.mesh, corners, true, |t| !cut(t)) {
            e.insert((Mesh3d(meshes.add(mesh)), MeshMaterial3d(surface.clone())));
        }
        let id = e.id();
        if let Some(mesh) = convert::bevy_mesh(&frag.mesh, corners, false, cut) {
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
    let mut entity = commands.entity(object);
    if breakable.runtime.timing == FractureTiming::OnImpact || breakable.runtime.depth > 1 {
        entity.insert(Cuttable {
            breakable: breakable.clone(),
            strength,
            surface,
            interior,
            uncuttable: Vec::new(),
        });
    }
    entity
        .remove::<(Mesh3d, MeshMaterial3d<StandardMaterial>)>()
        .insert(ShatterObject {
            fracture,
            masses,
            adjacency,
            state: BondState::new(bonds, strength, m.wear),
            body_of,
            fragments: entities,
            anchored,
            level: outcome.level,
            parent: outcome.parent,
        });
    body
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

/// What [`finish_fractures`] reads of a fracturing entity.
type TaskItem<'a> = (
    Entity,
    &'a Breakable,
    &'a mut FractureTask,
    &'a GlobalTransform,
    Option<&'a MeshMaterial3d<StandardMaterial>>,
);

/// Spawns the fragments of finished fractures.
#[allow(clippy::too_many_arguments)]
pub(crate) fn finish_fractures(
    mut commands: Commands,
    mut tasks: Query<TaskItem>,
    mut meshes: ResMut<Assets<Mesh>>,
    mut materials: ResMut<Assets<StandardMaterial>>,
    mut settings: ResMut<ShatterSettings>,
    mut fractured: MessageWriter<Fractured>,
    mut failed: MessageWriter<FractureFailed>,
) {
    for (entity, breakable, mut task, transform, material) in &mut tasks {
        let Some(result) = block_on(poll_once(&mut task.0)) else {
            continue;
        };
        commands
            .entity(entity)
            .remove::<(FractureTask, Breakable)>();
        let outcome = match result {
            Ok(outcome) => outcome,
            Err(error) => {
                warn!("bevy_shatter: {entity}: {error}");
                failed.write(FractureFailed {
                    object: entity,
                    error,
                });
                continue;
            }
        };
        let interior = settings
            .interior_material
            .get_or_insert_with(|| {
                let [r, g, b] = shatter_geom::io::INTERIOR_COLOR;
                materials.add(Color::linear_rgb(r, g, b))
            })
            .clone();
        let surface = material
            .map(|m| m.0.clone())
            .unwrap_or_else(|| interior.clone());
        let message = Fractured {
            object: entity,
            fragments: outcome.fracture.fragments.len(),
            bonds: outcome.fracture.bonds.len(),
        };
        spawn_fragments(
            &mut commands,
            &mut meshes,
            entity,
            breakable,
            outcome,
            transform.compute_transform(),
            surface,
            interior,
        );
        fractured.write(message);
    }
}
