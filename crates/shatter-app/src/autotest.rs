//! `--autotest DIR`: a scripted session on the default scene that drives the app through
//! the same code paths as a user (the panels' state methods and synthetic clicks), takes
//! screenshots and writes `DIR/state.json`, then exits.
//!
//! Script: screenshot the scene; add an object through the Add Object panel; Start; fire
//! at the wall; screenshot the debris; explode at the crate; Pause; Reset; load
//! `assets/scenes/bridge.toml` through the Scene panel, Start, and screenshot the bridge
//! before and after its pillar is blown away (the slab breaking off by stress); load
//! `assets/scenes/runtime.toml`, Start, and screenshot the bird and the pane cut where
//! the balls landed.

use std::path::PathBuf;

use bevy::app::AppExit;
use bevy::prelude::*;
use bevy::render::view::screenshot::{Screenshot, save_to_disk};
use serde_json::{Value, json};

use crate::camera::OrbitCamera;
use crate::commands::ObjectId;
use crate::commands::SimCommand;
use crate::input::SyntheticClick;
use crate::sim_bridge::{ShatterWorld, SimStats, to_bevy};
use crate::ui::forms::ShapeKind;
use crate::ui::{FrameRate, PendingCommands, UiState};

/// Runs the scripted session and exits.
#[derive(Debug, Clone)]
pub struct AutotestPlugin {
    /// Folder for the screenshots and `state.json`.
    pub dir: PathBuf,
}

impl Plugin for AutotestPlugin {
    fn build(&self, app: &mut App) {
        app.insert_resource(Autotest {
            dir: self.dir.clone(),
            step: 0,
            step_frame: 0,
            step_time: 0.0,
            shots: Vec::new(),
            record: serde_json::Map::new(),
            fps_samples: Vec::new(),
        })
        .add_systems(Last, run_script);
    }
}

#[derive(Resource)]
struct Autotest {
    dir: PathBuf,
    step: usize,
    /// Frame count when the current step began.
    step_frame: u64,
    /// Simulated time when the current step began.
    step_time: f64,
    shots: Vec<PathBuf>,
    record: serde_json::Map<String, Value>,
    fps_samples: Vec<f64>,
}

/// Frames any step may wait before the run is declared stuck.
const STEP_TIMEOUT_FRAMES: u64 = 3000;

fn stats_json(s: &SimStats) -> Value {
    serde_json::to_value(s).unwrap_or(Value::Null)
}

