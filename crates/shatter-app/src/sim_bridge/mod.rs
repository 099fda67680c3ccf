//! The only module that talks to the simulation.
//!
//! Everything else in the app sees [`SimBridge`]: it applies [`SimCommand`]s to a
//! [`shatter_sim::World`], advances it in fixed steps, and reads back what to draw
//! (fragment and projectile meshes once, poses every frame) and the statistics for the
//! overlay. The conversions between the panels' [`ObjectSpec`] and the simulation's own
//! spec live in [`crate::spec_convert`]; the scenes it loads in `scenes.rs`, the check of
//! custom mesh files in `custom_mesh.rs`. What it refuses is an [`AppError`].

mod custom_mesh;
mod scenes;

use bevy::prelude::{Quat, Resource, Vec3};
use shatter_sim::{ExplosionSpec, ProjectileShape, RunState, SimEvent, World};

pub use self::custom_mesh::check_custom_mesh;
pub use self::scenes::{DEFAULT_SCENE, EXAMPLE_FILES, EXAMPLE_SCENES};
use crate::commands::{BondModel, ObjectId, ObjectSpec, ShapeChoice, SimCommand};
pub use crate::error::AppError;
use crate::render::fragment_mesh::{FlatPart, flat_trimesh, fragment_parts};
use crate::spec_convert::{from_sim_spec, projectile_points, to_sim_spec};

/// Bevy's vector (glam 0.32) from the simulation's (glam 0.33).
pub fn to_bevy(v: glam::Vec3) -> Vec3 {
    Vec3::from_array(v.to_array())
}

/// The simulation's vector (glam 0.33) from Bevy's (glam 0.32).
pub fn to_sim(v: Vec3) -> glam::Vec3 {
    glam::Vec3::from_array(v.to_array())
}

/// Bevy's quaternion from the simulation's.
pub fn quat_to_bevy(q: glam::Quat) -> Quat {
    Quat::from_array(q.to_array())
}

/// Keys of projectiles have this bit set in [`PieceKey::object`].
pub const PROJECTILE_BIT: u64 = 1 << 40;

/// Identifies one drawable piece: a fragment of one build of an object, or a projectile.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct PieceKey {
    /// Object id, or [`PROJECTILE_BIT`] | the projectile's firing index.
    pub object: ObjectId,
    /// Bumped whenever geometry may have changed (edit, load, reset, clean), so stale
    /// meshes are replaced.
    pub build: u32,
    /// Fragment index (0 for projectiles).
    pub fragment: u32,
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

/// Numbers for the overlay and the autotest.
#[derive(Debug, Clone, Copy, Default, PartialEq, serde::Serialize)]
pub struct SimStats {
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
    /// Smoothed wall-clock time of one simulation step, in ms.
    pub step_ms: f64,
    /// Simulated seconds since start.
    pub time: f64,
    /// Started and not paused.
    pub running: bool,
    /// Paused.
    pub paused: bool,
}

/// At most this many fixed steps per frame; time beyond is dropped (the simulation then
/// runs slower than the clock instead of freezing the window).
pub const MAX_STEPS_PER_FRAME: usize = 4;

/// The simulation as the app sees it.
#[derive(Resource)]
pub struct SimBridge {
    world: World,
    /// Bond model for objects added from now on (`None`: the world's default).
    bond_model: Option<BondModel>,
    build: u32,
    accumulator: f64,
    step_ms: f64,
}

impl Default for SimBridge {
    fn default() -> Self {
        Self::from_world(World::new(shatter_sim::WorldSettings::default()))
    }
}

impl SimBridge {
    /// A bridge over an existing world, which from now on reads mesh files from the
    /// web page's picked files before the disk ([`crate::picked_files`]).
    pub fn from_world(mut world: World) -> Self {
        world.set_files(crate::picked_files::picked_files().clone());
        Self {
            world,
            bond_model: None,
            build: 0,
            accumulator: 0.0,
            step_ms: 0.0,
        }
    }

