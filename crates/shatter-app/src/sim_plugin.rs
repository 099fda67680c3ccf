//! Applies queued commands to the simulation before bevy_shatter steps it, and shows what
//! went wrong in a step in the status line.

use bevy::prelude::*;
use bevy_shatter::world::{ShatterWorld, ShatterWorldPlugin, ShatterWorldSystems, WorldEvent};
use shatter_sim::SimEvent;

use crate::sim_bridge::SandboxWorld;
use crate::ui::{PendingCommands, UiState};

/// Adds bevy_shatter's [`ShatterWorldPlugin`] (which steps and draws the world), opening
/// the default scene unless a world is already there, and feeds it the panels' commands.
#[derive(Debug, Default)]
pub struct SimPlugin;

/// An example scene ([`crate::sim_bridge::EXAMPLE_SCENES`]) to open once the first frame
/// has been drawn, into the (empty) world the app started with. The web page starts this
/// way, so its first frame does not wait for the scene's fracture. A name that is not an
/// example is logged and the default scene opens.
#[derive(Resource, Debug, Clone, PartialEq, Eq)]
pub struct OpenAfterFirstFrame(pub String);

impl Plugin for SimPlugin {
    fn build(&self, app: &mut App) {
        if !app.world().contains_resource::<ShatterWorld>() {
            app.insert_resource(ShatterWorld::default_scene());
        }
        app.add_plugins(ShatterWorldPlugin).add_systems(
            Update,
            (
                open_after_first_frame.before(apply_commands),
                apply_commands.before(ShatterWorldSystems::Step),
                report_events.after(ShatterWorldSystems::Step),
            ),
        );
    }
}

/// Open the [`OpenAfterFirstFrame`] scene, once a frame has been drawn and the state
/// line that says so logged ([`crate::state_log`]: at the second frame's end): at the
/// third frame's update.
fn open_after_first_frame(
    mut commands: Commands,
    pending: Option<Res<OpenAfterFirstFrame>>,
    mut updates: Local<u32>,
    mut world: ResMut<ShatterWorld>,
) {
    let Some(pending) = pending else { return };
    *updates += 1;
    if *updates < 3 {
        return;
    }
    commands.remove_resource::<OpenAfterFirstFrame>();
    if let Err(e) = world.load_example(&pending.0) {
        error!("scene={}: {e}", pending.0);
        if let Err(e) = world.load_example("default") {
            error!("default scene: {e}");
        }
    }
}

/// Apply every queued command; report errors and new ids to the UI.
pub fn apply_commands(
    mut world: ResMut<ShatterWorld>,
    mut pending: ResMut<PendingCommands>,
    mut ui_state: ResMut<UiState>,
) {
    for cmd in pending.0.drain(..) {
        let what = cmd.clone();
        match world.apply(cmd) {
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

/// The status line's message for a step's event, if it is one the user should see
/// (bodies removed, a runtime cut that failed).
pub fn status_message(event: &SimEvent) -> Option<String> {
    match event {
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
    }
}

fn report_events(mut events: MessageReader<WorldEvent>, mut ui_state: ResMut<UiState>) {
    if let Some(last) = events.read().filter_map(|e| status_message(&e.0)).last() {
        warn!("{last}");
        ui_state.status = last;
    }
}
