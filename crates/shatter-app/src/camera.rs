//! A camera that orbits, pans, zooms (mouse) and flies (WASD + Q/E).
//!
//! - right drag: orbit around the focus point;
//! - middle drag, or Shift + right drag: pan;
//! - wheel: zoom;
//! - W/A/S/D: fly forward/left/back/right, Q/E: down/up (Shift: faster).

use bevy::core_pipeline::tonemapping::Tonemapping;
use bevy::input::mouse::{AccumulatedMouseMotion, AccumulatedMouseScroll, MouseScrollUnit};
use bevy::prelude::*;
use bevy_egui::input::EguiWantsInput;

/// Orbit-camera state: the camera looks at `focus` from `distance` along yaw/pitch.
#[derive(Component, Debug, Clone, Copy, PartialEq)]
pub struct OrbitCamera {
    /// Point looked at.
    pub focus: Vec3,
    /// Rotation around +Y, radians.
    pub yaw: f32,
    /// Elevation, radians (positive looks down at the focus).
    pub pitch: f32,
    /// Distance from the focus.
    pub distance: f32,
}

impl Default for OrbitCamera {
    fn default() -> Self {
        Self {
            // The default scene's wall, in the middle of the free part of the window.
            focus: Vec3::new(0.0, 0.9, 0.8),
            yaw: 0.3,
            pitch: 0.3,
            distance: 8.5,
        }
    }
}

impl OrbitCamera {
    /// Camera position.
    pub fn eye(&self) -> Vec3 {
        let dir = Vec3::new(
            self.yaw.sin() * self.pitch.cos(),
            self.pitch.sin(),
            self.yaw.cos() * self.pitch.cos(),
        );
        self.focus + dir * self.distance
    }

    /// Camera transform looking at the focus.
    pub fn transform(&self) -> Transform {
        Transform::from_translation(self.eye()).looking_at(self.focus, Vec3::Y)
    }

    /// Orbit by mouse delta (pixels).
    pub fn orbit(&mut self, delta: Vec2) {
        self.yaw -= delta.x * 0.005;
        self.pitch = (self.pitch + delta.y * 0.005).clamp(-1.5, 1.5);
    }

    /// Pan by mouse delta (pixels), proportional to the distance.
    pub fn pan(&mut self, delta: Vec2) {
        let t = self.transform();
        let scale = self.distance * 0.0015;
        self.focus += (-*t.right() * delta.x + *t.up() * delta.y) * scale;
    }

    /// Zoom by wheel lines (positive: closer).
    pub fn zoom(&mut self, lines: f32) {
        self.distance = (self.distance * (1.0 - lines * 0.1)).clamp(0.5, 500.0);
    }

    /// Fly: `local` is (right, up, forward) in metres, forward along the horizontal view.
    pub fn fly(&mut self, local: Vec3) {
        let t = self.transform();
        let fwd = Vec3::new(t.forward().x, 0.0, t.forward().z).normalize_or_zero();
        let right = Vec3::new(t.right().x, 0.0, t.right().z).normalize_or_zero();
        self.focus += right * local.x + Vec3::Y * local.y + fwd * local.z;
    }
}

/// Spawns the camera and moves it from mouse and keyboard input.
#[derive(Debug, Clone, Default)]
pub struct CameraPlugin {
    /// Starting view.
    pub start: OrbitCamera,
}

impl Plugin for CameraPlugin {
    fn build(&self, app: &mut App) {
        let start = self.start;
        app.add_systems(Startup, move |mut commands: Commands| {
            commands.spawn((
                Camera3d::default(),
                // Khronos PBR Neutral: an asset's base colours come out as its author
                // painted them (TonyMcMapface, Bevy's default, desaturates them), and it
                // needs no lookup table, so neither build ships Bevy's `tonemapping_luts`.
                Tonemapping::KhronosPbrNeutral,
                start.transform(),
                start,
            ));
        })
        .add_systems(Update, (control_camera, software_renderer_without_msaa));
    }
}

