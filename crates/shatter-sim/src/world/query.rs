//! Reading the world: ray casts for clicks, poses for renderers, the state digest,
//! momentum, and explicit bond breaks.

use std::collections::BTreeMap;
use std::sync::Arc;

use glam::{Mat3, Vec3};
use rapier3d::prelude::*;
use shatter_geom::fracture::Fracture;

use crate::bonds::clusters::Loads;
use crate::bonds::joints;
use crate::bonds::split::world_com;
use crate::bonds::tags::{Kind, untag};
use crate::object::{BondModel, ProjectileSpec};
use crate::world::state::{ObjectId, World};

/// A projectile as a renderer sees it.
#[derive(Debug, Clone)]
pub struct ProjectileView<'a> {
    /// Firing order since the last reset (stable while the projectile flies).
    pub index: usize,
    /// What was fired.
    pub spec: &'a ProjectileSpec,
    /// Current pose.
    pub pose: Pose,
}

impl World {
    /// The first object hit by the ray from `origin` along `dir`, and the hit point.
    /// Projectiles and the ground are ignored.
    pub fn ray_cast(&self, origin: Vec3, dir: Vec3) -> Option<(ObjectId, Vec3)> {
        let dir = dir.try_normalize()?;
        let ray = Ray::new(origin, dir);
        // A direct scan of the fragment colliders rather than the broad phase, which only
        // sees new bodies after a step (the app clicks on objects before Start).
        let mut best: Option<(Real, u32)> = None;
        for (_, co) in self.physics.colliders.iter() {
            // (A disabled collider is an enclosed fragment's: its neighbours are hit first.)
            if !co.is_enabled() {
                continue;
            }
            let Some((Kind::Fragment, object, _)) = untag(co.user_data) else {
                continue;
            };
            let max = best.map_or(Real::MAX, |(t, _)| t);
            if co.compute_aabb().cast_local_ray(&ray, max, true).is_none() {
                continue;
            }
            if let Some(t) = co.shape().cast_ray(co.position(), &ray, max, true)
                && best.is_none_or(|(bt, _)| t < bt)
            {
                best = Some((t, object));
            }
        }
        let (toi, object) = best?;
        Some((ObjectId(object), ray.point_at(toi)))
    }

    /// World transform of fragment `f` of object `id`: it maps the fragment's vertices
    /// (in [`World::object_fracture`], the object's scaled frame) to the world. `None` if
    /// the fragment has no body (removed, expired, diverged).
    pub fn fragment_pose(&self, id: ObjectId, f: u32) -> Option<Pose> {
        let live = self.objects.get(&id)?.live.as_ref()?;
        let body = (*live.body.get(f as usize)?)?;
        self.physics.bodies.get(body).map(|rb| *rb.position())
    }

    /// Every fragment of object `id` that has a body, with its pose (see
    /// [`World::fragment_pose`]), in fragment order. Empty for an unknown or expired object.
    pub fn fragment_poses(&self, id: ObjectId) -> Vec<(u32, Pose)> {
        let Some(live) = self.objects.get(&id).and_then(|r| r.live.as_ref()) else {
            return Vec::new();
        };
        live.body
            .iter()
            .enumerate()
            .filter_map(|(f, b)| {
                let rb = self.physics.bodies.get((*b)?)?;
                Some((f as u32, *rb.position()))
            })
            .collect()
    }

    /// The scaled fracture of object `id`: fragment meshes (with interior flags) in the
    /// frame that [`World::fragment_pose`] maps to the world.
    pub fn object_fracture(&self, id: ObjectId) -> Option<Arc<Fracture>> {
        Some(self.objects.get(&id)?.prepared.fracture.clone())
    }

    /// Colour of object `id`.
    pub fn object_color(&self, id: ObjectId) -> Option<[f32; 3]> {
        Some(self.objects.get(&id)?.spec.color)
    }

    /// Whether object `id` currently has bodies (not expired).
    pub fn object_alive(&self, id: ObjectId) -> bool {
        self.objects.get(&id).is_some_and(|r| r.live.is_some())
    }

