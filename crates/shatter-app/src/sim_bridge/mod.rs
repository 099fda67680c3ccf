//! The only module that changes the simulation.
//!
//! The simulation is bevy_shatter's [`ShatterWorld`] resource: a [`shatter_sim::World`]
//! that [`ShatterWorldPlugin`](bevy_shatter::world::ShatterWorldPlugin) steps and draws.
//! [`SandboxWorld`] applies the panels' [`SimCommand`]s to it and builds it from the app's
//! scenes (`scenes.rs`); [`check_custom_mesh`] and [`load_projectile`] are the checks the
//! forms call for a file, reading the web page's picked files before the disk
//! ([`crate::picked_files`]). What the simulation refuses is an [`AppError`].

mod scenes;

pub use bevy_shatter::world::{
    MAX_STEPS_PER_FRAME, PieceKey, PieceOwner, PiecePose, ShatterWorld, WorldStats as SimStats,
};
use shatter_sim::{ExplosionSpec, World};

pub use self::scenes::{DEFAULT_SCENE, EXAMPLE_FILES, EXAMPLE_SCENES};
use crate::commands::{ObjectId, ProjectileShape, SimCommand};
pub use crate::error::AppError;

/// The vector conversions between Bevy (glam 0.32) and the simulation (glam 0.33).
pub use bevy_shatter::{from_bevy as to_sim, to_bevy};

/// Whether a custom mesh file can be a breakable object (for the forms' validation):
/// [`bevy_shatter::world::check_mesh_file`] on the picked files and the disk.
pub fn check_custom_mesh(path: &std::path::Path) -> Result<(), AppError> {
    Ok(bevy_shatter::world::check_mesh_file(
        path,
        crate::picked_files::picked_files(),
    )?)
}

/// A custom projectile's shape from its mesh file (for the Fire panel):
/// [`bevy_shatter::world::projectile_from_file`] on the picked files and the disk.
pub fn load_projectile(path: &std::path::Path) -> Result<ProjectileShape, AppError> {
    Ok(bevy_shatter::world::projectile_from_file(
        path,
        crate::picked_files::picked_files(),
    )?)
}

/// The sandbox's operations on the [`ShatterWorld`].
pub trait SandboxWorld: Sized {
    /// A world that reads mesh files from the web page's picked files before the disk.
    fn sandbox(world: World) -> Self;

    /// Apply a command. Returns the new object's id for [`SimCommand::AddObject`], and
    /// `Err` with why when the simulation refuses it (nothing changes then); the error's
    /// `Display` is the message for the user.
    fn apply(&mut self, cmd: SimCommand) -> Result<Option<ObjectId>, AppError>;

    /// The default scene (`assets/scenes/default.toml`, embedded). Should the bundled
    /// file ever fail to build (this crate's tests check it does not), the error is
    /// logged and the world is empty.
    fn default_scene() -> Self;

    /// The world of a scene file's text.
    fn from_scene_text(text: &str) -> Result<Self, AppError>;

    /// Replace the world with a scene file's; on error the current scene stays.
    fn load_scene(&mut self, path: &std::path::Path) -> Result<(), AppError>;

    /// Replace the world with the example scene `name` ([`EXAMPLE_SCENES`]); on error the
    /// current scene stays.
    fn load_example(&mut self, name: &str) -> Result<(), AppError>;
}

impl SandboxWorld for ShatterWorld {
    fn sandbox(mut world: World) -> Self {
        world.set_files(crate::picked_files::picked_files().clone());
        ShatterWorld::new(world)
    }

    fn apply(&mut self, cmd: SimCommand) -> Result<Option<ObjectId>, AppError> {
        match cmd {
            SimCommand::Start => self.start(),
            SimCommand::TogglePause => self.toggle_pause(),
            SimCommand::Reset => self.reset(),
            SimCommand::Clean => self.clean(),
            SimCommand::AddObject(spec) => return Ok(Some(self.add_object(*spec)?)),
            SimCommand::EditObject(id, spec) => self.edit_object(id, *spec)?,
            SimCommand::DeleteObject(id) => self.delete_object(id)?,
            SimCommand::Fire(p) => self.fire(p)?,
            SimCommand::Explode {
                position,
                radius,
                power,
            } => self.explode(ExplosionSpec {
                position,
                radius: radius as f32,
                power: power as f32,
            })?,
            SimCommand::SetBondModel(m) => self.bond_model = Some(m),
            SimCommand::SaveScene(p) => {
                let text = self.world().to_scene_toml()?;
                crate::scene_store::write(&p, &text)?;
            }
            SimCommand::LoadScene(p) => self.load_scene(&p)?,
            SimCommand::LoadExample(name) => self.load_example(&name)?,
        }
        Ok(None)
    }

    fn default_scene() -> Self {
        scenes::default_scene()
    }

    fn from_scene_text(text: &str) -> Result<Self, AppError> {
        scenes::from_scene_text(text)
    }

    fn load_scene(&mut self, path: &std::path::Path) -> Result<(), AppError> {
        scenes::load_scene(self, path)
    }

    fn load_example(&mut self, name: &str) -> Result<(), AppError> {
        scenes::load_example(self, name)
    }
}
