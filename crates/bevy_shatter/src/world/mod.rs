//! A whole [`shatter_sim::World`] in Bevy: the simulator's own bodies, bonds, stress
//! solver, runtime cuts and damage, stepped by Bevy and drawn as entities.
//!
//! [`ShatterPlugin`](crate::ShatterPlugin) puts fragments into the game's own physics
//! (avian). This is the other way in, for a tool that wants everything shatter's world
//! does exactly as the CLI runs it (the sandbox, a viewer, a replay): a [`ShatterWorld`]
//! resource owns the world and is the only way to change it, so every rebuild is seen;
//! [`ShatterWorldPlugin`] advances it in the world's fixed steps, sends what happened as
//! [`WorldEvent`] messages, and keeps one entity per fragment and projectile in step with
//! it ([`Piece`]), drawn in the object's colour or, for a mesh file's model, with the
//! file's materials and textures.
//!
//! It needs no physics plugin, and no camera or light: the application brings those.
//!
//! ```
//! use bevy::prelude::*;
//! use bevy_shatter::world::{ShatterWorld, ShatterWorldPlugin};
//! use shatter_sim::scene::Scene;
//!
//! let scene = Scene::parse(r#"
//!     [[objects]]
//!     shape = "cube"
//!     method = "grid"
//!     grid = [2, 2, 2]
//!     position = [0.0, 0.5, 0.0]
//! "#).unwrap();
//! let mut app = App::new();
//! app.add_plugins((MinimalPlugins, AssetPlugin::default(), ShatterWorldPlugin))
//!     .init_asset::<Mesh>()
//!     .init_asset::<StandardMaterial>()
//!     .init_asset::<Image>()
//!     .insert_resource(ShatterWorld::new(scene.build(None).unwrap()));
//! app.update();
//! let pieces = app.world_mut().query::<&bevy_shatter::world::Piece>().iter(app.world()).count();
//! assert_eq!(pieces, 8);
//! ```

mod draw;
pub mod mesh;
mod mesh_file;

use bevy::prelude::*;
use shatter_sim::{
    BondModel, ExplosionSpec, ObjectId, ObjectSpec, ProjectileSpec, RunState, SimError, SimEvent,
    World, WorldSettings,
};

pub use self::draw::{Piece, RenderStats};
use self::mesh::{FlatPart, flat_trimesh, fragment_parts};
pub use self::mesh_file::{
    MemoryFiles, MeshFileError, check_mesh_file, pick_file, projectile_from_file,
};
use crate::convert::{quat_to_bevy, to_bevy};

/// Steps a [`ShatterWorld`] resource and draws it.
///
/// In `Update`, [`ShatterWorldSystems::Step`] advances the world by the frame's time in
/// its own fixed steps (at most [`MAX_STEPS_PER_FRAME`] a frame) and writes the step's
/// [`WorldEvent`]s; in `PostUpdate`, [`ShatterWorldSystems::Draw`] spawns, moves and
/// despawns the [`Piece`] entities. Put the systems that change the world before `Step`.
#[derive(Debug, Clone, Copy, Default)]
pub struct ShatterWorldPlugin;

/// The plugin's system sets (see [`ShatterWorldPlugin`]).
#[derive(SystemSet, Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum ShatterWorldSystems {
    /// Advances the world (`Update`).
    Step,
    /// Keeps the pieces' entities in step with it (`PostUpdate`).
    Draw,
}

/// Something that happened in a step of the [`ShatterWorld`]: the world's own event.
#[derive(Message, Debug, Clone, PartialEq)]
pub struct WorldEvent(pub SimEvent);

impl Plugin for ShatterWorldPlugin {
    fn build(&self, app: &mut App) {
        if !app.world().contains_resource::<ShatterWorld>() {
            app.insert_resource(ShatterWorld::default());
        }
        app.add_message::<WorldEvent>()
            .init_resource::<RenderStats>()
            .add_systems(Update, advance.in_set(ShatterWorldSystems::Step))
            .add_systems(Startup, draw::setup)
            .add_systems(
                PostUpdate,
                draw::sync_pieces
                    .in_set(ShatterWorldSystems::Draw)
                    .before(bevy::transform::TransformSystems::Propagate),
            );
    }
}

fn advance(mut world: ResMut<ShatterWorld>, time: Res<Time>, mut out: MessageWriter<WorldEvent>) {
    world.advance(time.delta_secs_f64());
    out.write_batch(world.take_events().into_iter().map(WorldEvent));
}

/// At most this many fixed steps per frame; time beyond is dropped (the simulation then
/// runs slower than the clock instead of freezing the window).
pub const MAX_STEPS_PER_FRAME: usize = 4;

/// Identifies one drawable piece: a fragment of one build of an object, or a projectile.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct PieceKey {
    /// What the piece belongs to.
    pub owner: PieceOwner,
    /// Bumped whenever geometry may have changed (edit, load, reset, clean), so stale
    /// meshes are replaced.
    pub build: u32,
    /// Fragment index (0 for projectiles).
    pub fragment: u32,
}

