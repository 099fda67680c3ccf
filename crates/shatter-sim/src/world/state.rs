//! The world: its objects, projectiles and schedule, and the start / pause / reset / clean
//! controls. Every object keeps its spec and prepared geometry; reset rebuilds the physics
//! from them, so the initial state comes back bit for bit.

use std::collections::BTreeMap;
use std::sync::Arc;

use rapier3d::prelude::*;

use crate::bonds::live::{LiveObject, StressState, Surface, object_pose};
use crate::bonds::tags::{Kind, tag};
use crate::bonds::{clusters, joints};
use crate::error::SimError;
use crate::object::prepare::{prepare, resolve_fracture};
use crate::object::{BondModel, ExplosionSpec, ObjectSpec, Prepared, ProjectileSpec};
use crate::runtime::FractureTiming;
use crate::world::cut::PendingCut;
pub(crate) use crate::world::settings::{ObjectId, RunState};
use crate::world::settings::{SimEvent, Stats, WorldSettings};
use shatter_geom::io::{FileSystem, Layered, MemoryFiles};

/// A breakable object: what was asked for, its geometry, and its live physics state.
#[derive(Debug)]
pub(crate) struct ObjectRecord {
    pub spec: ObjectSpec,
    pub prepared: Arc<Prepared>,
    pub live: Option<LiveObject>,
    /// The object this one was cut from at runtime (`None`: added by the user). Cut
    /// objects go on reset.
    pub parent: Option<ObjectId>,
    /// Fracture level of the fragments (see [`World::object_level`]).
    pub level: u32,
    /// Pieces and seed of the runtime cuts of this object's line.
    pub cut_pieces: u32,
    pub cut_seed: u64,
    /// Fragments whose cut failed (not tried again).
    pub uncuttable: std::collections::BTreeSet<u32>,
}

impl ObjectRecord {
    /// The record of an object the user added.
    fn added(spec: ObjectSpec, prepared: Arc<Prepared>) -> ObjectRecord {
        let default = crate::object::FractureParams::default();
        let params = spec.source.params().unwrap_or(&default);
        let (cut_pieces, cut_seed) = (params.pieces, params.seed);
        let level = u32::from(spec.runtime.timing != FractureTiming::OnImpact);
        ObjectRecord {
            spec,
            prepared,
            live: None,
            parent: None,
            level,
            cut_pieces,
            cut_seed,
            uncuttable: Default::default(),
        }
    }
}

/// A fired projectile.
#[derive(Debug, Clone)]
pub(crate) struct Projectile {
    pub spec: ProjectileSpec,
    pub body: Option<RigidBodyHandle>,
    pub fired_at: f64,
}

/// A timed action from a scene.
#[derive(Debug, Clone)]
pub(crate) enum Action {
    Fire(ProjectileSpec),
    Explode(ExplosionSpec),
}

