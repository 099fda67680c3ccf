//! Runtime fracture on avian bodies, as shatter's own world does it
//! (`shatter_sim::world::runtime_step`): a hit on a body holding a single cuttable
//! fragment, hard enough, cuts that fragment in that step around the hit point with
//! [`runtime::cut_fragment`] (its new fragments inherit its convex pieces). The old body goes; the cut's fragments become a new object (its
//! own [`ShatterObject`] entity, one level deeper) on one bonded body at the same pose,
//! moving as the material did there. The hit is kept ([`PendingHit`]) and loads the new
//! bonds in the next step, once avian has given the new body its mass, so the cells
//! around the impact come loose.

use std::collections::BTreeMap;
use std::sync::Arc;

use avian3d::prelude::*;
use bevy::prelude::*;
use shatter_sim::breaking::{inherited_velocity, part_centre};
use shatter_sim::runtime;

use crate::bonds::BodyQuery;
use crate::breakable::Outcome;
use crate::components::{Cuttable, Fragment, PendingHit, ShatterObject};
use crate::convert::{from_bevy, to_bevy};
use crate::spawn::spawn_fragments;
use crate::{Breakable, RuntimeFractured, ShatterSettings};

/// A hit that asks for a cut.
struct Request {
    object: Entity,
    fragment: u32,
    body: Entity,
    /// Impact point, world frame.
    point: Vec3,
    magnitude: f32,
    force: f32,
    impulse: Vec3,
    other_mass: f32,
}

/// The impulse-weighted mean of a contact pair's points (world frame); `None` without
/// points.
fn impact_point(pair: &ContactPair) -> Option<Vec3> {
    let (mut sum, mut weight, mut plain, mut count) = (Vec3::ZERO, 0.0f32, Vec3::ZERO, 0usize);
    for point in pair.manifolds.iter().flat_map(|m| m.points.iter()) {
        let w = point.normal_impulse.max(0.0);
        sum += point.point * w;
        weight += w;
        plain += point.point;
        count += 1;
    }
    if weight > 0.0 && sum.is_finite() {
        Some(sum / weight)
    } else {
        (count > 0).then(|| plain / count as f32)
    }
}

/// Cuts the fragments whose body was hit hard enough in the last physics step.
#[allow(clippy::too_many_arguments)]
pub(crate) fn cut_on_impact(
    mut commands: Commands,
    collisions: Collisions,
    fragments: Query<&Fragment>,
    bodies: BodyQuery,
    mut objects: Query<(&mut ShatterObject, &mut Cuttable)>,
    mut meshes: ResMut<Assets<Mesh>>,
    settings: Res<ShatterSettings>,
    time: Res<Time<Fixed>>,
    mut out: MessageWriter<RuntimeFractured>,
) {
    let dt = time.timestep().as_secs_f32();
    if dt <= 0.0 {
        return;
    }
    let mass_of = |e: Option<Entity>| {
        e.and_then(|e| bodies.get(e).ok())
            .filter(|b| b.0.is_dynamic())
            .map_or(0.0, |b| b.1.value())
    };
    // The strongest hit on each cuttable fragment.
    let mut strongest: BTreeMap<(Entity, u32), Request> = BTreeMap::new();
    for pair in collisions.iter() {
        let raw = pair.total_normal_impulse();
        let magnitude = raw.length() * settings.contact_scale;
        if !(magnitude.is_finite() && magnitude > 0.0) {
            continue;
        }
        for (collider, body, other, sign) in [
            (pair.collider1, pair.body1, pair.body2, -1.0),
            (pair.collider2, pair.body2, pair.body1, 1.0),
        ] {
            let (Ok(fragment), Some(body)) = (fragments.get(collider), body) else {
                continue;
            };
            let Ok((object, cuttable)) = objects.get(fragment.object) else {
                continue;
            };
            let f = fragment.index;
            // A body holding this fragment alone.
            if object.body_of.get(f as usize) != Some(&Some(body))
                || object.body_of.iter().filter(|b| **b == Some(body)).count() != 1
                || cuttable.uncuttable.contains(&f)
            {
                continue;
            }
            let size = runtime::fragment_size(&object.fracture, f as usize);
            let rules = &cuttable.breakable.runtime;
            let threshold = rules.impulse.unwrap_or(cuttable.strength * dt);
            if !rules.cuts(object.level, size) || magnitude < threshold {
                continue;
            }
            let Some(point) = impact_point(pair) else {
                continue;
            };
            let key = (fragment.object, f);
            if strongest
                .get(&key)
                .is_some_and(|r| r.magnitude >= magnitude)
            {
                continue;
            }
            strongest.insert(
                key,
                Request {
                    object: fragment.object,
                    fragment: f,
                    body,
                    point,
                    magnitude,
                    force: magnitude / dt,
                    impulse: raw * sign,
                    other_mass: mass_of(other),
                },
            );
        }
    }
    for request in strongest.into_values() {
        let Ok((mut object, mut cuttable)) = objects.get_mut(request.object) else {
            continue;
        };
        match cut(
            &mut commands,
            &mut meshes,
            &mut object,
            &cuttable,
            &bodies,
            &request,
        ) {
            Ok(message) => {
                out.write(message);
            }
            Err(reason) => {
                warn!(
                    "bevy_shatter: runtime cut of fragment {} of {} failed: {reason}",
                    request.fragment, request.object
                );
                cuttable.uncuttable.push(request.fragment);
            }
        }
    }
}

