//! Applies queued commands to the simulation and advances it every frame.

use bevy::prelude::*;

use crate::sim_bridge::SimBridge;
use crate::ui::{PendingCommands, UiState};

/// Owns the [`SimBridge`] resource and steps it.
#[derive(Debug, Default)]
pub struct SimPlugin;

impl Plugin for SimPlugin {
    fn build(&self, app: &mut App) {
        if !app.world().contains_resource::<SimBridge>() {
            app.insert_resource(SimBridge::default_scene());
        }
        app.add_systems(Update, (apply_commands, advance).chain());
    }
}

/// Apply every queued command; report errors and new ids to the UI.
pub fn apply_commands(
    mut bridge: ResMut<SimBridge>,
    mut pending: ResMut<PendingCommands>,
    mut ui_state: ResMut<UiState>,
) {
    for cmd in pending.0.drain(..) {
        let what = cmd.clone();
        match bridge.apply(cmd) {
            Ok(Some(id)) => ui_state.object_added(id),
            Ok(None) => {}
            Err(e) => {
                warn!(
                    "command failed: {e} ({})",
                    format!("{what:?}").chars().take(60).collect::<String>()
                );
                ui_state.command_failed(&what, e);
            }
        }
    }
}

fn advance(mut bridge: ResMut<SimBridge>, time: Res<Time>, mut ui_state: ResMut<UiState>) {
    if let Some(last) = bridge.advance(time.delta_secs_f64()).pop() {
        warn!("{last}");
        ui_state.status = last;
    }
}