/// The simulation: a Rapier world with breakable objects, projectiles and explosions.
///
/// ```
/// use shatter_sim::{ObjectSpec, World, WorldSettings};
/// use shatter_sim::testing::box_grid_fracture;
///
/// let mut world = World::new(WorldSettings::default());
/// let wall = box_grid_fracture([4, 2, 1], [2.0, 1.0, 0.5].into());
/// let id = world.add_object(ObjectSpec::from_fracture(wall, [0.0, 0.5, 0.0].into()))?;
/// world.start();
/// for _ in 0..10 {
///     world.step();
/// }
/// assert_eq!(world.stats().steps, 10);
/// assert_eq!(world.stats().fragments, 8);
/// assert!(world.fragment_pose(id, 0).is_some());
/// # Ok::<(), shatter_sim::SimError>(())
/// ```
pub struct World {
    pub(crate) settings: WorldSettings,
    pub(crate) physics: PhysicsWorld,
    pub(crate) ground: Option<RigidBodyHandle>,
    pub(crate) objects: BTreeMap<ObjectId, ObjectRecord>,
    pub(crate) projectiles: Vec<Projectile>,
    pub(crate) schedule: Vec<(f64, Action)>,
    pub(crate) next_action: usize,
    pub(crate) next_id: u32,
    pub(crate) state: RunState,
    pub(crate) stats: Stats,
    pub(crate) events: Vec<SimEvent>,
    /// Debris bodies in the order they appeared: (object, body).
    pub(crate) debris: std::collections::VecDeque<(u32, RigidBodyHandle)>,
    /// Broken bonds by cause of objects removed since start (expired or deleted), so the
    /// counters never go down during a run.
    pub(crate) retired: [usize; 3],
    /// Per object, its broken-bond counts at the last [`SimEvent::BondsBroken`] report.
    pub(crate) reported: BTreeMap<u32, [usize; 3]>,
    /// Runtime cuts under way.
    pub(crate) cuts: Vec<PendingCut>,
    /// Files read before the disk when an object names a mesh file ([`World::files`]).
    pub(crate) files: Arc<MemoryFiles>,
    /// The calling thread's CPU time in nanoseconds, if set ([`World::set_cpu_clock`]).
    pub(crate) cpu_clock: Option<fn() -> Option<u64>>,
    /// The bodies' states at the start of the step ([`WorldSettings::contact_speed_cap`]).
    pub(crate) speed_cap: crate::world::speed_cap::SpeedCap,
}

// A world is shared between threads (a Bevy resource, a game's system): on every target,
// the web included, where a runtime cut waits as plain data.
const _: fn() = || {
    fn shared<T: Send + Sync>() {}
    shared::<World>();
};

impl World {
    /// An empty world (with a ground if the settings ask for one).
    pub fn new(settings: WorldSettings) -> World {
        let mut world = World {
            settings,
            physics: PhysicsWorld::new(),
            ground: None,
            objects: BTreeMap::new(),
            projectiles: Vec::new(),
            schedule: Vec::new(),
            next_action: 0,
            next_id: 0,
            state: RunState::Stopped,
            stats: Stats::default(),
            events: Vec::new(),
            debris: Default::default(),
            retired: [0; 3],
            reported: BTreeMap::new(),
            cuts: Vec::new(),
            files: Arc::default(),
            cpu_clock: None,
            speed_cap: Default::default(),
        };
        world.rebuild();
        world
    }

    /// The files an object's mesh file (and the files it refers to: a `.gltf`'s buffers,
    /// an OBJ's MTL and textures) is read from before the disk: a program that has the
    /// bytes (the web page's picked files) puts them here, or shares its own set with
    /// [`World::set_files`].
    ///
    /// ```
    /// use shatter_sim::{FractureSource, ObjectSpec, World, WorldSettings};
    /// let mut world = World::new(WorldSettings::default());
    /// let tet = b"v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
    /// world.files().insert("picked/tet.obj", tet.to_vec());
    /// let mut spec = ObjectSpec::from_fracture(Default::default(), [0.0, 1.0, 0.0].into());
    /// spec.source = FractureSource::MeshFile {
    ///     path: "picked/tet.obj".into(),
    ///     params: Default::default(),
    /// };
    /// let id = world.add_object(spec)?;
    /// assert!(world.object_fracture(id).unwrap().fragments.len() > 1);
    /// # Ok::<(), shatter_sim::SimError>(())
    /// ```
    pub fn files(&self) -> &Arc<MemoryFiles> {
        &self.files
    }

    /// Reads mesh files from `files` (before the disk) from now on.
    pub fn set_files(&mut self, files: Arc<MemoryFiles>) {
        self.files = files;
    }

    /// The settings.
    pub fn settings(&self) -> &WorldSettings {
        &self.settings
    }

    /// Measures the CPU time of each step's stress solves with `clock` (the calling
    /// thread's CPU time in nanoseconds, `None` where it cannot be read) into
    /// [`Stats::stress_solve_cpu_ms`](crate::Stats::stress_solve_cpu_ms); `None` stops
    /// it. The simulation reads no clock of its own but the wall clock: benchmarks pass
    /// one (the lab reads `CLOCK_THREAD_CPUTIME_ID`).
    pub fn set_cpu_clock(&mut self, clock: Option<fn() -> Option<u64>>) {
        self.cpu_clock = clock;
    }

