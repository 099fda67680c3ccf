//! The thesis's bond model: one rigid body per fragment, a breakable fixed joint per bond.
//!
//! Rapier has no breakable joints, so after each step every joint's impulse is read and a
//! joint whose force `|linear impulse| / (dt / substeps)` exceeds the break force is
//! removed. (Rapier stores the impulse of the last substep, hence the substep dt.)

use glam::Vec3;
use rapier3d::prelude::*;

use crate::bonds::live::{Attach, LiveObject, Surface};
use crate::bonds::tags::{Kind, tag};

/// Builds the bodies, colliders and joints of a joints-model object.
pub(crate) fn build(
    world: &mut PhysicsWorld,
    live: &mut LiveObject,
    object: u32,
    pose: Pose,
    surface: Surface,
    ground: RigidBodyHandle,
) {
    let prepared = live.prepared.clone();
    let attach = Attach {
        object,
        surface,
        force_events: None,
    };
    for f in 0..prepared.fracture.fragments.len() as u32 {
        let body = world.insert_body(RigidBodyBuilder::dynamic().pose(pose).user_data(tag(
            Kind::Fragment,
            object,
            f,
        )));
        if live.attach_fragment(world, f, body, attach) == 0 {
            world.remove_body(body);
            continue;
        }
        world.bodies[body].recompute_mass_properties_from_colliders(&world.colliders);
    }
    for (i, bond) in prepared.fracture.bonds.iter().enumerate() {
        let (Some(a), Some(b)) = (live.body[bond.a as usize], live.body[bond.b as usize]) else {
            continue;
        };
        let c = bond.centroid.as_vec3();
        let joint = FixedJointBuilder::new()
            .local_anchor1(c)
            .local_anchor2(c)
            .contacts_enabled(false);
        live.joints[i] = Some(world.insert_impulse_joint(a, b, joint));
    }
    for (f, anchored) in prepared.anchored.iter().enumerate() {
        let Some(body) = live.body[f] else { continue };
        if !*anchored {
            continue;
        }
        let c = prepared.fracture.fragments[f].centroid.as_vec3();
        let ground_pose = world
            .bodies
            .get(ground)
            .map_or(Pose::IDENTITY, |g| *g.position());
        let frame1 =
            ground_pose.inverse() * Pose::from_parts(pose.transform_point(c), pose.rotation);
        let joint = FixedJointBuilder::new()
            .local_frame1(frame1)
            .local_frame2(Pose::from_translation(c))
            .contacts_enabled(false);
        let handle = world.insert_impulse_joint(ground, body, joint);
        live.anchor_joints.push((f as u32, handle));
    }
}

/// The force a joint applied during the last step.
fn joint_force(joint: &ImpulseJoint, substep_dt: f32) -> f32 {
    let i = joint.impulses;
    Vec3::new(i[0], i[1], i[2]).length() / substep_dt
}

/// Removes the joints whose force exceeded the break force; returns how many broke.
pub(crate) fn break_overloaded(world: &mut PhysicsWorld, live: &mut LiveObject) -> usize {
    let params = &world.integration_parameters;
    let substep_dt = params.dt / params.num_solver_iterations.max(1) as f32;
    let strength = live.bonds.strength;
    let mut broke = 0;
    for b in 0..live.joints.len() {
        let Some(handle) = live.joints[b] else {
            continue;
        };
        let over = world
            .impulse_joints
            .get(handle)
            .is_some_and(|j| joint_force(j, substep_dt) > strength);
        if over {
            world.remove_impulse_joint(handle);
            live.joints[b] = None;
            live.mark_broken(b);
            broke += 1;
        }
    }
    let mut kept = Vec::with_capacity(live.anchor_joints.len());
    for (f, handle) in std::mem::take(&mut live.anchor_joints) {
        let over = world
            .impulse_joints
            .get(handle)
            .is_some_and(|j| joint_force(j, substep_dt) > strength);
        if over {
            world.remove_impulse_joint(handle);
        } else if world.impulse_joints.contains(handle) {
            kept.push((f, handle));
        }
    }
    live.anchor_joints = kept;
    broke
}

/// Breaks every joint of bonds in `bonds` (explicit breaks, e.g. from the API).
pub(crate) fn break_bonds(world: &mut PhysicsWorld, live: &mut LiveObject, bonds: &[u32]) {
    for &b in bonds {
        let b = b as usize;
        if b >= live.joints.len() {
            continue;
        }
        if let Some(handle) = live.joints[b].take() {
            world.remove_impulse_joint(handle);
        }
        live.mark_broken(b);
    }
}

/// Largest joint force of the last step (diagnostics).
pub(crate) fn max_force(world: &PhysicsWorld, live: &LiveObject) -> f32 {
    let params = &world.integration_parameters;
    let substep_dt = params.dt / params.num_solver_iterations.max(1) as f32;
    live.joints
        .iter()
        .flatten()
        .chain(live.anchor_joints.iter().map(|(_, h)| h))
        .filter_map(|h| world.impulse_joints.get(*h))
        .map(|j| joint_force(j, substep_dt))
        .fold(0.0, f32::max)
}
