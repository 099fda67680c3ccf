//! Drawing of the panels with egui. Only layout lives here: every decision is a method of
//! [`UiState`] or a form's `validate`, tested without a window.

use bevy_egui::egui::{self, Color32, RichText, Ui};

use crate::commands::{BondModel, MaterialPreset, MethodKind, Pattern, SimCommand};
use crate::sim_bridge::{SimStats, check_custom_mesh, load_projectile};
use crate::ui::forms::{FieldErrors, ShapeKind};
use crate::ui::state::{AddObjectPage, UiState};

const ERROR: Color32 = Color32::from_rgb(255, 110, 90);
const FIELD_WIDTH: f32 = 56.0;

/// Draw every panel; returns the commands the user gave this frame.
pub fn draw_panels(
    ctx: &egui::Context,
    ui_state: &mut UiState,
    stats: &SimStats,
    fps: f64,
) -> Vec<SimCommand> {
    let mut out = Vec::new();
    egui::Window::new("shatter")
        .anchor(egui::Align2::LEFT_TOP, [8.0, 8.0])
        .default_width(300.0)
        .resizable(false)
        .vscroll(true)
        .show(ctx, |ui| {
            scene_controls(ui, ui_state, stats, &mut out);
            ui.separator();
            add_object_panel(ui, ui_state, &mut out);
            ui.separator();
            fire_panel(ui, ui_state);
            ui.separator();
            force_panel(ui, ui_state);
            ui.separator();
            scene_file_panel(ui, ui_state, &mut out);
            if !ui_state.status.is_empty() {
                ui.separator();
                ui.label(RichText::new(&ui_state.status).small());
            }
        });
    egui::Window::new("overlay")
        .title_bar(false)
        .resizable(false)
        .anchor(egui::Align2::RIGHT_TOP, [-8.0, 8.0])
        .show(ctx, |ui| overlay(ui, stats, fps));
    out
}

fn overlay(ui: &mut Ui, stats: &SimStats, fps: f64) {
    egui::Grid::new("overlay_grid").show(ui, |ui| {
        let rows = [
            ("fps", format!("{fps:.0}")),
            ("bodies", stats.bodies.to_string()),
            ("fragments", stats.fragments.to_string()),
            (
                "bonds broken",
                format!("{} / {}", stats.bonds_broken, stats.bonds_total),
            ),
            (
                "impact/stress/damage",
                format!(
                    "{} / {} / {}",
                    stats.bonds_broken_by[0], stats.bonds_broken_by[1], stats.bonds_broken_by[2]
                ),
            ),
            (
                "worn bonds",
                format!(
                    "{} (lowest health {:.2})",
                    stats.bonds_damaged, stats.min_bond_health
                ),
            ),
            (
                "runtime cuts",
                format!("{} (depth {})", stats.runtime_fractures, stats.max_depth),
            ),
            ("speeds capped", stats.speeds_capped.to_string()),
            ("step", format!("{:.2} ms", stats.step_ms)),
            ("time", format!("{:.2} s", stats.time)),
        ];
        for (k, v) in rows {
            ui.label(k);
            ui.monospace(v);
            ui.end_row();
        }
    });
    let state = if stats.paused {
        "paused"
    } else if stats.running {
        "running"
    } else {
        "stopped"
    };
    ui.label(RichText::new(state).strong());
}

fn scene_controls(ui: &mut Ui, s: &mut UiState, stats: &SimStats, out: &mut Vec<SimCommand>) {
    ui.horizontal(|ui| {
        if ui.button("Start").on_hover_text("Enter").clicked() {
            out.push(SimCommand::Start);
        }
        if ui.button("Reset").on_hover_text("R").clicked() {
            out.push(SimCommand::Reset);
        }
        if ui.button("Clean").clicked() {
            out.push(SimCommand::Clean);
        }
        let pause = if stats.paused { "Resume" } else { "Pause" };
        if ui.button(pause).on_hover_text("P").clicked() {
            out.push(SimCommand::TogglePause);
        }
    });
    ui.horizontal(|ui| {
        if ui.selectable_label(s.edit_mode, "Edit").clicked() {
            s.toggle_edit();
        }
        if ui.selectable_label(s.delete_mode, "Delete").clicked() {
            s.toggle_delete();
        }
        ui.label("Bonds:");
        for &m in BondModel::ALL {
            let current = s.bond_model.unwrap_or_default();
            if ui.selectable_label(current == m, m.name()).clicked() && current != m {
                s.bond_model = Some(m);
                out.push(SimCommand::SetBondModel(m));
            }
        }
    });
}