    /// Changes the settings and rebuilds the world (like [`World::reset`]).
    pub fn set_settings(&mut self, settings: WorldSettings) {
        self.settings = settings;
        self.reset();
    }

    /// Fresh physics: ground, then every object in id order, in its initial state.
    pub(crate) fn rebuild(&mut self) {
        let mut physics = PhysicsWorld::new();
        physics.gravity = self.settings.gravity;
        physics.integration_parameters.dt = self.settings.dt;
        physics.integration_parameters.num_solver_iterations =
            self.settings.solver_iterations.max(1);
        self.physics = physics;
        self.ground = None;
        // Objects cut at runtime go; the ones they were cut from come back whole. A cut
        // under way is dropped (its thread finishes on its own).
        self.objects.retain(|_, r| r.parent.is_none());
        self.cuts.clear();
        // ... and their ids are given again, so a run after a reset repeats the first.
        self.next_id = self.objects.keys().last().map_or(0, |id| id.0 + 1);
        if self.settings.ground {
            let s = self.settings.ground_size;
            let ground = self.physics.insert_body(
                RigidBodyBuilder::fixed()
                    .translation(Vector::new(0.0, -0.5, 0.0))
                    .user_data(tag(Kind::Ground, 0, 0)),
            );
            self.physics.insert_collider(
                ColliderBuilder::cuboid(s, 0.5, s)
                    .friction(self.settings.ground_friction)
                    .user_data(tag(Kind::Ground, 0, 0)),
                Some(ground),
            );
            self.ground = Some(ground);
        } else {
            self.ground = Some(self.physics.insert_body(RigidBodyBuilder::fixed()));
        }
        let ids: Vec<ObjectId> = self.objects.keys().copied().collect();
        for id in ids {
            self.build_object(id);
        }
        self.projectiles.clear();
        self.next_action = 0;
        self.debris.clear();
        self.retired = [0; 3];
        self.reported.clear();
        self.stats = Stats::default();
        self.events.clear();
        self.refresh();
    }

    /// Updates the statistics after an edit (no time passes).
    pub(crate) fn refresh(&mut self) {
        self.update_counts();
    }

    /// Builds the live state of object `id` from its prepared geometry.
    pub(crate) fn build_object(&mut self, id: ObjectId) {
        let default_model = self.settings.bond_model;
        let Some(ground) = self.ground else { return };
        let Some(record) = self.objects.get_mut(&id) else {
            return;
        };
        let spec = &record.spec;
        let model = spec.bond_model.unwrap_or(default_model);
        let mut live =
            LiveObject::empty(model, record.prepared.clone(), spec.effective_break_force());
        if model == BondModel::Clusters {
            live.bonds.wear = spec.material.wear;
            live.stress = StressState::new(
                &record.prepared,
                spec.material.limits(),
                (
                    self.settings.stress_budget,
                    self.settings.stress_spring_budget,
                    self.settings.stress_build_budget,
                ),
            )
            .map(Box::new);
        }
        let pose = object_pose(spec.position, spec.rotation);
        let surface = Surface {
            density: spec.material.density,
            friction: spec.material.friction,
            restitution: spec.material.restitution,
            boxes: self.settings.box_colliders,
            hide_enclosed: !self.settings.enclosed_colliders,
            skip_held: model == BondModel::Joints && self.settings.skip_held_contacts,
        };
        match model {
            BondModel::Joints => {
                joints::build(&mut self.physics, &mut live, id.0, pose, surface, ground)
            }
            BondModel::Clusters => {
                clusters::build(&mut self.physics, &mut live, id.0, pose, surface)
            }
        }
        record.live = Some(live);
    }

