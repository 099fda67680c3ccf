//! Runtime fracture in the world: a hit on a body holding one cuttable fragment starts a
//! cut around the hit point; when it is ready the fragment is replaced by a new, bonded
//! object that moves as the material did, and the hit loads its bonds.
//!
//! A cut runs on a thread (native) while the simulation goes on, and is applied at a step
//! fixed when it starts: `1 + ⌊estimate / dt⌋` steps later, the estimate from
//! [`shatter_geom::budget::Estimate::voronoi_fracture`]. The body stays whole until
//! then. Because the step is fixed in advance (not "when the thread is done"), a run is
//! the same on a fast machine and a slow one; a slow machine waits for the thread at that
//! step. On the web (no threads) the cut runs at that step.

use std::collections::BTreeMap;
use std::sync::Arc;

use glam::{DVec3, Vec3};
use rapier3d::prelude::*;
use web_time::Instant;

use crate::bonds::clusters::{self, Loads};
use crate::bonds::split::world_com;
use crate::bonds::tags::{Kind, untag};
use crate::breaking::inherited_velocity;
use crate::error::SimError;
use crate::object::prepare::prepare_with;
use crate::object::{BondModel, FractureSource};
use crate::runtime::{self, FractureTiming, cut_seed};
use crate::world::cut::{CutInput, CutJob, CutResult, PendingCut};
use crate::world::settings::SimEvent;
use crate::world::state::{ObjectId, ObjectRecord, World};
use crate::world::step::ContactHit;

/// The cut of `record`'s fragment `fragment` at `impact`: its model, the pieces of its
/// level ([`runtime::pieces_at`]) and the seed of its line.
fn cut_input(record: &ObjectRecord, fragment: u32, impact: DVec3) -> CutInput {
    CutInput::new(
        record.prepared.fracture.clone(),
        fragment as usize,
        impact,
        runtime::pieces_at(record.cut_pieces, record.level),
        cut_seed(record.cut_seed, fragment, record.level),
    )
}

/// What a cut needs from the record of the fragment it cuts.
struct CutRequest {
    object: ObjectId,
    fragment: u32,
    impact: DVec3,
    /// The hit's force, impulse on the fragment and the other body's mass.
    hit: (f32, Vec3, f32),
}

impl World {
    /// Starts cuts for this step's hits: the strongest hit on each body that holds a single
    /// cuttable fragment (see [`crate::runtime::RuntimeFracture::cuts`]) whose impulse
    /// passes the object's threshold.
    pub(crate) fn start_cuts(&mut self, hits: &[ContactHit]) {
        let mut strongest: BTreeMap<(u32, u32), (f32, CutRequest)> = BTreeMap::new();
        for hit in hits {
            for (collider, sign) in [(hit.collider1, -1.0), (hit.collider2, 1.0)] {
                let Some(request) = self.cut_request(hit, collider, sign) else {
                    continue;
                };
                let magnitude = hit.impulse.length();
                let key = (request.object.0, request.fragment);
                if strongest.get(&key).is_none_or(|(m, _)| magnitude > *m) {
                    strongest.insert(key, (magnitude, request));
                }
            }
        }
        for (_, (_, request)) in strongest {
            self.start_cut(request);
        }
    }

    /// The cut a hit on `collider` asks for, if its fragment is cuttable and the hit hard
    /// enough.
    fn cut_request(
        &self,
        hit: &ContactHit,
        collider: ColliderHandle,
        sign: f32,
    ) -> Option<CutRequest> {
        let co = self.physics.colliders.get(collider)?;
        let Some((Kind::Fragment, object, f)) = untag(co.user_data) else {
            return None;
        };
        let id = ObjectId(object);
        let record = self.objects.get(&id)?;
        let live = record.live.as_ref()?;
        if live.model != BondModel::Clusters || record.uncuttable.contains(&f) {
            return None;
        }
        let body = (*live.body.get(f as usize)?)?;
        // The cheap tests first: most hits on most objects cut nothing, and counting the
        // fragments on the body costs a pass over the object's fragments.
        let size = runtime::fragment_size(&record.prepared.fracture, f as usize);
        if !record.spec.runtime.cuts(record.level, size) {
            return None;
        }
        let threshold = record
            .spec
            .runtime
            .impulse
            .unwrap_or(record.spec.effective_break_force() * self.settings.dt);
        let impulse = hit.impulse * sign;
        if impulse.length() < threshold {
            return None;
        }
        if live.body.iter().filter(|b| **b == Some(body)).count() != 1
            || self.cuts.iter().any(|c| c.object == id && c.fragment == f)
        {
            return None;
        }
        let rb = self.physics.bodies.get(body)?;
        let fragment = &record.prepared.fracture.fragments[f as usize];
        let impact = match hit.point {
            Some(p) => rb.position().inverse_transform_point(p).as_dvec3(),
            None => fragment.centroid,
        };
        Some(CutRequest {
            object: id,
            fragment: f,
            impact,
            hit: (hit.force, impulse, hit.other_mass(&self.physics, sign)),
        })
    }

