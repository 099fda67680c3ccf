//! The components the plugin puts on a fractured object, its bodies and its fragments.

use std::sync::Arc;

use bevy::prelude::*;
use shatter_geom::fracture::Fracture;
use shatter_sim::breaking::{BondState, Graph};

use crate::Breakable;

/// A fragment of a fractured object: a child of its body entity, with the surface mesh,
/// the entity's own material and a collider; its interior (cut) faces are a child entity
/// with the interior material.
#[derive(Component, Debug, Clone, Copy, PartialEq, Eq)]
pub struct Fragment {
    /// The object (the former [`Breakable`](crate::Breakable) entity).
    pub object: Entity,
    /// The fragment's index in the fracture.
    pub index: u32,
}

/// The record of a fractured object, on the former [`Breakable`](crate::Breakable)
/// entity: its fracture, bond state and which body holds each fragment.
#[derive(Component, Debug, Clone)]
pub struct ShatterObject {
    /// The fracture (object frame).
    pub fracture: Arc<Fracture>,
    /// Per fragment, its mass (kg).
    pub masses: Vec<f32>,
    /// Per fragment, its bonds.
    pub adjacency: Vec<Vec<u32>>,
    /// Per bond, broken or not and its health.
    pub state: BondState,
    /// Per fragment, its body entity (`None`: no collider, or removed).
    pub body_of: Vec<Option<Entity>>,
    /// Per fragment, its entity (`Entity::PLACEHOLDER` without a collider).
    pub fragments: Vec<Entity>,
    /// Per fragment, whether it is fixed to the world.
    pub anchored: Vec<bool>,
    /// The fragments' fracture level ([`shatter_sim::runtime::RuntimeFracture::depth`]):
    /// 0 for an `on_impact` object's intact body, 1 for a fracture made at spawn (or
    /// loaded) and for an intact body's first runtime cut, one more per cut after.
    pub level: u32,
    /// The object this one was cut from at runtime (`None` for a [`Breakable`](crate::Breakable)
    /// entity's own record).
    pub parent: Option<Entity>,
}

impl ShatterObject {
    /// The bond graph for [`shatter_sim::breaking`].
    pub fn graph(&self) -> Graph<'_> {
        Graph {
            bonds: &self.fracture.bonds,
            adjacency: &self.adjacency,
            masses: &self.masses,
        }
    }

    /// Number of distinct bodies holding fragments.
    pub fn bodies(&self) -> usize {
        let mut b: Vec<Entity> = self.body_of.iter().flatten().copied().collect();
        b.sort();
        b.dedup();
        b.len()
    }
}

/// A rigid body made by the plugin, holding fragments of `object`.
#[derive(Component, Debug, Clone, Copy, PartialEq, Eq)]
pub struct ShatterBody {
    /// The object.
    pub object: Entity,
}

/// What an object needs to be cut at runtime, kept on its entity (the [`Breakable`] is
/// removed once it is fractured).
#[derive(Component, Debug, Clone)]
pub(crate) struct Cuttable {
    /// The object's settings; `seed` is the seed of its line of cuts.
    pub breakable: Breakable,
    /// The bonds' break force (N), also the threshold `strength · dt`.
    pub strength: f32,
    /// The entity's own (surface) material, kept on the new fragments.
    pub surface: Handle<StandardMaterial>,
    /// The interior material of cut faces.
    pub interior: Handle<StandardMaterial>,
    /// Fragments whose cut failed: not tried again.
    pub uncuttable: Vec<u32>,
}

/// The hit that cut an object, still to load the new object's bonds (next step).
#[derive(Component, Debug, Clone, Copy)]
pub(crate) struct PendingHit {
    /// The new fragment nearest the impact.
    pub fragment: u32,
    /// Contact force (N, scaled by the plugin's `contact_scale`).
    pub force: f32,
    /// Impulse on the cut fragment (N·s, world frame).
    pub impulse: Vec3,
    /// The other body's mass (0 when static).
    pub other_mass: f32,
}
