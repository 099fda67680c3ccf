//! The live state of a breakable object in the physics world, shared by both bond models.

use std::sync::Arc;

use glam::{Quat, Vec3};
use rapier3d::prelude::*;

use crate::bonds::tags::{Kind, tag};
use crate::breaking::{BondState, BreakCause, Graph};
use crate::object::{BondModel, Prepared};
use crate::stress::{BondGraph, SolverSettings, StressLimits, StressSolver};

/// A breakable object's bodies, colliders, joints and bond states.
#[derive(Debug, Clone)]
pub(crate) struct LiveObject {
    /// Bond model in use.
    pub model: BondModel,
    /// Geometry.
    pub prepared: Arc<Prepared>,
    /// Per fragment, its body (`None`: no valid collider, removed or diverged).
    pub body: Vec<Option<RigidBodyHandle>>,
    /// Per fragment, its colliders.
    pub colliders: Vec<Vec<ColliderHandle>>,
    /// Per bond, broken or not and its health (the engine-free break state).
    pub bonds: BondState,
    /// Per bond, its joint (joints model).
    pub joints: Vec<Option<ImpulseJointHandle>>,
    /// Joints to the world of anchored fragments (joints model): (fragment, joint).
    pub anchor_joints: Vec<(u32, ImpulseJointHandle)>,
    /// Stress solver state (clusters objects with anchored fragments).
    pub stress: Option<Box<StressState>>,
    /// Which fragments the joints hold, whose contacts are skipped (joints model).
    pub held: crate::bonds::held::Held,
    /// Per fragment, whether it is on its body without colliders ([`LiveObject::hide`]):
    /// an enclosed fragment whose bonds all hold (clusters model).
    pub hidden: Vec<bool>,
    /// How the hidden fragments' colliders are made when they are exposed (`None`: the
    /// object hides none).
    pub attach: Option<Attach>,
}

/// How an object's fragments get their colliders ([`LiveObject::attach_fragment`]).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Attach {
    /// The object's id.
    pub object: u32,
    /// Its material's values.
    pub surface: Surface,
    /// The contact-force event threshold (N), if any.
    pub force_events: Option<f32>,
}

/// The stress solver of an anchored cluster object.
#[derive(Debug, Clone)]
pub(crate) struct StressState {
    /// The bond graph in the object's frame.
    pub graph: BondGraph,
    /// The solver with its last solution.
    pub solver: StressSolver,
    /// The material's limits.
    pub limits: StressLimits,
    /// Bonds that carry nothing: broken, or touching a fragment without a body.
    pub mask: Vec<bool>,
    /// [`BondState::version`](crate::breaking::BondState::version) the mask was built at (`u64::MAX`: never).
    pub mask_version: u64,
    /// Forces (object frame) waiting for the next solve: explosions between steps.
    pub pending: Vec<(u32, glam::DVec3)>,
    /// The impulses (world frame) of those explosions on the same fragments, given to
    /// the pieces the solve breaks loose.
    pub pending_impulses: std::collections::BTreeMap<u32, (glam::Vec3, f32)>,
}

impl StressState {
    /// The state for `prepared`, or `None` if nothing is anchored (then no island ever
    /// carries a static load).
    /// The islands and their multigrid hierarchies are built here, with the object,
    /// rather than in its first step.
    pub fn new(
        prepared: &Prepared,
        limits: StressLimits,
        (budget, spring_budget, build_budget): (Option<usize>, Option<usize>, Option<usize>),
    ) -> Option<StressState> {
        if !prepared.anchored.iter().any(|a| *a) {
            return None;
        }
        let nodes = prepared
            .fracture
            .fragments
            .iter()
            .zip(&prepared.masses)
            .map(|(f, m)| crate::stress::Node {
                mass: f64::from(*m),
                centroid: f.centroid,
            })
            .collect();
        let bonds = prepared
            .fracture
            .bonds
            .iter()
            .map(|b| crate::stress::GraphBond {
                a: b.a,
                b: b.b,
                area: b.area,
                centroid: b.centroid,
                normal: b.normal,
            })
            .collect();
        let graph = BondGraph::new(nodes, bonds, prepared.anchored.clone()).ok()?;
        let mut solver = StressSolver::new(
            &graph,
            SolverSettings {
                budget,
                spring_budget,
                build_budget,
                ..SolverSettings::default()
            },
        );
        let m = prepared.fracture.bonds.len();
        solver.prepare(&graph, &vec![false; m]);
        Some(StressState {
            graph,
            solver,
            limits,
            mask: vec![false; m],
            mask_version: u64::MAX,
            pending: Vec::new(),
            pending_impulses: Default::default(),
        })
    }
}

