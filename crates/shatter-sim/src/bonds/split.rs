//! Splitting a cluster body into the connected components of its intact bonds.
//!
//! Every component becomes a body with the old body's pose (all bodies of an object share
//! the object's frame, so colliders keep their offsets). A component of a moving body
//! moves as its material did: `v_i = v + ω × (c_i − c)`, `ω_i = ω`. This conserves linear
//! momentum (`Σ m_i c_i = M c`) and angular momentum about any fixed point (the parallel
//! axis terms `Σ m_i r_i × (ω × r_i)` are exactly what the old inertia held beyond the
//! parts' own inertia). A component freed from a fixed (anchored) body starts at rest and
//! receives the impulses its fragments took during the step.

use std::collections::BTreeMap;

use crate::breaking::{inherited_velocity, launch_velocity};

use glam::Vec3;
use rapier3d::prelude::*;

use crate::bonds::live::LiveObject;
use crate::bonds::tags::{Kind, tag};

/// The connected components (fragment lists, ascending) of the fragments on `body`,
/// ordered by their smallest fragment.
pub(crate) fn components(live: &LiveObject, body: RigidBodyHandle) -> Vec<Vec<u32>> {
    crate::breaking::components(&live.graph(), &live.bonds, &live.body, body)
}

/// World centre of mass of a body from its local mass properties (valid right after
/// `recompute_mass_properties_from_colliders`, before any step).
pub(crate) fn world_com(rb: &RigidBody) -> Vec3 {
    rb.position()
        .transform_point(rb.mass_properties().local_mprops.local_com)
}

/// Splits `body` into its components; returns each component's body and fragments
/// (ascending), the first keeping `body`, or nothing when `body` does not split. `impulses` are the impulses the fragments received this step; a part freed
/// from a fixed body is launched by them at most at `max_launch` m/s.
pub(crate) fn split(
    world: &mut PhysicsWorld,
    live: &mut LiveObject,
    object: u32,
    body: RigidBodyHandle,
    impulses: &BTreeMap<u32, (Vec3, f32)>,
    max_launch: f32,
) -> Vec<(RigidBodyHandle, Vec<u32>)> {
    let parts = components(live, body);
    let Some(old) = world.bodies.get(body) else {
        return Vec::new();
    };
    if parts.len() < 2 {
        return Vec::new();
    }
    let pose = *old.position();
    let was_dynamic = old.is_dynamic();
    let (v, w, c) = (old.linvel(), old.angvel(), world_com(old));
    let mut handles = vec![body];
    for part in &parts[1..] {
        let new = world.insert_body(
            RigidBodyBuilder::dynamic()
                .pose(pose)
                .ccd_enabled(false)
                .user_data(tag(Kind::Fragment, object, part[0])),
        );
        for &f in part {
            for &co in &live.colliders[f as usize] {
                world.colliders.set_parent(co, Some(new), &mut world.bodies);
            }
            live.body[f as usize] = Some(new);
        }
        handles.push(new);
    }
    // A hidden fragment with a broken bond may now face another body.
    for part in &parts {
        live.expose_broken(world, part);
    }
    for (part, &h) in parts.iter().zip(&handles) {
        let anchored = part.iter().any(|&f| live.prepared.anchored[f as usize]);
        let Some(rb) = world.bodies.get_mut(h) else {
            continue;
        };
        let ty = if anchored {
            RigidBodyType::Fixed
        } else {
            RigidBodyType::Dynamic
        };
        if rb.body_type() != ty {
            rb.set_body_type(ty, true);
        }
        if anchored {
            // A fixed part's mass is not used before Rapier's next step, which recomputes
            // it (its colliders changed): doing it here too would cost a second pass over
            // what is often the whole anchored wall. (Its additional mass may still count
            // hidden fragments now on other parts; a fixed body does not use it, and the
            // part is given its own when it comes loose.)
            continue;
        }
        live.set_mass(world, h, part);
        let Some(rb) = world.bodies.get_mut(h) else {
            continue;
        };
        if was_dynamic {
            let ci = world_com(rb);
            rb.set_linvel(inherited_velocity(v, w, c, ci), true);
            rb.set_angvel(w, true);
        } else {
            let v0 = launch_velocity(impulses, part, rb.mass()).clamp_length_max(max_launch);
            rb.set_linvel(v0, true);
            rb.set_angvel(Vec3::ZERO, true);
        }
    }
    handles.into_iter().zip(parts).collect()
}
