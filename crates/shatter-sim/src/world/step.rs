//! One fixed step: timed actions, Rapier and bond breaking (its upkeep after: `upkeep`);
//! firing and explosions.

use std::collections::BTreeMap;
use std::sync::Mutex;
use web_time::Instant;

use glam::{Quat, Vec3};
use rapier3d::prelude::*;

use crate::bonds::clusters::{self, Loads};
use crate::bonds::held::HeldContacts;
use crate::bonds::live::LiveObject;
use crate::bonds::tags::{Kind, tag, untag};
use crate::bonds::{joints, split};
use crate::object::{BondModel, ExplosionSpec, ProjectileShape, ProjectileSpec};
use crate::world::settings::WorldSettings;
use crate::world::settings::{BreakCause, SimEvent};
use crate::world::state::{Action, ObjectId, Projectile, RunState, World};

/// One contact-force report: the two colliders, the impulse on `collider2` and the force.
#[derive(Debug, Clone, Copy)]
pub(crate) struct ContactHit {
    pub collider1: ColliderHandle,
    pub collider2: ColliderHandle,
    pub impulse: Vec3,
    pub force: f32,
    /// Where it touched (world frame): the contact points' mean, weighted by their
    /// impulses when the solver reports any.
    pub point: Option<Vec3>,
}

impl ContactHit {
    /// The mass of the body on the other side from the one `sign` names (`+1`: the hit
    /// seen from `collider2`, so the other is `collider1`); 0 when it is not dynamic.
    pub(crate) fn other_mass(&self, physics: &PhysicsWorld, sign: f32) -> f32 {
        let other = if sign > 0.0 {
            self.collider1
        } else {
            self.collider2
        };
        physics
            .colliders
            .get(other)
            .and_then(|c| c.parent())
            .and_then(|b| physics.bodies.get(b))
            .filter(|rb| rb.is_dynamic())
            .map_or(0.0, |rb| rb.mass())
    }
}

/// Collects Rapier's contact-force events during a step.
#[derive(Default)]
struct HitCollector(Mutex<Vec<ContactHit>>);

impl EventHandler for HitCollector {
    fn handle_collision_event(
        &self,
        _bodies: &RigidBodySet,
        _colliders: &ColliderSet,
        _event: CollisionEvent,
        _contact_pair: Option<&ContactPair>,
    ) {
    }

    fn handle_contact_force_event(
        &self,
        _dt: Real,
        _bodies: &RigidBodySet,
        colliders: &ColliderSet,
        contact_pair: &ContactPair,
        total_force_magnitude: Real,
    ) {
        let hit = ContactHit {
            collider1: contact_pair.collider1,
            collider2: contact_pair.collider2,
            impulse: contact_pair.total_impulse(),
            force: total_force_magnitude,
            point: contact_point(colliders, contact_pair),
        };
        if let Ok(mut hits) = self.0.lock() {
            hits.push(hit);
        }
    }

    fn handle_soft_body_tear_event(&self, _soft_bodies: &SoftBodySet, _event: &SoftBodyTearEvent) {}
}

/// The contact points' mean in the world frame, weighted by their normal impulses (plain
/// mean when they are all zero).
fn contact_point(colliders: &ColliderSet, pair: &ContactPair) -> Option<Vec3> {
    let pose = colliders.get(pair.collider1)?.position();
    let (mut sum, mut weight, mut plain, mut n) = (Vec3::ZERO, 0.0f32, Vec3::ZERO, 0usize);
    for manifold in pair.manifolds() {
        for point in &manifold.points {
            let p = pose.transform_point(point.local_p1);
            let w = point.data.impulse.max(0.0);
            sum += p * w;
            weight += w;
            plain += p;
            n += 1;
        }
    }
    if weight > 0.0 {
        Some(sum / weight)
    } else if n > 0 {
        Some(plain / n as f32)
    } else {
        None
    }
}

