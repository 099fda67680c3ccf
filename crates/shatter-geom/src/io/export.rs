//! What the writers export: named meshes whose triangles are flagged surface or interior,
//! optionally with a material per triangle (over a material list shared by all objects)
//! and attributes per corner.

use super::MeshIoError;
use crate::TriMesh;
use crate::fracture::Fragment;
use crate::model::{Corners, Material, Model};

/// One object to export: a named mesh whose triangles are flagged surface or interior
/// (cut faces of a fragment), optionally with per-triangle materials and per-corner
/// attributes.
///
/// Materials: with [`with_materials`](Self::with_materials) each triangle names its
/// material in the list handed to the writer ([`write_glb_with_materials`](super::write_glb_with_materials),
/// [`save_obj_with_materials`](super::save_obj_with_materials)); without, surface
/// triangles get the list's first material and interior ones the `interior` material
/// (the writers add one when the list has none).
///
/// ```
/// use shatter_geom::{io::ExportObject, shapes};
/// let cube = shapes::cube();
/// let flags = vec![false; 12];
/// let obj = ExportObject::new("fragment_0", &cube).with_interior(&flags);
/// assert_eq!(obj.name, "fragment_0");
/// ```
#[derive(Debug, Clone, Copy)]
pub struct ExportObject<'a> {
    /// Object name (whitespace is replaced by `_` in OBJ files).
    pub name: &'a str,
    /// The mesh.
    pub mesh: &'a TriMesh,
    /// Per triangle: `true` for an interior (cut) face. `None`: all surface.
    pub interior: Option<&'a [bool]>,
    /// Per triangle: its material, an index into the writer's material list.
    pub material: Option<&'a [u32]>,
    /// Per-corner attributes (UVs, normals, colours), one entry per triangle.
    pub corners: Option<&'a Corners>,
}

/// The object names of a fracture's `n` fragments in exported files: `fragment_0`, ….
pub fn fragment_names(n: usize) -> Vec<String> {
    (0..n).map(|i| format!("fragment_{i}")).collect()
}

/// Material names used by the writers.
pub const SURFACE_MATERIAL: &str = "surface";
/// Material of interior (cut) faces.
pub const INTERIOR_MATERIAL: &str = "interior";
/// Base colours (linear RGB) of the two materials: a light grey surface and a
/// terracotta interior.
pub const SURFACE_COLOR: [f32; 3] = [0.8, 0.8, 0.8];
/// Base colour of interior faces.
pub const INTERIOR_COLOR: [f32; 3] = [0.8, 0.35, 0.2];

/// How much of an object's own colour its cut faces keep ([`interior_color_of`]).
pub const INTERIOR_SHADE: f32 = 0.45;

/// The colour of the cut faces of an object that has a colour of its own (linear RGB in
/// `[0, 1]`; the sandbox's objects, a recorded run): darker, and pulled slightly towards
/// a neutral grey so cut faces read as raw material. The one rule for it; a file's
/// fragments without a colour of their own take [`INTERIOR_COLOR`].
///
/// ```
/// use shatter_geom::io::interior_color_of;
/// let [r, g, b] = interior_color_of([1.0, 0.0, 0.0]);
/// assert!((r - 0.49).abs() < 1e-6 && g == 0.04 && b == 0.04);
/// ```
pub fn interior_color_of(surface: [f32; 3]) -> [f32; 3] {
    surface.map(|c| (c * INTERIOR_SHADE + 0.04).min(1.0))
}

impl<'a> ExportObject<'a> {
    /// An object whose triangles are all surface.
    pub fn new(name: &'a str, mesh: &'a TriMesh) -> Self {
        Self {
            name,
            mesh,
            interior: None,
            material: None,
            corners: None,
        }
    }

    /// A model's mesh with its materials (indices into `model.materials`, which is the
    /// list to hand the writer) and corner attributes.
    ///
    /// ```
    /// use shatter_geom::{io::{self, ExportObject}, model::Model, shapes};
    /// let model = Model::from_mesh(shapes::cube());
    /// let mut glb = Vec::new();
    /// io::write_glb_with_materials(&mut glb, &[ExportObject::of_model("cube", &model)], &model.materials)
    ///     .unwrap();
    /// let doc = gltf::Gltf::from_slice(&glb).unwrap();
    /// // The model's one material, and the `interior` material the writer adds.
    /// assert_eq!(doc.materials().count(), 2);
    /// ```
    pub fn of_model(name: &'a str, model: &'a Model) -> Self {
        Self::new(name, &model.mesh)
            .with_materials(&model.material)
            .with_corners(&model.corners)
    }

    /// A fracture's fragment: its mesh, interior flags, corner attributes and (when it
    /// has one per triangle) its materials, indices into the fracture's `materials`.
    pub fn of_fragment(name: &'a str, fragment: &'a Fragment) -> Self {
        let o = Self::new(name, &fragment.mesh)
            .with_interior(&fragment.interior)
            .with_corners(&fragment.corners);
        if fragment.material.len() == fragment.mesh.triangles.len() {
            o.with_materials(&fragment.material)
        } else {
            o
        }
    }

