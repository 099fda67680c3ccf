//! The repair's working state: welded positions, triangles, and per triangle its corner
//! attributes and material, kept side by side so that every step (drop, flip, split,
//! add) carries a triangle's attributes along with it.

use glam::DVec3;

use crate::TriMesh;
use crate::model::{Corners, Model};

/// A triangle soup with per-corner attributes and a material per triangle.
#[derive(Debug, Clone, Default)]
pub(super) struct Soup {
    /// Positions (welded as the steps go).
    pub pos: Vec<DVec3>,
    /// Triangles, indices into `pos`.
    pub tris: Vec<[u32; 3]>,
    /// Per triangle: corner attributes (each present vector has one entry per triangle).
    pub corners: Corners,
    /// Per triangle: material index.
    pub material: Vec<u32>,
}

/// The attributes of one new corner.
#[derive(Debug, Clone, Copy, Default)]
pub(super) struct Corner {
    pub uv: [f32; 2],
    pub normal: [f32; 3],
    pub color: [f32; 4],
}

impl Corner {
    /// The weighted sum `Σ w_i · c_i`.
    pub fn mix(parts: &[(f64, Corner)]) -> Corner {
        let mut out = Corner::default();
        for &(w, c) in parts {
            let w = w as f32;
            for k in 0..2 {
                out.uv[k] += w * c.uv[k];
            }
            for k in 0..3 {
                out.normal[k] += w * c.normal[k];
            }
            for k in 0..4 {
                out.color[k] += w * c.color[k];
            }
        }
        out
    }
}

impl Soup {
    /// The soup of a model (positions as they are; the weld comes next).
    pub fn from_model(model: &Model) -> Soup {
        Soup {
            pos: model.mesh.positions.clone(),
            tris: model.mesh.triangles.clone(),
            corners: model.corners.clone(),
            material: model.material.clone(),
        }
    }

    /// The model of the soup, with `materials`; unused positions are dropped.
    pub fn into_model(self, materials: Vec<crate::model::Material>) -> Model {
        let mut map = vec![u32::MAX; self.pos.len()];
        let mut positions = Vec::new();
        let triangles = self
            .tris
            .iter()
            .map(|t| {
                t.map(|i| {
                    let m = &mut map[i as usize];
                    if *m == u32::MAX {
                        *m = positions.len() as u32;
                        positions.push(self.pos[i as usize]);
                    }
                    *m
                })
            })
            .collect();
        Model {
            mesh: TriMesh::new(positions, triangles),
            corners: self.corners,
            material: self.material,
            materials,
        }
    }

    /// The mesh of the triangles (all positions).
    pub fn mesh(&self) -> TriMesh {
        TriMesh::new(self.pos.clone(), self.tris.clone())
    }

    /// Corner `k` of triangle `t`'s attributes (zeros where absent).
    pub fn corner(&self, t: usize, k: usize) -> Corner {
        Corner {
            uv: self.corners.uv.as_ref().map_or([0.0; 2], |v| v[t][k]),
            normal: self.corners.normal.as_ref().map_or([0.0; 3], |v| v[t][k]),
            color: self.corners.color.as_ref().map_or([0.0; 4], |v| v[t][k]),
        }
    }

    /// Keeps the triangles `keep` selects, in that order.
    pub fn select(&mut self, keep: &[usize]) {
        self.tris = keep.iter().map(|&t| self.tris[t]).collect();
        self.corners = self.corners.select(keep);
        self.material = keep.iter().map(|&t| self.material[t]).collect();
    }

    /// Keeps the triangles for which `keep` is true.
    pub fn retain(&mut self, keep: &[bool]) {
        let chosen: Vec<usize> = (0..self.tris.len()).filter(|&t| keep[t]).collect();
        if chosen.len() != self.tris.len() {
            self.select(&chosen);
        }
    }

    /// Reverses triangle `t`'s winding (its attributes' corners swap with it; normals
    /// that disagree with the new winding are turned, those that agree are kept, so a
    /// triangle wound against its stored normals gets them right).
    pub fn flip(&mut self, t: usize) {
        self.tris[t].swap(1, 2);
        let face = self.face_normal(t);
        if let Some(v) = &mut self.corners.uv {
            v[t].swap(1, 2);
        }
        if let Some(v) = &mut self.corners.color {
            v[t].swap(1, 2);
        }
        if let Some(v) = &mut self.corners.normal {
            v[t].swap(1, 2);
            for n in &mut v[t] {
                let d = face.dot(DVec3::new(
                    f64::from(n[0]),
                    f64::from(n[1]),
                    f64::from(n[2]),
                ));
                if d < 0.0 {
                    *n = n.map(|c| -c);
                }
            }
        }
    }

    /// Unnormalised right-hand normal of triangle `t`.
    pub fn face_normal(&self, t: usize) -> DVec3 {
        let [a, b, c] = self.tris[t].map(|i| self.pos[i as usize]);
        (b - a).cross(c - a)
    }

    /// Appends triangle `tri` with the corners' attributes and `material`. Normals, if
    /// the soup has them, are the given ones.
    pub fn push(&mut self, tri: [u32; 3], corners: [Corner; 3], material: u32) {
        self.tris.push(tri);
        self.material.push(material);
        if let Some(v) = &mut self.corners.uv {
            v.push(corners.map(|c| c.uv));
        }
        if let Some(v) = &mut self.corners.normal {
            v.push(corners.map(|c| c.normal));
        }
        if let Some(v) = &mut self.corners.color {
            v.push(corners.map(|c| c.color));
        }
    }

    /// Signed volume of the triangles `tris` select (about `origin`).
    pub fn volume_of(&self, tris: &[u32], origin: DVec3) -> f64 {
        tris.iter()
            .map(|&t| {
                let [a, b, c] = self.tris[t as usize].map(|i| self.pos[i as usize] - origin);
                a.dot(b.cross(c))
            })
            .sum::<f64>()
            / 6.0
    }
}

/// Key of an undirected edge.
pub(super) fn edge_key(a: u32, b: u32) -> u64 {
    (u64::from(a.min(b)) << 32) | u64::from(a.max(b))
}
