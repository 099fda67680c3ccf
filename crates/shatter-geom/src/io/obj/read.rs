//! The OBJ reader, hand-written: `tobj` failed on real files ("line 4841: read error" on
//! bytes that are not UTF-8), fan-triangulates concave polygons, stops at the first
//! unknown statement and cannot report lines, points or missing materials as warnings.
//!
//! Read: `v` (with optional `w` or RGB(A) vertex colours), `vt`, `vn`, `f` / `fo`
//! (with `v`, `v/vt`, `v//vn`, `v/vt/vn` corners, negative relative indices, polygons
//! ear-clipped), `usemtl`, `mtllib`. Counted and skipped with a warning: `l`, `p`,
//! free-form geometry, faces of fewer than three distinct corners, unknown statements.
//! Ignored: groups, objects, smoothing groups and the other display statements.

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use glam::DVec3;

use super::lines::{Line, decode, lines};
use super::mtl;
use crate::TriMesh;
use crate::io::image::ImageCache;
use crate::io::load::{MAX_TRIANGLES, ReadContext};
use crate::io::polygon::Triangulator;
use crate::io::{MeshIoError, WarningKind};
use crate::model::{Corners, Material, Model};

/// No texture coordinate or normal at a corner.
const NONE: u32 = u32::MAX;

/// `current_material` before any `usemtl` and before the first face.
const UNNAMED: u32 = u32::MAX;

/// A face corner: indices (0-based) of its position, texture coordinate and normal.
#[derive(Clone, Copy)]
struct Corner {
    v: u32,
    vt: u32,
    vn: u32,
}

/// Statements counted and skipped, by the warning they give.
#[derive(Default)]
struct Skipped {
    count: usize,
    first_line: usize,
}

impl Skipped {
    fn add(&mut self, line: usize) {
        if self.count == 0 {
            self.first_line = line;
        }
        self.count += 1;
    }
}

/// Statements that only matter to display or to free-form geometry, ignored silently.
const IGNORED: [&str; 14] = [
    "o",
    "g",
    "s",
    "mg",
    "lod",
    "usemap",
    "maplib",
    "shadow_obj",
    "trace_obj",
    "bevel",
    "c_interp",
    "d_interp",
    "ctech",
    "stech",
];

/// Free-form geometry statements (curves and surfaces), skipped with a warning.
const FREE_FORM: [&str; 14] = [
    "vp", "cstype", "deg", "bmat", "step", "curv", "curv2", "surf", "parm", "trim", "hole", "scrv",
    "sp", "end",
];

struct Reader<'a, 'c> {
    cx: &'c mut ReadContext<'a>,
    positions: Vec<DVec3>,
    /// Vertex colours as read (RGBA), per position; `None` for a vertex without.
    colors: Vec<Option<[f32; 4]>>,
    uvs: Vec<[f32; 2]>,
    normals: Vec<[f32; 3]>,
    triangles: Vec<[Corner; 3]>,
    /// Per triangle: index into `material_names`.
    material: Vec<u32>,
    material_names: Vec<String>,
    material_ids: HashMap<String, u32>,
    current_material: u32,
    libraries: Vec<Material>,
    library_paths: Vec<PathBuf>,
    images: ImageCache,
    /// Positive indices beyond what was read so far (forward references), checked at the
    /// end: (line, what, index, count needed).
    forward: Vec<(usize, &'static str, i64)>,
    lines_skipped: Skipped,
    points_skipped: Skipped,
    free_form: Skipped,
    degenerate: Skipped,
    unknown: Skipped,
    unknown_first: String,
    triangulator: Triangulator,
    corner_buffer: Vec<Corner>,
    fan_fallback: Skipped,
}

impl<'a, 'c> Reader<'a, 'c> {
    fn error(&self, line: usize, message: String) -> MeshIoError {
        MeshIoError::Obj {
            path: self.cx.path.to_path_buf(),
            line: Some(line),
            message,
        }
    }

    fn number(&self, line: usize, word: &str) -> Result<f64, MeshIoError> {
        match word.parse::<f64>() {
            Ok(v) if v.is_finite() => Ok(v),
            Ok(_) => Err(self.error(
                line,
                format!("'{word}' is not a finite number (NaN and infinities are refused)"),
            )),
            Err(_) => Err(self.error(line, format!("'{word}' is not a number"))),
        }
    }