    /// A fracture's fragments, named by `names` (see [`fragment_names`]).
    pub fn of_fragments(fragments: &'a [Fragment], names: &'a [String]) -> Vec<Self> {
        fragments
            .iter()
            .zip(names)
            .map(|(f, name)| Self::of_fragment(name, f))
            .collect()
    }

    /// With per-triangle interior flags.
    pub fn with_interior(self, interior: &'a [bool]) -> Self {
        Self {
            interior: Some(interior),
            ..self
        }
    }

    /// With a material per triangle (indices into the writer's material list).
    pub fn with_materials(self, material: &'a [u32]) -> Self {
        Self {
            material: Some(material),
            ..self
        }
    }

    /// With per-corner attributes.
    pub fn with_corners(self, corners: &'a Corners) -> Self {
        Self {
            corners: Some(corners),
            ..self
        }
    }

    /// Whether triangle `t` is interior.
    pub(crate) fn is_interior(&self, t: usize) -> bool {
        self.interior
            .and_then(|f| f.get(t))
            .copied()
            .unwrap_or(false)
    }

    /// Checks flags, materials and attributes against the triangles, and the indices.
    pub(crate) fn validate(&self, materials: usize) -> Result<(), MeshIoError> {
        let triangles = self.mesh.triangles.len();
        let bad = |message: String| MeshIoError::BadObject {
            object: self.name.to_string(),
            message,
        };
        if let Some(flags) = self.interior
            && flags.len() != triangles
        {
            return Err(MeshIoError::InteriorFlags {
                object: self.name.to_string(),
                flags: flags.len(),
                triangles,
            });
        }
        if let Some(m) = self.material {
            if m.len() != triangles {
                return Err(bad(format!(
                    "{} material indices for {triangles} triangles",
                    m.len()
                )));
            }
            if let Some((t, &i)) = m
                .iter()
                .enumerate()
                .find(|&(_, &i)| i as usize >= materials)
            {
                return Err(bad(format!(
                    "triangle {t} has material {i}, but there are {materials} materials"
                )));
            }
        }
        if let Some(c) = self.corners {
            for (name, len) in [
                ("uv", c.uv.as_ref().map(Vec::len)),
                ("normal", c.normal.as_ref().map(Vec::len)),
                ("color", c.color.as_ref().map(Vec::len)),
            ] {
                if let Some(len) = len
                    && len != triangles
                {
                    return Err(bad(format!(
                        "{len} {name} entries for {triangles} triangles"
                    )));
                }
            }
            let finite = |v: &[f32]| v.iter().all(|x| x.is_finite());
            let ok = c.uv.iter().flatten().all(|t| t.iter().all(|x| finite(x)))
                && c.normal
                    .iter()
                    .flatten()
                    .all(|t| t.iter().all(|x| finite(x)))
                && c.color
                    .iter()
                    .flatten()
                    .all(|t| t.iter().all(|x| finite(x)));
            if !ok {
                return Err(bad("an attribute value is not finite".into()));
            }
        }
        let vertices = self.mesh.positions.len();
        for (triangle, tri) in self.mesh.triangles.iter().enumerate() {
            if let Some(&index) = tri.iter().find(|&&i| i as usize >= vertices) {
                return Err(MeshIoError::BadIndex {
                    object: self.name.to_string(),
                    triangle,
                    index,
                    vertices,
                });
            }
        }
        Ok(())
    }
}

/// The material list a writer writes, and which entry interior faces without a
/// material of their own take.
pub(crate) struct ExportMaterials {
    pub list: Vec<Material>,
    pub interior: u32,
}

impl ExportMaterials {
    /// `given`, or the default `surface` / `interior` pair; an `interior` material is
    /// appended when the list has none.
    pub fn new(given: Option<&[Material]>) -> ExportMaterials {
        let mut list = match given {
            Some(m) if !m.is_empty() => m.to_vec(),
            _ => {
                let mut surface = Material::named(SURFACE_MATERIAL);
                surface.base_color[..3].copy_from_slice(&SURFACE_COLOR);
                surface.roughness = 0.8;
                vec![surface]
            }
        };
        let interior = match list.iter().position(|m| m.name == INTERIOR_MATERIAL) {
            Some(i) => i,
            None => {
                let mut m = Material::named(INTERIOR_MATERIAL);
                m.base_color[..3].copy_from_slice(&INTERIOR_COLOR);
                m.roughness = 0.8;
                list.push(m);
                list.len() - 1
            }
        };
        ExportMaterials {
            list,
            interior: interior as u32,
        }
    }

    /// The material of triangle `t` of `o`.
    pub fn of(&self, o: &ExportObject<'_>, t: usize) -> u32 {
        match o.material {
            Some(m) => m[t],
            None if o.is_interior(t) => self.interior,
            None => 0,
        }
    }

    /// Validates every object against this list.
    pub fn validate(&self, objects: &[ExportObject<'_>]) -> Result<(), MeshIoError> {
        objects.iter().try_for_each(|o| o.validate(self.list.len()))
    }
}
