//! STL import (ASCII and binary, hand-written: `stl_io` failed with "failed to fill whole
//! buffer" on a binary file whose triangle count disagrees with its size, which should
//! load what it holds) and export (binary through `stl_io`).

use std::io::Write;
use std::path::Path;

use glam::DVec3;

use super::context::{MAX_TRIANGLES, ReadContext};
use super::{MeshIoError, WarningKind};
use crate::TriMesh;
use crate::model::Model;

/// STL flavour to write.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StlFormat {
    /// `solid … endsolid` text.
    Ascii,
    /// 80-byte header, triangle count, 50 bytes per triangle.
    Binary,
}

/// Whether the bytes are ASCII STL: `solid` first, `facet` or `endsolid` early and no
/// NUL byte there. A binary file whose size matches its triangle count is binary even
/// when its header starts with `solid` (3ds Max writes such headers).
fn looks_ascii(bytes: &[u8]) -> bool {
    if bytes.len() >= 84 {
        let count = u32::from_le_bytes([bytes[80], bytes[81], bytes[82], bytes[83]]) as u64;
        if 84 + 50 * count == bytes.len() as u64 {
            return false;
        }
    }
    let head = &bytes[..bytes.len().min(1024)];
    if head.contains(&0) {
        return false;
    }
    let text = String::from_utf8_lossy(head);
    text.trim_start().starts_with("solid") && (text.contains("facet") || text.contains("endsolid"))
}

pub(crate) fn read_stl(bytes: &[u8], cx: &mut ReadContext<'_>) -> Result<Model, MeshIoError> {
    let soup = if looks_ascii(bytes) {
        read_ascii(bytes, cx)?
    } else {
        read_binary(bytes, cx)?
    };
    let positions: Vec<DVec3> = soup.iter().flatten().copied().collect();
    let triangles = (0..soup.len() as u32)
        .map(|t| [3 * t, 3 * t + 1, 3 * t + 2])
        .collect();
    Ok(Model::from_mesh(
        TriMesh::new(positions, triangles).welded(),
    ))
}

fn read_binary(bytes: &[u8], cx: &mut ReadContext<'_>) -> Result<Vec<[DVec3; 3]>, MeshIoError> {
    if bytes.len() < 84 {
        return Err(MeshIoError::Stl {
            path: cx.path.to_path_buf(),
            message: format!(
                "truncated binary STL: {} bytes, the header alone needs 84",
                bytes.len()
            ),
        });
    }
    let announced = u32::from_le_bytes([bytes[80], bytes[81], bytes[82], bytes[83]]) as u64;
    let present = (bytes.len() as u64 - 84) / 50;
    if present != announced {
        cx.warn(
            WarningKind::Truncated,
            1,
            format!(
                "binary STL header announces {announced} triangles ({} bytes) but the file has {} bytes: read the {present} triangles it holds",
                84 + 50 * announced,
                bytes.len()
            ),
        );
    }
    if present as usize > MAX_TRIANGLES {
        return Err(MeshIoError::TooLarge {
            path: cx.path.to_path_buf(),
            message: format!("{present} triangles; shatter takes at most {MAX_TRIANGLES}"),
        });
    }
    let float = |b: &[u8]| f64::from(f32::from_le_bytes([b[0], b[1], b[2], b[3]]));
    let point = |b: &[u8]| DVec3::new(float(&b[0..4]), float(&b[4..8]), float(&b[8..12]));
    Ok(bytes[84..]
        .chunks_exact(50)
        .map(|r| [point(&r[12..24]), point(&r[24..36]), point(&r[36..48])])
        .collect())
}

