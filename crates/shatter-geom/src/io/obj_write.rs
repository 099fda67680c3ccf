//! OBJ (+ MTL) export.

use std::io::Write;
use std::path::Path;

use super::export::{INTERIOR_COLOR, INTERIOR_MATERIAL, SURFACE_COLOR, SURFACE_MATERIAL};
use super::{ExportObject, MeshIoError};

/// Writes the objects as OBJ text: one `o` per object, its surface faces under
/// `usemtl surface` and its interior faces under `usemtl interior`, vertices with full
/// `f64` precision (shortest round-trip form). With `mtllib`, a `mtllib` line names the
/// material file (write it with [`write_mtl`]).
///
/// ```
/// use shatter_geom::{io::{self, ExportObject}, shapes};
/// let cube = shapes::cube();
/// let mut flags = vec![false; 12];
/// flags[0] = true;
/// let mut text = Vec::new();
/// io::write_obj(&mut text, &[ExportObject::new("a cube", &cube).with_interior(&flags)], None)
///     .unwrap();
/// let text = String::from_utf8(text).unwrap();
/// assert!(text.contains("o a_cube\n"));
/// assert!(text.contains("usemtl interior\n"));
/// assert_eq!(text.lines().filter(|l| l.starts_with("f ")).count(), 12);
/// ```
pub fn write_obj<W: Write>(
    mut out: W,
    objects: &[ExportObject<'_>],
    mtllib: Option<&str>,
) -> Result<(), MeshIoError> {
    for o in objects {
        o.validate()?;
    }
    write_unchecked(&mut out, objects, mtllib).map_err(|e| MeshIoError::io("<OBJ output>", e))
}

fn write_unchecked<W: Write + ?Sized>(
    out: &mut W,
    objects: &[ExportObject<'_>],
    mtllib: Option<&str>,
) -> std::io::Result<()> {
    writeln!(out, "# shatter: {} objects", objects.len())?;
    if let Some(lib) = mtllib {
        writeln!(out, "mtllib {lib}")?;
    }
    let mut base = 1usize;
    for (i, o) in objects.iter().enumerate() {
        let name: String = o
            .name
            .chars()
            .map(|c| if c.is_whitespace() { '_' } else { c })
            .collect();
        if name.is_empty() {
            writeln!(out, "o object_{i}")?;
        } else {
            writeln!(out, "o {name}")?;
        }
        for p in &o.mesh.positions {
            writeln!(out, "v {} {} {}", p.x, p.y, p.z)?;
        }
        for (interior, material) in [(false, SURFACE_MATERIAL), (true, INTERIOR_MATERIAL)] {
            let faces: Vec<&[u32; 3]> = o
                .mesh
                .triangles
                .iter()
                .enumerate()
                .filter(|&(t, _)| o.is_interior(t) == interior)
                .map(|(_, f)| f)
                .collect();
            if faces.is_empty() {
                continue;
            }
            writeln!(out, "usemtl {material}")?;
            for f in faces {
                let [a, b, c] = f.map(|i| i as usize + base);
                writeln!(out, "f {a} {b} {c}")?;
            }
        }
        base += o.mesh.positions.len();
    }
    Ok(())
}

/// Writes the MTL file defining the `surface` and `interior` materials.
pub fn write_mtl<W: Write>(mut out: W) -> std::io::Result<()> {
    writeln!(out, "# shatter materials")?;
    for (name, [r, g, b]) in [
        (SURFACE_MATERIAL, SURFACE_COLOR),
        (INTERIOR_MATERIAL, INTERIOR_COLOR),
    ] {
        writeln!(out, "newmtl {name}")?;
        writeln!(out, "Ka 0 0 0")?;
        writeln!(out, "Kd {r} {g} {b}")?;
        writeln!(out, "Ks 0 0 0")?;
        writeln!(out, "d 1")?;
        writeln!(out, "illum 1")?;
    }
    Ok(())
}

/// Writes `path` (OBJ, see [`write_obj`]) and its material file next to it (same name,
/// `.mtl` extension), referenced by a `mtllib` line.
pub fn save_obj(path: impl AsRef<Path>, objects: &[ExportObject<'_>]) -> Result<(), MeshIoError> {
    let path = path.as_ref();
    let mtl_path = path.with_extension("mtl");
    let mtl_name = mtl_path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_else(|| "materials.mtl".into());
    for o in objects {
        o.validate()?;
    }
    let write = |p: &Path, f: &dyn Fn(&mut dyn Write) -> std::io::Result<()>| {
        let file = std::fs::File::create(p).map_err(|e| MeshIoError::io(p, e))?;
        let mut out = std::io::BufWriter::new(file);
        f(&mut out)
            .and_then(|()| out.flush())
            .map_err(|e| MeshIoError::io(p, e))
    };
    write(path, &|out| write_unchecked(out, objects, Some(&mtl_name)))?;
    write(&mtl_path, &|out| write_mtl(out))
}
