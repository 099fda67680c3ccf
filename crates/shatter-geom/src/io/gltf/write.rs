//! GLB (binary glTF 2.0) export: one node per object, the materials with their images
//! embedded, TEXCOORD_0, NORMAL and COLOR_0 when the objects have them.
//!
//! [`GlbBuilder`] is public so that other writers (the animated export of a run in
//! `shatter-report`) build on the same meshes and materials and add nodes and
//! animations of their own.

use std::collections::HashMap;
use std::io::Write;
use std::path::Path;
use std::sync::Arc;

use serde_json::{Value, json};

use crate::io::export::ExportMaterials;
use crate::io::{ExportObject, MeshIoError};
use crate::model::{Image, Material};
use crate::util::FastMap;

const FLOAT: u32 = 5126;
const UNSIGNED_INT: u32 = 5125;
const ARRAY_BUFFER: u32 = 34962;
const ELEMENT_ARRAY_BUFFER: u32 = 34963;
const TRIANGLES: u32 = 4;

/// Builds a GLB: a binary chunk with its buffer views and accessors, meshes, materials
/// with embedded images, nodes, and any other top-level entry (animations).
///
/// ```
/// use serde_json::json;
/// use shatter_geom::{io::{ExportObject, GlbBuilder}, model::Material, shapes};
/// let cube = shapes::cube();
/// let mut glb = GlbBuilder::new();
/// let materials = glb.add_materials(&[Material::named("stone")]);
/// let mesh = glb.add_mesh(&ExportObject::new("cube", &cube), &|_| materials[0]).unwrap();
/// let node = glb.add_node(json!({ "name": "cube", "mesh": mesh, "translation": [0.0, 2.0, 0.0] }));
/// let bytes = glb.finish(&[node]).unwrap();
/// let doc = gltf::Gltf::from_slice(&bytes).unwrap();
/// assert_eq!(doc.nodes().next().unwrap().transform().decomposed().0, [0.0, 2.0, 0.0]);
/// ```
#[derive(Default)]
pub struct GlbBuilder {
    bin: Vec<u8>,
    views: Vec<Value>,
    accessors: Vec<Value>,
    meshes: Vec<Value>,
    materials: Vec<Value>,
    images: Vec<Value>,
    textures: Vec<Value>,
    image_index: HashMap<*const Image, usize>,
    nodes: Vec<Value>,
    extra: Vec<(String, Value)>,
}

impl GlbBuilder {
    /// An empty document.
    pub fn new() -> GlbBuilder {
        GlbBuilder::default()
    }

    fn push_view(&mut self, bytes: &[u8], target: Option<u32>) -> usize {
        // Views start 4-byte aligned.
        while !self.bin.len().is_multiple_of(4) {
            self.bin.push(0);
        }
        let offset = self.bin.len();
        self.bin.extend_from_slice(bytes);
        let mut view = json!({ "buffer": 0, "byteOffset": offset, "byteLength": bytes.len() });
        if let Some(t) = target {
            view["target"] = json!(t);
        }
        self.views.push(view);
        self.views.len() - 1
    }

    /// Appends an accessor of `N`-component float elements (vertex data when `vertex`,
    /// else animation data); `bounds` adds its min and max. Returns its index.
    pub fn push_floats<const N: usize>(
        &mut self,
        elements: &[[f32; N]],
        vertex: bool,
        bounds: bool,
    ) -> usize {
        let bytes: Vec<u8> = elements
            .iter()
            .flatten()
            .flat_map(|v| v.to_le_bytes())
            .collect();
        let view = self.push_view(&bytes, vertex.then_some(ARRAY_BUFFER));
        let kind = match N {
            1 => "SCALAR",
            2 => "VEC2",
            3 => "VEC3",
            _ => "VEC4",
        };
        let mut accessor = json!({
            "bufferView": view,
            "componentType": FLOAT,
            "count": elements.len(),
            "type": kind,
        });
        if bounds && !elements.is_empty() {
            let mut lo = [f32::INFINITY; N];
            let mut hi = [f32::NEG_INFINITY; N];
            for e in elements {
                for k in 0..N {
                    lo[k] = lo[k].min(e[k]);
                    hi[k] = hi[k].max(e[k]);
                }
            }
            accessor["min"] = json!(lo.to_vec());
            accessor["max"] = json!(hi.to_vec());
        }
        self.accessors.push(accessor);
        self.accessors.len() - 1
    }