    /// Per bond of object `id`: broken or not.
    pub fn bond_states(&self, id: ObjectId) -> Option<Vec<bool>> {
        Some(self.objects.get(&id)?.live.as_ref()?.bonds.broken.clone())
    }

    /// Per bond of object `id`: its health, 1 when new, worn by hits below the break
    /// force (damage); a broken bond keeps the health it had when it broke.
    pub fn bond_health(&self, id: ObjectId) -> Option<Vec<f32>> {
        Some(self.objects.get(&id)?.live.as_ref()?.bonds.health.clone())
    }

    /// The bond model object `id` uses.
    pub fn object_bond_model(&self, id: ObjectId) -> Option<BondModel> {
        Some(self.objects.get(&id)?.live.as_ref()?.model)
    }

    /// Distinct bodies of object `id`, in fragment order.
    pub fn object_bodies(&self, id: ObjectId) -> Vec<RigidBodyHandle> {
        let Some(live) = self.objects.get(&id).and_then(|r| r.live.as_ref()) else {
            return Vec::new();
        };
        let mut seen = std::collections::BTreeSet::new();
        live.body
            .iter()
            .flatten()
            .filter(|h| seen.insert(h.into_raw_parts()))
            .copied()
            .collect()
    }

    /// Per fragment of object `id`, how many colliders it has now: one per convex piece,
    /// and none for a fragment without a body or an enclosed one whose bonds all hold
    /// ([`WorldSettings::enclosed_colliders`](crate::WorldSettings::enclosed_colliders)).
    /// Empty for an unknown object.
    ///
    /// ```
    /// use shatter_sim::testing::box_grid_fracture;
    /// use shatter_sim::{ObjectSpec, World, WorldSettings};
    /// let mut world = World::new(WorldSettings::default());
    /// let spec = ObjectSpec::from_fracture(box_grid_fracture([3, 3, 3], [3.0, 3.0, 3.0].into()), [0.0, 5.0, 0.0].into());
    /// let id = world.add_object(spec).unwrap();
    /// let colliders = world.fragment_colliders(id);
    /// // The centre brick (1, 1, 1) is enclosed by its six bonded neighbours.
    /// assert_eq!(colliders[13], 0);
    /// assert_eq!(colliders.iter().filter(|&&n| n == 1).count(), 26);
    /// ```
    pub fn fragment_colliders(&self, id: ObjectId) -> Vec<usize> {
        self.objects
            .get(&id)
            .and_then(|r| r.live.as_ref())
            .map(|live| live.colliders.iter().map(Vec::len).collect())
            .unwrap_or_default()
    }

    /// Pairs of colliders in contact after the last step (Rapier's narrow phase, pairs
    /// with at least one active contact).
    pub fn touching_pairs(&self) -> usize {
        self.physics
            .narrow_phase
            .contact_pairs()
            .filter(|p| p.has_any_active_contact())
            .count()
    }

    /// The linear speed of the fastest dynamic body (fragments' and projectiles'; m/s),
    /// 0 without any.
    pub fn fastest_speed(&self) -> f32 {
        self.physics
            .bodies
            .iter()
            .filter(|(_, rb)| rb.is_dynamic())
            .map(|(_, rb)| rb.linvel().length())
            .fold(0.0, f32::max)
    }

