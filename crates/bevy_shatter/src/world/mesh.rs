//! Render meshes for fragments.
//!
//! Every triangle gets its own three vertices (so normals are per face, never smoothed
//! across the sharp edges of a fragment) and a vertex colour: the object's colour on the
//! original surface, a darker shade on interior (cut) faces.
//!
//! A fragment of a file's model (one with materials) is drawn as the file looks instead:
//! one part per material, with the corners' UVs, the file's normals on its surface
//! (smooth where it is smooth), its vertex colours, and the material's base colour and
//! texture ([`FlatPart`]).

use bevy::asset::RenderAssetUsages;
use bevy::mesh::{Mesh, PrimitiveTopology};
use shatter_geom::TriMesh;
use shatter_geom::fracture::Fragment;
use shatter_geom::model::Material;

/// Flat-shaded vertex data of one fragment.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct FlatMesh {
    /// Three positions per triangle.
    pub positions: Vec<[f32; 3]>,
    /// The face normal, repeated for the triangle's three vertices.
    pub normals: Vec<[f32; 3]>,
    /// Linear RGBA colour per vertex.
    pub colors: Vec<[f32; 4]>,
    /// Texture coordinates per vertex (glTF's convention, which Bevy shares), or empty.
    pub uvs: Vec<[f32; 2]>,
}

/// The triangles of one fragment drawn with one material.
#[derive(Debug, Clone, PartialEq)]
pub struct FlatPart {
    /// The file's material and its index in the fracture's list; `None`: the object's
    /// colour, carried by the vertex colours.
    pub material: Option<(u32, Material)>,
    /// The vertices.
    pub mesh: FlatMesh,
}

/// `fragment` as parts to draw: one per material of `materials` (the fracture's list)
/// that its triangles use, or, when the list is empty (a built-in shape), one part in
/// `color` as [`flat_mesh`] draws it.
pub fn fragment_parts(
    fragment: &Fragment,
    color: [f32; 3],
    materials: &[Material],
) -> Vec<FlatPart> {
    if materials.is_empty() || fragment.material.len() != fragment.mesh.triangles.len() {
        return vec![FlatPart {
            material: None,
            mesh: flat_mesh(fragment, color),
        }];
    }
    let mut by_material: std::collections::BTreeMap<u32, Vec<usize>> = Default::default();
    for (t, &m) in fragment.material.iter().enumerate() {
        by_material.entry(m).or_default().push(t);
    }
    let corners = &fragment.corners;
    by_material
        .into_iter()
        .map(|(m, tris)| {
            let mut mesh = FlatMesh::for_triangles(tris.len(), corners.uv.is_some());
            for t in tris {
                let [a, b, c] = fragment.mesh.triangle(t);
                let face = face_normal(a, b, c);
                let interior = fragment.interior.get(t).copied().unwrap_or(false);
                let normals = match &corners.normal {
                    Some(list) if !interior => list[t],
                    _ => [face; 3],
                };
                let colors = corners.color.as_ref().map_or([[1.0; 4]; 3], |list| list[t]);
                for (k, p) in [a, b, c].into_iter().enumerate() {
                    mesh.positions.push(p.as_vec3().to_array());
                    mesh.normals.push(normals[k]);
                    mesh.colors.push(colors[k]);
                }
                if let Some(uv) = &corners.uv {
                    mesh.uvs.extend_from_slice(&uv[t]);
                }
            }
            let material = materials.get(m as usize).cloned().map(|mat| (m, mat));
            FlatPart { material, mesh }
        })
        .collect()
}

impl FlatMesh {
    /// Empty, with room for `triangles` triangles (and their UVs when `uvs`).
    fn for_triangles(triangles: usize, uvs: bool) -> FlatMesh {
        let n = 3 * triangles;
        FlatMesh {
            positions: Vec::with_capacity(n),
            normals: Vec::with_capacity(n),
            colors: Vec::with_capacity(n),
            uvs: Vec::with_capacity(if uvs { n } else { 0 }),
        }
    }
}

