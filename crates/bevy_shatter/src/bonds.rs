//! Breaking bonds from avian's contacts with shatter-sim's engine-free logic, and
//! splitting bodies into islands.

use std::collections::BTreeMap;

use avian3d::prelude::*;
use bevy::prelude::*;
use shatter_sim::breaking::{
    Graph, Loads, components, contact_share, inherited_velocity, launch_velocity, part_centre,
    weight_relief,
};

use crate::components::{Fragment, PendingHit, ShatterBody, ShatterObject};
use crate::convert::{from_bevy, to_bevy};
use crate::{BondBroken, ShatterSettings, Split};

pub(crate) type BodyQuery<'w, 's> = Query<
    'w,
    's,
    (
        &'static RigidBody,
        &'static ComputedMass,
        &'static ComputedCenterOfMass,
        &'static Transform,
        &'static LinearVelocity,
        &'static AngularVelocity,
    ),
>;

/// Loads the bonds from the last step's contacts (and the hits that cut objects at
/// runtime in the step before), breaks them, splits bodies.
#[allow(clippy::too_many_arguments)]
pub(crate) fn break_bonds(
    mut commands: Commands,
    collisions: Collisions,
    pending: Query<(Entity, &PendingHit)>,
    fragments: Query<&Fragment>,
    bodies: BodyQuery,
    mut objects: Query<&mut ShatterObject>,
    settings: Res<ShatterSettings>,
    gravity: Res<Gravity>,
    time: Res<Time<Fixed>>,
    mut broken_out: MessageWriter<BondBroken>,
    mut split_out: MessageWriter<Split>,
) {
    let dt = time.timestep().as_secs_f32();
    if dt <= 0.0 {
        return;
    }
    let dynamic_mass = |e: Option<Entity>| {
        e.and_then(|e| bodies.get(e).ok())
            .filter(|b| b.0.is_dynamic())
            .map(|b| b.1.value())
    };
    // Contact forces per fragment body, for the weight relief.
    let mut hits = Vec::new();
    let mut sums: BTreeMap<Entity, f32> = BTreeMap::new();
    for pair in collisions.iter() {
        let impulse = pair.total_normal_impulse();
        let force = impulse.length() / dt * settings.contact_scale;
        if !(force.is_finite() && force > 0.0) {
            continue;
        }
        for (collider, body, other, sign) in [
            (pair.collider1, pair.body1, pair.body2, -1.0),
            (pair.collider2, pair.body2, pair.body1, 1.0),
        ] {
            let Ok(fragment) = fragments.get(collider) else {
                continue;
            };
            if let Some(b) = body {
                *sums.entry(b).or_insert(0.0) += force;
            }
            hits.push((*fragment, body, dynamic_mass(other), force, impulse * sign));
        }
    }
    // A runtime cut's hit loads its new object's bonds as a contact would have.
    for (object, hit) in &pending {
        commands.entity(object).remove::<PendingHit>();
        let Some(body) = objects
            .get(object)
            .ok()
            .and_then(|o| o.body_of.get(hit.fragment as usize).copied().flatten())
        else {
            continue;
        };
        *sums.entry(body).or_insert(0.0) += hit.force;
        let fragment = Fragment {
            object,
            index: hit.fragment,
        };
        let other = (hit.other_mass > 0.0).then_some(hit.other_mass);
        hits.push((fragment, Some(body), other, hit.force, hit.impulse));
    }
    if hits.is_empty() {
        return;
    }
    let g = gravity.0.length();
    let mut loads: BTreeMap<Entity, Loads> = BTreeMap::new();
    for (fragment, body, other_mass, force, impulse) in hits {
        let Ok(object) = objects.get(fragment.object) else {
            continue;
        };
        let body_mass = dynamic_mass(body);
        let relief = match (body_mass, body.and_then(|b| sums.get(&b))) {
            (Some(m), Some(sum)) => weight_relief(*sum, m, g),
            _ => 1.0,
        };
        let share = contact_share(object.masses[fragment.index as usize], body_mass);
        loads.entry(fragment.object).or_default().add_contact(
            &object.graph(),
            &object.state,
            fragment.index,
            force * share * relief,
            from_bevy(impulse),
            other_mass.unwrap_or(0.0),
        );
    }
    for (entity, loads) in loads {
        let Ok(mut object) = objects.get_mut(entity) else {
            continue;
        };
        let object = &mut *object;
        let graph = Graph {
            bonds: &object.fracture.bonds,
            adjacency: &object.adjacency,
            masses: &object.masses,
        };
        let broken = object.state.apply(&graph, &loads);
        let mut to_split = Vec::new();
        for b in &broken {
            broken_out.write(BondBroken {
                object: entity,
                bond: *b,
            });
            if let Some(body) = object.body_of[b.fragments[0] as usize]
                && !to_split.contains(&body)
            {
                to_split.push(body);
            }
        }
        to_split.sort();
        for body in to_split {
            if let Some(split) = split_body(&mut commands, object, entity, body, &bodies, &loads) {
                split_out.write(split);
            }
        }
    }
}