    fn numbers<const N: usize>(
        &self,
        line: usize,
        keyword: &str,
        words: &[&str],
        min: usize,
    ) -> Result<([f64; N], usize), MeshIoError> {
        if words.len() < min {
            return Err(self.error(
                line,
                format!(
                    "'{keyword}' needs at least {min} numbers, found {}",
                    words.len()
                ),
            ));
        }
        let mut out = [0.0; N];
        for (o, w) in out.iter_mut().zip(words) {
            *o = self.number(line, w)?;
        }
        Ok((out, words.len().min(N)))
    }

    /// A 0-based index from a file's 1-based (or negative, relative) index `word`, with
    /// `count` elements of its kind read so far.
    fn index(
        &mut self,
        line: usize,
        word: &str,
        count: usize,
        what: &'static str,
    ) -> Result<u32, MeshIoError> {
        let i: i64 = word
            .parse()
            .map_err(|_| self.error(line, format!("bad face index {word:?}")))?;
        let count = count as i64;
        let resolved = match i {
            0 => {
                return Err(self.error(line, format!("face index 0 ({what}s are numbered from 1)")));
            }
            i if i < 0 => count + i,
            i => i - 1,
        };
        if resolved < 0 {
            return Err(self.error(
                line,
                format!("face references {what} {i} but only {count} precede it"),
            ));
        }
        if resolved >= count {
            // Defined further down, perhaps: checked at the end.
            self.forward.push((line, what, i));
        }
        u32::try_from(resolved).map_err(|_| self.error(line, format!("{what} index {i} too large")))
    }

    fn face(&mut self, line: usize, words: &[&str]) -> Result<(), MeshIoError> {
        let mut corners = std::mem::take(&mut self.corner_buffer);
        corners.clear();
        for w in words {
            let mut parts = w.split('/');
            let v = parts.next().unwrap_or("");
            let vt = parts.next().unwrap_or("");
            let vn = parts.next().unwrap_or("");
            let v = self.index(line, v, self.positions.len(), "vertex")?;
            let vt = if vt.is_empty() {
                NONE
            } else {
                self.index(line, vt, self.uvs.len(), "texture coordinate")?
            };
            let vn = if vn.is_empty() {
                NONE
            } else {
                self.index(line, vn, self.normals.len(), "normal")?
            };
            let c = Corner { v, vt, vn };
            // A corner repeating the previous one adds nothing.
            if corners.last().is_none_or(|p: &Corner| p.v != v) {
                corners.push(c);
            }
        }
        while corners.len() > 1 && corners.first().map(|c| c.v) == corners.last().map(|c| c.v) {
            corners.pop();
        }
        if corners.len() < 3 {
            self.degenerate.add(line);
        } else if corners.len() == 3 {
            self.push_triangle([corners[0], corners[1], corners[2]], line)?;
        } else {
            // Forward references have no position yet: fan those polygons.
            let points: Option<Vec<DVec3>> = corners
                .iter()
                .map(|c| self.positions.get(c.v as usize).copied())
                .collect();
            let tris = points.and_then(|p| self.triangulator.triangulate(&p));
            match tris {
                Some(tris) => {
                    for t in tris {
                        self.push_triangle(t.map(|k| corners[k]), line)?;
                    }
                }
                None => {
                    self.fan_fallback.add(line);
                    for k in 1..corners.len() - 1 {
                        self.push_triangle([corners[0], corners[k], corners[k + 1]], line)?;
                    }
                }
            }
        }
        self.corner_buffer = corners;
        Ok(())
    }

    fn push_triangle(&mut self, t: [Corner; 3], line: usize) -> Result<(), MeshIoError> {
        if self.triangles.len() >= MAX_TRIANGLES {
            return Err(MeshIoError::TooLarge {
                path: self.cx.path.to_path_buf(),
                message: format!(
                    "line {line}: more than {MAX_TRIANGLES} triangles; shatter takes at most that many"
                ),
            });
        }
        if self.current_material == UNNAMED {
            // Faces before any `usemtl`: the unnamed material (named "default").
            self.use_material("");
        }
        self.triangles.push(t);
        self.material.push(self.current_material);
        Ok(())
    }

