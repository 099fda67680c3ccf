//! The Bevy side of the panels: one system drawing them in egui's pass, queuing the
//! commands they produce.

use bevy::prelude::*;
use bevy_egui::{EguiContexts, EguiPrimaryContextPass};

use crate::commands::SimCommand;
use crate::sim_bridge::ShatterWorld;
use crate::ui::panels::draw_panels;
use crate::ui::state::UiState;

/// Commands waiting to be applied to the simulation this frame.
#[derive(Resource, Debug, Default)]
pub struct PendingCommands(pub Vec<SimCommand>);

/// Smoothed frames per second, for the overlay and the autotest.
#[derive(Resource, Debug, Default, Clone, Copy)]
pub struct FrameRate {
    /// Exponential moving average of 1 / frame time.
    pub fps: f64,
    /// Frames drawn so far.
    pub frames: u64,
}

/// Draws the panels and queues their commands.
#[derive(Debug, Default)]
pub struct UiPlugin;

impl Plugin for UiPlugin {
    fn build(&self, app: &mut App) {
        app.init_resource::<UiState>()
            .init_resource::<PendingCommands>()
            .init_resource::<FrameRate>()
            .add_systems(Update, measure_frame_rate)
            .add_systems(EguiPrimaryContextPass, draw_ui);
    }
}

fn measure_frame_rate(time: Res<Time>, mut rate: ResMut<FrameRate>) {
    let dt = time.delta_secs_f64();
    rate.frames += 1;
    if dt > 0.0 {
        let inst = 1.0 / dt;
        rate.fps = if rate.fps == 0.0 {
            inst
        } else {
            0.9 * rate.fps + 0.1 * inst
        };
    }
}

fn draw_ui(
    mut fonts_set: Local<bool>,
    mut contexts: EguiContexts,
    mut ui_state: ResMut<UiState>,
    mut pending: ResMut<PendingCommands>,
    bridge: Res<ShatterWorld>,
    rate: Res<FrameRate>,
) -> Result {
    let ctx = contexts.ctx_mut()?;
    if !*fonts_set {
        // Takes effect from the next pass; the first frame draws no text.
        ctx.set_fonts(crate::ui::fonts::panel_fonts());
        *fonts_set = true;
    }
    let stats = bridge.stats();
    let cmds = draw_panels(ctx, &mut ui_state, &stats, rate.fps);
    pending.0.extend(cmds);
    Ok(())
}