    fn push_indices(&mut self, indices: &[u32]) -> usize {
        let count = indices.len();
        let bytes: Vec<u8> = indices.iter().flat_map(|i| i.to_le_bytes()).collect();
        let view = self.push_view(&bytes, Some(ELEMENT_ARRAY_BUFFER));
        self.accessors.push(json!({
            "bufferView": view,
            "componentType": UNSIGNED_INT,
            "count": count,
            "type": "SCALAR",
        }));
        self.accessors.len() - 1
    }

    fn image(&mut self, image: &Arc<Image>) -> usize {
        let key = Arc::as_ptr(image);
        if let Some(&t) = self.image_index.get(&key) {
            return t;
        }
        let view = self.push_view(&image.bytes, None);
        self.images.push(json!({
            "name": image.name,
            "bufferView": view,
            "mimeType": image.format.mime(),
        }));
        self.textures
            .push(json!({ "source": self.images.len() - 1, "sampler": 0 }));
        let t = self.textures.len() - 1;
        self.image_index.insert(key, t);
        t
    }

    /// Adds materials (images embedded once each, however many materials share them);
    /// returns their indices in the document.
    pub fn add_materials(&mut self, materials: &[Material]) -> Vec<usize> {
        materials
            .iter()
            .map(|m| {
                let mut pbr = json!({
                    "baseColorFactor": m.base_color,
                    "metallicFactor": m.metallic,
                    "roughnessFactor": m.roughness,
                });
                if let Some(t) = &m.base_color_texture {
                    pbr["baseColorTexture"] = json!({ "index": self.image(&t.image) });
                }
                let mut v = json!({ "name": m.name, "pbrMetallicRoughness": pbr });
                if m.base_color[3] < 1.0 {
                    v["alphaMode"] = json!("BLEND");
                }
                self.materials.push(v);
                self.materials.len() - 1
            })
            .collect()
    }

