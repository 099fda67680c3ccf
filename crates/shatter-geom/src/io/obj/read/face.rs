//! Faces: their corners' indices resolved (1-based, negative relative, forward
//! references noted for the end), polygons ear-clipped (fanned when that fails) into
//! triangles.

use glam::DVec3;

use super::{Corner, NONE, Reader, UNNAMED};
use crate::io::MeshIoError;
use crate::io::context::MAX_TRIANGLES;

impl<'a, 'c> Reader<'a, 'c> {
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

    pub(super) fn face(&mut self, line: usize, words: &[&str]) -> Result<(), MeshIoError> {
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
}