    fn use_material(&mut self, name: &str) {
        let next = self.material_names.len() as u32;
        let id = *self.material_ids.entry(name.to_string()).or_insert(next);
        if id == next {
            self.material_names.push(name.to_string());
        }
        self.current_material = id;
    }

    fn material_library(&mut self, rest: &str) {
        // A name may hold spaces: the whole rest first, then each word.
        let whole = self.cx.resolve(Path::new(&rest.replace('\\', "/")));
        let candidates: Vec<PathBuf> =
            if rest.split_whitespace().count() > 1 && self.cx.read(&whole).is_err() {
                rest.split_whitespace()
                    .map(|w| self.cx.resolve(Path::new(&w.replace('\\', "/"))))
                    .collect()
            } else {
                vec![whole]
            };
        for path in candidates {
            if self.library_paths.contains(&path) {
                continue;
            }
            self.library_paths.push(path.clone());
            if let Some(materials) = mtl::read_library(self.cx, &path, &mut self.images) {
                self.libraries.extend(materials);
            }
        }
    }

    fn statement(&mut self, line: &Line<'_>) -> Result<(), MeshIoError> {
        let n = line.number;
        let (keyword, rest) = match line.text.split_once(char::is_whitespace) {
            Some((k, r)) => (k, r.trim()),
            None => (&*line.text, ""),
        };
        let words: Vec<&str> = rest.split_whitespace().collect();
        match keyword {
            "v" => {
                let (c, len) = self.numbers::<7>(n, "v", &words, 3)?;
                self.positions.push(DVec3::new(c[0], c[1], c[2]));
                let color = match len {
                    6 => Some([c[3] as f32, c[4] as f32, c[5] as f32, 1.0]),
                    7 => Some([c[3] as f32, c[4] as f32, c[5] as f32, c[6] as f32]),
                    _ => None,
                };
                self.colors.push(color);
            }
            "vt" => {
                let (c, _) = self.numbers::<3>(n, "vt", &words, 1)?;
                // OBJ's v points up; the model's (glTF's) points down.
                self.uvs.push([c[0] as f32, (1.0 - c[1]) as f32]);
            }
            "vn" => {
                let (c, _) = self.numbers::<3>(n, "vn", &words, 3)?;
                let v = DVec3::from(c);
                // Unit already (within f32 rounding): kept as written, so a written
                // normal reads back bit for bit.
                let v = if (v.length_squared() - 1.0).abs() > 1e-6 && v.length_squared() > 0.0 {
                    v.normalize()
                } else {
                    v
                };
                self.normals.push(v.as_vec3().to_array());
            }
            "f" | "fo" => self.face(n, &words)?,
            "l" => self.lines_skipped.add(n),
            "p" => self.points_skipped.add(n),
            "usemtl" => self.use_material(rest),
            "mtllib" => self.material_library(rest),
            k if IGNORED.contains(&k) => {}
            k if FREE_FORM.contains(&k) => self.free_form.add(n),
            k => {
                if self.unknown.count == 0 {
                    self.unknown_first = k.chars().take(40).collect();
                }
                self.unknown.add(n);
            }
        }
        Ok(())
    }

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

    fn finish(mut self) -> Result<Model, MeshIoError> {
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

pub(crate) fn read_obj(bytes: &[u8], cx: &mut ReadContext<'_>) -> Result<Model, MeshIoError> {
    let text = decode(bytes);
    let mut reader = Reader {
        cx,
        positions: Vec::new(),
        colors: Vec::new(),
        uvs: Vec::new(),
        normals: Vec::new(),
        triangles: Vec::new(),
        material: Vec::new(),
        material_names: Vec::new(),
        material_ids: HashMap::new(),
        current_material: UNNAMED,
        libraries: Vec::new(),
        library_paths: Vec::new(),
        images: ImageCache::default(),
        forward: Vec::new(),
        lines_skipped: Skipped::default(),
        points_skipped: Skipped::default(),
        free_form: Skipped::default(),
        degenerate: Skipped::default(),
        unknown: Skipped::default(),
        unknown_first: String::new(),
        triangulator: Triangulator::new(),
        corner_buffer: Vec::new(),
        fan_fallback: Skipped::default(),
    };
    for line in lines(&text) {
        reader.statement(&line)?;
    }
    reader.finish()
}
