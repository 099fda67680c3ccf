//! What an animated export holds, and its validation.

use crate::ReportError;

/// A fragment's (or projectile's) mesh in its own local frame.
#[derive(Debug, Clone, PartialEq)]
pub struct FragmentMesh {
    /// Name of the mesh in the file.
    pub name: String,
    /// Vertex positions in the local frame.
    pub positions: Vec<[f32; 3]>,
    /// Triangles, wound counter-clockwise seen from outside.
    pub triangles: Vec<[u32; 3]>,
    /// Per triangle: `true` for an interior (cut) face, drawn with `interior_color`.
    /// Empty means every face is on the surface.
    pub interior: Vec<bool>,
    /// Linear RGB colour of the surface faces, each channel in `0..=1`.
    pub color: [f32; 3],
    /// Linear RGB colour of the interior faces.
    pub interior_color: [f32; 3],
}

impl FragmentMesh {
    /// A mesh whose faces are all surface faces, in one colour.
    pub fn new(
        name: impl Into<String>,
        positions: Vec<[f32; 3]>,
        triangles: Vec<[u32; 3]>,
        color: [f32; 3],
    ) -> Self {
        Self {
            name: name.into(),
            positions,
            triangles,
            interior: Vec::new(),
            color,
            interior_color: shatter_geom::io::interior_color_of(color),
        }
    }
}

/// A rigid placement: `world = translation + rotation · local`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Pose {
    /// Translation.
    pub translation: [f32; 3],
    /// Rotation as a unit quaternion `[x, y, z, w]` (the glTF order).
    pub rotation: [f32; 4],
}

impl Pose {
    /// No translation, no rotation.
    pub const IDENTITY: Pose = Pose {
        translation: [0.0; 3],
        rotation: [0.0, 0.0, 0.0, 1.0],
    };

    /// A pose from a translation and a quaternion `[x, y, z, w]`.
    pub fn new(translation: [f32; 3], rotation: [f32; 4]) -> Self {
        Self {
            translation,
            rotation,
        }
    }
}

/// One animated node: a mesh and its pose at every sample time of the scene.
#[derive(Debug, Clone, PartialEq)]
pub struct AnimatedNode {
    /// Name of the node (shown in Blender's outliner).
    pub name: String,
    /// Index into [`AnimatedScene::meshes`].
    pub mesh: usize,
    /// Pose at each of [`AnimatedScene::times`] (same length).
    pub poses: Vec<Pose>,
    /// Whether the node exists at each time (same length), or empty for "always".
    /// A hidden node is scaled to zero (a `STEP` scale channel), so fragments removed
    /// during the run (lifetime, debris cap) vanish in viewers.
    pub visible: Vec<bool>,
}

/// A whole animated export: sample times shared by all nodes, meshes and nodes.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct AnimatedScene {
    /// Sample times in seconds: finite, at least 0, strictly increasing. Empty for a
    /// still scene (nodes then have no poses and sit at the identity).
    pub times: Vec<f32>,
    /// The meshes (a node refers to one by index; several nodes may share one).
    pub meshes: Vec<FragmentMesh>,
    /// The nodes, each keyframed at every time.
    pub nodes: Vec<AnimatedNode>,
}

