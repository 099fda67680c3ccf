//! shatter's interactive sandbox: the thesis's breakable-object system in Bevy + egui.
//!
//! The sandbox is panels, a camera, an autotest and a web page over bevy_shatter: the
//! simulation is its [`ShatterWorld`](bevy_shatter::world::ShatterWorld), stepped and
//! drawn by its [`ShatterWorldPlugin`](bevy_shatter::world::ShatterWorldPlugin). One
//! plugin per concern — [`camera::CameraPlugin`], [`render::SceneRenderPlugin`] (lights
//! and ground), [`ui::UiPlugin`], [`input::ClickPlugin`], [`sim_plugin::SimPlugin`] and
//! [`autotest::AutotestPlugin`] — gathered by [`ShatterAppPlugin`]. The world is changed
//! only through [`sim_bridge::SandboxWorld`]; the panels only produce typed
//! [`commands::SimCommand`]s, validated by pure functions in [`ui::forms`]. Errors are
//! typed ([`ui::fields::FieldError`], [`ui::forms::FormError`], [`error::AppError`]) and
//! become text only where they are shown: the panels, the log and the autotest's record.
//!
//! ```no_run
//! use bevy::prelude::*;
//! use shatter_app::ShatterAppPlugin;
//!
//! App::new()
//!     .add_plugins(DefaultPlugins)
//!     .add_plugins(ShatterAppPlugin::default())
//!     .run();
//! ```

#![cfg_attr(test, allow(clippy::unwrap_used))]

pub mod autotest;
pub mod camera;
pub mod commands;
pub mod error;
pub mod input;
pub mod picked_files;
pub mod render;
pub mod scene_store;
pub mod sim_bridge;
pub mod sim_plugin;
pub mod state_log;
pub mod ui;

use std::path::PathBuf;

use bevy::prelude::*;
use bevy_egui::EguiPlugin;

/// Everything the sandbox needs on top of Bevy's `DefaultPlugins`.
#[derive(Debug, Clone, Default)]
pub struct ShatterAppPlugin {
    /// Run the scripted session and write its results to this folder.
    pub autotest: Option<PathBuf>,
    /// Print the state as a `SHATTER_STATE` JSON line twice a second (the web page).
    pub log_state: bool,
}

impl Plugin for ShatterAppPlugin {
    fn build(&self, app: &mut App) {
        app.add_plugins(EguiPlugin::default()).add_plugins((
            camera::CameraPlugin::default(),
            render::SceneRenderPlugin::default(),
            ui::UiPlugin,
            input::ClickPlugin,
            sim_plugin::SimPlugin,
        ));
        if self.log_state {
            app.add_plugins(state_log::StateLogPlugin::default());
        }
        if let Some(dir) = &self.autotest {
            app.add_plugins(autotest::AutotestPlugin { dir: dir.clone() });
        }
    }
}
