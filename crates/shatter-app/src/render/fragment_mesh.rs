//! Flat-shaded render meshes for fragments.
//!
//! Every triangle gets its own three vertices (so normals are per face, never smoothed
//! across the sharp edges of a fragment) and a vertex colour: the object's colour on the
//! original surface, a darker shade on interior (cut) faces.

use bevy::asset::RenderAssetUsages;
use bevy::mesh::{Mesh, PrimitiveTopology};
use shatter_geom::TriMesh;
use shatter_geom::fracture::Fragment;

/// How much darker interior (cut) faces are than the surface.
pub const INTERIOR_SHADE: f32 = 0.45;

/// Flat-shaded vertex data of one fragment.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct FlatMesh {
    /// Three positions per triangle.
    pub positions: Vec<[f32; 3]>,
    /// The face normal, repeated for the triangle's three vertices.
    pub normals: Vec<[f32; 3]>,
    /// Linear RGBA colour per vertex.
    pub colors: Vec<[f32; 4]>,
}

/// The colour of interior faces for a surface colour (linear RGB in `[0, 1]`).
pub fn interior_color(surface: [f32; 3]) -> [f32; 3] {
    // Darker, and pulled slightly towards a neutral grey so cut faces read as raw material.
    surface.map(|c| (c * INTERIOR_SHADE + 0.04).min(1.0))
}

/// Split `fragment` into flat-shaded triangles coloured by `color` (linear RGB in
/// `[0, 1]`, the simulation's convention).
///
/// Degenerate triangles (zero area) get the normal of +Y rather than NaN.
pub fn flat_mesh(fragment: &Fragment, color: [f32; 3]) -> FlatMesh {
    flat_trimesh(&fragment.mesh, &fragment.interior, color)
}

/// Flat-shaded triangles of any mesh; `interior[t]` marks the triangles drawn in the
/// interior shade (missing entries are surface).
pub fn flat_trimesh(mesh: &TriMesh, interior: &[bool], color: [f32; 3]) -> FlatMesh {
    let n = mesh.triangles.len() * 3;
    let mut out = FlatMesh {
        positions: Vec::with_capacity(n),
        normals: Vec::with_capacity(n),
        colors: Vec::with_capacity(n),
    };
    let surface = color;
    let inner = interior_color(color);
    for t in 0..mesh.triangles.len() {
        let [a, b, c] = mesh.triangle(t);
        let normal = (b - a)
            .cross(c - a)
            .try_normalize()
            .unwrap_or(glam::DVec3::Y);
        let is_interior = interior.get(t).copied().unwrap_or(false);
        let col = if is_interior { inner } else { surface };
        for p in [a, b, c] {
            out.positions.push(p.as_vec3().to_array());
            out.normals.push(normal.as_vec3().to_array());
            out.colors.push([col[0], col[1], col[2], 1.0]);
        }
    }
    out
}

/// A Bevy mesh from flat vertex data (kept in main memory too, for nothing else needs it).
pub fn to_bevy_mesh(flat: FlatMesh) -> Mesh {
    Mesh::new(
        PrimitiveTopology::TriangleList,
        RenderAssetUsages::RENDER_WORLD,
    )
    .with_inserted_attribute(Mesh::ATTRIBUTE_POSITION, flat.positions)
    .with_inserted_attribute(Mesh::ATTRIBUTE_NORMAL, flat.normals)
    .with_inserted_attribute(Mesh::ATTRIBUTE_COLOR, flat.colors)
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::{DMat3, DVec3};

    fn tetra(interior_face: usize) -> Fragment {
        let mesh = TriMesh::new(
            vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z],
            vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]],
        );
        let mut interior = vec![false; 4];
        interior[interior_face] = true;
        Fragment {
            mesh,
            interior,
            corners: Default::default(),
            material: vec![0; 4],
            convex_pieces: vec![],
            volume: 1.0 / 6.0,
            centroid: DVec3::splat(0.25),
            inertia: DMat3::IDENTITY,
        }
    }

    #[test]
    fn every_triangle_gets_its_own_vertices_and_outward_normal() {
        let frag = tetra(3);
        let flat = flat_mesh(&frag, [1.0, 0.0, 0.0]);
        assert_eq!(flat.positions.len(), 12);
        let centroid = glam::Vec3::splat(0.25);
        for tri in 0..4 {
            let n = glam::Vec3::from_array(flat.normals[tri * 3]);
            assert!((n.length() - 1.0).abs() < 1e-5);
            // All three vertices share the face normal (flat shading).
            assert_eq!(flat.normals[tri * 3], flat.normals[tri * 3 + 2]);
            let p = glam::Vec3::from_array(flat.positions[tri * 3]);
            assert!(
                n.dot(p - centroid) > 0.0,
                "normal of face {tri} points inward"
            );
        }
    }

    #[test]
    fn interior_faces_are_darker() {
        let frag = tetra(1);
        let flat = flat_mesh(&frag, [0.8, 0.6, 0.4]);
        let surface = flat.colors[0];
        let interior = flat.colors[3];
        assert_ne!(surface, interior);
        for ch in 0..3 {
            assert!(interior[ch] < surface[ch]);
        }
        // Faces 2 and 3 are surface again.
        assert_eq!(flat.colors[6], surface);
        assert_eq!(flat.colors[9], surface);
    }
}
