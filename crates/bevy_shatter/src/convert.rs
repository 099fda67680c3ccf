//! Conversions between Bevy's meshes and glam 0.32 and shatter's (glam 0.33).

#[cfg(feature = "avian")]
use bevy::asset::RenderAssetUsages;
#[cfg(feature = "avian")]
use bevy::mesh::{Indices, PrimitiveTopology, VertexAttributeValues};
use bevy::prelude::*;
#[cfg(feature = "avian")]
use shatter_geom::mesh::TriMesh;
#[cfg(feature = "avian")]
use shatter_geom::model::{Corners, Material, Model};

/// shatter's vector (glam 0.33) to Bevy's (glam 0.32).
pub fn to_bevy(v: glam::Vec3) -> Vec3 {
    Vec3::from_array(v.to_array())
}

/// Bevy's vector (glam 0.32) to shatter's (glam 0.33).
pub fn from_bevy(v: Vec3) -> glam::Vec3 {
    glam::Vec3::from_array(v.to_array())
}

/// shatter's rotation (glam 0.33) to Bevy's (glam 0.32).
pub fn quat_to_bevy(q: glam::Quat) -> Quat {
    Quat::from_array(q.to_array())
}

#[cfg(feature = "avian")]
/// A Bevy triangle list as a shatter model: the positions welded into one surface (Bevy's
/// shapes repeat a corner per face), the mesh's `UV_0` and normals kept per triangle
/// corner, one material. The fragments then carry the entity's texture mapping, so its
/// own material draws them as it drew the whole. `None` without positions or triangles.
pub(crate) fn model(mesh: &Mesh) -> Option<Model> {
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
    if triangles.is_empty()
        || triangles
            .iter()
            .flatten()
            .any(|&i| i as usize >= positions.len())
    {
        return None;
    }
    // A vertex attribute as per-corner values, when there is one per vertex.
    fn per_corner<T: Copy>(values: &[T], n: usize, triangles: &[[u32; 3]]) -> Option<Vec<[T; 3]>> {
        (values.len() == n).then(|| {
            triangles
                .iter()
                .map(|t| t.map(|i| values[i as usize]))
                .collect()
        })
    }
    let n = positions.len();
    let uv = match mesh.attribute(Mesh::ATTRIBUTE_UV_0) {
        Some(VertexAttributeValues::Float32x2(uv)) => per_corner(uv, n, &triangles),
        _ => None,
    };
    let normal = match mesh.attribute(Mesh::ATTRIBUTE_NORMAL) {
        Some(VertexAttributeValues::Float32x3(normals)) => per_corner(normals, n, &triangles),
        _ => None,
    };
    let count = triangles.len();
    let model = Model {
        mesh: TriMesh::new(positions, triangles).welded(),
        corners: Corners {
            uv,
            normal,
            color: None,
        },
        material: vec![0; count],
        materials: vec![Material::default()],
    };
    // Non-finite UVs or normals: fracture the shape alone rather than fail.
    if model.check().is_err() {
        return Some(Model::from_mesh(model.mesh));
    }
    Some(model)
}

#[cfg(feature = "avian")]
/// The triangles of `mesh` where `keep` holds as a Bevy mesh (`None` if there are
/// none): with the corners' UVs where the fragment has them, and their normals where
/// `smooth` (the surface), else flat-shaded.
pub(crate) fn bevy_mesh(
    mesh: &TriMesh,
    corners: &Corners,
    smooth: bool,
    keep: impl Fn(usize) -> bool,
) -> Option<Mesh> {
    let mut positions = Vec::new();
    let mut normals = Vec::new();
    let mut uvs = Vec::new();
    for (t, tri) in mesh.triangles.iter().enumerate() {
        if !keep(t) {
            continue;
        }
        let p = tri.map(|i| mesh.positions[i as usize].as_vec3());
        let flat = (p[1] - p[0])
            .cross(p[2] - p[0])
            .normalize_or_zero()
            .to_array();
        let n = match &corners.normal {
            Some(list) if smooth => list[t],
            _ => [flat; 3],
        };
        for (k, v) in p.into_iter().enumerate() {
            positions.push(v.to_array());
            normals.push(n[k]);
        }
        if let Some(uv) = &corners.uv {
            uvs.extend_from_slice(&uv[t]);
        }
    }
    if positions.is_empty() {
        return None;
    }
    let count = positions.len() as u32;
    let out = Mesh::new(
        PrimitiveTopology::TriangleList,
        RenderAssetUsages::default(),
    )
    .with_inserted_attribute(Mesh::ATTRIBUTE_POSITION, positions)
    .with_inserted_attribute(Mesh::ATTRIBUTE_NORMAL, normals)
    .with_inserted_indices(Indices::U32((0..count).collect()));
    Some(if uvs.is_empty() {
        out
    } else {
        out.with_inserted_attribute(Mesh::ATTRIBUTE_UV_0, uvs)
    })
}
