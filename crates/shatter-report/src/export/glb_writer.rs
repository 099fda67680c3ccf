//! Encodes an [`AnimatedScene`] as binary glTF 2.0: the JSON document is built with
//! `serde_json`, the container with the `gltf` crate's [`gltf::binary::Glb`].
//!
//! Layout: one buffer; one buffer view and accessor per array. Meshes are flat shaded
//! (three vertices and a face normal per triangle) with up to two primitives, surface
//! and interior, each with its material. One animation, "run": per node a LINEAR
//! translation and rotation sampler over the shared time accessor, plus a STEP scale
//! sampler when the node is hidden at some time.

use std::borrow::Cow;
use std::collections::HashMap;
use std::path::Path;

use serde_json::{Value, json};

use super::scene::{AnimatedScene, FragmentMesh, Pose};
use crate::ReportError;

const FLOAT: u32 = 5126;
const UNSIGNED_INT: u32 = 5125;
const ARRAY_BUFFER: u32 = 34962;
const ELEMENT_ARRAY_BUFFER: u32 = 34963;

/// Writes `scene` to `path` as an animated GLB file.
///
/// ```
/// use shatter_report::export::{AnimatedNode, AnimatedScene, FragmentMesh, Pose, write_animated_glb};
///
/// let tetra = FragmentMesh::new(
///     "tetra",
///     vec![[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
///     vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]],
///     [0.8, 0.3, 0.2],
/// );
/// let falling = AnimatedNode {
///     name: "fragment_0".into(),
///     mesh: 0,
///     poses: vec![Pose::IDENTITY, Pose::new([0.0, -1.0, 0.0], [0.0, 0.0, 0.0, 1.0])],
///     visible: vec![],
/// };
/// let scene = AnimatedScene { times: vec![0.0, 1.0], meshes: vec![tetra], nodes: vec![falling] };
/// let dir = tempfile::tempdir()?;
/// write_animated_glb(dir.path().join("run.glb"), &scene)?;
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn write_animated_glb(
    path: impl AsRef<Path>,
    scene: &AnimatedScene,
) -> Result<(), ReportError> {
    let path = path.as_ref();
    let bytes = animated_glb_bytes(scene)?;
    std::fs::write(path, bytes).map_err(|e| ReportError::io(path, e))
}

/// The GLB file for `scene`, in memory.
pub fn animated_glb_bytes(scene: &AnimatedScene) -> Result<Vec<u8>, ReportError> {
    scene.validate()?;
    let mut bin = BinaryBuffer::default();
    let mut materials = Materials::default();
    let meshes: Vec<Value> = scene
        .meshes
        .iter()
        .map(|m| mesh_json(m, &mut bin, &mut materials))
        .collect();

    let nodes: Vec<Value> = scene
        .nodes
        .iter()
        .map(|node| {
            let first = node.poses.first().copied().unwrap_or(Pose::IDENTITY);
            let shown = node.visible.first().copied().unwrap_or(true);
            let mut v = json!({
                "name": node.name,
                "mesh": node.mesh,
                "translation": first.translation,
                "rotation": normalized(first.rotation),
            });
            if !shown {
                v["scale"] = json!([0.0, 0.0, 0.0]);
            }
            v
        })
        .collect();

    let mut document = json!({
        "asset": { "version": "2.0", "generator": "shatter-report" },
        "scene": 0,
        "scenes": [{ "name": "shatter run", "nodes": (0..nodes.len()).collect::<Vec<_>>() }],
        "nodes": nodes,
        "meshes": meshes,
        "materials": materials.json,
    });
    if !scene.times.is_empty() && !scene.nodes.is_empty() {
        document["animations"] = json!([animation_json(scene, &mut bin)]);
    }
    document["buffers"] = json!([{ "byteLength": bin.data.len() }]);
    document["bufferViews"] = Value::Array(bin.views);
    document["accessors"] = Value::Array(bin.accessors);

    let json_bytes = serde_json::to_vec(&document).map_err(|e| ReportError::Gltf(e.to_string()))?;
    let glb = gltf::binary::Glb {
        header: gltf::binary::Header {
            magic: *b"glTF",
            version: 2,
            // Recomputed by `to_vec`.
            length: 0,
        },
        json: Cow::Owned(json_bytes),
        bin: Some(Cow::Owned(bin.data)),
    };
    glb.to_vec().map_err(|e| ReportError::Gltf(e.to_string()))
}

/// The binary chunk with its buffer views and accessors.
#[derive(Default)]
struct BinaryBuffer {
    data: Vec<u8>,
    views: Vec<Value>,
    accessors: Vec<Value>,
}

impl BinaryBuffer {
    fn push_view(&mut self, bytes: impl Iterator<Item = [u8; 4]>, target: Option<u32>) -> usize {
        let offset = self.data.len();
        for b in bytes {
            self.data.extend_from_slice(&b);
        }
        let mut view = json!({
            "buffer": 0,
            "byteOffset": offset,
            "byteLength": self.data.len() - offset,
        });
        if let Some(t) = target {
            view["target"] = json!(t);
        }
        self.views.push(view);
        self.views.len() - 1
    }