    /// Removes the live bodies of object `id` (the record stays, so reset restores it).
    pub(crate) fn remove_live(&mut self, id: ObjectId) {
        let Some(live) = self.objects.get_mut(&id).and_then(|r| r.live.take()) else {
            return;
        };
        for (r, n) in self.retired.iter_mut().zip(live.bonds.broken_by) {
            *r += n;
        }
        let mut bodies: Vec<RigidBodyHandle> = live.body.iter().flatten().copied().collect();
        bodies.sort_by_key(|h| h.into_raw_parts());
        bodies.dedup();
        for b in bodies {
            self.physics.remove_body(b);
        }
        self.debris.retain(|(o, _)| *o != id.0);
    }

    /// Adds a breakable object and returns its id. Its fracture is computed (or taken) and
    /// scaled now; its bodies appear at once in its initial state.
    pub fn add_object(&mut self, spec: ObjectSpec) -> Result<ObjectId, SimError> {
        let id = ObjectId(self.next_id);
        let prepared = self.prepare_spec(&spec, &format!("object {}", id.0))?;
        self.next_id += 1;
        self.objects.insert(id, ObjectRecord::added(spec, prepared));
        self.build_object(id);
        self.refresh();
        Ok(id)
    }

    fn prepare_spec(&self, spec: &ObjectSpec, key: &str) -> Result<Arc<Prepared>, SimError> {
        spec.validate(key)?;
        let model = spec.bond_model.unwrap_or(self.settings.bond_model);
        let runtime = spec.runtime;
        if model == BondModel::Joints
            && (runtime.timing == FractureTiming::OnImpact || runtime.depth > 1)
        {
            return Err(SimError::invalid(
                format!("{key}.fracture"),
                "runtime fracture (on_impact, depth > 1) needs the clusters bond model",
            ));
        }
        let fracture = resolve_fracture(spec, key, &Layered(&*self.files, FileSystem))?;
        let prepared = prepare(&fracture, spec.scale, spec.material.density, spec.anchored);
        if prepared.shapes.iter().all(|p| p.is_empty()) {
            return Err(SimError::EmptyFracture {
                key: key.to_string(),
                reason: format!(
                    "{} fragments, none with a convex piece",
                    prepared.shapes.len()
                ),
            });
        }
        Ok(Arc::new(prepared))
    }

    /// Replaces the parameters of object `id` and rebuilds it in its new initial state.
    /// On error nothing changes.
    pub fn edit_object(&mut self, id: ObjectId, spec: ObjectSpec) -> Result<(), SimError> {
        if !self.objects.contains_key(&id) {
            return Err(SimError::NoSuchObject(id.0));
        }
        let prepared = self.prepare_spec(&spec, &format!("object {}", id.0))?;
        self.remove_descendants(id);
        self.remove_live(id);
        if let Some(record) = self.objects.get_mut(&id) {
            *record = ObjectRecord::added(spec, prepared);
        }
        self.build_object(id);
        self.refresh();
        Ok(())
    }

    /// Deletes object `id` (also from the initial state).
    pub fn delete_object(&mut self, id: ObjectId) -> Result<(), SimError> {
        if !self.objects.contains_key(&id) {
            return Err(SimError::NoSuchObject(id.0));
        }
        self.remove_descendants(id);
        self.remove_live(id);
        self.objects.remove(&id);
        self.refresh();
        Ok(())
    }

    /// Removes the objects cut from `id` at runtime, and theirs.
    fn remove_descendants(&mut self, id: ObjectId) {
        let children: Vec<ObjectId> = self
            .objects
            .iter()
            .filter(|(_, r)| r.parent == Some(id))
            .map(|(c, _)| *c)
            .collect();
        for c in children {
            self.remove_descendants(c);
            self.remove_live(c);
            self.objects.remove(&c);
        }
        self.cuts.retain(|c| c.object != id);
    }

    /// The spec of object `id`.
    pub fn object_spec(&self, id: ObjectId) -> Option<&ObjectSpec> {
        self.objects.get(&id).map(|r| &r.spec)
    }

