//! Encodes an [`AnimatedScene`] as binary glTF 2.0 on `shatter-geom`'s GLB writer
//! ([`GlbBuilder`]): the meshes and their materials are written as every other GLB
//! shatter writes, and this module adds the nodes' poses and the animation.
//!
//! Layout: meshes flat shaded (three vertices and a face normal per triangle) with up to
//! two primitives, surface and interior, each with its material (one material per
//! distinct colour). One animation, "run": per node a LINEAR translation and rotation
//! sampler over the shared time accessor, plus a STEP scale sampler when the node is
//! hidden at some time.

use std::collections::HashMap;
use std::path::Path;

use serde_json::{Value, json};
use shatter_geom::io::{ExportObject, GlbBuilder};
use shatter_geom::model::Material;
use shatter_geom::{DVec3, TriMesh};

use super::scene::{AnimatedScene, FragmentMesh, Pose};
use crate::ReportError;

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
    let mut glb = GlbBuilder::new();
    let mut materials = Materials::default();
    let meshes: Vec<Option<usize>> = scene
        .meshes
        .iter()
        .map(|m| add_mesh(m, &mut glb, &mut materials))
        .collect();
    let ids = glb.add_materials(&materials.list);

    let nodes: Vec<usize> = scene
        .nodes
        .iter()
        .map(|node| {
            let first = node.poses.first().copied().unwrap_or(Pose::IDENTITY);
            let shown = node.visible.first().copied().unwrap_or(true);
            let mut v = json!({
                "name": node.name,
                "translation": first.translation,
                "rotation": normalized(first.rotation),
            });
            if let Some(m) = meshes[node.mesh] {
                v["mesh"] = json!(m);
            }
            if !shown {
                v["scale"] = json!([0.0, 0.0, 0.0]);
            }
            glb.add_node(v)
        })
        .collect();
    // Materials were numbered before they were added; they are added first of all, so
    // the numbers are the document's.
    debug_assert!(ids.iter().enumerate().all(|(i, &id)| i == id));
    if !scene.times.is_empty() && !scene.nodes.is_empty() {
        let animation = animation_json(scene, &mut glb);
        glb.set("animations", json!([animation]));
    }
    glb.finish(&nodes)
        .map_err(|e| ReportError::Gltf(e.to_string()))
}

/// Materials, one per distinct colour (surface or interior), numbered in order.
#[derive(Default)]
struct Materials {
    list: Vec<Material>,
    by_colour: HashMap<[u32; 3], usize>,
}

impl Materials {
    fn index(&mut self, colour: [f32; 3], interior: bool) -> usize {
        let colour = colour.map(|c| c.clamp(0.0, 1.0));
        let key = colour.map(f32::to_bits);
        if let Some(&i) = self.by_colour.get(&key) {
            return i;
        }
        let mut m = Material::named(if interior { "interior" } else { "surface" });
        m.base_color = [colour[0], colour[1], colour[2], 1.0];
        m.roughness = 0.8;
        self.list.push(m);
        self.by_colour.insert(key, self.list.len() - 1);
        self.list.len() - 1
    }
}

fn add_mesh(mesh: &FragmentMesh, glb: &mut GlbBuilder, materials: &mut Materials) -> Option<usize> {
    let positions = mesh
        .positions
        .iter()
        .map(|p| DVec3::from(p.map(f64::from)))
        .collect();
    let tri = TriMesh::new(positions, mesh.triangles.clone());
    let surface = materials.index(mesh.color, false);
    let interior = materials.index(mesh.interior_color, true);
    let object = ExportObject::new(&mesh.name, &tri);
    glb.add_mesh(&object, &|t| {
        if mesh.interior.get(t).copied().unwrap_or(false) {
            interior
        } else {
            surface
        }
    })
}

fn animation_json(scene: &AnimatedScene, glb: &mut GlbBuilder) -> Value {
    let times: Vec<[f32; 1]> = scene.times.iter().map(|&t| [t]).collect();
    let input = glb.push_floats(&times, false, true);
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
        let t = glb.push_floats(&translations, false, false);
        add(t, "LINEAR", k, "translation");
        let r = glb.push_floats(&rotations, false, false);
        add(r, "LINEAR", k, "rotation");
        if node.visible.iter().any(|&v| !v) {
            let scales: Vec<[f32; 3]> = node
                .visible
                .iter()
                .map(|&v| if v { [1.0; 3] } else { [0.0; 3] })
                .collect();
            let s = glb.push_floats(&scales, false, false);
            add(s, "STEP", k, "scale");
        }
    }
    json!({ "name": "run", "samplers": samplers, "channels": channels })
}

fn normalized(q: [f32; 4]) -> [f32; 4] {
    let n = q.iter().map(|c| c * c).sum::<f32>().sqrt();
    q.map(|c| c / n)
}
