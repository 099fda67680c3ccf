//! `shatter-app`: the interactive fracture sandbox.
//!
//! ```text
//! shatter-app [--autotest DIR] [--scene NAME]
//! ```
//!
//! `--scene` opens one of the example scenes instead of the default (the web page takes
//! it from its address: `index.html?scene=textured`).

use std::path::PathBuf;
use std::process::ExitCode;

use bevy::prelude::*;
use bevy::window::{PresentMode, WindowResolution};
use shatter_app::ShatterAppPlugin;
use shatter_app::sim_bridge::{SandboxWorld, ShatterWorld};
use shatter_app::sim_plugin::OpenAfterFirstFrame;

const USAGE: &str = "usage: shatter-app [--autotest DIR] [--scene NAME]";

/// Called by the web page (web/index.html) with a file the user picked: a mesh file, which
/// the Custom shape of the Add Object and Fire panels can then name, or a file a mesh
/// refers to (a `.gltf`'s `.bin`, an OBJ's `.mtl`, a texture), kept beside it. Returns an
/// error message, or an empty string when the file reads as a mesh (or was kept).
#[cfg(target_arch = "wasm32")]
#[wasm_bindgen::prelude::wasm_bindgen]
pub fn add_mesh(name: String, bytes: Vec<u8>) -> String {
    let files = shatter_app::picked_files::picked_files();
    match bevy_shatter::world::pick_file(files, &name, bytes) {
        Ok(()) => String::new(),
        Err(e) => e.to_string(),
    }
}

/// Why the command line is refused; its `Display` is what is printed.
#[derive(Debug, thiserror::Error)]
enum ArgsError {
    /// `--autotest` without a folder.
    #[error("--autotest needs a folder")]
    NoFolder,
    /// `--scene` without a name.
    #[error("--scene needs the name of an example scene")]
    NoScene,
    /// `-h` / `--help`: the usage.
    #[error("{}", USAGE)]
    Help,
    /// Anything else.
    #[error("unknown argument '{arg}'\n{USAGE}", USAGE = USAGE)]
    Unknown {
        /// The argument.
        arg: String,
    },
}

/// The command line: the autotest's folder and the example scene to open.
fn parse_args(args: &[String]) -> Result<(Option<PathBuf>, Option<String>), ArgsError> {
    let mut autotest = None;
    let mut scene = None;
    let mut it = args.iter();
    while let Some(a) = it.next() {
        match a.as_str() {
            "--autotest" => {
                let dir = it.next().ok_or(ArgsError::NoFolder)?;
                autotest = Some(PathBuf::from(dir));
            }
            "--scene" => scene = Some(it.next().ok_or(ArgsError::NoScene)?.clone()),
            "-h" | "--help" => return Err(ArgsError::Help),
            other => {
                return Err(ArgsError::Unknown {
                    arg: other.to_owned(),
                });
            }
        }
    }
    Ok((autotest, scene))
}

/// The example scene the page's address asks for (`?scene=NAME`), in the web build.
#[cfg(target_arch = "wasm32")]
fn page_scene() -> Option<String> {
    let search = web_sys::window()?.location().search().ok()?;
    search
        .trim_start_matches('?')
        .split('&')
        .find_map(|kv| kv.strip_prefix("scene="))
        .map(str::to_owned)
}

#[cfg(not(target_arch = "wasm32"))]
fn page_scene() -> Option<String> {
    None
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let (autotest, scene) = match parse_args(&args) {
        Ok(a) => a,
        Err(msg) => {
            eprintln!("{msg}");
            return ExitCode::from(2);
        }
    };
    if let Some(dir) = &autotest
        && let Err(e) = std::fs::create_dir_all(dir)
    {
        eprintln!("cannot create {}: {e}", dir.display());
        return ExitCode::from(2);
    }
    let window = Window {
        title: "shatter".to_owned(),
        resolution: WindowResolution::new(1280, 720),
        // The autotest measures the real frame rate, not the display's.
        present_mode: if autotest.is_some() {
            PresentMode::AutoNoVsync
        } else {
            PresentMode::AutoVsync
        },
        // In the browser: draw into the page's canvas (web/index.html) and keep the
        // page from scrolling or opening menus on the app's keys and clicks.
        canvas: cfg!(target_arch = "wasm32").then(|| "#shatter-canvas".to_owned()),
        prevent_default_event_handling: true,
        ..default()
    };
    let mut app = App::new();
    app.add_plugins(DefaultPlugins.set(WindowPlugin {
        primary_window: Some(window),
        ..default()
    }));
    if cfg!(target_arch = "wasm32") {
        // The page draws its first frame on an empty world and opens the scene (the
        // address's `?scene=`, else the default) right after it: downloading and starting
        // the wasm is all the first frame waits for, not the scene's fracture.
        app.insert_resource(ShatterWorld::sandbox(shatter_sim::World::new(
            Default::default(),
        )))
        .insert_resource(OpenAfterFirstFrame(
            page_scene().unwrap_or_else(|| "default".to_owned()),
        ));
    } else if let Some(name) = scene {
        let mut world = ShatterWorld::sandbox(shatter_sim::World::new(Default::default()));
        if let Err(e) = world.load_example(&name) {
            eprintln!("--scene {name}: {e}");
            return ExitCode::from(2);
        }
        app.insert_resource(world);
    }
    let exit = app
        .add_plugins(ShatterAppPlugin {
            autotest,
            log_state: cfg!(target_arch = "wasm32"),
        })
        .run();
    match exit {
        AppExit::Success => ExitCode::SUCCESS,
        AppExit::Error(code) => ExitCode::from(code.get()),
    }
}