    fn start_cut(&mut self, request: CutRequest) {
        let Some(record) = self.objects.get(&request.object) else {
            return;
        };
        let input = cut_input(record, request.fragment, request.impact);
        let estimate = input.estimate();
        let lag = 1 + (estimate.seconds / f64::from(self.settings.dt)).floor() as u64;
        let job = CutJob::start(input);
        let (force, impulse, other_mass) = request.hit;
        self.cuts.push(PendingCut {
            object: request.object,
            fragment: request.fragment,
            impact: request.impact,
            force,
            impulse,
            other_mass,
            due: self.stats.steps + lag.min(600),
            job,
        });
    }

    /// Applies the cuts due at this step.
    pub(crate) fn finish_cuts(&mut self) {
        let steps = self.stats.steps;
        let (due, later): (Vec<PendingCut>, Vec<PendingCut>) = std::mem::take(&mut self.cuts)
            .into_iter()
            .partition(|c| c.due <= steps);
        self.cuts = later;
        let t0 = Instant::now();
        for cut in due {
            let (object, fragment) = (cut.object, cut.fragment);
            let hit = (cut.force, cut.impulse, cut.other_mass);
            let impact = cut.impact;
            match cut.job.finish() {
                Ok(cut) => {
                    if let Err(reason) =
                        self.replace_fragment(object, fragment, cut, impact, Some(hit))
                    {
                        self.cut_failed(object, fragment, reason);
                    }
                }
                Err(reason) => self.cut_failed(object, fragment, reason),
            }
        }
        self.stats.cut_apply_ms = t0.elapsed().as_secs_f64() * 1e3;
    }

    fn cut_failed(&mut self, object: ObjectId, fragment: u32, reason: String) {
        if let Some(record) = self.objects.get_mut(&object) {
            record.uncuttable.insert(fragment);
        }
        self.events.push(SimEvent::FractureFailed {
            object: object.0,
            fragment,
            reason,
        });
    }

    /// Cuts fragment `fragment` of object `id` now, around `point` (world frame), without
    /// loading the new bonds: a game's or a script's own demolition. The fragment must be
    /// alone on its body (an `on_impact` object's intact body, or a loose fragment); the
    /// cut pieces follow [`crate::runtime::pieces_at`] for its level. Returns the new
    /// object's id.
    ///
    /// ```
    /// use shatter_sim::runtime::{FractureTiming, RuntimeFracture};
    /// use shatter_sim::{FractureParams, FractureSource, ObjectSpec, Shape, World, WorldSettings};
    ///
    /// let mut world = World::new(WorldSettings::default());
    /// let mut spec = ObjectSpec::from_fracture(Default::default(), [0.0, 0.5, 0.0].into());
    /// spec.source = FractureSource::Shape { shape: Shape::Cube, params: FractureParams { pieces: 20, ..Default::default() } };
    /// spec.runtime = RuntimeFracture { timing: FractureTiming::OnImpact, ..Default::default() };
    /// let id = world.add_object(spec)?;
    /// assert_eq!(world.stats().fragments, 1); // one intact body
    /// let cut = world.cut_now(id, 0, [0.0, 1.0, 0.0].into())?;
    /// assert!(world.stats().fragments > 5);
    /// assert_eq!(world.spawned_from(cut), Some(id));
    /// # Ok::<(), shatter_sim::SimError>(())
    /// ```
    pub fn cut_now(
        &mut self,
        id: ObjectId,
        fragment: u32,
        point: Vec3,
    ) -> Result<ObjectId, SimError> {
        let key = format!("object {}.fragment {fragment}", id.0);
        let record = self.objects.get(&id).ok_or(SimError::NoSuchObject(id.0))?;
        let live = record
            .live
            .as_ref()
            .ok_or_else(|| SimError::invalid(&key, "the object has no bodies (expired)"))?;
        if live.model != BondModel::Clusters {
            return Err(SimError::invalid(
                &key,
                "runtime cuts need the clusters bond model",
            ));
        }
        let body = live
            .body
            .get(fragment as usize)
            .copied()
            .flatten()
            .ok_or_else(|| SimError::invalid(&key, "no such fragment with a body"))?;
        if live.body.iter().filter(|b| **b == Some(body)).count() != 1 {
            return Err(SimError::invalid(
                &key,
                "the fragment is bonded to others; only a body of one fragment is cut",
            ));
        }
        let rb = self
            .physics
            .bodies
            .get(body)
            .ok_or_else(|| SimError::invalid(&key, "the fragment's body is gone"))?;
        let impact = rb.position().inverse_transform_point(point).as_dvec3();
        let cut = cut_input(record, fragment, impact)
            .run()
            .map_err(|source| SimError::Fracture {
                key: key.clone(),
                source,
            })?;
        let t0 = Instant::now();
        let child = self
            .replace_fragment(id, fragment, cut, impact, None)
            .map_err(|reason| SimError::EmptyFracture { key, reason })?;
        self.stats.cut_apply_ms = t0.elapsed().as_secs_f64() * 1e3;
        self.report_breaks();
        self.update_counts();
        Ok(child)
    }

