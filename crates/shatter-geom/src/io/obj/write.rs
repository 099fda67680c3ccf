//! OBJ (+ MTL) export, with texture coordinates, normals, vertex colours and textures
//! copied next to the output.

use std::collections::HashMap;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use crate::io::export::ExportMaterials;
use crate::io::{ExportObject, MeshIoError};
use crate::model::{Image, Material};

/// A name without whitespace (OBJ and MTL names end at the first blank).
fn clean(name: &str) -> String {
    name.chars()
        .map(|c| if c.is_whitespace() { '_' } else { c })
        .collect()
}

/// Material names made unique and blank-free, in list order.
fn material_names(materials: &[Material]) -> Vec<String> {
    let mut seen = HashMap::new();
    materials
        .iter()
        .enumerate()
        .map(|(i, m)| {
            let base = if m.name.trim().is_empty() {
                format!("material_{i}")
            } else {
                clean(&m.name)
            };
            let n = seen.entry(base.clone()).or_insert(0usize);
            *n += 1;
            if *n == 1 { base } else { format!("{base}_{n}") }
        })
        .collect()
}

/// Writes the objects as OBJ text: one `o` per object, vertices with full `f64` precision
/// (shortest round-trip form), `vt` / `vn` when the objects carry UVs / normals (UVs
/// turned to OBJ's `v` up), vertex colours on `v` lines when they carry colours, and the
/// faces under `usemtl` of their material: `surface` and `interior` here (see
/// [`write_obj_with_materials`] for other lists). With `mtllib`, a `mtllib` line names the
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
    out: W,
    objects: &[ExportObject<'_>],
    mtllib: Option<&str>,
) -> Result<(), MeshIoError> {
    write_obj_with_materials(out, objects, None, mtllib)
}