/// Material values a collider needs.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Surface {
    pub density: f32,
    pub friction: f32,
    pub restitution: f32,
    /// A box-shaped piece collides as a cuboid ([`crate::WorldSettings::box_colliders`]).
    pub boxes: bool,
    /// Enclosed fragments get no colliders until a bond of theirs breaks
    /// ([`LiveObject::hide`]; the opposite of [`crate::WorldSettings::enclosed_colliders`]).
    pub hide_enclosed: bool,
    /// Contacts between fragments the joints hold are skipped
    /// ([`crate::bonds::held`]; joints model).
    pub skip_held: bool,
}

impl LiveObject {
    /// An object with no bodies yet.
    pub fn empty(model: BondModel, prepared: Arc<Prepared>, strength: f32) -> LiveObject {
        let n = prepared.fracture.fragments.len();
        let m = prepared.fracture.bonds.len();
        LiveObject {
            model,
            prepared,
            body: vec![None; n],
            colliders: vec![Vec::new(); n],
            bonds: BondState::new(m, strength, 0.0),
            joints: vec![None; m],
            anchor_joints: Vec::new(),
            stress: None,
            held: crate::bonds::held::Held {
                version: u64::MAX,
                near: Vec::new(),
            },
            hidden: vec![false; n],
            attach: None,
        }
    }

    /// Puts fragment `f` on `body` without colliders when it is enclosed
    /// ([`Prepared::enclosed`]), has collision shapes and its bonds all hold; returns
    /// whether it did. Its colliders are made, as [`LiveObject::attach`] says, when a bond
    /// of it breaks ([`LiveObject::expose_broken`]); meanwhile its mass counts in the
    /// body's additional mass properties ([`LiveObject::set_mass`]).
    ///
    /// (Disabled colliders would not do: Rapier's continuous collision detection still
    /// sweeps them, computing each one's mass properties every step the body moves fast.)
    pub fn hide(&mut self, f: u32, body: RigidBodyHandle) -> bool {
        let i = f as usize;
        let enclosed = self.prepared.enclosed.get(i).copied().unwrap_or(false);
        let shaped = self.prepared.shapes.get(i).is_some_and(|s| !s.is_empty());
        if self.attach.is_none() || !enclosed || !shaped || self.hidden[i] || self.any_broken(i) {
            return false;
        }
        self.body[i] = Some(body);
        self.hidden[i] = true;
        true
    }

    /// Makes the colliders of every hidden fragment of `fragments` that has a broken
    /// bond, on its body: its neighbour there may now be on another body, and it can be
    /// touched. Call after the fragments' bodies are set.
    pub fn expose_broken(&mut self, world: &mut PhysicsWorld, fragments: &[u32]) {
        let Some(attach) = self.attach else {
            return;
        };
        for &f in fragments {
            let i = f as usize;
            if !self.hidden.get(i).copied().unwrap_or(false) || !self.any_broken(i) {
                continue;
            }
            self.hidden[i] = false;
            if let Some(body) = self.body[i] {
                self.attach_fragment(world, f, body, attach);
            }
        }
    }

    /// Whether a bond of fragment `f` is broken.
    fn any_broken(&self, f: usize) -> bool {
        self.prepared.adjacency[f]
            .iter()
            .any(|&b| self.bonds.broken[b as usize])
    }

