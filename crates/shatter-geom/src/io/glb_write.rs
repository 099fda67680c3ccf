//! GLB (binary glTF 2.0) export: one node per object, two materials, flat normals.

use std::borrow::Cow;
use std::io::Write;
use std::path::Path;

use glam::Vec3;
use serde_json::{Value, json};

use super::export::{INTERIOR_COLOR, INTERIOR_MATERIAL, SURFACE_COLOR, SURFACE_MATERIAL};
use super::{ExportObject, MeshIoError};

const FLOAT: u32 = 5126;
const ARRAY_BUFFER: u32 = 34962;
const TRIANGLES: u32 = 4;

/// Accumulates the binary chunk and the JSON arrays that describe it.
#[derive(Default)]
struct Builder {
    bin: Vec<u8>,
    views: Vec<Value>,
    accessors: Vec<Value>,
}

impl Builder {
    /// Appends a VEC3 float accessor and returns its index.
    fn vec3_accessor(&mut self, data: &[Vec3], with_bounds: bool) -> usize {
        let offset = self.bin.len();
        for v in data {
            for c in v.to_array() {
                self.bin.extend_from_slice(&c.to_le_bytes());
            }
        }
        self.views.push(json!({
            "buffer": 0,
            "byteOffset": offset,
            "byteLength": self.bin.len() - offset,
            "target": ARRAY_BUFFER,
        }));
        let mut accessor = json!({
            "bufferView": self.views.len() - 1,
            "componentType": FLOAT,
            "count": data.len(),
            "type": "VEC3",
        });
        if with_bounds {
            let lo = data
                .iter()
                .fold(Vec3::splat(f32::INFINITY), |a, &b| a.min(b));
            let hi = data
                .iter()
                .fold(Vec3::splat(f32::NEG_INFINITY), |a, &b| a.max(b));
            accessor["min"] = json!(lo.to_array());
            accessor["max"] = json!(hi.to_array());
        }
        self.accessors.push(accessor);
        self.accessors.len() - 1
    }
}

/// Writes the objects as a GLB: one node (and mesh) per object, named after it, with up
/// to two primitives, the surface faces with material 0 (`surface`) and the interior
/// faces with material 1 (`interior`). Vertices are split per face with flat normals, as
/// fragments are shown flat-shaded. Positions are stored as `f32`, the glTF format's.
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
    for o in objects {
        o.validate()?;
    }
    let mut b = Builder::default();
    let mut nodes = Vec::with_capacity(objects.len());
    let mut meshes = Vec::new();
    for (i, o) in objects.iter().enumerate() {
        let name = if o.name.is_empty() {
            format!("object_{i}")
        } else {
            o.name.to_string()
        };
        let mut primitives = Vec::new();
        for (material, interior) in [(0, false), (1, true)] {
            let mut positions = Vec::new();
            let mut normals = Vec::new();
            for t in (0..o.mesh.triangles.len()).filter(|&t| o.is_interior(t) == interior) {
                let n = o.mesh.triangle_normal(t).as_vec3();
                let n = if n == Vec3::ZERO {
                    Vec3::Y
                } else {
                    n.normalize()
                };
                for p in o.mesh.triangle(t) {
                    positions.push(p.as_vec3());
                    normals.push(n);
                }
            }
            if positions.is_empty() {
                continue;
            }
            let position = b.vec3_accessor(&positions, true);
            let normal = b.vec3_accessor(&normals, false);
            primitives.push(json!({
                "attributes": { "POSITION": position, "NORMAL": normal },
                "material": material,
                "mode": TRIANGLES,
            }));
        }
        let mut node = json!({ "name": name });
        if !primitives.is_empty() {
            meshes.push(json!({ "name": name, "primitives": primitives }));
            node["mesh"] = json!(meshes.len() - 1);
        }
        nodes.push(node);
    }
    let material = |name: &str, [r, g, bl]: [f32; 3]| {
        json!({
            "name": name,
            "pbrMetallicRoughness": {
                "baseColorFactor": [r, g, bl, 1.0],
                "metallicFactor": 0.0,
                "roughnessFactor": 0.8,
            },
        })
    };
    let mut root = json!({
        "asset": { "version": "2.0", "generator": "shatter" },
        "scene": 0,
        "scenes": [{ "nodes": (0..nodes.len()).collect::<Vec<_>>() }],
        "nodes": nodes,
        "materials": [
            material(SURFACE_MATERIAL, SURFACE_COLOR),
            material(INTERIOR_MATERIAL, INTERIOR_COLOR),
        ],
    });
    if !meshes.is_empty() {
        root["meshes"] = json!(meshes);
        root["accessors"] = json!(b.accessors);
        root["bufferViews"] = json!(b.views);
        root["buffers"] = json!([{ "byteLength": b.bin.len() }]);
    }
    let json = serde_json::to_vec(&root)
        .map_err(|e| MeshIoError::io("<GLB output>", std::io::Error::other(e)))?;
    let glb = gltf::binary::Glb {
        header: gltf::binary::Header {
            magic: *b"glTF",
            version: 2,
            length: 0, // computed by the writer
        },
        json: Cow::Owned(json),
        bin: (!b.bin.is_empty()).then_some(Cow::Owned(b.bin)),
    };
    glb.to_writer(out).map_err(|e| match e {
        gltf::Error::Io(io) => MeshIoError::io("<GLB output>", io),
        other => MeshIoError::io("<GLB output>", std::io::Error::other(other.to_string())),
    })
}

/// Writes the objects to a GLB file (see [`write_glb`]).
pub fn save_glb(path: impl AsRef<Path>, objects: &[ExportObject<'_>]) -> Result<(), MeshIoError> {
    let path = path.as_ref();
    let mut bytes = Vec::new();
    write_glb(&mut bytes, objects)?;
    std::fs::write(path, bytes).map_err(|e| MeshIoError::io(path, e))
}
