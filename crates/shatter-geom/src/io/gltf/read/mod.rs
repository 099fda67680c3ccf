//! The glTF 2.0 / GLB reader: the scene's node trees with their transforms, every
//! triangle primitive (lists, strips, fans) with TEXCOORD_0, NORMAL and COLOR_0, and the
//! materials with their base-colour textures (embedded in the GLB, data URIs or external
//! files).

mod materials;
mod primitive;

use std::collections::HashMap;
use std::sync::Arc;

use glam::{DMat3, DMat4, DQuat, DVec3};

use super::container;
use super::json::{self, Root};
use crate::TriMesh;
use crate::io::context::{MAX_TRIANGLES, ReadContext};
use crate::io::{MeshIoError, WarningKind};
use crate::model::{Corners, Material, Model};
pub(crate) use materials::Materials;
use materials::default_material;
pub(crate) use primitive::{Decoded, decode_primitive};

/// The most node instances followed (a node tree may share subtrees, so instances can
/// grow exponentially with the number of nodes).
const MAX_INSTANCES: usize = 1_000_000;

/// Extensions that change how geometry is stored: a file that requires one cannot be
/// read.
const GEOMETRY_EXTENSIONS: [&str; 3] = [
    "KHR_draco_mesh_compression",
    "EXT_meshopt_compression",
    "KHR_meshopt_compression",
];

struct Reader<'a, 'c> {
    cx: &'c mut ReadContext<'a>,
    root: &'c Root,
    buffers: Vec<Result<Vec<u8>, String>>,
    /// Decoded primitives, per mesh (`None` until first used).
    decoded: HashMap<usize, Arc<Vec<Decoded>>>,
    positions: Vec<DVec3>,
    triangles: Vec<[u32; 3]>,
    uv: Vec<[[f32; 2]; 3]>,
    normal: Vec<[[f32; 3]; 3]>,
    color: Vec<[[f32; 4]; 3]>,
    has: [bool; 3],
    missing_uv: usize,
    /// Per triangle: the file's material index (`usize::MAX`: none).
    material: Vec<usize>,
    skipped_modes: (usize, usize),
}

impl Reader<'_, '_> {
    fn error(&self, message: String) -> MeshIoError {
        MeshIoError::Gltf {
            path: self.cx.path.to_path_buf(),
            message,
        }
    }

    fn decode_mesh(&mut self, m: usize) -> Result<Arc<Vec<Decoded>>, MeshIoError> {
        if let Some(d) = self.decoded.get(&m) {
            return Ok(d.clone());
        }
        let root = self.root;
        let mesh = root.meshes.get(m).ok_or_else(|| {
            self.error(format!(
                "a node names mesh {m}, but the file has {} meshes",
                root.meshes.len()
            ))
        })?;
        let mut out = Vec::new();
        for (p, prim) in mesh.primitives.iter().enumerate() {
            let what = format!("mesh {m} primitive {p}");
            let mode = prim.mode.unwrap_or(4);
            if mode < 4 {
                self.skipped_modes.0 += 1;
                continue;
            }
            if mode > 6 {
                self.skipped_modes.1 += 1;
                continue;
            }
            out.push(
                decode_primitive(self.root, &self.buffers, prim, &what, mode)
                    .map_err(|e| self.error(e))?,
            );
        }
        let out = Arc::new(out);
        self.decoded.insert(m, out.clone());
        Ok(out)
    }
}

