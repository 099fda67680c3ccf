//! The cluster bond model: connected fragments are one rigid body with a compound collider
//! (one convex collider per convex piece); a bond graph carries the loads.
//!
//! The loads and the break rule are the engine-free ones of [`crate::breaking`]; this file
//! reads Rapier's bodies for them. Loads, in newtons, accumulate over one step and are
//! compared with the break force directly (not scaled by the bond's area, so the same
//! break force means the same thing in both bond models):
//! - a contact force `F` on fragment `f` of a body of mass `M` (Rapier's contact-force
//!   events) loads the bonds at graph distance `d` from `f` with `F·(1 − m_f/M)·½^d`, for
//!   `d = 0, 1, 2` (the part of the impulse that must pass through the bonds to move the
//!   rest of the body; fixed bodies have `M = ∞`). Only the part of a body's contact
//!   forces beyond its weight counts (`World::weight_relief` in `world/step.rs`): a block
//!   resting on the ground holds, a hard landing or a hit loads it;
//! - an explosion of power `P` (N·s) and radius `r` loads each bond whose centroid is at
//!   distance `x < r` with `P·(1 − x/r)/dt`.
//!
//! A load below the break force wears the bond's health (damage, [`break_loaded`]).
//! Objects with anchored fragments also run the stress solver after each step
//! (`world/stress_step.rs`): gravity and the step's loads carried down to the anchors.

use std::collections::BTreeSet;

use glam::Vec3;
use rapier3d::prelude::*;

use crate::bonds::live::{Attach, LiveObject, Surface};
use crate::bonds::tags::{Kind, tag};
pub(crate) use crate::breaking::{EVENT_THRESHOLD_FRACTION, Loads};
use crate::breaking::{contact_share, explosion_load};

/// Builds one body holding every fragment (fixed if any fragment is anchored).
pub(crate) fn build(
    world: &mut PhysicsWorld,
    live: &mut LiveObject,
    object: u32,
    pose: Pose,
    surface: Surface,
) {
    let prepared = live.prepared.clone();
    let fixed = prepared.anchored.iter().any(|a| *a);
    let builder = if fixed {
        RigidBodyBuilder::fixed()
    } else {
        RigidBodyBuilder::dynamic()
    };
    let body = world.insert_body(builder.pose(pose).user_data(tag(Kind::Fragment, object, 0)));
    let threshold = live.bonds.strength * EVENT_THRESHOLD_FRACTION;
    let attach = Attach {
        object,
        surface,
        force_events: Some(threshold),
    };
    if surface.hide_enclosed {
        live.attach = Some(attach);
    }
    let mut any = false;
    for f in 0..prepared.fracture.fragments.len() as u32 {
        // An enclosed fragment (a block's interior brick) gets its colliders when a bond
        // of it breaks.
        if live.hide(f, body) {
            continue;
        }
        any |= live.attach_fragment(world, f, body, attach) > 0;
    }
    if !any {
        for f in 0..prepared.fracture.fragments.len() {
            live.body[f] = None;
        }
        world.remove_body(body);
        return;
    }
    let all: Vec<u32> = (0..prepared.fracture.fragments.len() as u32).collect();
    live.set_mass(world, body, &all);
}

/// Loads the bonds around fragment `f` with a contact force `force`.
pub(crate) fn load_from_contact(
    world: &PhysicsWorld,
    live: &LiveObject,
    f: u32,
    force: f32,
    impulse: Vec3,
    other_mass: f32,
    loads: &mut Loads,
) {
    let Some(body) = live.body.get(f as usize).copied().flatten() else {
        return;
    };
    let m_f = live.prepared.masses[f as usize];
    let body_mass = world
        .bodies
        .get(body)
        .filter(|rb| rb.is_dynamic())
        .map(|rb| rb.mass());
    let share = contact_share(m_f, body_mass);
    loads.add_contact(
        &live.graph(),
        &live.bonds,
        f,
        force * share,
        impulse,
        other_mass,
    );
}

/// Loads the bonds within `radius` of `centre` with an explosion of `power`.
pub(crate) fn load_from_explosion(
    world: &PhysicsWorld,
    live: &LiveObject,
    centre: Vec3,
    radius: f32,
    power: f32,
    dt: f32,
    loads: &mut Loads,
) {
    for (b, bond) in live.prepared.fracture.bonds.iter().enumerate() {
        if live.bonds.broken[b] {
            continue;
        }
        let Some(body) = live.body[bond.a as usize] else {
            continue;
        };
        let Some(rb) = world.bodies.get(body) else {
            continue;
        };
        let p = rb.position().transform_point(bond.centroid.as_vec3());
        if let Some(load) = explosion_load((p - centre).length(), radius, power, dt) {
            loads.add_bond(b as u32, load);
        }
    }
}

/// Applies the break rule ([`BondState::apply`](crate::breaking::BondState::apply)):
/// returns the bodies to split, sorted.
pub(crate) fn break_loaded(live: &mut LiveObject, loads: &Loads) -> Vec<RigidBodyHandle> {
    let prepared = live.prepared.clone();
    let graph = crate::breaking::Graph {
        bonds: &prepared.fracture.bonds,
        adjacency: &prepared.adjacency,
        masses: &prepared.masses,
    };
    let broken = live.bonds.apply(&graph, loads);
    let mut bodies = BTreeSet::new();
    for b in broken {
        if let Some(body) = live.body[b.fragments[0] as usize] {
            bodies.insert(body.into_raw_parts());
        }
    }
    bodies
        .into_iter()
        .map(|(i, g)| RigidBodyHandle::from_raw_parts(i, g))
        .collect()
}