    /// Replaces fragment `fragment` of `id` by `fracture` (in the object's frame) as a new
    /// object with the body's pose and motion; loads its bonds with `hit` at `impact`.
    fn replace_fragment(
        &mut self,
        id: ObjectId,
        fragment: u32,
        cut: CutResult,
        impact: DVec3,
        hit: Option<(f32, Vec3, f32)>,
    ) -> Result<ObjectId, String> {
        let CutResult { fracture, shapes } = cut;
        let record = self.objects.get(&id).ok_or("the object is gone")?;
        let live = record.live.as_ref().ok_or("the object has no bodies")?;
        let body = live
            .body
            .get(fragment as usize)
            .copied()
            .flatten()
            .ok_or("the fragment's body is gone")?;
        let rb = self
            .physics
            .bodies
            .get(body)
            .ok_or("the fragment's body is gone")?;
        let (pose, v, w, c, dynamic) = (
            *rb.position(),
            rb.linvel(),
            rb.angvel(),
            world_com(rb),
            rb.is_dynamic(),
        );
        let mut spec = record.spec.clone();
        let anchored = spec.anchored && !dynamic;
        let prepared = prepare_with(
            &fracture,
            Vec3::ONE,
            spec.material.density,
            anchored,
            Some(shapes),
        );
        if prepared.shapes.iter().all(|p| p.is_empty()) {
            return Err(format!(
                "{} fragments, none with a convex piece",
                prepared.shapes.len()
            ));
        }
        let pieces = fracture.fragments.len();
        spec.name = format!("{} · cut {}", record.spec.name, record.level + 1);
        spec.source = FractureSource::Prebuilt(Arc::new(fracture));
        spec.scale = Vec3::ONE;
        spec.position = pose.translation;
        spec.rotation = pose.rotation;
        spec.anchored = anchored;
        spec.runtime.timing = FractureTiming::Precomputed;
        let child_record = ObjectRecord {
            spec,
            prepared: Arc::new(prepared),
            live: None,
            parent: Some(id),
            level: record.level + 1,
            cut_pieces: record.cut_pieces,
            cut_seed: cut_seed(record.cut_seed, fragment, record.level),
            uncuttable: Default::default(),
        };
        let level = child_record.level;
        // The old fragment goes.
        if let Some(live) = self.objects.get_mut(&id).and_then(|r| r.live.as_mut()) {
            live.drop_fragment(fragment as usize);
        }
        self.physics.remove_body(body);
        self.debris.retain(|(_, h)| *h != body);
        let child = ObjectId(self.next_id);
        self.next_id += 1;
        self.objects.insert(child, child_record);
        self.build_object(child);
        // It moves as the material did there.
        for h in self.object_bodies(child) {
            if let Some(rb) = self.physics.bodies.get_mut(h)
                && rb.is_dynamic()
                && dynamic
            {
                let ci = world_com(rb);
                rb.set_linvel(inherited_velocity(v, w, c, ci), true);
                rb.set_angvel(w, true);
            }
        }
        if let Some((force, impulse, other_mass)) = hit {
            self.load_cut(child, impact, force, impulse, other_mass);
        }
        self.stats.runtime_fractures += 1;
        self.stats.max_depth = self.stats.max_depth.max(level);
        self.events.push(SimEvent::Fractured {
            object: id.0,
            fragment,
            into: child.0,
            fragments: pieces,
            level,
        });
        Ok(child)
    }

    /// Loads the new object's bonds with the hit that cut it, at the fragment nearest the
    /// impact.
    fn load_cut(
        &mut self,
        child: ObjectId,
        impact: DVec3,
        force: f32,
        impulse: Vec3,
        other_mass: f32,
    ) {
        let Some(live) = self.objects.get(&child).and_then(|r| r.live.as_ref()) else {
            return;
        };
        let nearest = live
            .prepared
            .fracture
            .fragments
            .iter()
            .enumerate()
            .min_by(|(_, a), (_, b)| {
                a.centroid
                    .distance_squared(impact)
                    .total_cmp(&b.centroid.distance_squared(impact))
            })
            .map(|(i, _)| i as u32);
        let Some(f) = nearest else { return };
        let mut loads = Loads::default();
        clusters::load_from_contact(
            &self.physics,
            live,
            f,
            force,
            impulse,
            other_mass,
            &mut loads,
        );
        self.apply_loads(BTreeMap::from([(child.0, loads)]));
    }

    /// The object that `id` was cut from (`None` for an object the user added).
    pub fn spawned_from(&self, id: ObjectId) -> Option<ObjectId> {
        self.objects.get(&id)?.parent
    }

    /// The fracture level of object `id`'s fragments: 0 for an `on_impact` object's
    /// intact body, 1 for a precomputed object or a first cut, and one more per cut after.
    pub fn object_level(&self, id: ObjectId) -> Option<u32> {
        Some(self.objects.get(&id)?.level)
    }

    /// Cuts under way (started, not yet applied).
    pub fn pending_cuts(&self) -> usize {
        self.cuts.len()
    }
}