/// The owner of a [`PieceKey`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum PieceOwner {
    /// A breakable object.
    Object(ObjectId),
    /// A projectile, by its firing index.
    Projectile(usize),
}

/// Where a piece is this frame: the transform from the piece's mesh frame to the world.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PiecePose {
    /// Which piece.
    pub key: PieceKey,
    /// Translation.
    pub translation: Vec3,
    /// Rotation.
    pub rotation: Quat,
}

/// Numbers for an overlay: the world's statistics and the step time.
#[derive(Debug, Clone, Copy, Default, PartialEq, serde::Serialize)]
pub struct WorldStats {
    /// Rigid bodies in the world (objects and projectiles, not the ground).
    pub bodies: usize,
    /// Fragments with a body.
    pub fragments: usize,
    /// Bonds (joints or cluster bonds) in all objects.
    pub bonds_total: usize,
    /// Bonds broken since start.
    pub bonds_broken: usize,
    /// Of those, broken by impact, by stress and by damage.
    pub bonds_broken_by: [usize; 3],
    /// Intact bonds worn by weak hits (damage).
    pub bonds_damaged: usize,
    /// The lowest health of an intact bond (1: none is worn).
    pub min_bond_health: f32,
    /// Runtime cuts since start.
    pub runtime_fractures: usize,
    /// The deepest fracture level a runtime cut reached.
    pub max_depth: u32,
    /// Bodies the contact speed cap slowed since start
    /// ([`WorldSettings::contact_speed_cap`]).
    pub speeds_capped: usize,
    /// Smoothed wall-clock time of one simulation step, in ms.
    pub step_ms: f64,
    /// Simulated seconds since start.
    pub time: f64,
    /// Started and not paused.
    pub running: bool,
    /// Paused.
    pub paused: bool,
}

/// A [`shatter_sim::World`] as a resource: the only way to change it, so that the
/// [`Piece`]s are rebuilt whenever its geometry may have changed.
#[derive(Resource)]
pub struct ShatterWorld {
    world: World,
    /// The bond model given to objects added or edited from now on and to scenes
    /// replaced through [`ShatterWorld::replace_with`] (`None`: their own, or the world's
    /// default).
    pub bond_model: Option<BondModel>,
    build: u32,
    accumulator: f64,
    step_ms: f64,
}

impl Default for ShatterWorld {
    /// An empty world with the default settings.
    fn default() -> Self {
        Self::new(World::new(WorldSettings::default()))
    }
}

impl ShatterWorld {
    /// The resource over `world`.
    pub fn new(world: World) -> Self {
        Self {
            world,
            bond_model: None,
            build: 0,
            accumulator: 0.0,
            step_ms: 0.0,
        }
    }

    /// The simulation (read only: change it through the methods here).
    pub fn world(&self) -> &World {
        &self.world
    }

    /// Start the simulation, or resume it when paused.
    pub fn start(&mut self) {
        if self.world.run_state() == RunState::Paused {
            self.world.resume();
        } else {
            self.world.start();
        }
    }

    /// Pause or resume.
    pub fn toggle_pause(&mut self) {
        self.world.toggle_pause();
    }

    /// Stop, and put every object back as it was built.
    pub fn reset(&mut self) {
        self.world.reset();
        self.new_build();
    }

    /// Remove every object and projectile.
    pub fn clean(&mut self) {
        self.world.clean();
        self.new_build();
    }

    /// Add an object (with [`ShatterWorld::bond_model`] when set). Nothing changes on
    /// error.
    pub fn add_object(&mut self, spec: ObjectSpec) -> Result<ObjectId, SimError> {
        let spec = self.with_bond_model(spec);
        self.world.add_object(spec)
    }

    /// Rebuild object `id` from `spec` (with [`ShatterWorld::bond_model`] when set).
    /// Nothing changes on error.
    pub fn edit_object(&mut self, id: ObjectId, spec: ObjectSpec) -> Result<(), SimError> {
        let spec = self.with_bond_model(spec);
        self.world.edit_object(id, spec)?;
        self.new_build();
        Ok(())
    }

    /// `spec` with [`ShatterWorld::bond_model`] when one is set.
    fn with_bond_model(&self, spec: ObjectSpec) -> ObjectSpec {
        ObjectSpec {
            bond_model: self.bond_model.or(spec.bond_model),
            ..spec
        }
    }

    /// Remove object `id`.
    pub fn delete_object(&mut self, id: ObjectId) -> Result<(), SimError> {
        self.world.delete_object(id)
    }

    /// Fire a projectile (checked first: nothing is fired on error).
    pub fn fire(&mut self, spec: ProjectileSpec) -> Result<(), SimError> {
        spec.validate("projectile")?;
        self.world.fire(spec);
        Ok(())
    }

    /// Set off an explosion (checked first: nothing happens on error).
    pub fn explode(&mut self, spec: ExplosionSpec) -> Result<(), SimError> {
        spec.validate("explosion")?;
        self.world.explode(spec);
        Ok(())
    }