    /// Adds `object` as a mesh with one primitive per material its triangles use
    /// (`material(t)` gives triangle `t`'s material index in the document). A primitive
    /// has one vertex per distinct position and attributes (a seam or a crease is two),
    /// and NORMAL only when the object has normals (a client computes flat normals
    /// where NORMAL is absent, as glTF 2.0 asks). Returns the mesh
    /// index, or `None` for an object without triangles. The object is not validated
    /// here: [`write_glb_with_materials`] does that.
    pub fn add_mesh(
        &mut self,
        object: &ExportObject<'_>,
        material: &dyn Fn(usize) -> usize,
    ) -> Option<usize> {
        let mesh = object.mesh;
        let mut by_material: Vec<(usize, Vec<usize>)> = Vec::new();
        for t in 0..mesh.triangles.len() {
            let m = material(t);
            match by_material.iter_mut().find(|(k, _)| *k == m) {
                Some((_, ts)) => ts.push(t),
                None => by_material.push((m, vec![t])),
            }
        }
        if by_material.is_empty() {
            return None;
        }
        by_material.sort_by_key(|(m, _)| *m);
        let corners = object.corners;
        let normal = corners.and_then(|c| c.normal.as_ref());
        let uv = corners.and_then(|c| c.uv.as_ref());
        let color = corners.and_then(|c| c.color.as_ref());
        let mut primitives = Vec::new();
        for (m, tris) in by_material {
            // One vertex per distinct position and attributes: the key is their bits,
            // zero where the object lacks an attribute (-0 is 0).
            let mut index: FastMap<[u32; 12], u32> = FastMap::default();
            let mut positions = Vec::with_capacity(3 * tris.len());
            let mut normals = Vec::new();
            let mut uvs = Vec::new();
            let mut colors = Vec::new();
            let mut indices = Vec::with_capacity(3 * tris.len());
            for &t in &tris {
                for (k, p) in mesh.triangle(t).into_iter().enumerate() {
                    let p = p.as_vec3().to_array();
                    let n = normal.map(|n| n[t][k]);
                    let u = uv.map(|u| u[t][k]);
                    let c = color.map(|c| c[t][k]);
                    let mut key = [0u32; 12];
                    let values = p.iter().chain(n.iter().flatten());
                    let values = values.chain(u.iter().flatten()).chain(c.iter().flatten());
                    for (slot, x) in key.iter_mut().zip(values) {
                        *slot = (x + 0.0).to_bits();
                    }
                    let next = positions.len() as u32;
                    let i = *index.entry(key).or_insert(next);
                    if i == next {
                        positions.push(p);
                        normals.extend(n);
                        uvs.extend(u);
                        colors.extend(c);
                    }
                    indices.push(i);
                }
            }
            let mut attributes = json!({
                "POSITION": self.push_floats(&positions, true, true),
            });
            // NORMAL only when the object has normals: without it a client computes
            // flat normals itself (glTF 2.0, "Meshes"), and a vertex then needs no copy
            // per face, so the faces stay joined when imported.
            if !normals.is_empty() {
                attributes["NORMAL"] = json!(self.push_floats(&normals, true, false));
            }
            if !uvs.is_empty() {
                attributes["TEXCOORD_0"] = json!(self.push_floats(&uvs, true, false));
            }
            if !colors.is_empty() {
                attributes["COLOR_0"] = json!(self.push_floats(&colors, true, false));
            }
            let indices = self.push_indices(&indices);
            primitives.push(json!({
                "attributes": attributes,
                "indices": indices,
                "material": m,
                "mode": TRIANGLES,
            }));
        }
        self.meshes
            .push(json!({ "name": object.name, "primitives": primitives }));
        Some(self.meshes.len() - 1)
    }

    /// Adds a node (its JSON: name, mesh, transform); returns its index.
    pub fn add_node(&mut self, node: Value) -> usize {
        self.nodes.push(node);
        self.nodes.len() - 1
    }

    /// Sets a top-level entry of the document (`animations`, say).
    pub fn set(&mut self, key: impl Into<String>, value: Value) {
        self.extra.push((key.into(), value));
    }

    /// The GLB file, with one scene of the nodes `scene`.
    pub fn finish(self, scene: &[usize]) -> Result<Vec<u8>, MeshIoError> {
        let mut root = json!({
            "asset": { "version": "2.0", "generator": "shatter" },
            "scene": 0,
            "scenes": [{ "nodes": scene }],
            "nodes": self.nodes,
        });
        let put = |root: &mut Value, key: &str, v: Vec<Value>| {
            if !v.is_empty() {
                root[key] = Value::Array(v);
            }
        };
        let has_textures = !self.textures.is_empty();
        put(&mut root, "meshes", self.meshes);
        put(&mut root, "materials", self.materials);
        put(&mut root, "images", self.images);
        put(&mut root, "textures", self.textures);
        if has_textures {
            // Linear filtering, repeat wrapping: glTF's defaults, written out.
            root["samplers"] =
                json!([{ "magFilter": 9729, "minFilter": 9987, "wrapS": 10497, "wrapT": 10497 }]);
        }
        put(&mut root, "accessors", self.accessors);
        put(&mut root, "bufferViews", self.views);
        for (k, v) in self.extra {
            root[k] = v;
        }
        if !self.bin.is_empty() {
            root["buffers"] = json!([{ "byteLength": self.bin.len() }]);
        }
        let json = serde_json::to_vec(&root)
            .map_err(|e| MeshIoError::io("<GLB output>", std::io::Error::other(e)))?;
        Ok(container(json, self.bin))
    }
}