    /// Projectiles in flight.
    pub fn projectiles(&self) -> Vec<ProjectileView<'_>> {
        self.projectiles
            .iter()
            .enumerate()
            .filter_map(|(index, p)| {
                let rb = self.physics.bodies.get(p.body?)?;
                Some(ProjectileView {
                    index,
                    spec: &p.spec,
                    pose: *rb.position(),
                })
            })
            .collect()
    }

    /// Linear momentum and angular momentum about `point` of all bodies of object `id`
    /// (each body: `m·v` and `m·(c − point) × v + I·ω`).
    pub fn object_momentum(&self, id: ObjectId, point: Vec3) -> (Vec3, Vec3) {
        let mut p = Vec3::ZERO;
        let mut l = Vec3::ZERO;
        for h in self.object_bodies(id) {
            let Some(rb) = self.physics.bodies.get(h) else {
                continue;
            };
            if !rb.is_dynamic() {
                continue;
            }
            let mprops = &rb.mass_properties().local_mprops;
            let m = mprops.mass();
            let c = world_com(rb);
            let r = Mat3::from_quat(rb.position().rotation);
            let inertia = r * mprops.reconstruct_inertia_matrix() * r.transpose();
            p += m * rb.linvel();
            l += m * (c - point).cross(rb.linvel()) + inertia * rb.angvel();
        }
        (p, l)
    }

    /// Sets the velocity of every dynamic body of object `id` to the rigid motion with
    /// linear velocity `v` at the centre of mass `centre` and angular velocity `w`.
    pub fn set_object_velocity(&mut self, id: ObjectId, centre: Vec3, v: Vec3, w: Vec3) {
        for h in self.object_bodies(id) {
            if let Some(rb) = self.physics.bodies.get_mut(h)
                && rb.is_dynamic()
            {
                let c = world_com(rb);
                rb.set_linvel(v + w.cross(c - centre), true);
                rb.set_angvel(w, true);
            }
        }
    }

    /// Breaks the given bonds of object `id` now (clusters split at once, joints are
    /// removed). Unknown indices are ignored.
    pub fn break_bonds(&mut self, id: ObjectId, bonds: &[u32]) {
        let Some(live) = self.objects.get_mut(&id).and_then(|r| r.live.as_mut()) else {
            return;
        };
        match live.model {
            BondModel::Joints => joints::break_bonds(&mut self.physics, live, bonds),
            BondModel::Clusters => {
                let strength = live.bonds.strength;
                let mut loads = Loads::default();
                for &b in bonds {
                    if (b as usize) < live.bonds.broken.len() {
                        loads.bonds.insert(b, strength * 2.0 + 1.0);
                    }
                }
                self.apply_loads(BTreeMap::from([(id.0, loads)]));
            }
        }
        self.report_breaks();
        self.update_counts();
    }

    /// Largest joint force (N) of object `id` in the last step (joints model; diagnostics).
    pub fn max_joint_force(&self, id: ObjectId) -> f32 {
        self.objects
            .get(&id)
            .and_then(|r| r.live.as_ref())
            .map_or(0.0, |live| joints::max_force(&self.physics, live))
    }

    /// A hash of the state: every object's fragment poses (bits of position and rotation)
    /// and bond states in id and fragment order, then the projectiles in firing order.
    /// Same scene and build → same digest.
    pub fn digest(&self) -> u64 {
        let mut h = Fnv::default();
        for (id, record) in &self.objects {
            h.write_u32(id.0);
            let Some(live) = &record.live else {
                h.write_u32(u32::MAX);
                continue;
            };
            for (f, body) in live.body.iter().enumerate() {
                h.write_u32(f as u32);
                match body.and_then(|b| self.physics.bodies.get(b)) {
                    Some(rb) => h.write_pose(rb.position()),
                    None => h.write_u32(u32::MAX),
                }
            }
            for &b in &live.bonds.broken {
                h.write_u32(u32::from(b));
            }
        }
        for p in &self.projectiles {
            match p.body.and_then(|b| self.physics.bodies.get(b)) {
                Some(rb) => h.write_pose(rb.position()),
                None => h.write_u32(u32::MAX),
            }
        }
        h.0
    }
}

/// FNV-1a, 64 bits: stable across runs and platforms (unlike `DefaultHasher`'s contract).
struct Fnv(u64);

impl Default for Fnv {
    fn default() -> Self {
        Fnv(0xcbf2_9ce4_8422_2325)
    }
}

impl Fnv {
    fn write_u32(&mut self, v: u32) {
        for byte in v.to_le_bytes() {
            self.0 ^= byte as u64;
            self.0 = self.0.wrapping_mul(0x0100_0000_01b3);
        }
    }

    fn write_pose(&mut self, p: &Pose) {
        for v in p.translation.to_array() {
            self.write_u32(v.to_bits());
        }
        for v in p.rotation.to_array() {
            self.write_u32(v.to_bits());
        }
    }
}