    /// The simulation (read only).
    pub fn world(&self) -> &World {
        &self.world
    }

    /// Apply a command. Returns the new object's id for [`SimCommand::AddObject`], and
    /// `Err` with why when the simulation refuses it (nothing changes then); the error's
    /// `Display` is the message for the user.
    pub fn apply(&mut self, cmd: SimCommand) -> Result<Option<ObjectId>, AppError> {
        match cmd {
            SimCommand::Start => {
                if self.world.run_state() == RunState::Paused {
                    self.world.resume();
                } else {
                    self.world.start();
                }
            }
            SimCommand::TogglePause => self.world.toggle_pause(),
            SimCommand::Reset => {
                self.world.reset();
                self.new_build();
            }
            SimCommand::Clean => {
                self.world.clean();
                self.new_build();
            }
            SimCommand::AddObject(spec) => {
                let sim = to_sim_spec(&spec, None, self.bond_model)?;
                let id = self.world.add_object(sim)?;
                return Ok(Some(u64::from(id.0)));
            }
            SimCommand::EditObject(id, spec) => {
                let sid = sim_id(id)?;
                let base = self
                    .world
                    .object_spec(sid)
                    .cloned()
                    .ok_or(AppError::NoObject(id))?;
                let sim = to_sim_spec(&spec, Some(&base), self.bond_model)?;
                self.world.edit_object(sid, sim)?;
                self.new_build();
            }
            SimCommand::DeleteObject(id) => {
                self.world.delete_object(sim_id(id)?)?;
            }
            SimCommand::Fire { spec, from, to } => {
                let primitive = match &spec.shape {
                    ShapeChoice::Builtin(s) => ProjectileShape::primitive(*s),
                    ShapeChoice::Custom(_) => None,
                };
                let shape = match primitive {
                    Some(p) => p,
                    None => ProjectileShape::Custom(projectile_points(&spec.shape)?),
                };
                let p = shatter_sim::ProjectileSpec {
                    shape,
                    size: spec.size as f32,
                    density: spec.density as f32,
                    speed: spec.speed as f32,
                    color: spec.color,
                    last: spec.lifetime.map(|t| t as f32),
                    from,
                    to,
                };
                p.validate("projectile")?;
                self.world.fire(p);
            }
            SimCommand::Explode {
                position,
                radius,
                power,
            } => {
                let e = ExplosionSpec {
                    position,
                    radius: radius as f32,
                    power: power as f32,
                };
                e.validate("explosion")?;
                self.world.explode(e);
            }
            SimCommand::SetBondModel(m) => self.bond_model = Some(m),
            SimCommand::SaveScene(p) => {
                let text = self.world.to_scene_toml()?;
                crate::scene_store::write(&p, &text)?;
            }
            SimCommand::LoadScene(p) => self.load_scene(&p)?,
            SimCommand::LoadExample(name) => self.load_example(&name)?,
        }
        Ok(None)
    }

    fn new_build(&mut self) {
        self.build = self.build.wrapping_add(1);
    }

    /// Advance by `dt` seconds of wall-clock time in the world's fixed steps (at most
    /// [`MAX_STEPS_PER_FRAME`] of them). Returns messages about bodies removed (diverged or
    /// expired) for the status line.
    pub fn advance(&mut self, dt: f64) -> Vec<String> {
        if self.world.run_state() != RunState::Running {
            self.accumulator = 0.0;
            return Vec::new();
        }
        let step = f64::from(self.world.settings().dt);
        self.accumulator += dt.clamp(0.0, 0.25);
        let mut steps = 0;
        while self.accumulator + 1e-6 >= step && steps < MAX_STEPS_PER_FRAME {
            if !self.world.step() {
                break;
            }
            self.accumulator -= step;
            steps += 1;
            let ms = self.world.stats().last_step_ms;
            self.step_ms = if self.step_ms == 0.0 {
                ms
            } else {
                0.9 * self.step_ms + 0.1 * ms
            };
        }
        if steps == MAX_STEPS_PER_FRAME {
            self.accumulator = self.accumulator.min(step);
        }
        self.world
            .take_events()
            .into_iter()
            .filter_map(|e| match e {
                SimEvent::Diverged { object, reason } => Some(match object {
                    Some(o) => format!("object {o}: a body diverged and was removed ({reason})"),
                    None => format!("a projectile diverged and was removed ({reason})"),
                }),
                SimEvent::FractureFailed {
                    object,
                    fragment,
                    reason,
                } => Some(format!(
                    "object {object}: the runtime cut of fragment {fragment} failed ({reason}); \
                     it stays whole"
                )),
                SimEvent::Expired(_)
                | SimEvent::BondsBroken { .. }
                | SimEvent::Split { .. }
                | SimEvent::Fractured { .. } => None,
            })
            .collect()
    }