impl World {
    /// Advances one fixed step if running; returns whether it did.
    pub fn step(&mut self) -> bool {
        if self.state != RunState::Running {
            return false;
        }
        let t0 = Instant::now();
        let time = self.stats.time;
        while let Some((at, action)) = self.schedule.get(self.next_action).cloned() {
            if at > time + 1e-9 {
                break;
            }
            self.next_action += 1;
            match action {
                Action::Fire(spec) => self.fire(spec),
                Action::Explode(spec) => self.explode(spec),
            }
        }
        let hits = HitCollector::default();
        for record in self.objects.values_mut() {
            if let Some(live) = record.live.as_mut()
                && live.model == BondModel::Joints
            {
                live.held.update(&live.prepared, &live.bonds);
            }
        }
        let filter = HeldContacts {
            objects: self
                .objects
                .iter()
                .filter_map(|(id, r)| r.live.as_ref().map(|live| (id.0, live)))
                .filter(|(_, live)| live.model == BondModel::Joints)
                .map(|(id, live)| (id, &live.held))
                .collect(),
        };
        let cap = self.settings.contact_speed_cap;
        if cap {
            self.speed_cap.record(&self.physics);
        }
        self.physics.step_with_events(&filter, &hits);
        if cap {
            let margin = self.settings.gravity.length() * self.settings.dt
                + self
                    .physics
                    .integration_parameters
                    .max_corrective_velocity();
            self.stats.speeds_capped += self.speed_cap.apply(&mut self.physics, margin);
        }
        self.stats.steps += 1;
        self.stats.time = self.stats.steps as f64 * self.settings.dt as f64;
        let hits = hits.0.into_inner().unwrap_or_default();
        self.break_joints();
        self.start_cuts(&hits);
        self.break_clusters(&hits);
        self.break_by_stress(&hits);
        self.finish_cuts();
        self.report_breaks();
        self.expire();
        self.guard();
        self.cap_debris();
        self.update_counts();
        self.stats.last_step_ms = t0.elapsed().as_secs_f64() * 1e3;
        true
    }

    fn break_joints(&mut self) {
        for (id, record) in self.objects.iter_mut() {
            let Some(live) = record.live.as_mut() else {
                continue;
            };
            if live.model != BondModel::Joints
                || joints::break_overloaded(&mut self.physics, live) == 0
            {
                continue;
            }
            // A fragment whose bonds (and anchor) are all gone is debris.
            for (f, body) in live.body.iter().enumerate() {
                let Some(h) = *body else { continue };
                let loose = live.prepared.adjacency[f]
                    .iter()
                    .all(|&b| live.bonds.broken[b as usize])
                    && !live.anchor_joints.iter().any(|(a, _)| *a as usize == f);
                if loose && !self.debris.contains(&(id.0, h)) {
                    self.debris.push_back((id.0, h));
                    tiny_debris(&mut self.physics, live, f as u32, self.settings.tiny_debris);
                }
            }
        }
    }

    fn break_clusters(&mut self, hits: &[ContactHit]) {
        let relief = self.weight_relief(hits);
        let mut loads: BTreeMap<u32, Loads> = BTreeMap::new();
        for hit in hits {
            for (collider, sign) in [(hit.collider1, -1.0), (hit.collider2, 1.0)] {
                let Some(co) = self.physics.colliders.get(collider) else {
                    continue;
                };
                let Some((Kind::Fragment, object, f)) = untag(co.user_data) else {
                    continue;
                };
                let Some(live) = self
                    .objects
                    .get(&ObjectId(object))
                    .and_then(|r| r.live.as_ref())
                else {
                    continue;
                };
                if live.model != BondModel::Clusters {
                    continue;
                }
                let other_mass = hit.other_mass(&self.physics, sign);
                let factor = co
                    .parent()
                    .and_then(|b| relief.get(&b.into_raw_parts()).copied())
                    .unwrap_or(1.0);
                let entry = loads.entry(object).or_default();
                clusters::load_from_contact(
                    &self.physics,
                    live,
                    f,
                    hit.force * factor,
                    hit.impulse * sign,
                    other_mass,
                    entry,
                );
            }
        }
        self.apply_loads(loads);
    }