#[allow(clippy::too_many_arguments)] // the script touches every part of the app
fn run_script(
    mut commands: Commands,
    mut test: ResMut<Autotest>,
    mut ui_state: ResMut<UiState>,
    mut pending: ResMut<PendingCommands>,
    mut click: ResMut<SyntheticClick>,
    bridge: Res<ShatterWorld>,
    rate: Res<FrameRate>,
    camera: Single<(&Camera, &GlobalTransform), With<OrbitCamera>>,
    mut exit: MessageWriter<AppExit>,
) {
    let frame = rate.frames;
    let stats = bridge.stats();
    let frames_in_step = frame.saturating_sub(test.step_frame);
    let sim_in_step = stats.time - test.step_time;
    if frames_in_step > STEP_TIMEOUT_FRAMES {
        let step = test.step;
        error!("autotest stuck at step {step}");
        test.record
            .insert("error".into(), json!(format!("stuck at step {step}")));
        write_state(&test);
        exit.write(AppExit::error());
        return;
    }
    if stats.running {
        test.fps_samples.push(rate.fps);
    }
    let (cam, cam_transform) = *camera;
    let screen_of = |p: Vec3| cam.world_to_viewport(cam_transform, p).ok();
    let mut shot = |test: &mut Autotest, name: &str| {
        let path = test.dir.join(name);
        commands
            .spawn(Screenshot::primary_window())
            .observe(save_to_disk(path.clone()));
        test.shots.push(path);
    };
    // Each arm returns whether the step is done.
    let done = match test.step {
        // Let the renderer warm up (pipelines compile on the first frames).
        0 => frames_in_step >= 40,
        1 => {
            shot(&mut test, "01_scene.png");
            test.record.insert("initial".into(), stats_json(&stats));
            true
        }
        // Add an object through the Add Object panel, as a user would.
        2 => {
            ui_state.open_add_panel();
            ui_state.add.shape = ShapeKind::Builtin(shatter_sim::Shape::Cylinder);
            ui_state.add.random_vertices = "30".into();
            ui_state.add.color = ["0.35".into(), "0.75".into(), "0.35".into()];
            // Right of the wall, in view, set down just above the ground.
            ui_state.transform.position = ["2.6".into(), "0.62".into(), "0.2".into()];
            ui_state.transform.scale = ["0.6".into(), "0.6".into(), "0.6".into()];
            ui_state.next_page(&crate::sim_bridge::check_custom_mesh);
            if let Some(cmd) = ui_state.draw(&crate::sim_bridge::check_custom_mesh) {
                pending.0.push(cmd);
            }
            true
        }
        3 => frames_in_step >= 10,
        4 => {
            shot(&mut test, "02_add_object_panel.png");
            true
        }
        5 => {
            if let Some(cmd) = ui_state.apply(&crate::sim_bridge::check_custom_mesh) {
                pending.0.push(cmd);
            }
            test.record
                .insert("after_add".into(), stats_json(&bridge.stats()));
            pending.0.push(SimCommand::Start);
            true
        }
        // Let things settle for half a second of simulated time.
        6 => sim_in_step >= 0.5,
        // Fire at the middle of the wall from the camera.
        7 => {
            test.record.insert("before_shot".into(), stats_json(&stats));
            let target = bridge
                .world()
                .object_spec(ObjectId(0))
                .map(|s| to_bevy(s.position))
                .unwrap_or(Vec3::new(0.0, 2.0, 0.0));
            click.0 = screen_of(target);
            true
        }
        8 => sim_in_step >= 0.4,
        9 => {
            shot(&mut test, "03_after_shot.png");
            test.record.insert("after_shot".into(), stats_json(&stats));
            true
        }
        10 => sim_in_step >= 1.0,
        // An explosion at the crate (object 3 of the default scene).
        11 => {
            ui_state.force_form.enabled = true;
            ui_state.force_form.radius = "1.5".into();
            ui_state.force_form.power = "150".into();
            ui_state.update_force();
            let target = bridge
                .world()
                .object_spec(ObjectId(3))
                .map(|s| to_bevy(s.position))
                .unwrap_or(Vec3::new(-3.0, 0.5, 1.5));
            click.0 = screen_of(target);
            test.record
                .insert("before_explosion".into(), stats_json(&stats));
            true
        }
        12 => sim_in_step >= 0.3,
        13 => {
            shot(&mut test, "04_explosion.png");
            test.record
                .insert("after_explosion".into(), stats_json(&stats));
            ui_state.force_form.enabled = false;
            ui_state.update_force();
            pending.0.push(SimCommand::TogglePause);
            true
        }
        14 => frames_in_step >= 10,
        15 => {
            shot(&mut test, "05_paused.png");
            test.record.insert("paused".into(), stats_json(&stats));
            pending.0.push(SimCommand::Reset);
            true
        }
        16 => frames_in_step >= 10,
        17 => {
            shot(&mut test, "06_reset.png");
            test.record.insert("after_reset".into(), stats_json(&stats));
            true
        }
        // The bridge scene, loaded as a user would, through the Scene panel.
        18 => {
            ui_state.scene_file.path = concat!(
                env!("CARGO_MANIFEST_DIR"),
                "/../../assets/scenes/bridge.toml"
            )
            .to_owned();
            match ui_state.scene_file.load() {
                Ok(cmd) => pending.0.push(cmd),
                Err(e) => {
                    test.record
                        .insert("bridge_error".into(), json!(e.to_string()));
                }
            }
            true
        }
        19 => frames_in_step >= 10,
        20 => {
            pending.0.push(SimCommand::Start);
            true
        }
        21 => sim_in_step >= 0.8,
        22 => {
            shot(&mut test, "07_bridge_standing.png");
            test.record
                .insert("bridge_before".into(), stats_json(&stats));
            true
        }
        // The pillar is blown away at 1 s; the slab breaks off and falls.
        23 => sim_in_step >= 0.35,
        24 => {
            shot(&mut test, "08_bridge_falling.png");
            test.record
                .insert("bridge_falling".into(), stats_json(&stats));
            true
        }
        25 => sim_in_step >= 2.0,
        26 => {
            shot(&mut test, "09_bridge_fallen.png");
            test.record
                .insert("bridge_fallen".into(), stats_json(&stats));
            true
        }
        // Runtime fracture: two objects that start whole, cut where the balls land.
        27 => {
            ui_state.scene_file.path = concat!(
                env!("CARGO_MANIFEST_DIR"),
                "/../../assets/scenes/runtime.toml"
            )
            .to_owned();
            match ui_state.scene_file.load() {
                Ok(cmd) => pending.0.push(cmd),
                Err(e) => {
                    test.record
                        .insert("runtime_error".into(), json!(e.to_string()));
                }
            }
            true
        }
        28 => frames_in_step >= 10,
        29 => {
            test.record
                .insert("runtime_before".into(), stats_json(&stats));
            pending.0.push(SimCommand::Start);
            true
        }
        // The balls land at about 0.9 s and 1.4 s.
        30 => sim_in_step >= 1.7,
        31 => {
            shot(&mut test, "10_runtime_cut.png");
            test.record.insert("runtime".into(), stats_json(&stats));
            true
        }
        // A user's own textured models (an OBJ with JPEG textures, a GLB with an
        // embedded PNG), whole and then broken by two balls.
        32 => {
            ui_state.scene_file.path = concat!(
                env!("CARGO_MANIFEST_DIR"),
                "/../../assets/scenes/textured.toml"
            )
            .to_owned();
            match ui_state.scene_file.load() {
                Ok(cmd) => pending.0.push(cmd),
                Err(e) => {
                    test.record
                        .insert("textured_error".into(), json!(e.to_string()));
                }
            }
            true
        }
        33 => frames_in_step >= 20,
        34 => {
            shot(&mut test, "11_textured_whole.png");
            test.record
                .insert("textured_before".into(), stats_json(&stats));
            pending.0.push(SimCommand::Start);
            true
        }
        // The balls land at about 0.7 s and 0.9 s.
        35 => sim_in_step >= 1.3,
        36 => {
            shot(&mut test, "12_textured_broken.png");
            test.record.insert("textured".into(), stats_json(&stats));
            true
        }
        // Wait for the screenshots to reach the disk.
        37 => test.shots.iter().all(|p| p.is_file()) && frames_in_step >= 5,
        _ => {
            write_state(&test);
            exit.write(AppExit::Success);
            return;
        }
    };
    if done {
        test.step += 1;
        test.step_frame = frame;
        test.step_time = stats.time;
    }
}

fn write_state(test: &Autotest) {
    let mut out = test.record.clone();
    if let Some(Value::Object(after)) = test.record.get("after_shot") {
        for key in ["bonds_broken", "bodies", "fragments"] {
            if let Some(v) = after.get(key) {
                out.insert(key.into(), v.clone());
            }
        }
    }
    let n = test.fps_samples.len().max(1) as f64;
    out.insert(
        "fps_mean_running".into(),
        json!(test.fps_samples.iter().sum::<f64>() / n),
    );
    out.insert(
        "screenshots".into(),
        json!(
            test.shots
                .iter()
                .filter_map(|p| p.file_name()?.to_str())
                .collect::<Vec<_>>()
        ),
    );
    let path = test.dir.join("state.json");
    let text = serde_json::to_string_pretty(&Value::Object(out)).unwrap_or_default();
    if let Err(e) = std::fs::write(&path, text) {
        error!("cannot write {}: {e}", path.display());
    }
}
