//! The live state of a breakable object in the physics world, shared by both bond models.

use std::sync::Arc;

use glam::{Quat, Vec3};
use rapier3d::prelude::*;

use crate::bonds::tags::{Kind, tag};
use crate::object::{BondModel, Prepared};

/// A breakable object's bodies, colliders, joints and bond states.
#[derive(Debug, Clone)]
pub(crate) struct LiveObject {
    /// Bond model in use.
    pub model: BondModel,
    /// Geometry.
    pub prepared: Arc<Prepared>,
    /// Break force of every bond (N).
    pub strength: f32,
    /// Per fragment, its body (`None`: no valid collider, removed or diverged).
    pub body: Vec<Option<RigidBodyHandle>>,
    /// Per fragment, its colliders.
    pub colliders: Vec<Vec<ColliderHandle>>,
    /// Per bond, broken or not.
    pub broken: Vec<bool>,
    /// Per bond, its joint (joints model).
    pub joints: Vec<Option<ImpulseJointHandle>>,
    /// Joints to the world of anchored fragments (joints model): (fragment, joint).
    pub anchor_joints: Vec<(u32, ImpulseJointHandle)>,
    /// Number of broken bonds.
    pub bonds_broken: usize,
}

/// Material values a collider needs.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Surface {
    pub density: f32,
    pub friction: f32,
    pub restitution: f32,
}

impl LiveObject {
    /// An object with no bodies yet.
    pub fn empty(model: BondModel, prepared: Arc<Prepared>, strength: f32) -> LiveObject {
        let n = prepared.fracture.fragments.len();
        let m = prepared.fracture.bonds.len();
        LiveObject {
            model,
            prepared,
            strength,
            body: vec![None; n],
            colliders: vec![Vec::new(); n],
            broken: vec![false; m],
            joints: vec![None; m],
            anchor_joints: Vec::new(),
            bonds_broken: 0,
        }
    }

    /// The fragments that currently have a body.
    pub fn alive_fragments(&self) -> usize {
        self.body.iter().filter(|b| b.is_some()).count()
    }

    /// Attaches colliders for fragment `f` to `body`, one per valid convex piece; returns
    /// how many were made.
    pub fn attach_fragment(
        &mut self,
        world: &mut PhysicsWorld,
        object: u32,
        f: u32,
        body: RigidBodyHandle,
        surface: Surface,
        force_events: Option<f32>,
    ) -> usize {
        let mut made = Vec::new();
        for piece in &self.prepared.pieces[f as usize] {
            let Some(builder) = ColliderBuilder::convex_hull(piece) else {
                continue;
            };
            let mut builder = builder
                .density(surface.density)
                .friction(surface.friction)
                .restitution(surface.restitution)
                .user_data(tag(Kind::Fragment, object, f));
            if let Some(threshold) = force_events {
                builder = builder
                    .active_events(ActiveEvents::CONTACT_FORCE_EVENTS)
                    .contact_force_event_threshold(threshold);
            }
            made.push(world.insert_collider(builder, Some(body)));
        }
        let count = made.len();
        if count > 0 {
            self.body[f as usize] = Some(body);
        }
        self.colliders[f as usize] = made;
        count
    }

    /// Marks bond `b` broken (idempotent).
    pub fn mark_broken(&mut self, b: usize) {
        if !self.broken[b] {
            self.broken[b] = true;
            self.bonds_broken += 1;
        }
    }
}

/// The pose of an object's frame.
pub(crate) fn object_pose(position: Vec3, rotation: Quat) -> Pose {
    Pose::from_parts(position, rotation)
}