fn error_line(ui: &mut Ui, errors: &FieldErrors, field: &str) {
    if let Some(msg) = errors.get(field) {
        ui.colored_label(ERROR, msg);
    }
}

fn text_row(ui: &mut Ui, label: &str, text: &mut String, errors: &FieldErrors, field: &str) {
    ui.horizontal(|ui| {
        ui.label(label);
        ui.add(egui::TextEdit::singleline(text).desired_width(FIELD_WIDTH * 1.6));
    });
    error_line(ui, errors, field);
}

fn triple_row(
    ui: &mut Ui,
    label: &str,
    texts: &mut [String; 3],
    errors: &FieldErrors,
    field: &str,
) {
    ui.horizontal(|ui| {
        ui.label(label);
        for t in texts.iter_mut() {
            ui.add(egui::TextEdit::singleline(t).desired_width(FIELD_WIDTH));
        }
    });
    error_line(ui, errors, field);
}

fn shape_row(ui: &mut Ui, kinds: &[ShapeKind], shape: &mut ShapeKind, path: &mut String) {
    ui.horizontal_wrapped(|ui| {
        for &k in kinds {
            ui.selectable_value(shape, k, k.label());
        }
    });
    if *shape == ShapeKind::Custom {
        ui.horizontal(|ui| {
            ui.label("File");
            ui.add(egui::TextEdit::singleline(path).desired_width(200.0));
        });
    }
}

fn add_object_panel(ui: &mut Ui, s: &mut UiState, out: &mut Vec<SimCommand>) {
    let title = match s.target {
        Some(id) if !s.awaiting_new_id => format!("Object {id}"),
        _ => "Add Object".to_owned(),
    };
    ui.horizontal(|ui| {
        ui.label(RichText::new(&title).strong());
        if s.add_page == AddObjectPage::Closed {
            if ui.button("Open").clicked() {
                s.open_add_panel();
            }
        } else if ui.small_button("Close").clicked() {
            s.close_add_panel();
        }
    });
    match s.add_page {
        AddObjectPage::Closed => {}
        AddObjectPage::Parameters => {
            let f = &mut s.add;
            shape_row(
                ui,
                &ShapeKind::object_options(),
                &mut f.shape,
                &mut f.custom_path,
            );
            error_line(ui, &s.add_errors, "shape");
            error_line(ui, &s.add_errors, "object");
            ui.horizontal(|ui| {
                egui::ComboBox::from_id_salt("method")
                    .selected_text(f.method.name())
                    .show_ui(ui, |ui| {
                        for &m in MethodKind::ALL {
                            ui.selectable_value(&mut f.method, m, m.name());
                        }
                    });
                if f.method == MethodKind::Voronoi {
                    egui::ComboBox::from_id_salt("pattern")
                        .selected_text(f.pattern.name())
                        .show_ui(ui, |ui| {
                            for &p in Pattern::ALL {
                                ui.selectable_value(&mut f.pattern, p, p.name());
                            }
                        });
                }
                egui::ComboBox::from_id_salt("material")
                    .selected_text(f.material.name())
                    .show_ui(ui, |ui| {
                        for &m in MaterialPreset::ALL {
                            ui.selectable_value(&mut f.material, m, m.name());
                        }
                    });
            });
            let rv = match f.method {
                MethodKind::Tetra => "Random Vertices",
                MethodKind::Grid => "Bricks along x",
                MethodKind::Voronoi | MethodKind::Slice => "Pieces",
            };
            text_row(
                ui,
                rv,
                &mut f.random_vertices,
                &s.add_errors,
                "random_vertices",
            );
            text_row(
                ui,
                "Breakforce",
                &mut f.break_force,
                &s.add_errors,
                "break_force",
            );
            if f.method == MethodKind::Tetra {
                text_row(ui, "Skip", &mut f.skip, &s.add_errors, "skip");
                ui.checkbox(&mut f.center, "Center");
            }
            text_row(ui, "Last (s)", &mut f.last, &s.add_errors, "last");
            triple_row(ui, "Color", &mut f.color, &s.add_errors, "color");
            error_line(ui, &s.add_errors, "material");
            if ui.button("Next").clicked() {
                s.next_page(&check_custom_mesh);
            }
            for field in ["position", "scale"] {
                error_line(ui, &s.add_errors, field);
            }
        }
        AddObjectPage::Transform => {
            triple_row(
                ui,
                "Position",
                &mut s.transform.position,
                &s.add_errors,
                "position",
            );
            triple_row(ui, "Scale", &mut s.transform.scale, &s.add_errors, "scale");
            ui.horizontal(|ui| {
                if ui.button("Draw").clicked()
                    && let Some(cmd) = s.draw(&check_custom_mesh)
                {
                    out.push(cmd);
                }
                if ui.button("Apply").clicked()
                    && let Some(cmd) = s.apply(&check_custom_mesh)
                {
                    out.push(cmd);
                }
                if ui.button("Back").clicked() {
                    s.back();
                }
            });
            // Errors of the first page (e.g. the file vanished) show here too.
            for field in [
                "shape",
                "random_vertices",
                "break_force",
                "skip",
                "last",
                "color",
                "object",
            ] {
                error_line(ui, &s.add_errors, field);
            }
        }
    }
}