    /// An accessor of `N`-component float elements; `bounds` adds min and max.
    fn push_floats<const N: usize>(
        &mut self,
        elements: &[[f32; N]],
        target: Option<u32>,
        bounds: bool,
    ) -> usize {
        let view = self.push_view(elements.iter().flatten().map(|v| v.to_le_bytes()), target);
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
        let view = self.push_view(
            indices.iter().map(|i| i.to_le_bytes()),
            Some(ELEMENT_ARRAY_BUFFER),
        );
        self.accessors.push(json!({
            "bufferView": view,
            "componentType": UNSIGNED_INT,
            "count": indices.len(),
            "type": "SCALAR",
        }));
        self.accessors.len() - 1
    }
}

/// Materials, one per distinct colour.
#[derive(Default)]
struct Materials {
    json: Vec<Value>,
    by_colour: HashMap<[u32; 3], usize>,
}

impl Materials {
    fn index(&mut self, colour: [f32; 3], interior: bool) -> usize {
        let key = colour.map(|c| c.clamp(0.0, 1.0).to_bits());
        if let Some(&i) = self.by_colour.get(&key) {
            return i;
        }
        let [r, g, b] = colour.map(|c| c.clamp(0.0, 1.0));
        self.json.push(json!({
            "name": if interior { "interior" } else { "surface" },
            "pbrMetallicRoughness": {
                "baseColorFactor": [r, g, b, 1.0],
                "metallicFactor": 0.0,
                "roughnessFactor": 0.8,
            },
        }));
        self.by_colour.insert(key, self.json.len() - 1);
        self.json.len() - 1
    }
}

fn mesh_json(mesh: &FragmentMesh, bin: &mut BinaryBuffer, materials: &mut Materials) -> Value {
    let mut primitives = Vec::new();
    for interior in [false, true] {
        let triangles: Vec<[u32; 3]> = mesh
            .triangles
            .iter()
            .enumerate()
            .filter(|&(t, _)| mesh.interior.get(t).copied().unwrap_or(false) == interior)
            .map(|(_, &tri)| tri)
            .collect();
        if triangles.is_empty() {
            continue;
        }
        let mut positions = Vec::with_capacity(3 * triangles.len());
        let mut normals = Vec::with_capacity(3 * triangles.len());
        for tri in &triangles {
            let [a, b, c] = tri.map(|i| mesh.positions[i as usize]);
            let n = face_normal(a, b, c);
            positions.extend([a, b, c]);
            normals.extend([n; 3]);
        }
        let indices: Vec<u32> = (0..positions.len() as u32).collect();
        let position = bin.push_floats(&positions, Some(ARRAY_BUFFER), true);
        let normal = bin.push_floats(&normals, Some(ARRAY_BUFFER), false);
        let index = bin.push_indices(&indices);
        let colour = if interior {
            mesh.interior_color
        } else {
            mesh.color
        };
        primitives.push(json!({
            "attributes": { "POSITION": position, "NORMAL": normal },
            "indices": index,
            "material": materials.index(colour, interior),
            "mode": 4,
        }));
    }
    json!({ "name": mesh.name, "primitives": primitives })
}

fn animation_json(scene: &AnimatedScene, bin: &mut BinaryBuffer) -> Value {
    let times: Vec<[f32; 1]> = scene.times.iter().map(|&t| [t]).collect();
    let input = bin.push_floats(&times, None, true);
    let mut samplers = Vec::new();
    let mut channels = Vec::new();
    let mut add = |output: usize, interpolation: &str, node: usize, path: &str| {
        samplers.push(json!({ "input": input, "output": output, "interpolation": interpolation }));
        channels.push(json!({
            "sampler": samplers.len() - 1,
            "target": { "node": node, "path": path },
        }));
    };
    for (k, node) in scene.nodes.iter().enumerate() {
        let translations: Vec<[f32; 3]> = node.poses.iter().map(|p| p.translation).collect();
        let mut rotations: Vec<[f32; 4]> =
            node.poses.iter().map(|p| normalized(p.rotation)).collect();
        // q and -q are the same rotation; keep neighbours in one hemisphere so that
        // interpolation takes the short way round.
        for i in 1..rotations.len() {
            let dot: f32 = (0..4).map(|c| rotations[i][c] * rotations[i - 1][c]).sum();
            if dot < 0.0 {
                rotations[i] = rotations[i].map(|c| -c);
            }
        }
        let t = bin.push_floats(&translations, None, false);
        add(t, "LINEAR", k, "translation");
        let r = bin.push_floats(&rotations, None, false);
        add(r, "LINEAR", k, "rotation");
        if node.visible.iter().any(|&v| !v) {
            let scales: Vec<[f32; 3]> = node
                .visible
                .iter()
                .map(|&v| if v { [1.0; 3] } else { [0.0; 3] })
                .collect();
            let s = bin.push_floats(&scales, None, false);
            add(s, "STEP", k, "scale");
        }
    }
    json!({ "name": "run", "samplers": samplers, "channels": channels })
}

fn normalized(q: [f32; 4]) -> [f32; 4] {
    let n = q.iter().map(|c| c * c).sum::<f32>().sqrt();
    q.map(|c| c / n)
}

/// Unit normal of a triangle (any unit vector for a degenerate one).
fn face_normal(a: [f32; 3], b: [f32; 3], c: [f32; 3]) -> [f32; 3] {
    let u = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
    let v = [c[0] - a[0], c[1] - a[1], c[2] - a[2]];
    let n = [
        u[1] * v[2] - u[2] * v[1],
        u[2] * v[0] - u[0] * v[2],
        u[0] * v[1] - u[1] * v[0],
    ];
    let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
    if len > 0.0 && len.is_finite() {
        n.map(|c| c / len)
    } else {
        [0.0, 1.0, 0.0]
    }
}