/// On a software renderer (Mesa's llvmpipe/lavapipe, SwiftShader) multisampling costs
/// more than everything else in the frame: turn it off there, once.
fn software_renderer_without_msaa(
    adapter: Option<Res<bevy::render::renderer::RenderAdapterInfo>>,
    cameras: Query<Entity, With<OrbitCamera>>,
    mut commands: Commands,
    mut done: Local<bool>,
) {
    if *done {
        return;
    }
    let Some(adapter) = adapter else {
        return;
    };
    *done = true;
    if format!("{:?}", adapter.device_type) == "Cpu" {
        info!("software renderer ({}): MSAA off", adapter.name);
        for camera in &cameras {
            commands.entity(camera).insert(Msaa::Off);
        }
    }
}

fn control_camera(
    mut cameras: Query<(&mut OrbitCamera, &mut Transform)>,
    buttons: Res<ButtonInput<MouseButton>>,
    keys: Res<ButtonInput<KeyCode>>,
    motion: Res<AccumulatedMouseMotion>,
    scroll: Res<AccumulatedMouseScroll>,
    egui_input: Option<Res<EguiWantsInput>>,
    time: Res<Time>,
) {
    let (pointer_busy, keyboard_busy) = egui_input
        .map(|e| (e.wants_pointer_input(), e.wants_keyboard_input()))
        .unwrap_or((false, false));
    for (mut cam, mut transform) in &mut cameras {
        let shift = keys.any_pressed([KeyCode::ShiftLeft, KeyCode::ShiftRight]);
        if !pointer_busy {
            if buttons.pressed(MouseButton::Middle)
                || (shift && buttons.pressed(MouseButton::Right))
            {
                cam.pan(motion.delta);
            } else if buttons.pressed(MouseButton::Right) {
                cam.orbit(motion.delta);
            }
            let lines = match scroll.unit {
                MouseScrollUnit::Line => scroll.delta.y,
                MouseScrollUnit::Pixel => scroll.delta.y / 40.0,
            };
            if lines != 0.0 {
                cam.zoom(lines);
            }
        }
        if !keyboard_busy {
            let mut local = Vec3::ZERO;
            for (key, d) in [
                (KeyCode::KeyW, Vec3::Z),
                (KeyCode::KeyS, -Vec3::Z),
                (KeyCode::KeyD, Vec3::X),
                (KeyCode::KeyA, -Vec3::X),
                (KeyCode::KeyE, Vec3::Y),
                (KeyCode::KeyQ, -Vec3::Y),
            ] {
                if keys.pressed(key) {
                    local += d;
                }
            }
            if local != Vec3::ZERO {
                let speed = if shift { 24.0 } else { 8.0 };
                cam.fly(local * speed * time.delta_secs());
            }
        }
        let t = cam.transform();
        if *transform != t {
            *transform = t;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn eye_is_at_distance_and_camera_faces_focus() {
        let cam = OrbitCamera::default();
        assert!((cam.eye().distance(cam.focus) - cam.distance).abs() < 1e-4);
        let t = cam.transform();
        let to_focus = (cam.focus - t.translation).normalize();
        assert!(t.forward().dot(to_focus) > 0.999);
    }

    #[test]
    fn fly_forward_moves_towards_focus_horizontally() {
        let mut cam = OrbitCamera::default();
        let before = cam.eye();
        cam.fly(Vec3::Z);
        let moved = cam.eye() - before;
        assert!(moved.y.abs() < 1e-5);
        assert!((moved.length() - 1.0).abs() < 1e-4);
        let horizontal_view = (cam.focus - before) * Vec3::new(1.0, 0.0, 1.0);
        assert!(moved.dot(horizontal_view) > 0.0);
    }

    #[test]
    fn zoom_and_pitch_stay_bounded() {
        let mut cam = OrbitCamera::default();
        for _ in 0..200 {
            cam.zoom(5.0);
            cam.orbit(Vec2::new(0.0, 500.0));
        }
        assert!(cam.distance >= 0.5);
        assert!(cam.pitch <= 1.5);
    }
}