/// The unit normal of triangle `a b c` (counter-clockwise from outside); +Y for a
/// degenerate one rather than NaN.
fn face_normal(a: glam::DVec3, b: glam::DVec3, c: glam::DVec3) -> [f32; 3] {
    (b - a)
        .cross(c - a)
        .try_normalize()
        .unwrap_or(glam::DVec3::Y)
        .as_vec3()
        .to_array()
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
    let mut out = FlatMesh::for_triangles(mesh.triangles.len(), false);
    let surface = color;
    let inner = shatter_geom::io::interior_color_of(color);
    for t in 0..mesh.triangles.len() {
        let [a, b, c] = mesh.triangle(t);
        let normal = face_normal(a, b, c);
        let is_interior = interior.get(t).copied().unwrap_or(false);
        let col = if is_interior { inner } else { surface };
        for p in [a, b, c] {
            out.positions.push(p.as_vec3().to_array());
            out.normals.push(normal);
            out.colors.push([col[0], col[1], col[2], 1.0]);
        }
    }
    out
}

/// A Bevy mesh from flat vertex data (kept in main memory too, for nothing else needs it).
pub fn to_bevy_mesh(flat: FlatMesh) -> Mesh {
    let mesh = Mesh::new(
        PrimitiveTopology::TriangleList,
        RenderAssetUsages::RENDER_WORLD,
    )
    .with_inserted_attribute(Mesh::ATTRIBUTE_POSITION, flat.positions)
    .with_inserted_attribute(Mesh::ATTRIBUTE_NORMAL, flat.normals)
    .with_inserted_attribute(Mesh::ATTRIBUTE_COLOR, flat.colors);
    if flat.uvs.is_empty() {
        mesh
    } else {
        mesh.with_inserted_attribute(Mesh::ATTRIBUTE_UV_0, flat.uvs)
    }
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
            convex_hulls: vec![],
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
    fn a_file_models_fragment_is_drawn_per_material_with_its_uvs_and_normals() {
        let mut frag = tetra(1);
        frag.material = vec![0, 1, 0, 0];
        let uv = |t: usize| [[t as f32, 0.0], [t as f32, 0.5], [t as f32, 1.0]];
        frag.corners.uv = Some((0..4).map(uv).collect());
        let smooth = [[0.0, 1.0, 0.0]; 3];
        frag.corners.normal = Some(vec![smooth; 4]);
        let materials = [Material::named("skin"), Material::named("interior")];
        let parts = fragment_parts(&frag, [0.8, 0.6, 0.4], &materials);
        assert_eq!(parts.len(), 2);
        let (m0, skin) = parts[0].material.clone().unwrap();
        assert_eq!((m0, skin.name.as_str()), (0, "skin"));
        assert_eq!(parts[1].material.as_ref().unwrap().0, 1);
        // Triangles 0, 2, 3 in the first part, with their own UVs, in order.
        assert_eq!(parts[0].mesh.positions.len(), 9);
        assert_eq!(parts[0].mesh.uvs.len(), 9);
        assert_eq!(parts[0].mesh.uvs[3..6], uv(2));
        assert_eq!(parts[1].mesh.uvs[..], uv(1));
        // The file's normals on the surface; the interior face flat, outward.
        assert!(parts[0].mesh.normals.iter().all(|n| *n == smooth[0]));
        let n = glam::Vec3::from_array(parts[1].mesh.normals[0]);
        let p = glam::Vec3::from_array(parts[1].mesh.positions[0]);
        assert!(n.dot(p - glam::Vec3::splat(0.25)) > 0.0 && n != glam::Vec3::Y);
        // No colour in the file: white, so the material's colour and texture show.
        assert!(parts[0].mesh.colors.iter().all(|c| *c == [1.0; 4]));
    }

    #[test]
    fn a_built_in_shape_is_one_part_in_the_objects_colour() {
        let frag = tetra(1);
        let parts = fragment_parts(&frag, [0.8, 0.6, 0.4], &[]);
        assert_eq!(parts.len(), 1);
        assert!(parts[0].material.is_none());
        assert_eq!(parts[0].mesh, flat_mesh(&frag, [0.8, 0.6, 0.4]));
        assert!(parts[0].mesh.uvs.is_empty());
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
