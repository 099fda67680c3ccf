//! What the writers export: named meshes with per-triangle surface / interior flags.

use super::MeshIoError;
use crate::TriMesh;

/// One object to export: a named mesh whose triangles are flagged surface or interior
/// (cut faces of a fragment). Writers give each kind its own material.
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

impl<'a> ExportObject<'a> {
    /// An object whose triangles are all surface.
    pub fn new(name: &'a str, mesh: &'a TriMesh) -> Self {
        Self {
            name,
            mesh,
            interior: None,
        }
    }

    /// With per-triangle interior flags.
    pub fn with_interior(self, interior: &'a [bool]) -> Self {
        Self {
            interior: Some(interior),
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

    /// Checks flags length and indices.
    pub(crate) fn validate(&self) -> Result<(), MeshIoError> {
        let triangles = self.mesh.triangles.len();
        if let Some(flags) = self.interior
            && flags.len() != triangles
        {
            return Err(MeshIoError::InteriorFlags {
                object: self.name.to_string(),
                flags: flags.len(),
                triangles,
            });
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
