//! The OBJ reader, hand-written: `tobj` failed on real files ("line 4841: read error" on
//! bytes that are not UTF-8), fan-triangulates concave polygons, stops at the first
//! unknown statement and cannot report lines, points or missing materials as warnings.
//!
//! Read: `v` (with optional `w` or RGB(A) vertex colours), `vt`, `vn`, `f` / `fo`
//! (with `v`, `v/vt`, `v//vn`, `v/vt/vn` corners, negative relative indices, polygons
//! ear-clipped), `usemtl`, `mtllib`. Counted and skipped with a warning: `l`, `p`,
//! free-form geometry, faces of fewer than three distinct corners, unknown statements.
//! Ignored: groups, objects, smoothing groups and the other display statements.

mod face;
mod finish;

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use glam::DVec3;

use super::lines::{Line, decode, lines};
use super::mtl;
use crate::io::MeshIoError;
use crate::io::context::ReadContext;
use crate::io::image::ImageCache;
use crate::io::polygon::Triangulator;
use crate::model::{Material, Model};

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
