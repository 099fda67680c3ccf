//! Conversions between Bevy's meshes and glam 0.32 and shatter's (glam 0.33).

use bevy::asset::RenderAssetUsages;
use bevy::mesh::{Indices, PrimitiveTopology, VertexAttributeValues};
use bevy::prelude::*;
use shatter_geom::mesh::TriMesh;

/// shatter's vector to Bevy's.
pub(crate) fn to_bevy(v: glam::Vec3) -> Vec3 {
    Vec3::from_array(v.to_array())
}

/// Bevy's vector to shatter's.
pub(crate) fn from_bevy(v: Vec3) -> glam::Vec3 {
    glam::Vec3::from_array(v.to_array())
}

/// A Bevy triangle list as a shatter mesh; `None` without positions or triangles.
pub(crate) fn tri_mesh(mesh: &Mesh) -> Option<TriMesh> {
    if mesh.primitive_topology() != PrimitiveTopology::TriangleList {
        return None;
    }
    let Some(VertexAttributeValues::Float32x3(positions)) =
        mesh.attribute(Mesh::ATTRIBUTE_POSITION)
    else {
        return None;
    };
    let positions: Vec<glam::DVec3> = positions
        .iter()
        .map(|p| glam::Vec3::from_array(*p).as_dvec3())
        .collect();
    let indices: Vec<u32> = match mesh.indices() {
        Some(i) => i.iter().map(|i| i as u32).collect(),
        None => (0..positions.len() as u32).collect(),
    };
    let triangles: Vec<[u32; 3]> = indices
        .chunks_exact(3)
        .map(|t| [t[0], t[1], t[2]])
        .collect();
    if triangles.is_empty() {
        return None;
    }
    Some(TriMesh::new(positions, triangles).welded())
}

/// The triangles of `mesh` where `keep` holds, flat-shaded, as a Bevy mesh (`None` if
/// there are none).
pub(crate) fn bevy_mesh(mesh: &TriMesh, keep: impl Fn(usize) -> bool) -> Option<Mesh> {
    let mut positions = Vec::new();
    let mut normals = Vec::new();
    for (t, tri) in mesh.triangles.iter().enumerate() {
        if !keep(t) {
            continue;
        }
        let p = tri.map(|i| mesh.positions[i as usize].as_vec3());
        let n = (p[1] - p[0]).cross(p[2] - p[0]).normalize_or_zero();
        for v in p {
            positions.push(v.to_array());
            normals.push(n.to_array());
        }
    }
    if positions.is_empty() {
        return None;
    }
    let count = positions.len() as u32;
    Some(
        Mesh::new(
            PrimitiveTopology::TriangleList,
            RenderAssetUsages::default(),
        )
        .with_inserted_attribute(Mesh::ATTRIBUTE_POSITION, positions)
        .with_inserted_attribute(Mesh::ATTRIBUTE_NORMAL, normals)
        .with_inserted_indices(Indices::U32((0..count).collect())),
    )
}