impl Reader<'_, '_> {
    fn instance(&mut self, mesh: usize, world: DMat4) -> Result<(), MeshIoError> {
        let primitives = self.decode_mesh(mesh)?;
        let mirror = world.determinant() < 0.0;
        let normal_matrix = DMat3::from_mat4(world).inverse().transpose();
        for d in primitives.iter() {
            if self.triangles.len() + d.triangles.len() > MAX_TRIANGLES {
                return Err(MeshIoError::TooLarge {
                    path: self.cx.path.to_path_buf(),
                    message: format!(
                        "the scene instances more than {MAX_TRIANGLES} triangles; shatter takes at most that many"
                    ),
                });
            }
            let base = self.positions.len() as u32;
            self.positions.extend(
                d.positions
                    .iter()
                    .map(|p| world.transform_point3(DVec3::from(p.map(f64::from)))),
            );
            let order: [usize; 3] = if mirror { [0, 2, 1] } else { [0, 1, 2] };
            for t in &d.triangles {
                let t = order.map(|k| t[k]);
                self.triangles.push(t.map(|i| i + base));
                self.material.push(d.material.unwrap_or(usize::MAX));
                let uv = match &d.uvs {
                    Some(uvs) => t.map(|i| uvs[i as usize]),
                    None => {
                        self.missing_uv += 3;
                        [[0.0; 2]; 3]
                    }
                };
                self.uv.push(uv);
                let normal = match &d.normals {
                    Some(ns) => t.map(|i| {
                        let n = normal_matrix * DVec3::from(ns[i as usize].map(f64::from));
                        n.normalize_or_zero().as_vec3().to_array()
                    }),
                    None => [[0.0; 3]; 3],
                };
                self.normal.push(normal);
                let color = match &d.colors {
                    Some(cs) => t.map(|i| cs[i as usize]),
                    None => [[1.0; 4]; 3],
                };
                self.color.push(color);
            }
            self.has[0] |= d.uvs.is_some();
            self.has[1] |= d.normals.is_some();
            self.has[2] |= d.colors.is_some();
        }
        Ok(())
    }

    /// Follows the node trees of `roots` (without recursion: a deep chain cannot
    /// overflow the stack), refusing cycles.
    fn walk(&mut self, roots: &[usize]) -> Result<(), MeshIoError> {
        let root = self.root;
        let mut on_path = vec![false; root.nodes.len()];
        // (node, parent transform, whether leaving it)
        let mut stack: Vec<(usize, DMat4, bool)> = roots
            .iter()
            .rev()
            .map(|&n| (n, DMat4::IDENTITY, false))
            .collect();
        let mut instances = 0usize;
        while let Some((n, parent, leaving)) = stack.pop() {
            if leaving {
                on_path[n] = false;
                continue;
            }
            let node = root.nodes.get(n).ok_or_else(|| {
                self.error(format!(
                    "the scene names node {n}, but the file has {} nodes",
                    root.nodes.len()
                ))
            })?;
            if on_path[n] {
                return Err(self.error(format!("node {n} is its own ancestor (a cycle)")));
            }
            instances += 1;
            if instances > MAX_INSTANCES {
                return Err(MeshIoError::TooLarge {
                    path: self.cx.path.to_path_buf(),
                    message: format!(
                        "the node hierarchy instances more than {MAX_INSTANCES} nodes"
                    ),
                });
            }
            let world =
                parent * local_transform(node).map_err(|e| self.error(format!("node {n}: {e}")))?;
            if let Some(m) = node.mesh {
                self.instance(m, world)?;
            }
            on_path[n] = true;
            stack.push((n, parent, true));
            for &c in node.children.iter().rev() {
                if c >= root.nodes.len() {
                    return Err(self.error(format!(
                        "node {n} names child {c}, but the file has {} nodes",
                        root.nodes.len()
                    )));
                }
                stack.push((c, world, false));
            }
        }
        Ok(())
    }
}

/// A node's local transform: its matrix, or translation · rotation · scale.
fn local_transform(node: &json::Node) -> Result<DMat4, String> {
    let m = match node.matrix {
        Some(m) => DMat4::from_cols_array(&m),
        None => {
            let t = DVec3::from(node.translation.unwrap_or([0.0; 3]));
            let [x, y, z, w] = node.rotation.unwrap_or([0.0, 0.0, 0.0, 1.0]);
            let q = DQuat::from_xyzw(x, y, z, w);
            let q = if q.length_squared() > 0.0 {
                q.normalize()
            } else {
                DQuat::IDENTITY
            };
            let s = DVec3::from(node.scale.unwrap_or([1.0; 3]));
            DMat4::from_scale_rotation_translation(s, q, t)
        }
    };
    if !m.is_finite() {
        return Err("its transform is not finite".into());
    }
    Ok(m)
}