/// The GLB container: header, JSON chunk (space-padded), binary chunk (zero-padded).
fn container(mut json: Vec<u8>, mut bin: Vec<u8>) -> Vec<u8> {
    while !json.len().is_multiple_of(4) {
        json.push(b' ');
    }
    while !bin.len().is_multiple_of(4) {
        bin.push(0);
    }
    let total = 12 + 8 + json.len() + if bin.is_empty() { 0 } else { 8 + bin.len() };
    let mut out = Vec::with_capacity(total);
    out.extend_from_slice(b"glTF");
    out.extend_from_slice(&2u32.to_le_bytes());
    out.extend_from_slice(&(total as u32).to_le_bytes());
    out.extend_from_slice(&(json.len() as u32).to_le_bytes());
    out.extend_from_slice(b"JSON");
    out.extend_from_slice(&json);
    if !bin.is_empty() {
        out.extend_from_slice(&(bin.len() as u32).to_le_bytes());
        out.extend_from_slice(b"BIN\0");
        out.extend_from_slice(&bin);
    }
    out
}

/// Writes the objects as a GLB: one node (and mesh) per object, named after it, with the
/// surface faces under material 0 (`surface`) and the interior faces under material 1
/// (`interior`). Vertices are shared where position and attributes agree; NORMAL is
/// written only for objects that carry normals. Positions are stored as `f32`, the glTF format's.
///
/// ```
/// use shatter_geom::{io::{self, ExportObject}, shapes};
/// let cube = shapes::cube();
/// let mut glb = Vec::new();
/// io::write_glb(&mut glb, &[ExportObject::new("cube", &cube)]).unwrap();
/// let doc = gltf::Gltf::from_slice(&glb).unwrap();
/// assert_eq!(doc.nodes().next().and_then(|n| n.name().map(String::from)), Some("cube".into()));
/// assert_eq!(doc.materials().count(), 2);
/// ```
pub fn write_glb<W: Write>(out: W, objects: &[ExportObject<'_>]) -> Result<(), MeshIoError> {
    write(out, objects, None)
}

/// Writes the objects as a GLB with the material list `materials` (each object's
/// triangles index it, see [`ExportObject`]), their images embedded, plus an `interior`
/// material when the list has none; TEXCOORD_0, NORMAL and COLOR_0 where the objects
/// have them.
pub fn write_glb_with_materials<W: Write>(
    out: W,
    objects: &[ExportObject<'_>],
    materials: &[Material],
) -> Result<(), MeshIoError> {
    write(out, objects, Some(materials))
}

fn write<W: Write>(
    mut out: W,
    objects: &[ExportObject<'_>],
    materials: Option<&[Material]>,
) -> Result<(), MeshIoError> {
    let materials = ExportMaterials::new(materials);
    materials.validate(objects)?;
    let mut b = GlbBuilder::new();
    let ids = b.add_materials(&materials.list);
    let mut nodes = Vec::with_capacity(objects.len());
    for (i, o) in objects.iter().enumerate() {
        let name = if o.name.is_empty() {
            format!("object_{i}")
        } else {
            o.name.to_string()
        };
        let named = ExportObject { name: &name, ..*o };
        let mesh = b.add_mesh(&named, &|t| ids[materials.of(o, t) as usize]);
        let mut node = json!({ "name": name });
        if let Some(m) = mesh {
            node["mesh"] = json!(m);
        }
        nodes.push(b.add_node(node));
    }
    let bytes = b.finish(&nodes)?;
    out.write_all(&bytes)
        .map_err(|e| MeshIoError::io("<GLB output>", e))
}

/// Writes the objects to a GLB file (see [`write_glb`]).
pub fn save_glb(path: impl AsRef<Path>, objects: &[ExportObject<'_>]) -> Result<(), MeshIoError> {
    save(path.as_ref(), objects, None)
}

/// Writes the objects to a GLB file with their materials (see
/// [`write_glb_with_materials`]).
pub fn save_glb_with_materials(
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
    let mut bytes = Vec::new();
    write(&mut bytes, objects, materials)?;
    std::fs::write(path, bytes).map_err(|e| MeshIoError::io(path, e))
}