    /// Exactly one fixed step if running (tests and scripted sessions).
    pub fn step_once(&mut self) -> bool {
        self.world.step()
    }

    /// Every drawable piece and its pose.
    pub fn poses(&self) -> Vec<PiecePose> {
        let mut out = Vec::new();
        for id in self.world.object_ids() {
            for (f, pose) in self.world.fragment_poses(id) {
                out.push(PiecePose {
                    key: PieceKey {
                        object: u64::from(id.0),
                        build: self.build,
                        fragment: f,
                    },
                    translation: to_bevy(pose.translation),
                    rotation: quat_to_bevy(pose.rotation),
                });
            }
        }
        for p in self.world.projectiles() {
            out.push(PiecePose {
                key: PieceKey {
                    object: PROJECTILE_BIT | p.index as u64,
                    build: self.build,
                    fragment: 0,
                },
                translation: to_bevy(p.pose.translation),
                rotation: quat_to_bevy(p.pose.rotation),
            });
        }
        out
    }

    /// The parts (one per material) that draw a piece, in the frame its [`PiecePose`]
    /// maps to the world.
    pub fn piece_parts(&self, key: PieceKey) -> Option<Vec<FlatPart>> {
        if key.build != self.build {
            return None;
        }
        if key.object & PROJECTILE_BIT != 0 {
            let index = (key.object & !PROJECTILE_BIT) as usize;
            let views = self.world.projectiles();
            let view = views.iter().find(|v| v.index == index)?;
            let mesh = view.spec.shape.mesh(view.spec.size);
            return Some(vec![FlatPart {
                material: None,
                mesh: flat_trimesh(&mesh, &[], view.spec.color),
            }]);
        }
        let id = shatter_sim::ObjectId(u32::try_from(key.object).ok()?);
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
    fn is_file_object(&self, mut id: shatter_sim::ObjectId) -> bool {
        while let Some(parent) = self.world.spawned_from(id) {
            id = parent;
        }
        self.world
            .object_spec(id)
            .is_some_and(|s| matches!(s.source, shatter_sim::FractureSource::MeshFile { .. }))
    }

    /// The specification of object `id` as the panels show it (for Edit).
    pub fn object_spec(&self, id: ObjectId) -> Option<ObjectSpec> {
        let spec = self.world.object_spec(sim_id(id).ok()?)?;
        Some(from_sim_spec(spec))
    }

    /// The object and point hit first by a ray (`dir` need not be unit).
    pub fn ray_cast(&self, origin: glam::Vec3, dir: glam::Vec3) -> Option<(ObjectId, glam::Vec3)> {
        self.world
            .ray_cast(origin, dir)
            .map(|(id, p)| (u64::from(id.0), p))
    }

    /// Overlay numbers.
    pub fn stats(&self) -> SimStats {
        let s = self.world.stats();
        let state = self.world.run_state();
        SimStats {
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
            step_ms: self.step_ms,
            time: s.time,
            running: state == RunState::Running,
            paused: state == RunState::Paused,
        }
    }
}

fn sim_id(id: ObjectId) -> Result<shatter_sim::ObjectId, AppError> {
    u32::try_from(id)
        .map(shatter_sim::ObjectId)
        .map_err(|_| AppError::NoObject(id))
}