/// Cuts `request`'s fragment: despawns its body, spawns the new object.
fn cut(
    commands: &mut Commands,
    meshes: &mut Assets<Mesh>,
    object: &mut ShatterObject,
    cuttable: &Cuttable,
    bodies: &BodyQuery,
    request: &Request,
) -> Result<RuntimeFractured, String> {
    let (rb, _, com, transform, v, w) = bodies
        .get(request.body)
        .map_err(|_| "the fragment's body is gone".to_string())?;
    let f = request.fragment;
    let level = object.level;
    // Bodies carry the object's frame (fragments sit at the identity under them).
    let local = transform.rotation.inverse() * (request.point - transform.translation);
    let seed = shatter_sim::runtime::cut_seed(cuttable.breakable.seed, f, level);
    let fracture = runtime::cut_fragment(
        &object.fracture,
        f as usize,
        from_bevy(local).as_dvec3(),
        runtime::pieces_at(cuttable.breakable.pieces, level),
        seed,
    )
    .map_err(|e| e.to_string())?;
    if fracture
        .fragments
        .iter()
        .all(|g| g.convex_pieces.is_empty())
    {
        return Err(format!(
            "{} fragments, none with a convex piece",
            fracture.fragments.len()
        ));
    }
    let dynamic = rb.is_dynamic();
    let anchored = !dynamic && object.anchored.get(f as usize).copied().unwrap_or(false);
    let centroids: Vec<glam::DVec3> = fracture.fragments.iter().map(|g| g.centroid).collect();
    let masses: Vec<f32> = fracture.fragments.iter().map(|g| g.volume as f32).collect();
    let all: Vec<u32> = (0..fracture.fragments.len() as u32).collect();
    let centre = part_centre(&centroids, &masses, &all);
    let nearest = centroids
        .iter()
        .enumerate()
        .min_by(|(_, a), (_, b)| {
            let p = from_bevy(local).as_dvec3();
            a.distance_squared(p).total_cmp(&b.distance_squared(p))
        })
        .map_or(0, |(i, _)| i as u32);
    let pieces = fracture.fragments.len();
    let breakable = Breakable {
        seed,
        anchored,
        ..cuttable.breakable.clone()
    };
    let pose = Transform::from_translation(transform.translation).with_rotation(transform.rotation);
    let child = commands.spawn(Name::new("shatter cut")).id();
    let body = spawn_fragments(
        commands,
        meshes,
        child,
        &breakable,
        Outcome {
            fracture: Arc::new(fracture),
            anchors: None,
            strength: Some(cuttable.strength),
            level: level + 1,
            parent: Some(request.object),
        },
        pose,
        cuttable.surface.clone(),
        cuttable.interior.clone(),
    );
    // The new body moves as the material did where it is.
    if dynamic {
        let c = transform.transform_point(com.0);
        let ci = centre.map_or(c, |p| pose.transform_point(to_bevy(p.as_vec3())));
        let velocity = to_bevy(inherited_velocity(
            from_bevy(v.0),
            from_bevy(w.0),
            from_bevy(c),
            from_bevy(ci),
        ));
        commands
            .entity(body)
            .insert((LinearVelocity(velocity), AngularVelocity(w.0)));
    }
    commands.entity(child).insert(PendingHit {
        fragment: nearest,
        force: request.force,
        impulse: request.impulse,
        other_mass: request.other_mass,
    });
    // The old fragment goes, with its body.
    commands.entity(request.body).despawn();
    object.body_of[f as usize] = None;
    object.fragments[f as usize] = Entity::PLACEHOLDER;
    object.state.touch();
    Ok(RuntimeFractured {
        object: child,
        parent: request.object,
        fragment: f,
        fragments: pieces,
        level: level + 1,
    })
}