    /// Ids of all objects, ascending.
    pub fn object_ids(&self) -> Vec<ObjectId> {
        self.objects.keys().copied().collect()
    }

    /// Schedules a projectile `at` seconds after start.
    pub fn schedule_projectile(&mut self, at: f64, spec: ProjectileSpec) {
        self.insert_action(at, Action::Fire(spec));
    }

    /// Schedules an explosion `at` seconds after start.
    pub fn schedule_explosion(&mut self, at: f64, spec: ExplosionSpec) {
        self.insert_action(at, Action::Explode(spec));
    }

    fn insert_action(&mut self, at: f64, action: Action) {
        // Stable: equal times keep insertion order.
        let pos = self.schedule.partition_point(|(t, _)| *t <= at);
        self.schedule.insert(pos, (at, action));
        if pos < self.next_action {
            self.next_action += 1;
        }
    }

    /// Starts (or resumes) the simulation.
    pub fn start(&mut self) {
        self.state = RunState::Running;
    }

    /// Holds the simulation.
    pub fn pause(&mut self) {
        if self.state == RunState::Running {
            self.state = RunState::Paused;
        }
    }

    /// Resumes after [`World::pause`].
    pub fn resume(&mut self) {
        if self.state == RunState::Paused {
            self.state = RunState::Running;
        }
    }

    /// Pause if running, resume if paused (the thesis's Pause button).
    pub fn toggle_pause(&mut self) {
        match self.state {
            RunState::Running => self.state = RunState::Paused,
            RunState::Paused => self.state = RunState::Running,
            RunState::Stopped => {}
        }
    }

    /// Whether the world is stopped, running or paused.
    pub fn run_state(&self) -> RunState {
        self.state
    }

    /// Stops and puts every object back in its initial state (rebuilt from its spec);
    /// fired projectiles disappear and the schedule starts over.
    pub fn reset(&mut self) {
        self.state = RunState::Stopped;
        self.rebuild();
    }

    /// Removes every object, projectile and scheduled action.
    pub fn clean(&mut self) {
        self.objects.clear();
        self.schedule.clear();
        self.reset();
    }

    /// Statistics after the last step.
    pub fn stats(&self) -> Stats {
        self.stats
    }

    /// Takes the events reported since the last call.
    pub fn take_events(&mut self) -> Vec<SimEvent> {
        std::mem::take(&mut self.events)
    }

    /// Recounts bodies, fragments and bonds.
    pub(crate) fn update_counts(&mut self) {
        let mut fragments = 0;
        let mut bonds_total = 0;
        let mut by = self.retired;
        let (mut damaged, mut min_health) = (0usize, 1.0f32);
        for record in self.objects.values() {
            bonds_total += record.prepared.fracture.bonds.len();
            if let Some(live) = &record.live {
                fragments += live.alive_fragments();
                for (t, n) in by.iter_mut().zip(live.bonds.broken_by) {
                    *t += n;
                }
                for (&h, &broken) in live.bonds.health.iter().zip(&live.bonds.broken) {
                    if !broken && h < 1.0 {
                        damaged += 1;
                        min_health = min_health.min(h);
                    }
                }
            }
        }
        self.stats.bonds_damaged = damaged;
        self.stats.min_bond_health = min_health;
        let bonds_broken = by.iter().sum();
        self.stats.bonds_broken_by_impact = by[0];
        self.stats.bonds_broken_by_stress = by[1];
        self.stats.bonds_broken_by_damage = by[2];
        let ground = usize::from(self.ground.is_some());
        self.stats.bodies = self.physics.bodies.len().saturating_sub(ground);
        self.stats.sleeping_bodies = self
            .physics
            .bodies
            .iter()
            .filter(|(_, rb)| rb.is_dynamic() && rb.is_sleeping())
            .count();
        self.stats.fragments = fragments;
        self.stats.bonds_total = bonds_total;
        self.stats.bonds_broken = bonds_broken;
    }
}
