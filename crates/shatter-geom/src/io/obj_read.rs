//! OBJ import through `tobj`, with the offending line located for error messages.

use std::io::{BufRead, Read};
use std::path::Path;

use glam::DVec3;

use super::MeshIoError;
use crate::TriMesh;

/// A `BufRead` over bytes that counts the lines handed out, so a parse error can be
/// placed on its line (`tobj` reports errors without one).
struct LineCounter<'a> {
    rest: &'a [u8],
    /// Lines started so far (the current one included).
    lines: usize,
    at_line_start: bool,
}

impl Read for LineCounter<'_> {
    fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
        let n = buf.len().min(self.rest.len());
        buf[..n].copy_from_slice(&self.rest[..n]);
        self.consume(n);
        Ok(n)
    }
}

impl BufRead for LineCounter<'_> {
    fn fill_buf(&mut self) -> std::io::Result<&[u8]> {
        Ok(self.rest)
    }

    fn consume(&mut self, amt: usize) {
        let amt = amt.min(self.rest.len());
        for &b in &self.rest[..amt] {
            if self.at_line_start {
                self.lines += 1;
            }
            self.at_line_start = b == b'\n';
        }
        self.rest = &self.rest[amt..];
    }
}

/// The first face line with a position index out of range: `(line, message)`.
fn find_bad_face(text: &str) -> Option<(usize, String)> {
    let total = text
        .lines()
        .filter(|l| l.trim_start().starts_with("v ") || l.trim_start().starts_with("v\t"))
        .count() as i64;
    let mut seen = 0i64;
    for (n, line) in text.lines().enumerate() {
        let mut words = line.split_whitespace();
        match words.next() {
            Some("v") => seen += 1,
            Some("f") => {
                for w in words {
                    let Some(Ok(i)) = w.split('/').next().map(str::parse::<i64>) else {
                        return Some((n + 1, format!("bad face index {w:?}")));
                    };
                    let resolved = if i < 0 { seen + 1 + i } else { i };
                    if resolved < 1 || resolved > total {
                        return Some((
                            n + 1,
                            format!("face references vertex {i} but the file has {total}"),
                        ));
                    }
                }
            }
            _ => {}
        }
    }
    None
}

pub(crate) fn read_obj(bytes: &[u8], path: &Path) -> Result<TriMesh, MeshIoError> {
    let error = |line: Option<usize>, message: String| MeshIoError::Obj {
        path: path.to_path_buf(),
        line,
        message,
    };
    let mut reader = LineCounter {
        rest: bytes,
        lines: 0,
        at_line_start: true,
    };
    let options = tobj::LoadOptions {
        triangulate: true,
        ignore_points: true,
        ignore_lines: true,
        ..Default::default()
    };
    // Materials are not needed: every `mtllib` is skipped.
    let loaded = tobj::load_obj_buf(&mut reader, &options, |_| {
        Err(tobj::LoadError::OpenFileFailed)
    });
    let models = match loaded {
        Ok((models, _materials)) => models,
        Err(e) => {
            use tobj::LoadError as E;
            let at_counter = error(Some(reader.lines.max(1)), e.to_string());
            return Err(match e {
                // Index errors surface when an object ends; find their line by scanning.
                E::FaceVertexOutOfBounds
                | E::FaceTexCoordOutOfBounds
                | E::FaceNormalOutOfBounds
                | E::FaceColorOutOfBounds
                | E::InvalidPolygon => match find_bad_face(&String::from_utf8_lossy(bytes)) {
                    Some((line, message)) => error(Some(line), message),
                    None => error(None, e.to_string()),
                },
                _ => at_counter,
            });
        }
    };
    let mut mesh = TriMesh::default();
    for model in &models {
        let m = &model.mesh;
        let offset = mesh.positions.len();
        let count = m.positions.len() / 3;
        mesh.positions.extend(
            m.positions
                .chunks_exact(3)
                .map(|c| DVec3::new(c[0], c[1], c[2])), // tobj with `use_f64`,
        );
        for tri in m.indices.chunks_exact(3) {
            if let Some(&bad) = tri.iter().find(|&&i| i as usize >= count) {
                return Err(error(
                    None,
                    format!("object {:?} references vertex {bad} of {count}", model.name),
                ));
            }
            let t = [tri[0], tri[1], tri[2]].map(|i| i as usize + offset);
            let t = t.map(u32::try_from);
            match t {
                [Ok(a), Ok(b), Ok(c)] => mesh.triangles.push([a, b, c]),
                _ => return Err(error(None, "more than 2^32 vertices".into())),
            }
        }
    }
    if let Some(v) = mesh.positions.iter().position(|p| !p.is_finite()) {
        return Err(error(
            None,
            format!("vertex {} has a non-finite coordinate", v + 1),
        ));
    }
    Ok(mesh)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parse_error_names_its_line() {
        let text = b"v 0 0 0\nv 1 0 0\nv zero 1 0\nf 1 2 3\n";
        let err = read_obj(text, Path::new("x.obj")).expect_err("bad position");
        assert!(err.to_string().starts_with("x.obj: line 3:"), "{err}");
    }

    #[test]
    fn negative_indices_resolve_relative_to_the_line() {
        assert_eq!(find_bad_face("v 0 0 0\nf -1 -1 -1\nv 1 1 1\n"), None);
        assert_eq!(find_bad_face("v 0 0 0\nf -2 -1 -1\n").map(|e| e.0), Some(2));
    }
}