fn fire_panel(ui: &mut Ui, s: &mut UiState) {
    egui::CollapsingHeader::new("Fire")
        .default_open(false)
        .show(ui, |ui| {
            let f = &mut s.fire;
            shape_row(
                ui,
                &ShapeKind::projectile_options(),
                &mut f.shape,
                &mut f.custom_path,
            );
            error_line(ui, &s.fire_errors, "shape");
            text_row(ui, "Last (s)", &mut f.last, &s.fire_errors, "last");
            triple_row(ui, "Color", &mut f.color, &s.fire_errors, "color");
            text_row(ui, "Speed", &mut f.speed, &s.fire_errors, "speed");
            text_row(ui, "Size", &mut f.size, &s.fire_errors, "size");
            text_row(ui, "Density", &mut f.density, &s.fire_errors, "density");
            ui.horizontal(|ui| {
                if ui.button("OK").clicked() && s.fire_ok(&load_projectile) {
                    s.status = "projectile set".to_owned();
                }
                let p = &s.projectile;
                ui.small(format!(
                    "{} {:.0} m/s",
                    p.shape.shape().map_or("custom", |s| s.name()),
                    p.speed
                ));
            });
        });
}

fn force_panel(ui: &mut Ui, s: &mut UiState) {
    ui.horizontal(|ui| {
        ui.label(RichText::new("Add Force").strong());
        ui.checkbox(&mut s.force_form.enabled, "isOn");
    });
    if s.force_form.enabled {
        text_row(
            ui,
            "Radius",
            &mut s.force_form.radius,
            &s.force_errors,
            "radius",
        );
        text_row(
            ui,
            "Power",
            &mut s.force_form.power,
            &s.force_errors,
            "power",
        );
    }
    s.update_force();
}

fn scene_file_panel(ui: &mut Ui, s: &mut UiState, out: &mut Vec<SimCommand>) {
    ui.horizontal(|ui| {
        ui.label("Scene");
        ui.add(egui::TextEdit::singleline(&mut s.scene_file.path).desired_width(130.0));
        if ui.button("Save").clicked() {
            match s.scene_file.save() {
                Ok(c) => {
                    s.scene_errors = FieldErrors::default();
                    out.push(c);
                }
                Err(e) => s.scene_errors = e,
            }
        }
        if ui.button("Load").clicked() {
            match s.scene_file.load() {
                Ok(c) => {
                    s.scene_errors = FieldErrors::default();
                    out.push(c);
                }
                Err(e) => s.scene_errors = e,
            }
        }
    });
    error_line(ui, &s.scene_errors, "path");
    ui.horizontal_wrapped(|ui| {
        ui.label("Examples");
        for (name, _) in crate::sim_bridge::EXAMPLE_SCENES {
            if ui.small_button(*name).clicked() {
                out.push(SimCommand::LoadExample((*name).to_owned()));
            }
        }
    });
}