    /// Per dynamic cluster body touched this step: the fraction of its reported contact
    /// forces that does more than hold it up, `max(0, (S − M·|g|) / S)` for a sum `S` of
    /// contact forces and a weight `M·|g|`. A body resting on the ground (S ≈ M·|g|) puts no
    /// load on its bonds; a hard landing or a hit (S ≫ M·|g|) nearly all of it. Bodies not
    /// in the map (fixed ones) take the full force.
    fn weight_relief(&self, hits: &[ContactHit]) -> BTreeMap<(u32, u32), f32> {
        // Keyed by the handle's raw parts (handles are not ordered); sums in hit order, so
        // the result is deterministic.
        let mut sums: BTreeMap<(u32, u32), f32> = BTreeMap::new();
        for hit in hits {
            for collider in [hit.collider1, hit.collider2] {
                let Some(co) = self.physics.colliders.get(collider) else {
                    continue;
                };
                if !matches!(untag(co.user_data), Some((Kind::Fragment, _, _))) {
                    continue;
                }
                if let Some(b) = co.parent() {
                    *sums.entry(b.into_raw_parts()).or_insert(0.0) += hit.force;
                }
            }
        }
        let g = self.settings.gravity.length();
        sums.into_iter()
            .filter_map(|(raw, sum)| {
                let rb = self
                    .physics
                    .bodies
                    .get(RigidBodyHandle::from_raw_parts(raw.0, raw.1))?;
                if !rb.is_dynamic() || sum <= 0.0 {
                    return None;
                }
                Some((raw, ((sum - rb.mass() * g) / sum).max(0.0)))
            })
            .collect()
    }

    /// Breaks overloaded bonds and splits the bodies they held.
    pub(crate) fn apply_loads(&mut self, loads: BTreeMap<u32, Loads>) {
        for (object, loads) in loads {
            let Some(live) = self
                .objects
                .get_mut(&ObjectId(object))
                .and_then(|r| r.live.as_mut())
            else {
                continue;
            };
            let bodies = clusters::break_loaded(live, &loads);
            let splits = split_bodies(
                &mut self.physics,
                &mut self.debris,
                live,
                object,
                bodies,
                &loads.impulses,
                &self.settings,
            );
            for parts in splits {
                self.events.push(SimEvent::Split { object, parts });
            }
        }
    }

    /// Pushes a [`SimEvent::BondsBroken`] per object and cause for the bonds broken since
    /// the last report.
    pub(crate) fn report_breaks(&mut self) {
        for (id, record) in &self.objects {
            let Some(live) = &record.live else { continue };
            let seen = self.reported.entry(id.0).or_insert([0; 3]);
            for cause in BreakCause::ALL {
                let (now, before) = (live.bonds.broken_by[cause.index()], seen[cause.index()]);
                if now > before {
                    self.events.push(SimEvent::BondsBroken {
                        object: id.0,
                        cause,
                        count: now - before,
                    });
                }
            }
            *seen = live.bonds.broken_by;
        }
    }

    /// Fires a projectile now.
    pub fn fire(&mut self, spec: ProjectileSpec) {
        let index = self.projectiles.len() as u32;
        let dir = (spec.to - spec.from).normalize_or(Vec3::NEG_Z);
        let rotation = Quat::from_rotation_arc(Vec3::Y, dir);
        let s = spec.size;
        let collider = match &spec.shape {
            ProjectileShape::Cube => ColliderBuilder::cuboid(s / 2.0, s / 2.0, s / 2.0),
            ProjectileShape::Sphere => ColliderBuilder::ball(s / 2.0),
            ProjectileShape::Capsule => ColliderBuilder::capsule_y(s / 4.0, s / 4.0),
            ProjectileShape::Cylinder => ColliderBuilder::cylinder(s / 2.0, s / 2.0),
            ProjectileShape::Custom(points) => {
                let pts: Vec<Vec3> = points.iter().map(|p| p.as_vec3() * s).collect();
                ColliderBuilder::convex_hull(&pts).unwrap_or_else(|| ColliderBuilder::ball(s / 2.0))
            }
        };
        let body = self.physics.insert_body(
            RigidBodyBuilder::dynamic()
                .pose(Pose::from_parts(spec.from, rotation))
                .linvel(dir * spec.speed)
                .ccd_enabled(true)
                .user_data(tag(Kind::Projectile, index, 0)),
        );
        self.physics.insert_collider(
            collider
                .density(spec.density)
                .friction(0.5)
                .restitution(0.1)
                .user_data(tag(Kind::Projectile, index, 0)),
            Some(body),
        );
        self.projectiles.push(Projectile {
            spec,
            body: Some(body),
            fired_at: self.stats.time,
        });
        self.update_counts();
    }

