//! Models: what a user's mesh file holds beyond positions — per-corner UVs, normals and
//! colours, a material per triangle, and the materials with their textures.
//!
//! A [`Model`] is a [`TriMesh`] plus [`Corners`] (attributes per triangle corner, so a
//! seam — one position, two UVs — stays a seam: topology welds by position, attributes
//! stay per corner) and a material index per triangle into [`Model::materials`].
//!
//! Conventions:
//! - UVs are in glTF's convention: origin at the image's top-left corner, `v` down. The
//!   OBJ reader and writer convert (`v' = 1 − v`).
//! - Normals are unit vectors in the mesh's frame; colours are linear RGBA.
//! - Every per-triangle vector (`Corners`' attributes and [`Model::material`]) has one
//!   entry per triangle of [`Model::mesh`], in triangle order.
//!
//! ```
//! use shatter_geom::model::{Corners, Material, Model};
//! use shatter_geom::shapes;
//!
//! let model = Model::from_mesh(shapes::cube());
//! assert_eq!(model.material.len(), 12);
//! assert_eq!(model.materials.len(), 1);
//! assert!(model.corners.uv.is_none());
//! model.check().unwrap();
//! ```

mod material;

pub use material::{Image, ImageFormat, Material, Texture};

use serde::{Deserialize, Serialize};

use crate::TriMesh;

/// Attributes per triangle corner: entry `t` holds the values at corners `0, 1, 2` of
/// triangle `t` (in the triangle's winding order). `None`: the model has no such
/// attribute.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct Corners {
    /// Texture coordinates (TEXCOORD_0), glTF convention (`v` down).
    pub uv: Option<Vec<[[f32; 2]; 3]>>,
    /// Unit normals.
    pub normal: Option<Vec<[[f32; 3]; 3]>>,
    /// Linear RGBA colours (COLOR_0).
    pub color: Option<Vec<[[f32; 4]; 3]>>,
}

impl Corners {
    /// The attributes of the triangles `keep` selects (in that order).
    pub fn select(&self, keep: &[usize]) -> Corners {
        fn pick<T: Copy>(v: &Option<Vec<T>>, keep: &[usize]) -> Option<Vec<T>> {
            v.as_ref().map(|v| keep.iter().map(|&t| v[t]).collect())
        }
        Corners {
            uv: pick(&self.uv, keep),
            normal: pick(&self.normal, keep),
            color: pick(&self.color, keep),
        }
    }

    /// Reverses the winding of triangle `t`'s attributes as [`TriMesh::flipped`] does
    /// its corners (corners 1 and 2 swap).
    pub fn flip(&mut self, t: usize) {
        if let Some(v) = &mut self.uv {
            v[t].swap(1, 2);
        }
        if let Some(v) = &mut self.normal {
            v[t].swap(1, 2);
            for n in &mut v[t] {
                *n = n.map(|c| -c);
            }
        }
        if let Some(v) = &mut self.color {
            v[t].swap(1, 2);
        }
    }

    /// Lengths of the attributes that are present, with their names.
    fn lengths(&self) -> impl Iterator<Item = (&'static str, usize)> {
        [
            ("uv", self.uv.as_ref().map(Vec::len)),
            ("normal", self.normal.as_ref().map(Vec::len)),
            ("color", self.color.as_ref().map(Vec::len)),
        ]
        .into_iter()
        .filter_map(|(name, len)| Some((name, len?)))
    }
}

/// A triangle mesh with per-corner attributes and materials (see the module docs).
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct Model {
    /// Positions and triangles.
    pub mesh: TriMesh,
    /// Attributes per triangle corner.
    pub corners: Corners,
    /// Per triangle: its material, an index into `materials`.
    pub material: Vec<u32>,
    /// The materials (at least one when there are triangles).
    pub materials: Vec<Material>,
}

/// Why a [`Model`]'s parts do not fit together.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ModelError {
    /// A per-triangle attribute has the wrong length.
    #[error("{attribute} has {len} entries for {triangles} triangles")]
    Length {
        /// Which attribute (`uv`, `normal`, `color`, `material`).
        attribute: &'static str,
        /// Its length.
        len: usize,
        /// The number of triangles.
        triangles: usize,
    },
    /// A triangle names a material that does not exist.
    #[error("triangle {triangle} has material {material}, but there are {materials} materials")]
    Material {
        /// The triangle.
        triangle: usize,
        /// Its material index.
        material: u32,
        /// The number of materials.
        materials: usize,
    },
    /// An attribute value is NaN or infinite.
    #[error("{attribute} of triangle {triangle} is not finite")]
    NotFinite {
        /// Which attribute.
        attribute: &'static str,
        /// The triangle.
        triangle: usize,
    },
}