fn read_ascii(bytes: &[u8], cx: &mut ReadContext<'_>) -> Result<Vec<[DVec3; 3]>, MeshIoError> {
    let text = String::from_utf8_lossy(bytes);
    let error = |line: usize, message: String| MeshIoError::Stl {
        path: cx.path.to_path_buf(),
        message: format!("line {line}: {message}"),
    };
    let mut soup = Vec::new();
    let mut facet: Vec<DVec3> = Vec::new();
    let mut short = (0usize, 0usize);
    let mut polygons = 0usize;
    let mut close = |facet: &mut Vec<DVec3>, line: usize, soup: &mut Vec<[DVec3; 3]>| {
        match facet.len() {
            0 => {}
            1 | 2 => {
                if short.0 == 0 {
                    short.1 = line;
                }
                short.0 += 1;
            }
            n => {
                if n > 3 {
                    polygons += 1;
                }
                for k in 1..n - 1 {
                    soup.push([facet[0], facet[k], facet[k + 1]]);
                }
            }
        }
        facet.clear();
    };
    for (n, line) in text.lines().enumerate() {
        let mut words = line.split_whitespace();
        match words.next() {
            Some("vertex") => {
                let mut p = [0.0; 3];
                for c in &mut p {
                    let w = words
                        .next()
                        .ok_or_else(|| error(n + 1, "a vertex needs three coordinates".into()))?;
                    *c = match w.parse::<f64>() {
                        Ok(v) if v.is_finite() => v,
                        _ => return Err(error(n + 1, format!("'{w}' is not a finite number"))),
                    };
                }
                facet.push(DVec3::from(p));
            }
            Some("endloop") | Some("endfacet") | Some("facet") | Some("endsolid") => {
                close(&mut facet, n + 1, &mut soup);
            }
            _ => {}
        }
        if soup.len() > MAX_TRIANGLES {
            return Err(MeshIoError::TooLarge {
                path: cx.path.to_path_buf(),
                message: format!(
                    "more than {MAX_TRIANGLES} triangles; shatter takes at most that many"
                ),
            });
        }
    }
    close(&mut facet, text.lines().count(), &mut soup);
    if short.0 > 0 {
        cx.warn(
            WarningKind::SkippedElements,
            short.0,
            format!(
                "skipped {} facets of fewer than three vertices (first ending at line {})",
                short.0, short.1
            ),
        );
    }
    if polygons > 0 {
        cx.warn(
            WarningKind::Unsupported,
            polygons,
            format!("{polygons} facets have more than three vertices: fan-triangulated"),
        );
    }
    Ok(soup)
}

/// Writes `mesh` as STL (single precision, as the format stores). Facet normals are the
/// triangles' right-hand normals.
///
/// ```
/// use shatter_geom::{io, shapes};
/// let mut ascii = Vec::new();
/// io::write_stl(&mut ascii, &shapes::cube(), io::StlFormat::Ascii).unwrap();
/// assert!(ascii.starts_with(b"solid"));
/// let mut binary = Vec::new();
/// io::write_stl(&mut binary, &shapes::cube(), io::StlFormat::Binary).unwrap();
/// assert_eq!(binary.len(), 84 + 50 * 12);
/// ```
pub fn write_stl<W: Write>(mut out: W, mesh: &TriMesh, format: StlFormat) -> std::io::Result<()> {
    let facets = (0..mesh.triangles.len()).map(|t| {
        let n = mesh.triangle_normal(t).as_vec3();
        let [a, b, c] = mesh.triangle(t).map(|p| p.as_vec3());
        (n, [a, b, c])
    });
    match format {
        StlFormat::Binary => {
            let triangles: Vec<stl_io::Triangle> = facets
                .map(|(n, v)| stl_io::Triangle {
                    normal: stl_io::Vector::new(n.to_array()),
                    vertices: v.map(|p| stl_io::Vector::new(p.to_array())),
                })
                .collect();
            stl_io::write_stl(&mut out, triangles.iter())
        }
        StlFormat::Ascii => {
            writeln!(out, "solid shatter")?;
            for (n, v) in facets {
                writeln!(out, "  facet normal {} {} {}", n.x, n.y, n.z)?;
                writeln!(out, "    outer loop")?;
                for p in v {
                    writeln!(out, "      vertex {} {} {}", p.x, p.y, p.z)?;
                }
                writeln!(out, "    endloop")?;
                writeln!(out, "  endfacet")?;
            }
            writeln!(out, "endsolid shatter")
        }
    }
}

/// Writes `mesh` to an STL file (see [`write_stl`]).
pub fn save_stl(
    path: impl AsRef<Path>,
    mesh: &TriMesh,
    format: StlFormat,
) -> Result<(), MeshIoError> {
    let path = path.as_ref();
    let file = std::fs::File::create(path).map_err(|e| MeshIoError::io(path, e))?;
    let mut out = std::io::BufWriter::new(file);
    write_stl(&mut out, mesh, format)
        .and_then(|()| out.flush())
        .map_err(|e| MeshIoError::io(path, e))
}
