//! Prints the simulation's state as one JSON line at a fixed wall-clock period, prefixed
//! with `SHATTER_STATE `. The web page and its end-to-end test (`web/e2e.mjs`) read these
//! lines from the browser console to know that frames are drawn and bonds broke.

use bevy::prelude::*;
use serde_json::json;

use crate::render::RenderStats;
use crate::sim_bridge::ShatterWorld;
use crate::ui::FrameRate;

/// Logs `SHATTER_STATE {json}` once the first frame has been drawn, once the first frame
/// whose world has fragments (a scene opened after the first frame) has, and every
/// `period_secs` seconds of wall-clock time. The web page times its first frame by the
/// first line and its scene by the first with fragments.
#[derive(Debug, Clone)]
pub struct StateLogPlugin {
    /// Seconds between lines.
    pub period_secs: f32,
}

impl Default for StateLogPlugin {
    fn default() -> Self {
        Self { period_secs: 0.5 }
    }
}

#[derive(Resource)]
struct StateLogTimer(Timer);

impl Plugin for StateLogPlugin {
    fn build(&self, app: &mut App) {
        app.insert_resource(StateLogTimer(Timer::from_seconds(
            self.period_secs,
            TimerMode::Repeating,
        )))
        .add_systems(Last, log_state);
    }
}

/// The line for a state and a frame count: every [`SimStats`](crate::sim_bridge::SimStats)
/// field, plus `frames`.
pub fn state_line(bridge: &ShatterWorld, frames: u64) -> String {
    state_line_with(bridge, frames, 0)
}

/// [`state_line`], plus `textured_materials`: the drawn file materials that carry a
/// texture ([`RenderStats`]), so the web page's test sees a textured model drawn.
pub fn state_line_with(bridge: &ShatterWorld, frames: u64, textured_materials: usize) -> String {
    let mut value = serde_json::to_value(bridge.stats()).unwrap_or_else(|_| json!({}));
    if let Some(map) = value.as_object_mut() {
        map.insert("frames".to_owned(), json!(frames));
        map.insert("textured_materials".to_owned(), json!(textured_materials));
    }
    format!("SHATTER_STATE {value}")
}

fn log_state(
    time: Res<Time<Real>>,
    mut timer: ResMut<StateLogTimer>,
    bridge: Res<ShatterWorld>,
    rate: Res<FrameRate>,
    render: Option<Res<RenderStats>>,
    mut scene_from: Local<Option<u64>>,
) {
    // `FrameRate` counts frames in `Update` and this runs in `Last`. The render sub-app
    // draws a frame after the main world's update, so at the second frame's `Last` the
    // first frame has been drawn.
    let first = rate.frames == 2;
    // The scene's line likewise waits one frame: the frame whose update opened it has
    // then been drawn.
    if scene_from.is_none() && bridge.stats().fragments > 0 {
        *scene_from = Some(rate.frames);
    }
    let scene = *scene_from == Some(rate.frames.saturating_sub(1));
    if timer.0.tick(time.delta()).just_finished() || first || scene {
        let textured = render.map_or(0, |r| r.textured_materials);
        info!("{}", state_line_with(&bridge, rate.frames, textured));
    }
}