impl AnimatedScene {
    /// Checks every index, length and value; the first problem is reported.
    pub fn validate(&self) -> Result<(), ReportError> {
        let bad = |m: String| Err(ReportError::Scene(m));
        for (i, &t) in self.times.iter().enumerate() {
            if !t.is_finite() || t < 0.0 {
                return bad(format!("time {i} is {t}; times must be finite and >= 0"));
            }
            if i > 0 && t <= self.times[i - 1] {
                return bad(format!(
                    "time {i} ({t}) is not after time {} ({}); times must increase",
                    i - 1,
                    self.times[i - 1]
                ));
            }
        }
        for (m, mesh) in self.meshes.iter().enumerate() {
            if mesh.triangles.is_empty() {
                return bad(format!("mesh {m} '{}' has no triangles", mesh.name));
            }
            if let Some(v) = mesh.positions.iter().position(|p| !all_finite(p)) {
                return bad(format!("mesh {m} vertex {v} is not finite"));
            }
            let n = mesh.positions.len();
            for (t, tri) in mesh.triangles.iter().enumerate() {
                if let Some(&i) = tri.iter().find(|&&i| i as usize >= n) {
                    return bad(format!(
                        "mesh {m} triangle {t} uses vertex {i} but there are {n} vertices"
                    ));
                }
            }
            if !mesh.interior.is_empty() && mesh.interior.len() != mesh.triangles.len() {
                return bad(format!(
                    "mesh {m} has {} interior flags for {} triangles",
                    mesh.interior.len(),
                    mesh.triangles.len()
                ));
            }
            if !all_finite(&mesh.color) || !all_finite(&mesh.interior_color) {
                return bad(format!("mesh {m} has a non-finite colour"));
            }
        }
        for (k, node) in self.nodes.iter().enumerate() {
            if node.mesh >= self.meshes.len() {
                return bad(format!(
                    "node {k} '{}' uses mesh {} but there are {} meshes",
                    node.name,
                    node.mesh,
                    self.meshes.len()
                ));
            }
            if node.poses.len() != self.times.len() {
                return bad(format!(
                    "node {k} '{}' has {} poses for {} times",
                    node.name,
                    node.poses.len(),
                    self.times.len()
                ));
            }
            if !node.visible.is_empty() && node.visible.len() != self.times.len() {
                return bad(format!(
                    "node {k} '{}' has {} visibility flags for {} times",
                    node.name,
                    node.visible.len(),
                    self.times.len()
                ));
            }
            for (i, pose) in node.poses.iter().enumerate() {
                let q = pose.rotation;
                let norm2: f32 = q.iter().map(|c| c * c).sum();
                if !all_finite(&pose.translation) || !all_finite(&q) || norm2 < 1e-12 {
                    return bad(format!(
                        "node {k} '{}' pose {i} is not finite or has a zero rotation",
                        node.name
                    ));
                }
            }
        }
        Ok(())
    }
}

fn all_finite(v: &[f32]) -> bool {
    v.iter().all(|c| c.is_finite())
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;

    fn tetra() -> FragmentMesh {
        FragmentMesh::new(
            "t",
            vec![[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
            vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]],
            [0.8, 0.2, 0.2],
        )
    }

    fn scene() -> AnimatedScene {
        AnimatedScene {
            times: vec![0.0, 0.5],
            meshes: vec![tetra()],
            nodes: vec![AnimatedNode {
                name: "n".into(),
                mesh: 0,
                poses: vec![Pose::IDENTITY; 2],
                visible: vec![],
            }],
        }
    }

    fn message(s: &AnimatedScene) -> String {
        s.validate().unwrap_err().to_string()
    }

    #[test]
    fn a_consistent_scene_validates() {
        scene().validate().unwrap();
    }

    #[test]
    fn times_must_increase() {
        let mut s = scene();
        s.times = vec![0.5, 0.5];
        assert!(message(&s).contains("time 1 (0.5) is not after time 0"));
    }

    #[test]
    fn a_bad_triangle_index_is_named() {
        let mut s = scene();
        s.meshes[0].triangles[2] = [0, 9, 2];
        assert!(message(&s).contains("mesh 0 triangle 2 uses vertex 9 but there are 4"));
    }

    #[test]
    fn pose_count_must_match_times() {
        let mut s = scene();
        s.nodes[0].poses.pop();
        assert!(message(&s).contains("has 1 poses for 2 times"));
    }

    #[test]
    fn a_bad_mesh_index_is_named() {
        let mut s = scene();
        s.nodes[0].mesh = 3;
        assert!(message(&s).contains("uses mesh 3 but there are 1 meshes"));
    }

    #[test]
    fn a_zero_quaternion_is_refused() {
        let mut s = scene();
        s.nodes[0].poses[1].rotation = [0.0; 4];
        assert!(message(&s).contains("pose 1"));
    }
}