pub(crate) fn read_gltf(bytes: &[u8], cx: &mut ReadContext<'_>) -> Result<Model, MeshIoError> {
    let error = |path: &std::path::Path, message: String| MeshIoError::Gltf {
        path: path.to_path_buf(),
        message,
    };
    let parts = container::split(bytes).map_err(|e| error(cx.path, e))?;
    let root = container::document(parts.json).map_err(|e| error(cx.path, e))?;
    if let Some(ext) = root
        .extensions_required
        .iter()
        .find(|e| GEOMETRY_EXTENSIONS.contains(&e.as_str()))
    {
        return Err(error(
            cx.path,
            format!(
                "the file requires {ext} (compressed geometry), which shatter cannot read; export it without compression"
            ),
        ));
    }
    let buffers = container::buffers(cx, &root, parts.bin);
    let mut reader = Reader {
        cx,
        root: &root,
        buffers,
        decoded: HashMap::new(),
        positions: Vec::new(),
        triangles: Vec::new(),
        uv: Vec::new(),
        normal: Vec::new(),
        color: Vec::new(),
        has: [false; 3],
        missing_uv: 0,
        material: Vec::new(),
        skipped_modes: (0, 0),
    };
    let scene = match root.scene {
        Some(s) => Some(root.scenes.get(s).ok_or_else(|| {
            error(
                reader.cx.path,
                format!(
                    "the default scene is {s}, but the file has {} scenes",
                    root.scenes.len()
                ),
            )
        })?),
        None => root.scenes.first(),
    };
    match scene {
        Some(scene) => reader.walk(&scene.nodes)?,
        None => {
            for m in 0..root.meshes.len() {
                reader.instance(m, DMat4::IDENTITY)?;
            }
        }
    }
    finish(reader)
}

fn finish(mut r: Reader<'_, '_>) -> Result<Model, MeshIoError> {
    let (points_lines, unknown) = r.skipped_modes;
    if points_lines > 0 {
        r.cx.warn(
            WarningKind::SkippedElements,
            points_lines,
            format!("skipped {points_lines} point or line primitives"),
        );
    }
    if unknown > 0 {
        r.cx.warn(
            WarningKind::SkippedElements,
            unknown,
            format!("skipped {unknown} primitives of an unknown mode"),
        );
    }
    if r.has[0] && r.missing_uv > 0 {
        r.cx.warn(
            WarningKind::MissingAttribute,
            r.missing_uv,
            format!(
                "{} corners of primitives without TEXCOORD_0 given UV 0, 0",
                r.missing_uv
            ),
        );
    }
    let mesh = TriMesh::new(
        std::mem::take(&mut r.positions),
        std::mem::take(&mut r.triangles),
    );
    if r.has[1] {
        // Primitives without normals: their faces' normals.
        for (t, n) in r.normal.iter_mut().enumerate() {
            if n.iter().all(|c| *c == [0.0; 3]) {
                *n = [mesh
                    .triangle_normal(t)
                    .normalize_or(DVec3::Y)
                    .as_vec3()
                    .to_array(); 3];
            }
        }
    }
    // Materials: the ones triangles use, in order of first use.
    let mut order: HashMap<usize, u32> = HashMap::new();
    let mut used = Vec::new();
    let material: Vec<u32> = r
        .material
        .iter()
        .map(|&m| {
            *order.entry(m).or_insert_with(|| {
                used.push(m);
                (used.len() - 1) as u32
            })
        })
        .collect();
    let mut materials = Materials::new(r.root);
    let materials: Vec<Material> = used
        .iter()
        .map(|&m| {
            if m == usize::MAX {
                default_material()
            } else {
                materials.material(r.cx, &r.buffers, m)
            }
        })
        .collect();
    let corners = Corners {
        uv: r.has[0].then_some(r.uv),
        normal: r.has[1].then_some(r.normal),
        color: r.has[2].then_some(r.color),
    };
    Ok(Model {
        mesh: mesh.welded(),
        corners,
        material,
        materials: if materials.is_empty() {
            vec![default_material()]
        } else {
            materials
        },
    })
}