    /// Sets off an explosion now: cluster bonds in the radius are loaded (and may break),
    /// then every dynamic body whose centre of mass is in the radius gets an impulse
    /// `power·(1 − d/radius)` pointing away from the centre, less where it would make
    /// the body faster than [`WorldSettings::max_launch_speed`](crate::WorldSettings)
    /// (then it leaves at that speed, in the direction the full impulse gave it).
    pub fn explode(&mut self, spec: ExplosionSpec) {
        let mut loads: BTreeMap<u32, Loads> = BTreeMap::new();
        for (id, record) in &self.objects {
            let Some(live) = record.live.as_ref() else {
                continue;
            };
            if live.model == BondModel::Clusters {
                let entry = loads.entry(id.0).or_default();
                clusters::load_from_explosion(
                    &self.physics,
                    live,
                    spec.position,
                    spec.radius,
                    spec.power,
                    self.settings.dt,
                    entry,
                );
            }
        }
        self.apply_loads(loads);
        self.queue_explosion_forces(&spec);
        self.report_breaks();
        let ground = self.ground;
        let mut pushes = Vec::new();
        for (h, rb) in self.physics.bodies.iter() {
            if Some(h) == ground || !rb.is_dynamic() {
                continue;
            }
            let c = split::world_com(rb);
            let d = c - spec.position;
            let x = d.length();
            if x < spec.radius {
                let dir = if x > 1e-6 { d / x } else { Vec3::Y };
                pushes.push((h, dir * spec.power * (1.0 - x / spec.radius)));
            }
        }
        let limit = self.settings.max_launch_speed;
        for (h, impulse) in pushes {
            if let Some(rb) = self.physics.bodies.get_mut(h) {
                let most = limit.max(rb.linvel().length());
                rb.apply_impulse(impulse, true);
                if rb.linvel().length() > most {
                    rb.set_linvel(rb.linvel().clamp_length_max(most), true);
                }
            }
        }
        self.update_counts();
    }
}

/// Splits each of `bodies` into its components and lists the new single-fragment dynamic
/// bodies as debris. Returns, per body that split, the fragments of each of its parts
/// (the part that kept the old body first). Parts freed from a fixed body are launched at
/// most at `settings.max_launch_speed`; tiny debris is put in its collision group
/// ([`tiny_debris`]).
pub(crate) fn split_bodies(
    physics: &mut PhysicsWorld,
    debris: &mut std::collections::VecDeque<(u32, RigidBodyHandle)>,
    live: &mut LiveObject,
    object: u32,
    bodies: Vec<RigidBodyHandle>,
    impulses: &BTreeMap<u32, (Vec3, f32)>,
    settings: &WorldSettings,
) -> Vec<Vec<Vec<u32>>> {
    let mut splits = Vec::new();
    for body in bodies {
        let split = split::split(
            physics,
            live,
            object,
            body,
            impulses,
            settings.max_launch_speed,
        );
        let mut parts = Vec::with_capacity(split.len());
        for (i, (h, fragments)) in split.into_iter().enumerate() {
            let dynamic = physics.bodies.get(h).is_some_and(|rb| rb.is_dynamic());
            // (A new body cannot be listed yet; only the old one is looked up.)
            if fragments.len() == 1 && dynamic && (i > 0 || !debris.contains(&(object, h))) {
                debris.push_back((object, h));
                tiny_debris(physics, live, fragments[0], settings.tiny_debris);
            }
            parts.push(fragments);
        }
        if parts.is_empty() {
            continue;
        }
        splits.push(parts);
    }
    splits
}

/// Collision group of tiny debris ([`WorldSettings::tiny_debris`]): its members do not
/// collide with each other, only with everything else (whose groups are the default, all
/// memberships and all filters).
pub(crate) const TINY_DEBRIS_GROUPS: InteractionGroups = InteractionGroups::new(
    Group::GROUP_32,
    Group::ALL.difference(Group::GROUP_32),
    InteractionTestMode::And,
);

/// Puts fragment `f`'s colliders in the tiny-debris group when its size is under `size`.
pub(crate) fn tiny_debris(physics: &mut PhysicsWorld, live: &LiveObject, f: u32, size: f32) {
    if live
        .prepared
        .sizes
        .get(f as usize)
        .is_none_or(|&s| s >= size)
    {
        return;
    }
    for &c in &live.colliders[f as usize] {
        if let Some(co) = physics.colliders.get_mut(c) {
            co.set_collision_groups(TINY_DEBRIS_GROUPS);
        }
    }
}
