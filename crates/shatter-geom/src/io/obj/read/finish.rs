//! The end of the file: forward references checked, the skipped statements reported,
//! and the model assembled with its corner attributes and materials.

use glam::DVec3;

use super::{Corner, NONE, Reader};
use crate::TriMesh;
use crate::io::{MeshIoError, WarningKind};
use crate::model::{Corners, Material, Model};

impl<'a, 'c> Reader<'a, 'c> {
    fn warnings(&mut self) {
        let plural = |n: usize| if n == 1 { "" } else { "s" };
        let skipped = [
            (&self.lines_skipped, "line element"),
            (&self.points_skipped, "point element"),
            (&self.free_form, "free-form (curve or surface) statement"),
            (
                &self.degenerate,
                "face with fewer than three distinct corners",
            ),
        ];
        let mut out = Vec::new();
        for (s, what) in skipped {
            if s.count > 0 {
                let what = if s.count == 1 {
                    what.to_string()
                } else {
                    what.replacen("face", "faces", 1)
                        .replacen("element", "elements", 1)
                        .replacen("statement", "statements", 1)
                };
                out.push((
                    WarningKind::SkippedElements,
                    s.count,
                    format!(
                        "skipped {} {what} (first at line {})",
                        s.count, s.first_line
                    ),
                ));
            }
        }
        if self.fan_fallback.count > 0 {
            let s = &self.fan_fallback;
            out.push((
                WarningKind::Unsupported,
                s.count,
                format!(
                    "{} polygon{} could not be ear-clipped (no area, or corners defined later) and {} fan-triangulated (first at line {})",
                    s.count,
                    plural(s.count),
                    if s.count == 1 { "was" } else { "were" },
                    s.first_line
                ),
            ));
        }
        if self.unknown.count > 0 {
            out.push((
                WarningKind::Unsupported,
                self.unknown.count,
                format!(
                    "skipped {} unknown statement{} (first at line {}: '{}')",
                    self.unknown.count,
                    plural(self.unknown.count),
                    self.unknown.first_line,
                    self.unknown_first
                ),
            ));
        }
        for (kind, count, message) in out {
            self.cx.warn(kind, count, message);
        }
    }

    pub(super) fn finish(mut self) -> Result<Model, MeshIoError> {
        for &(line, what, i) in &self.forward {
            let count = match what {
                "vertex" => self.positions.len(),
                "normal" => self.normals.len(),
                _ => self.uvs.len(),
            };
            if i > count as i64 {
                let message = format!("face references {what} {i} but the file has {count}");
                return Err(self.error(line, message));
            }
        }
        self.warnings();
        let triangles: Vec<[u32; 3]> = self.triangles.iter().map(|t| t.map(|c| c.v)).collect();
        let mesh = TriMesh::new(std::mem::take(&mut self.positions), triangles);
        let mut corners = Corners::default();

        let any = |f: fn(&Corner) -> u32| self.triangles.iter().flatten().any(|c| f(c) != NONE);
        if any(|c| c.vt) {
            let mut missing = 0usize;
            let uv = self
                .triangles
                .iter()
                .map(|t| {
                    t.map(|c| match self.uvs.get(c.vt as usize) {
                        Some(&uv) => uv,
                        None => {
                            missing += 1;
                            [0.0, 0.0]
                        }
                    })
                })
                .collect();
            corners.uv = Some(uv);
            if missing > 0 {
                self.cx.warn(
                    WarningKind::MissingAttribute,
                    missing,
                    format!("{missing} face corners have no texture coordinate (given 0, 0)"),
                );
            }
        }
        if any(|c| c.vn) {
            let mut missing = 0usize;
            let normal = self
                .triangles
                .iter()
                .enumerate()
                .map(|(t, tri)| {
                    let flat = mesh.triangle_normal(t).normalize_or(DVec3::Y).as_vec3();
                    tri.map(|c| match self.normals.get(c.vn as usize) {
                        Some(&n) if n != [0.0; 3] => n,
                        _ => {
                            missing += 1;
                            flat.to_array()
                        }
                    })
                })
                .collect();
            corners.normal = Some(normal);
            if missing > 0 {
                self.cx.warn(
                    WarningKind::MissingAttribute,
                    missing,
                    format!("{missing} face corners have no usable normal (given the face's)"),
                );
            }
        }
        if self.colors.iter().any(Option::is_some) {
            let peak = self
                .colors
                .iter()
                .flatten()
                .flat_map(|c| c[..3].iter().copied())
                .fold(0.0f32, f32::max);
            // Some exporters write 0..255.
            let scale = if peak > 1.0 {
                self.cx.warn(
                    WarningKind::Unsupported,
                    1,
                    format!("vertex colours go up to {peak}: read as 0..255"),
                );
                1.0 / 255.0
            } else {
                1.0
            };
            let color = self
                .triangles
                .iter()
                .map(|t| {
                    t.map(|c| match self.colors.get(c.v as usize).copied().flatten() {
                        Some([r, g, b, a]) => [r * scale, g * scale, b * scale, a.clamp(0.0, 1.0)],
                        None => [1.0; 4],
                    })
                })
                .collect();
            corners.color = Some(color);
        }

        // Materials: the ones faces use, in order of first use.
        let mut unknown = Vec::new();
        let materials: Vec<Material> = if self.material_names.is_empty() {
            vec![Material::named("default")]
        } else {
            self.material_names
                .iter()
                .map(
                    |name| match self.libraries.iter().find(|m| &m.name == name) {
                        Some(m) => m.clone(),
                        None => {
                            unknown.push(name.clone());
                            Material::named(if name.is_empty() { "default" } else { name })
                        }
                    },
                )
                .collect()
        };
        let unknown: Vec<String> = unknown.into_iter().filter(|n| !n.is_empty()).collect();
        if !unknown.is_empty() {
            let shown: Vec<String> = unknown.iter().take(5).map(|n| format!("'{n}'")).collect();
            self.cx.warn(
                WarningKind::UnknownMaterial,
                unknown.len(),
                format!(
                    "{} material{} used but not defined in any material library, given a default: {}{}",
                    unknown.len(),
                    if unknown.len() == 1 { "" } else { "s" },
                    shown.join(", "),
                    if unknown.len() > 5 { ", ..." } else { "" }
                ),
            );
        }
        Ok(Model {
            mesh,
            corners,
            material: self.material,
            materials,
        })
    }
}
