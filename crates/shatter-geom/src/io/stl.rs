//! STL import (ASCII and binary, through `stl_io`) and export.

use std::io::{Cursor, Write};
use std::path::Path;

use glam::DVec3;

use super::MeshIoError;
use crate::TriMesh;

/// STL flavour to write.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StlFormat {
    /// `solid … endsolid` text.
    Ascii,
    /// 80-byte header, triangle count, 50 bytes per triangle.
    Binary,
}

/// Whether the bytes look like ASCII STL: `solid` first, and `facet` or `endsolid` early
/// (some binary files start their header with `solid` too).
fn looks_ascii(bytes: &[u8]) -> bool {
    let head = &bytes[..bytes.len().min(1024)];
    let text = String::from_utf8_lossy(head);
    let trimmed = text.trim_start();
    trimmed.starts_with("solid") && (text.contains("facet") || text.contains("endsolid"))
}

pub(crate) fn read_stl(bytes: &[u8], path: &Path) -> Result<TriMesh, MeshIoError> {
    let error = |message: String| MeshIoError::Stl {
        path: path.to_path_buf(),
        message,
    };
    if !looks_ascii(bytes) {
        if bytes.len() < 84 {
            return Err(error(format!(
                "truncated binary STL: {} bytes, the header alone needs 84",
                bytes.len()
            )));
        }
        let count = u32::from_le_bytes([bytes[80], bytes[81], bytes[82], bytes[83]]) as u64;
        let needed = 84 + 50 * count;
        if (bytes.len() as u64) < needed {
            return Err(error(format!(
                "truncated binary STL: the header announces {count} triangles ({needed} bytes) \
                 but the file has {} bytes",
                bytes.len()
            )));
        }
    }
    let indexed = stl_io::read_stl(&mut Cursor::new(bytes)).map_err(|e| error(e.to_string()))?;
    let positions: Vec<DVec3> = indexed
        .vertices
        .iter()
        .map(|v| DVec3::new(f64::from(v[0]), f64::from(v[1]), f64::from(v[2])))
        .collect();
    if let Some(v) = positions.iter().position(|p| !p.is_finite()) {
        return Err(error(format!("vertex {v} has a non-finite coordinate")));
    }
    let mut triangles = Vec::with_capacity(indexed.faces.len());
    for (t, face) in indexed.faces.iter().enumerate() {
        let ids = face.vertices.map(u32::try_from);
        match ids {
            [Ok(a), Ok(b), Ok(c)] if [a, b, c].iter().all(|&i| (i as usize) < positions.len()) => {
                triangles.push([a, b, c]);
            }
            _ => return Err(error(format!("triangle {t} has a bad vertex index"))),
        }
    }
    Ok(TriMesh::new(positions, triangles).welded())
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
