//! The scenes the sandbox's [`ShatterWorld`] is built from or replaced by: the default scene, the
//! example scenes built into the app, and scene files (from the disk, or from the web
//! page's storage in the web build, see [`crate::scene_store`]).

use std::path::Path;

use shatter_sim::scene::Scene;

use super::{SandboxWorld, ShatterWorld};
use crate::error::AppError;

/// The scene the app opens with (also embedded in the web build).
pub const DEFAULT_SCENE: &str = include_str!("../../../../assets/scenes/default.toml");

/// The example scenes of `assets/scenes`, built into the app (so the web page has them
/// too), by name, in the order the Scene panel lists them.
pub const EXAMPLE_SCENES: &[(&str, &str)] = &[
    ("default", DEFAULT_SCENE),
    (
        "bridge",
        include_str!("../../../../assets/scenes/bridge.toml"),
    ),
    (
        "collapse",
        include_str!("../../../../assets/scenes/collapse.toml"),
    ),
    (
        "runtime",
        include_str!("../../../../assets/scenes/runtime.toml"),
    ),
    (
        "explosion",
        include_str!("../../../../assets/scenes/explosion.toml"),
    ),
    ("wall", include_str!("../../../../assets/scenes/wall.toml")),
    ("bird", include_str!("../../../../assets/scenes/bird.toml")),
    (
        "thesis_joints",
        include_str!("../../../../assets/scenes/thesis_joints.toml"),
    ),
    (
        "textured",
        include_str!("../../../../assets/scenes/textured.toml"),
    ),
];

/// The files the example scenes name (`textured`: the spider OBJ with its MTL and JPEG
/// textures, the textured box GLB), built into the app under the paths the scenes give,
/// so an example loads the same from any folder and in the web page.
pub const EXAMPLE_FILES: &[(&str, &[u8])] = &[
    (
        "../../tests/corpus/obj/spider/spider.obj",
        include_bytes!("../../../../tests/corpus/obj/spider/spider.obj"),
    ),
    (
        "../../tests/corpus/obj/spider/spider.mtl",
        include_bytes!("../../../../tests/corpus/obj/spider/spider.mtl"),
    ),
    (
        "../../tests/corpus/obj/spider/SpiderTex.jpg",
        include_bytes!("../../../../tests/corpus/obj/spider/SpiderTex.jpg"),
    ),
    (
        "../../tests/corpus/obj/spider/drkwood2.jpg",
        include_bytes!("../../../../tests/corpus/obj/spider/drkwood2.jpg"),
    ),
    (
        "../../tests/corpus/obj/spider/engineflare1.jpg",
        include_bytes!("../../../../tests/corpus/obj/spider/engineflare1.jpg"),
    ),
    (
        "../../tests/corpus/obj/spider/wal67ar_small.jpg",
        include_bytes!("../../../../tests/corpus/obj/spider/wal67ar_small.jpg"),
    ),
    (
        "../../tests/corpus/obj/spider/wal69ar_small.jpg",
        include_bytes!("../../../../tests/corpus/obj/spider/wal69ar_small.jpg"),
    ),
    (
        "../../tests/corpus/gltf/BoxTextured.glb",
        include_bytes!("../../../../tests/corpus/gltf/BoxTextured.glb"),
    ),
];

/// See [`SandboxWorld::default_scene`]: a brick wall, the bird, a glass pane and a crate
/// on the ground.
pub(super) fn default_scene() -> ShatterWorld {
    from_scene_text(DEFAULT_SCENE).unwrap_or_else(|e| {
        bevy::log::error!("default scene: {e}");
        ShatterWorld::sandbox(shatter_sim::World::new(Default::default()))
    })
}

pub(super) fn from_scene_text(text: &str) -> Result<ShatterWorld, AppError> {
    let scene = Scene::parse(text)?;
    let world = scene.build_with_files(None, crate::picked_files::picked_files().clone())?;
    Ok(ShatterWorld::sandbox(world))
}

pub(super) fn load_scene(world: &mut ShatterWorld, path: &Path) -> Result<(), AppError> {
    let scene = if cfg!(target_arch = "wasm32") {
        let text = crate::scene_store::read(path)?;
        Scene::parse(&text).map_err(|source| AppError::SceneText {
            path: path.into(),
            source,
        })?
    } else {
        // From the file, so mesh paths resolve relative to the scene's folder.
        Scene::load(path)?
    };
    replace_world(world, &scene)
}

pub(super) fn load_example(world: &mut ShatterWorld, name: &str) -> Result<(), AppError> {
    let Some(&(name, text)) = EXAMPLE_SCENES.iter().find(|(n, _)| *n == name) else {
        let valid: Vec<&str> = EXAMPLE_SCENES.iter().map(|(n, _)| *n).collect();
        return Err(AppError::UnknownExample {
            name: name.to_owned(),
            valid: valid.join(", "),
        });
    };
    let scene = Scene::parse(text).map_err(|source| AppError::ExampleText { name, source })?;
    let files = crate::picked_files::picked_files();
    for (path, bytes) in EXAMPLE_FILES {
        if !files.contains(path) {
            files.insert(path, bytes.to_vec());
        }
    }
    replace_world(world, &scene)
}

/// Build `scene` (with the bond model chosen in the panel) and make it the world.
fn replace_world(world: &mut ShatterWorld, scene: &Scene) -> Result<(), AppError> {
    world.replace_with(|bond_model| {
        scene.build_with_files(bond_model, crate::picked_files::picked_files().clone())
    })?;
    Ok(())
}