    /// Replace the world by the one `build` makes, given [`ShatterWorld::bond_model`]
    /// (typically `|m| scene.build_with_files(m, files)`); on error the current world
    /// stays.
    pub fn replace_with<E>(
        &mut self,
        build: impl FnOnce(Option<BondModel>) -> Result<World, E>,
    ) -> Result<(), E> {
        self.world = build(self.bond_model)?;
        self.accumulator = 0.0;
        self.new_build();
        Ok(())
    }

    fn new_build(&mut self) {
        self.build = self.build.wrapping_add(1);
    }

    /// Advance by `dt` seconds of wall-clock time in the world's fixed steps (at most
    /// [`MAX_STEPS_PER_FRAME`] of them). Returns the steps taken. The events stay in the
    /// world (the plugin's system sends them as [`WorldEvent`]s).
    pub fn advance(&mut self, dt: f64) -> usize {
        if self.world.run_state() != RunState::Running {
            self.accumulator = 0.0;
            return 0;
        }
        let step = f64::from(self.world.settings().dt);
        self.accumulator += dt.clamp(0.0, 0.25);
        let mut steps = 0;
        while self.accumulator + 1e-6 >= step && steps < MAX_STEPS_PER_FRAME {
            if !self.step_once() {
                break;
            }
            self.accumulator -= step;
            steps += 1;
        }
        if steps == MAX_STEPS_PER_FRAME {
            self.accumulator = self.accumulator.min(step);
        }
        steps
    }

    /// Exactly one fixed step if running; whether it ran.
    pub fn step_once(&mut self) -> bool {
        if !self.world.step() {
            return false;
        }
        let ms = self.world.stats().last_step_ms;
        self.step_ms = if self.step_ms == 0.0 {
            ms
        } else {
            0.9 * self.step_ms + 0.1 * ms
        };
        true
    }

    /// The events of the steps since the last call (the plugin takes them every frame).
    pub fn take_events(&mut self) -> Vec<SimEvent> {
        self.world.take_events()
    }

    /// Every drawable piece and its pose.
    pub fn poses(&self) -> Vec<PiecePose> {
        let piece = |owner, fragment, pose: shatter_sim::Pose| PiecePose {
            key: PieceKey {
                owner,
                build: self.build,
                fragment,
            },
            translation: to_bevy(pose.translation),
            rotation: quat_to_bevy(pose.rotation),
        };
        let mut out = Vec::new();
        for id in self.world.object_ids() {
            for (f, pose) in self.world.fragment_poses(id) {
                out.push(piece(PieceOwner::Object(id), f, pose));
            }
        }
        for p in self.world.projectiles() {
            out.push(piece(PieceOwner::Projectile(p.index), 0, p.pose));
        }
        out
    }

    /// The parts (one per material) that draw a piece, in the frame its [`PiecePose`]
    /// maps to the world; `None` for a piece of an older build or one that is gone.
    pub fn piece_parts(&self, key: PieceKey) -> Option<Vec<FlatPart>> {
        if key.build != self.build {
            return None;
        }
        let id = match key.owner {
            PieceOwner::Projectile(index) => {
                let views = self.world.projectiles();
                let view = views.iter().find(|v| v.index == index)?;
                let mesh = view.spec.shape.mesh(view.spec.size);
                return Some(vec![FlatPart {
                    material: None,
                    mesh: flat_trimesh(&mesh, &[], view.spec.color),
                }]);
            }
            PieceOwner::Object(id) => id,
        };
        let fracture = self.world.object_fracture(id)?;
        let color = self.world.object_color(id)?;
        let fragment = fracture.fragments.get(key.fragment as usize)?;
        // A file's model is drawn with its own materials; a built-in shape (whose
        // fracture carries only a default surface material) in the object's colour.
        let materials: &[_] = if self.is_file_object(id) {
            &fracture.materials
        } else {
            &[]
        };
        Some(fragment_parts(fragment, color, materials))
    }

    /// Whether object `id`, or the object a runtime cut made it from, is a mesh file's.
    fn is_file_object(&self, mut id: ObjectId) -> bool {
        while let Some(parent) = self.world.spawned_from(id) {
            id = parent;
        }
        self.world
            .object_spec(id)
            .is_some_and(|s| matches!(s.source, shatter_sim::FractureSource::MeshFile { .. }))
    }

    /// The overlay's numbers.
    pub fn stats(&self) -> WorldStats {
        let s = self.world.stats();
        let state = self.world.run_state();
        WorldStats {
            bodies: s.bodies,
            fragments: s.fragments,
            bonds_total: s.bonds_total,
            bonds_broken: s.bonds_broken,
            bonds_broken_by: [
                s.bonds_broken_by_impact,
                s.bonds_broken_by_stress,
                s.bonds_broken_by_damage,
            ],
            bonds_damaged: s.bonds_damaged,
            min_bond_health: s.min_bond_health,
            runtime_fractures: s.runtime_fractures,
            max_depth: s.max_depth,
            speeds_capped: s.speeds_capped,
            step_ms: self.step_ms,
            time: s.time,
            running: state == RunState::Running,
            paused: state == RunState::Paused,
        }
    }
}