/// [`write_obj`] with the material list `materials` (indexed by the objects' triangles;
/// `None`: `surface` / `interior`), an `interior` material added when the list has none.
pub fn write_obj_with_materials<W: Write>(
    mut out: W,
    objects: &[ExportObject<'_>],
    materials: Option<&[Material]>,
    mtllib: Option<&str>,
) -> Result<(), MeshIoError> {
    let materials = ExportMaterials::new(materials);
    materials.validate(objects)?;
    write_unchecked(&mut out, objects, &materials, mtllib)
        .map_err(|e| MeshIoError::io("<OBJ output>", e))
}

fn write_unchecked<W: Write + ?Sized>(
    out: &mut W,
    objects: &[ExportObject<'_>],
    materials: &ExportMaterials,
    mtllib: Option<&str>,
) -> std::io::Result<()> {
    let names = material_names(&materials.list);
    writeln!(out, "# shatter: {} objects", objects.len())?;
    if let Some(lib) = mtllib {
        writeln!(out, "mtllib {lib}")?;
    }
    let (mut v_base, mut vt_base, mut vn_base) = (1usize, 1usize, 1usize);
    for (i, o) in objects.iter().enumerate() {
        let name = clean(o.name);
        if name.is_empty() {
            writeln!(out, "o object_{i}")?;
        } else {
            writeln!(out, "o {name}")?;
        }
        let corners = o.corners;
        // A colour per vertex: the colour of its first corner.
        let mut vertex_color: Vec<Option<[f32; 4]>> = vec![None; o.mesh.positions.len()];
        if let Some(colors) = corners.and_then(|c| c.color.as_ref()) {
            for (t, tri) in o.mesh.triangles.iter().enumerate() {
                for k in 0..3 {
                    vertex_color[tri[k] as usize].get_or_insert(colors[t][k]);
                }
            }
        }
        let has_color = vertex_color.iter().any(Option::is_some);
        for (v, p) in o.mesh.positions.iter().enumerate() {
            match vertex_color[v].filter(|_| has_color) {
                Some([r, g, b, _]) => writeln!(out, "v {} {} {} {r} {g} {b}", p.x, p.y, p.z)?,
                None if has_color => writeln!(out, "v {} {} {} 1 1 1", p.x, p.y, p.z)?,
                None => writeln!(out, "v {} {} {}", p.x, p.y, p.z)?,
            }
        }
        // Distinct UVs and normals, each written once.
        let mut uv_index: HashMap<[u32; 2], usize> = HashMap::new();
        let mut uv_of = Vec::new();
        if let Some(uvs) = corners.and_then(|c| c.uv.as_ref()) {
            for &[u, v] in uvs.iter().flatten() {
                let next = uv_index.len();
                if *uv_index.entry([u.to_bits(), v.to_bits()]).or_insert(next) == next {
                    // In f64, as the reader flips it back: exact both ways.
                    uv_of.push([f64::from(u), 1.0 - f64::from(v)]);
                }
            }
            for [u, v] in &uv_of {
                writeln!(out, "vt {u} {v}")?;
            }
        }
        let mut vn_index: HashMap<[u32; 3], usize> = HashMap::new();
        let mut vn_of = Vec::new();
        if let Some(normals) = corners.and_then(|c| c.normal.as_ref()) {
            for tri in normals {
                for n in tri {
                    let key = n.map(f32::to_bits);
                    let next = vn_index.len();
                    if *vn_index.entry(key).or_insert(next) == next {
                        vn_of.push(*n);
                    }
                }
            }
            for [x, y, z] in &vn_of {
                writeln!(out, "vn {x} {y} {z}")?;
            }
        }
        let mut by_material: Vec<(u32, Vec<usize>)> = Vec::new();
        for t in 0..o.mesh.triangles.len() {
            let m = materials.of(o, t);
            match by_material.iter_mut().find(|(k, _)| *k == m) {
                Some((_, ts)) => ts.push(t),
                None => by_material.push((m, vec![t])),
            }
        }
        by_material.sort_by_key(|(m, _)| *m);
        let uv = corners.and_then(|c| c.uv.as_ref());
        let normal = corners.and_then(|c| c.normal.as_ref());
        for (m, tris) in by_material {
            writeln!(out, "usemtl {}", names[m as usize])?;
            for t in tris {
                let tri = o.mesh.triangles[t];
                write!(out, "f")?;
                for k in 0..3 {
                    let v = tri[k] as usize + v_base;
                    let vt = uv.map(|uv| {
                        let [a, b] = uv[t][k];
                        uv_index[&[a.to_bits(), b.to_bits()]] + vt_base
                    });
                    let vn = normal.map(|n| vn_index[&n[t][k].map(f32::to_bits)] + vn_base);
                    match (vt, vn) {
                        (None, None) => write!(out, " {v}")?,
                        (Some(vt), None) => write!(out, " {v}/{vt}")?,
                        (None, Some(vn)) => write!(out, " {v}//{vn}")?,
                        (Some(vt), Some(vn)) => write!(out, " {v}/{vt}/{vn}")?,
                    }
                }
                writeln!(out)?;
            }
        }
        v_base += o.mesh.positions.len();
        vt_base += uv_of.len();
        vn_base += vn_of.len();
    }
    Ok(())
}

/// Writes the MTL file defining the `surface` and `interior` materials.
pub fn write_mtl<W: Write>(out: W) -> std::io::Result<()> {
    let materials = ExportMaterials::new(None);
    write_materials(out, &materials.list, &[])
}

/// Writes `materials` as MTL; `textures[i]` is the file name material `i`'s texture
/// was copied to (if any).
fn write_materials<W: Write>(
    mut out: W,
    materials: &[Material],
    textures: &[Option<String>],
) -> std::io::Result<()> {
    writeln!(out, "# shatter materials")?;
    for (i, (m, name)) in materials.iter().zip(material_names(materials)).enumerate() {
        let [r, g, b, a] = m.base_color;
        writeln!(out, "newmtl {name}")?;
        writeln!(out, "Ka 0 0 0")?;
        writeln!(out, "Kd {r} {g} {b}")?;
        writeln!(out, "Ks 0 0 0")?;
        writeln!(out, "d {a}")?;
        writeln!(out, "Pm {}", m.metallic)?;
        writeln!(out, "Pr {}", m.roughness)?;
        writeln!(out, "illum 1")?;
        if let Some(Some(file)) = textures.get(i) {
            writeln!(out, "map_Kd {file}")?;
        }
    }
    Ok(())
}

/// Writes `path` (OBJ, see [`write_obj`]) and its material file next to it (same name,
/// `.mtl` extension), referenced by a `mtllib` line.
pub fn save_obj(path: impl AsRef<Path>, objects: &[ExportObject<'_>]) -> Result<(), MeshIoError> {
    save(path.as_ref(), objects, None)
}

/// [`save_obj`] with a material list (see [`write_obj_with_materials`]): the MTL file
/// defines each material, and each texture image is copied next to `path` (named
/// after its source file, made unique) and referenced by `map_Kd`.
pub fn save_obj_with_materials(
    path: impl AsRef<Path>,
    objects: &[ExportObject<'_>],
    materials: &[Material],
) -> Result<(), MeshIoError> {
    save(path.as_ref(), objects, Some(materials))
}

fn save(
    path: &Path,
    objects: &[ExportObject<'_>],
    materials: Option<&[Material]>,
) -> Result<(), MeshIoError> {
    let materials = ExportMaterials::new(materials);
    materials.validate(objects)?;
    let mtl_path = path.with_extension("mtl");
    let mtl_name = mtl_path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_else(|| "materials.mtl".into());
    let dir = path.parent().map(Path::to_path_buf).unwrap_or_default();
    let stem = path
        .file_stem()
        .map(|s| clean(&s.to_string_lossy()))
        .unwrap_or_else(|| "model".into());
    let (textures, files) = texture_files_of(&stem, &materials.list);
    for f in &files {
        let file: PathBuf = dir.join(&f.name);
        std::fs::write(&file, &f.image.bytes).map_err(|e| MeshIoError::io(&file, e))?;
    }
    let write = |p: &Path, f: &dyn Fn(&mut dyn Write) -> std::io::Result<()>| {
        let file = std::fs::File::create(p).map_err(|e| MeshIoError::io(p, e))?;
        let mut out = std::io::BufWriter::new(file);
        f(&mut out)
            .and_then(|()| out.flush())
            .map_err(|e| MeshIoError::io(p, e))
    };
    write(path, &|out| {
        write_unchecked(out, objects, &materials, Some(&mtl_name))
    })?;
    write(&mtl_path, &|out| {
        write_materials(out, &materials.list, &textures)
    })
}

/// A texture image to write next to an OBJ file, under `name` (the name its MTL file's
/// `map_Kd` gives).
#[derive(Debug, Clone)]
pub struct TextureFile {
    /// The file name (no folder), unique among the output's textures.
    pub name: String,
    /// The image, whose bytes are the file.
    pub image: Arc<Image>,
}

/// The texture files an OBJ named `stem` (file name without extension) with these
/// materials has next to it, each image once (`{stem}_{image name}.{ext}`), and per
/// material of the writer's list (the materials, plus `interior` when they have none) the
/// name its `map_Kd` gives. For writers that write the files themselves (e.g. through
/// temporary files); [`save_obj_with_materials`] does it all.
///
/// ```
/// use std::sync::Arc;
/// use shatter_geom::io;
/// use shatter_geom::model::{Image, ImageFormat, Material, Texture};
/// let image = Arc::new(Image { name: "wood.png".into(), format: ImageFormat::Png,
///                              bytes: vec![1, 2, 3], source: None });
/// let mut m = Material::named("wood");
/// m.base_color_texture = Some(Texture { image });
/// let (names, files) = io::texture_files("crate", &[m]);
/// assert_eq!(names, [Some("crate_wood.png".to_string()), None]); // + interior
/// assert_eq!(files.len(), 1);
/// let mut mtl = Vec::new();
/// io::write_mtl_with_materials(&mut mtl, &[Material::named("wood")], &names).unwrap();
/// assert!(String::from_utf8(mtl).unwrap().contains("map_Kd crate_wood.png"));
/// ```
pub fn texture_files(
    stem: &str,
    materials: &[Material],
) -> (Vec<Option<String>>, Vec<TextureFile>) {
    texture_files_of(&clean(stem), &ExportMaterials::new(Some(materials)).list)
}

fn texture_files_of(stem: &str, list: &[Material]) -> (Vec<Option<String>>, Vec<TextureFile>) {
    let mut written: HashMap<*const Image, String> = HashMap::new();
    let mut files: Vec<TextureFile> = Vec::new();
    let mut textures = Vec::new();
    for m in list {
        let Some(t) = &m.base_color_texture else {
            textures.push(None);
            continue;
        };
        let key = Arc::as_ptr(&t.image);
        if let Some(name) = written.get(&key) {
            textures.push(Some(name.clone()));
            continue;
        }
        let taken: Vec<String> = files.iter().map(|f| f.name.clone()).collect();
        let name = texture_name(&t.image, stem, &taken);
        written.insert(key, name.clone());
        files.push(TextureFile {
            name: name.clone(),
            image: t.image.clone(),
        });
        textures.push(Some(name));
    }
    (textures, files)
}

/// Writes the MTL file of the material list `materials` (plus `interior` when it has
/// none, as the OBJ writer's list), `textures[i]` being the file of material `i`'s
/// texture (see [`texture_files`]).
pub fn write_mtl_with_materials<W: Write>(
    out: W,
    materials: &[Material],
    textures: &[Option<String>],
) -> std::io::Result<()> {
    write_materials(out, &ExportMaterials::new(Some(materials)).list, textures)
}

/// A file name for `image` next to the output: `{stem}_{image name}` with the image's
/// extension, blank-free, not yet `taken`.
fn texture_name(image: &Image, stem: &str, taken: &[String]) -> String {
    let base = Path::new(&image.name)
        .file_stem()
        .map(|s| clean(&s.to_string_lossy()))
        .filter(|s| !s.is_empty())
        .unwrap_or_else(|| "texture".into());
    let ext = image.format.extension();
    let mut name = format!("{stem}_{base}.{ext}");
    let mut k = 2;
    while taken.contains(&name) {
        name = format!("{stem}_{base}_{k}.{ext}");
        k += 1;
    }
    name
}
