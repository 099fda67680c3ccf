//! Left clicks in the 3D view: fire, explode, select for Edit, or delete; and the
//! keyboard shortcuts of the scene controls (Enter: Start, P: Pause, R: Reset).

use bevy::prelude::*;
use bevy::window::PrimaryWindow;
use bevy_egui::input::EguiWantsInput;

use crate::camera::OrbitCamera;
use crate::commands::SimCommand;
use crate::sim_bridge::{ShatterWorld, to_sim};
use crate::ui::{ClickOutcome, PendingCommands, UiState};

/// A click to perform as if the user had made it (used by the autotest), in window
/// coordinates (logical pixels, origin top-left).
#[derive(Resource, Debug, Default)]
pub struct SyntheticClick(pub Option<Vec2>);

/// Turns left clicks into commands, ignoring clicks egui consumes.
#[derive(Debug, Default)]
pub struct ClickPlugin;

impl Plugin for ClickPlugin {
    fn build(&self, app: &mut App) {
        app.init_resource::<SyntheticClick>()
            .add_systems(Update, (handle_click, handle_shortcuts));
    }
}

#[allow(clippy::too_many_arguments)] // one system reading everything a click needs
fn handle_click(
    buttons: Res<ButtonInput<MouseButton>>,
    window: Single<&Window, With<PrimaryWindow>>,
    camera: Single<(&Camera, &GlobalTransform), With<OrbitCamera>>,
    egui_input: Option<Res<EguiWantsInput>>,
    mut synthetic: ResMut<SyntheticClick>,
    bridge: Res<ShatterWorld>,
    mut ui_state: ResMut<UiState>,
    mut pending: ResMut<PendingCommands>,
) {
    let cursor = if let Some(p) = synthetic.0.take() {
        p
    } else {
        if !buttons.just_pressed(MouseButton::Left) {
            return;
        }
        if egui_input.is_some_and(|e| e.wants_pointer_input() || e.is_pointer_over_area()) {
            return;
        }
        let Some(p) = window.cursor_position() else {
            return;
        };
        p
    };
    let (camera, camera_transform) = *camera;
    let Ok(ray) = camera.viewport_to_world(camera_transform, cursor) else {
        return;
    };
    let (origin, dir) = (to_sim(ray.origin), to_sim(*ray.direction));
    let hit = bridge.world().ray_cast(origin, dir);
    match ui_state.click(origin, dir, hit) {
        ClickOutcome::Command(cmd) => pending.0.push(cmd),
        ClickOutcome::Edit(id) => {
            if let Some(spec) = bridge.world().object_spec(id) {
                ui_state.edit_object(id, spec);
            }
        }
        ClickOutcome::Nothing => {}
    }
}

/// The scene control a key stands for, if any.
pub fn shortcut(key: KeyCode) -> Option<SimCommand> {
    match key {
        KeyCode::Enter | KeyCode::NumpadEnter => Some(SimCommand::Start),
        KeyCode::KeyP => Some(SimCommand::TogglePause),
        KeyCode::KeyR => Some(SimCommand::Reset),
        _ => None,
    }
}

fn handle_shortcuts(
    keys: Res<ButtonInput<KeyCode>>,
    egui_input: Option<Res<EguiWantsInput>>,
    mut pending: ResMut<PendingCommands>,
) {
    // Typing in a text field is not a shortcut.
    if egui_input.is_some_and(|e| e.wants_keyboard_input()) {
        return;
    }
    for key in keys.get_just_pressed() {
        if let Some(cmd) = shortcut(*key) {
            pending.0.push(cmd);
        }
    }
}
