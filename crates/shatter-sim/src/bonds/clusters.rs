//! The cluster bond model: connected fragments are one rigid body with a compound collider
//! (one convex collider per convex piece); a bond graph carries the loads.
//!
//! Loads, in newtons, accumulate over one step and are compared with the break force
//! directly (not scaled by the bond's area, so the same break force means the same thing
//! in both bond models):
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

use std::collections::{BTreeMap, BTreeSet};

use glam::Vec3;
use rapier3d::prelude::*;

use crate::bonds::live::{LiveObject, Surface};
use crate::bonds::tags::{Kind, tag};
use crate::world::BreakCause;

/// Contact forces are reported only above this fraction of the break force.
pub(crate) const EVENT_THRESHOLD_FRACTION: f32 = 0.25;
/// Graph distance over which a contact load spreads.
const LOAD_DEPTH: usize = 2;
/// Attenuation per graph step.
const LOAD_ATTENUATION: f32 = 0.5;

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
    let threshold = live.strength * EVENT_THRESHOLD_FRACTION;
    let mut any = false;
    for f in 0..prepared.fracture.fragments.len() as u32 {
        any |= live.attach_fragment(world, object, f, body, surface, Some(threshold)) > 0;
    }
    if !any {
        world.remove_body(body);
        return;
    }
    world.bodies[body].recompute_mass_properties_from_colliders(&world.colliders);
}

/// Bond loads of one object during one step, and the impulses its fragments received.
#[derive(Debug, Default, Clone)]
pub(crate) struct Loads {
    /// Bond index → load (N).
    pub bonds: BTreeMap<u32, f32>,
    /// Fragment → impulse received (N·s) and the mass of the dynamic body that gave it,
    /// used to launch pieces freed from fixed bodies.
    pub impulses: BTreeMap<u32, (Vec3, f32)>,
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
    let entry = loads.impulses.entry(f).or_insert((Vec3::ZERO, 0.0));
    entry.0 += impulse;
    entry.1 = entry.1.max(other_mass);
    let m_f = live.prepared.masses[f as usize];
    let share = match world.bodies.get(body) {
        Some(rb) if rb.is_dynamic() && rb.mass() > 0.0 => (1.0 - m_f / rb.mass()).max(0.0),
        _ => 1.0,
    };
    let mut frontier = vec![f];
    let mut seen_fragments = BTreeSet::from([f]);
    let mut seen_bonds = BTreeSet::new();
    let mut load = force * share;
    for _ in 0..=LOAD_DEPTH {
        let mut next = Vec::new();
        for &g in &frontier {
            for &b in &live.prepared.adjacency[g as usize] {
                if live.broken[b as usize] || !seen_bonds.insert(b) {
                    continue;
                }
                *loads.bonds.entry(b).or_insert(0.0) += load;
                let bond = &live.prepared.fracture.bonds[b as usize];
                let other = if bond.a == g { bond.b } else { bond.a };
                if seen_fragments.insert(other) {
                    next.push(other);
                }
            }
        }
        frontier = next;
        load *= LOAD_ATTENUATION;
    }
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
        if live.broken[b] {
            continue;
        }
        let Some(body) = live.body[bond.a as usize] else {
            continue;
        };
        let Some(rb) = world.bodies.get(body) else {
            continue;
        };
        let p = rb.position().transform_point(bond.centroid.as_vec3());
        let x = (p - centre).length();
        if x < radius {
            *loads.bonds.entry(b as u32).or_insert(0.0) += power * (1.0 - x / radius) / dt;
        }
    }
}

/// Breaks the bonds whose load exceeds the strength (cause: impact) and wears the others
/// down: a load `x·strength` with `x < 1` takes `wear·x` of the bond's health, and a bond
/// whose health reaches 0 breaks (cause: damage). Returns the bodies to split, sorted.
pub(crate) fn break_loaded(live: &mut LiveObject, loads: &Loads) -> Vec<RigidBodyHandle> {
    let mut bodies = BTreeSet::new();
    for (&b, &load) in &loads.bonds {
        let i = b as usize;
        if live.broken[i] {
            continue;
        }
        let cause = if load > live.strength {
            BreakCause::Impact
        } else {
            live.health[i] -= live.wear * (load / live.strength).max(0.0);
            if live.health[i] > 0.0 {
                continue;
            }
            BreakCause::Damage
        };
        live.mark_broken_by(i, cause);
        let a = live.prepared.fracture.bonds[i].a;
        if let Some(body) = live.body[a as usize] {
            bodies.insert(body.into_raw_parts());
        }
    }
    bodies
        .into_iter()
        .map(|(i, g)| RigidBodyHandle::from_raw_parts(i, g))
        .collect()
}