    /// Sets the mass properties of `body`, which holds `fragments`: those of its
    /// colliders (Rapier's sum) and, as the body's additional mass properties, those of
    /// its hidden fragments, which have no colliders.
    pub fn set_mass(&self, world: &mut PhysicsWorld, body: RigidBodyHandle, fragments: &[u32]) {
        let mut extra = MassProperties::default();
        if let Some(attach) = self.attach {
            for &f in fragments {
                if self.hidden.get(f as usize).copied().unwrap_or(false) {
                    extra += self.exact_mass(f, attach.surface.density, Vec3::ZERO);
                }
            }
        }
        let colliders = &world.colliders;
        if let Some(rb) = world.bodies.get_mut(body) {
            rb.set_additional_mass_properties(extra, false);
            rb.recompute_mass_properties_from_colliders(colliders);
        }
    }

    /// The fragments that currently have a body.
    pub fn alive_fragments(&self) -> usize {
        self.body.iter().filter(|b| b.is_some()).count()
    }

    /// Attaches colliders for fragment `f` to `body`, one per valid convex piece, made as
    /// `attach` says; returns how many were made.
    pub fn attach_fragment(
        &mut self,
        world: &mut PhysicsWorld,
        f: u32,
        body: RigidBodyHandle,
        attach: Attach,
    ) -> usize {
        let Attach {
            object,
            surface,
            force_events,
        } = attach;
        let mut made = Vec::new();
        for piece in &self.prepared.shapes[f as usize] {
            let (builder, offset) = match piece.cuboid.filter(|_| surface.boxes) {
                Some((centre, half)) => (
                    ColliderBuilder::cuboid(half.x, half.y, half.z).translation(centre),
                    centre,
                ),
                None => (ColliderBuilder::new(piece.hull.clone()), Vec3::ZERO),
            };
            // The fragment's exact mass properties sit on its first collider (in that
            // collider's frame: the object's, moved by a cuboid's offset); the others
            // only collide. (The hulls' own would be up to a few per cent off where a
            // piece is convex only within the decomposition's tolerance, and a runtime
            // cut or a split would then change the momentum.)
            let mprops = if made.is_empty() {
                self.exact_mass(f, surface.density, offset)
            } else {
                MassProperties::default()
            };
            let mut builder = builder
                .active_hooks(if surface.skip_held {
                    ActiveHooks::FILTER_CONTACT_PAIRS
                } else {
                    ActiveHooks::empty()
                })
                .mass_properties(mprops)
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

    /// Fragment `f`'s mass properties at `density` in the object's frame moved by
    /// `offset` (a collider's frame): mass, centroid and inertia from its exact volume
    /// and inertia tensor.
    fn exact_mass(&self, f: u32, density: f32, offset: Vec3) -> MassProperties {
        let fragment = &self.prepared.fracture.fragments[f as usize];
        let mass = self.prepared.masses[f as usize];
        let i = fragment.inertia * f64::from(density);
        let centroid = fragment.centroid - offset.as_dvec3();
        MassProperties::with_inertia_matrix(centroid.as_vec3(), mass, i.as_mat3())
    }

    /// Marks bond `b` broken by an impact (idempotent).
    pub fn mark_broken(&mut self, b: usize) {
        self.mark_broken_by(b, BreakCause::Impact);
    }

    /// Marks bond `b` broken by `cause` (idempotent); returns whether it was intact.
    pub fn mark_broken_by(&mut self, b: usize, cause: BreakCause) -> bool {
        self.bonds.mark_broken(b, cause)
    }

    /// The bond graph, for the engine-free break logic.
    pub fn graph(&self) -> Graph<'_> {
        Graph {
            bonds: &self.prepared.fracture.bonds,
            adjacency: &self.prepared.adjacency,
            masses: &self.prepared.masses,
        }
    }

    /// Takes fragment `f`'s body away (removed debris, diverged body).
    pub fn drop_fragment(&mut self, f: usize) {
        self.body[f] = None;
        self.colliders[f].clear();
        self.hidden[f] = false;
        self.bonds.touch();
    }
}

/// The pose of an object's frame.
pub(crate) fn object_pose(position: Vec3, rotation: Quat) -> Pose {
    Pose::from_parts(position, rotation)
}
