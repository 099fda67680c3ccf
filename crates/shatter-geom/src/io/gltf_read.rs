//! glTF / GLB import through the `gltf` crate.

use std::path::Path;

use glam::{DMat4, DVec3};
use gltf::mesh::Mode;

use super::MeshIoError;
use crate::TriMesh;

/// Deepest node hierarchy followed (guards against cycles in malformed files).
const MAX_DEPTH: usize = 256;

struct Reader<'a> {
    buffers: &'a [gltf::buffer::Data],
    path: &'a Path,
    mesh: TriMesh,
}

impl Reader<'_> {
    fn error(&self, message: String) -> MeshIoError {
        MeshIoError::Gltf {
            path: self.path.to_path_buf(),
            message,
        }
    }

    fn add_node(
        &mut self,
        node: gltf::Node<'_>,
        parent: DMat4,
        depth: usize,
    ) -> Result<(), MeshIoError> {
        if depth > MAX_DEPTH {
            return Err(self.error(format!("node hierarchy deeper than {MAX_DEPTH}")));
        }
        let local = node.transform().matrix().map(|c| c.map(f64::from));
        let world = parent * DMat4::from_cols_array_2d(&local);
        if let Some(mesh) = node.mesh() {
            self.add_mesh(&mesh, world)?;
        }
        for child in node.children() {
            self.add_node(child, world, depth + 1)?;
        }
        Ok(())
    }

    fn add_mesh(&mut self, mesh: &gltf::Mesh<'_>, world: DMat4) -> Result<(), MeshIoError> {
        let mirror = world.determinant() < 0.0;
        for primitive in mesh.primitives() {
            let mode = primitive.mode();
            if !matches!(
                mode,
                Mode::Triangles | Mode::TriangleStrip | Mode::TriangleFan
            ) {
                continue;
            }
            let buffers = self.buffers;
            let reader = primitive.reader(|b| buffers.get(b.index()).map(|d| &d.0[..]));
            let Some(positions) = reader.read_positions() else {
                return Err(self.error(format!(
                    "mesh {} primitive {} has no readable POSITION",
                    mesh.index(),
                    primitive.index()
                )));
            };
            let offset = self.mesh.positions.len();
            let count = positions.len();
            self.mesh.positions.extend(positions.map(|p| {
                world.transform_point3(DVec3::new(
                    f64::from(p[0]),
                    f64::from(p[1]),
                    f64::from(p[2]),
                ))
            }));
            let indices: Vec<u32> = match reader.read_indices() {
                Some(ix) => ix.into_u32().collect(),
                None => (0..count as u32).collect(),
            };
            if let Some(&bad) = indices.iter().find(|&&i| i as usize >= count) {
                return Err(self.error(format!(
                    "mesh {} primitive {} references vertex {bad} of {count}",
                    mesh.index(),
                    primitive.index()
                )));
            }
            let base = u32::try_from(offset).map_err(|_| self.error("too many vertices".into()))?;
            let mut push = |t: [u32; 3]| {
                let t = t.map(|i| i + base);
                self.mesh
                    .triangles
                    .push(if mirror { [t[0], t[2], t[1]] } else { t });
            };
            match mode {
                Mode::TriangleStrip => {
                    for (k, w) in indices.windows(3).enumerate() {
                        push(if k % 2 == 0 {
                            [w[0], w[1], w[2]]
                        } else {
                            [w[1], w[0], w[2]]
                        });
                    }
                }
                Mode::TriangleFan => {
                    for w in indices.get(1..).unwrap_or(&[]).windows(2) {
                        push([indices[0], w[0], w[1]]);
                    }
                }
                _ => {
                    for t in indices.chunks_exact(3) {
                        push([t[0], t[1], t[2]]);
                    }
                }
            }
        }
        Ok(())
    }
}

pub(crate) fn read_gltf(
    bytes: &[u8],
    path: &Path,
    base: Option<&Path>,
) -> Result<TriMesh, MeshIoError> {
    let error = |message: String| MeshIoError::Gltf {
        path: path.to_path_buf(),
        message,
    };
    let gltf = gltf::Gltf::from_slice(bytes).map_err(|e| error(e.to_string()))?;
    let buffers = gltf::import_buffers(&gltf.document, base, gltf.blob.clone())
        .map_err(|e| error(format!("buffers: {e}")))?;
    let mut reader = Reader {
        buffers: &buffers,
        path,
        mesh: TriMesh::default(),
    };
    let doc = &gltf.document;
    match doc.default_scene().or_else(|| doc.scenes().next()) {
        Some(scene) => {
            for node in scene.nodes() {
                reader.add_node(node, DMat4::IDENTITY, 0)?;
            }
        }
        None => {
            for mesh in doc.meshes() {
                reader.add_mesh(&mesh, DMat4::IDENTITY)?;
            }
        }
    }
    if let Some(v) = reader.mesh.positions.iter().position(|p| !p.is_finite()) {
        return Err(error(format!("vertex {v} has a non-finite coordinate")));
    }
    Ok(reader.mesh)
}