impl Model {
    /// A model of `mesh` alone: no corner attributes, every triangle of one default
    /// material ([`Material::default`]).
    pub fn from_mesh(mesh: TriMesh) -> Model {
        let n = mesh.triangles.len();
        Model {
            mesh,
            corners: Corners::default(),
            material: vec![0; n],
            materials: vec![Material::default()],
        }
    }

    /// Checks that every per-triangle vector has one entry per triangle, every material
    /// index exists and every attribute value is finite. (The mesh itself is checked by
    /// [`TriMesh::check`] and [`TriMesh::validate_solid`].)
    pub fn check(&self) -> Result<(), ModelError> {
        let triangles = self.mesh.triangles.len();
        let material = ("material", self.material.len());
        for (attribute, len) in self.corners.lengths().chain(std::iter::once(material)) {
            if len != triangles {
                return Err(ModelError::Length {
                    attribute,
                    len,
                    triangles,
                });
            }
        }
        if let Some((triangle, &material)) = self
            .material
            .iter()
            .enumerate()
            .find(|&(_, &m)| m as usize >= self.materials.len())
        {
            return Err(ModelError::Material {
                triangle,
                material,
                materials: self.materials.len(),
            });
        }
        fn finite<const N: usize>(
            v: &Option<Vec<[[f32; N]; 3]>>,
            attribute: &'static str,
        ) -> Result<(), ModelError> {
            let Some(v) = v else { return Ok(()) };
            match v
                .iter()
                .position(|c| c.iter().flatten().any(|x| !x.is_finite()))
            {
                Some(triangle) => Err(ModelError::NotFinite {
                    attribute,
                    triangle,
                }),
                None => Ok(()),
            }
        }
        finite(&self.corners.uv, "uv")?;
        finite(&self.corners.normal, "normal")?;
        finite(&self.corners.color, "color")
    }

    /// The model with only the triangles `keep` selects (in that order); positions are
    /// kept as they are (unused ones included).
    pub fn select(&self, keep: &[usize]) -> Model {
        Model {
            mesh: TriMesh::new(
                self.mesh.positions.clone(),
                keep.iter().map(|&t| self.mesh.triangles[t]).collect(),
            ),
            corners: self.corners.select(keep),
            material: keep.iter().map(|&t| self.material[t]).collect(),
            materials: self.materials.clone(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shapes;

    #[test]
    fn check_names_the_attribute_whose_length_is_wrong() {
        let mut m = Model::from_mesh(shapes::cube());
        m.corners.uv = Some(vec![[[0.0; 2]; 3]; 11]);
        let err = m.check().unwrap_err();
        assert_eq!(
            err,
            ModelError::Length {
                attribute: "uv",
                len: 11,
                triangles: 12
            }
        );
    }

    #[test]
    fn check_finds_a_missing_material_and_a_nan() {
        let mut m = Model::from_mesh(shapes::cube());
        m.material[5] = 3;
        assert!(matches!(
            m.check(),
            Err(ModelError::Material { triangle: 5, .. })
        ));
        m.material[5] = 0;
        let mut normals = vec![[[0.0, 1.0, 0.0]; 3]; 12];
        normals[7][2][0] = f32::NAN;
        m.corners.normal = Some(normals);
        assert!(matches!(
            m.check(),
            Err(ModelError::NotFinite {
                attribute: "normal",
                triangle: 7
            })
        ));
    }

    #[test]
    fn flip_swaps_corners_and_turns_normals() {
        let mut c = Corners {
            uv: Some(vec![[[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]]),
            normal: Some(vec![[[0.0, 0.0, 1.0]; 3]]),
            color: None,
        };
        c.flip(0);
        assert_eq!(
            c.uv.as_ref().unwrap()[0],
            [[0.0, 0.0], [0.0, 1.0], [1.0, 0.0]]
        );
        assert_eq!(c.normal.as_ref().unwrap()[0][1], [0.0, 0.0, -1.0]);
    }

    #[test]
    fn select_keeps_the_chosen_triangles_attributes_in_order() {
        let mut m = Model::from_mesh(shapes::cube());
        m.corners.uv = Some((0..12).map(|t| [[t as f32, 0.0]; 3]).collect());
        m.material = (0..12).map(|t| t % 2).collect();
        m.materials.push(Material::named("second"));
        let s = m.select(&[7, 2]);
        assert_eq!(
            s.mesh.triangles,
            vec![m.mesh.triangles[7], m.mesh.triangles[2]]
        );
        assert_eq!(s.corners.uv.as_ref().unwrap()[0][0][0], 7.0);
        assert_eq!(s.material, vec![1, 0]);
        s.check().unwrap();
    }
}