/// Splits `body` into the islands of its intact bonds; `None` if it is still one.
fn split_body(
    commands: &mut Commands,
    object: &mut ShatterObject,
    entity: Entity,
    body: Entity,
    bodies: &BodyQuery,
    loads: &Loads,
) -> Option<Split> {
    let parts = components(&object.graph(), &object.state, &object.body_of, body);
    if parts.len() < 2 {
        return None;
    }
    let (rb, _, com, transform, v, w) = bodies.get(body).ok()?;
    let was_dynamic = rb.is_dynamic();
    let c = transform.transform_point(com.0);
    let centroids: Vec<glam::DVec3> = object
        .fracture
        .fragments
        .iter()
        .map(|f| f.centroid)
        .collect();
    let mut handles = vec![body];
    for (i, part) in parts.iter().enumerate() {
        let anchored = part.iter().any(|&f| object.anchored[f as usize]);
        let part_mass: f32 = part.iter().map(|&f| object.masses[f as usize]).sum();
        let velocity = if anchored {
            Vec3::ZERO
        } else if was_dynamic {
            let ci = part_centre(&centroids, &object.masses, part)
                .map_or(c, |p| transform.transform_point(to_bevy(p.as_vec3())));
            to_bevy(inherited_velocity(
                from_bevy(v.0),
                from_bevy(w.0),
                from_bevy(c),
                from_bevy(ci),
            ))
        } else {
            to_bevy(launch_velocity(&loads.impulses, part, part_mass))
        };
        let angular = if was_dynamic && !anchored {
            w.0
        } else {
            Vec3::ZERO
        };
        let kind = if anchored {
            RigidBody::Static
        } else {
            RigidBody::Dynamic
        };
        if i == 0 {
            commands.entity(body).insert((
                kind,
                LinearVelocity(velocity),
                AngularVelocity(angular),
            ));
        } else {
            let new = commands
                .spawn((
                    kind,
                    *transform,
                    Visibility::default(),
                    LinearVelocity(velocity),
                    AngularVelocity(angular),
                    ShatterBody { object: entity },
                    Name::new("shatter body"),
                ))
                .id();
            for &f in part {
                commands
                    .entity(object.fragments[f as usize])
                    .insert(ChildOf(new));
                object.body_of[f as usize] = Some(new);
            }
            handles.push(new);
        }
    }
    Some(Split {
        object: entity,
        bodies: handles,
        parts,
    })
}

/// Removes plugin bodies whose state is not finite or whose speed ran away.
pub(crate) fn guard(
    mut commands: Commands,
    bodies: Query<(Entity, &ShatterBody, &Transform, &LinearVelocity)>,
    mut objects: Query<&mut ShatterObject>,
    settings: Res<ShatterSettings>,
) {
    for (e, body, t, v) in &bodies {
        let finite = t.translation.is_finite() && t.rotation.is_finite() && v.0.is_finite();
        if finite && v.0.length() <= settings.max_speed {
            continue;
        }
        warn!(
            "bevy_shatter: body {e} diverged (speed {}), removed",
            v.0.length()
        );
        if let Ok(mut object) = objects.get_mut(body.object) {
            for slot in object.body_of.iter_mut() {
                if *slot == Some(e) {
                    *slot = None;
                }
            }
            object.state.touch();
        }
        commands.entity(e).despawn();
    }
}
