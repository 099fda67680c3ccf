//! The animated export of a run (`--export RUN.glb`): a node per fragment of every object
//! and per projectile, keyframed at a fixed rate.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use shatter_geom::TriMesh;
use shatter_report::export::{FragmentMesh, Pose as KeyPose};
use shatter_report::record::RunRecorder;
use shatter_sim::{ObjectId, Pose, ProjectileSpec, World};

use crate::error::{LabError, ResultExt};

/// What `--export` wrote.
#[derive(Debug, Clone, serde::Serialize)]
pub struct ExportSummary {
    /// The GLB file.
    pub path: PathBuf,
    /// Nodes in the file (fragments + projectiles).
    pub nodes: usize,
    /// Nodes that are fragments (one per fragment of every object).
    pub fragment_nodes: usize,
    /// Nodes that are projectiles (one per projectile in flight at some keyframe).
    pub projectile_nodes: usize,
    /// Keyframes per node.
    pub keyframes: usize,
}

/// The animated export of a run: a node per fragment of every object (registered at
/// the start) and per projectile (registered at the first keyframe it is in flight).
pub struct RunExport {
    recorder: RunRecorder,
    /// Per object: its id and the node of each fragment, in fragment order.
    objects: Vec<(ObjectId, Vec<usize>)>,
    /// Per projectile seen in flight, by firing order ([`shatter_sim::ProjectileView::index`]):
    /// its node.
    projectiles: BTreeMap<usize, usize>,
    fragment_nodes: usize,
}

impl RunExport {
    /// Registers every fragment of every object of `world` and records the initial
    /// keyframe (time 0); `fps` keyframes per simulated second (0: one per step).
    pub fn new(world: &World, fps: f64) -> Result<Self, LabError> {
        let mut recorder = RunRecorder::new().with_keyframe_rate(fps);
        let mut objects = Vec::new();
        let mut fragment_nodes = 0;
        for id in world.object_ids() {
            let Some(fracture) = world.object_fracture(id) else {
                continue;
            };
            let colour = world.object_color(id).unwrap_or([0.8; 3]);
            let name = world
                .object_spec(id)
                .map(|s| s.name.trim().to_string())
                .filter(|n| !n.is_empty())
                .unwrap_or_else(|| format!("object_{}", id.0));
            let mut nodes = Vec::with_capacity(fracture.fragments.len());
            for (f, fragment) in fracture.fragments.iter().enumerate() {
                let mut mesh =
                    fragment_mesh(format!("{name}/fragment_{f}"), &fragment.mesh, colour);
                if fragment.interior.len() == fragment.mesh.triangles.len() {
                    mesh.interior = fragment.interior.clone();
                }
                let m = recorder.add_mesh(mesh);
                let node = recorder.add_node(format!("{name}/fragment_{f}"), m);
                nodes.push(node.map_err(|e| LabError::input(crate::error::chain(&e)))?);
            }
            fragment_nodes += nodes.len();
            objects.push((id, nodes));
        }
        let mut export = Self {
            recorder,
            objects,
            projectiles: BTreeMap::new(),
            fragment_nodes,
        };
        export.observe(world, false)?;
        Ok(export)
    }

    /// Records a keyframe of every fragment and projectile when the rate asks for one,
    /// or when `last` (the final state). A projectile that flies only between two
    /// keyframes gets no node.
    pub fn observe(&mut self, world: &World, last: bool) -> Result<(), LabError> {
        let time = world.stats().time;
        let keyframe =
            self.recorder.wants_keyframe(time) || (last && self.recorder.can_record_at(time));
        if !keyframe {
            return Ok(());
        }
        let mut poses = self.track_projectiles(world)?;
        for (id, nodes) in &self.objects {
            for (f, pose) in world.fragment_poses(*id) {
                if let Some(&node) = nodes.get(f as usize) {
                    poses.push((node, key_pose(&pose)));
                }
            }
        }
        self.recorder
            .record_keyframe(time, poses)
            .input_err("recording the --export animation")
    }

    /// The poses of the projectiles in flight; one seen for the first time gets its
    /// node (named after its firing order).
    fn track_projectiles(&mut self, world: &World) -> Result<Vec<(usize, KeyPose)>, LabError> {
        let mut poses = Vec::new();
        for view in world.projectiles() {
            let node = match self.projectiles.get(&view.index) {
                Some(&node) => node,
                None => {
                    let name = format!("projectile_{}", view.index);
                    let mesh = self
                        .recorder
                        .add_mesh(projectile_mesh(name.clone(), view.spec));
                    let node = self
                        .recorder
                        .add_node(name, mesh)
                        .map_err(|e| LabError::input(crate::error::chain(&e)))?;
                    self.projectiles.insert(view.index, node);
                    node
                }
            };
            poses.push((node, key_pose(&view.pose)));
        }
        Ok(poses)
    }

    /// Writes the GLB file to `temp`, for `path`.
    pub fn write(self, temp: &Path, path: &Path) -> Result<ExportSummary, LabError> {
        self.recorder
            .write_glb(temp)
            .input_err(format!("cannot write --export {}", path.display()))?;
        Ok(ExportSummary {
            path: path.to_path_buf(),
            nodes: self.recorder.node_count(),
            fragment_nodes: self.fragment_nodes,
            projectile_nodes: self.projectiles.len(),
            keyframes: self.recorder.keyframe_count(),
        })
    }
}

fn key_pose(p: &Pose) -> KeyPose {
    KeyPose::new(p.translation.to_array(), p.rotation.to_array())
}

/// A mesh for the export, in `f32`.
fn fragment_mesh(name: String, mesh: &TriMesh, colour: [f32; 3]) -> FragmentMesh {
    FragmentMesh::new(
        name,
        mesh.positions
            .iter()
            .map(|p| p.as_vec3().to_array())
            .collect(),
        mesh.triangles.clone(),
        colour,
    )
}

/// The projectile's shape as a mesh in its body's frame, sized like its collider.
fn projectile_mesh(name: String, spec: &ProjectileSpec) -> FragmentMesh {
    fragment_mesh(name, &spec.shape.mesh(spec.size), spec.color)
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;
    use shatter_geom::DVec3;
    use shatter_sim::ProjectileShape;

    #[test]
    fn projectile_meshes_have_the_collider_size() {
        let spec = |shape| ProjectileSpec {
            shape,
            size: 0.4,
            ..ProjectileSpec::default()
        };
        let extent = |m: &FragmentMesh| {
            let mut lo = [f32::INFINITY; 3];
            let mut hi = [f32::NEG_INFINITY; 3];
            for p in &m.positions {
                for k in 0..3 {
                    lo[k] = lo[k].min(p[k]);
                    hi[k] = hi[k].max(p[k]);
                }
            }
            [0, 1, 2].map(|k| hi[k] - lo[k])
        };
        // The round shapes are polygons: their width across flats is a little smaller.
        let close = |a: [f32; 3], b: [f32; 3]| (0..3).all(|k| (a[k] - b[k]).abs() < 5e-3);
        let cube = projectile_mesh("c".into(), &spec(ProjectileShape::Cube));
        assert!(close(extent(&cube), [0.4; 3]), "{:?}", extent(&cube));
        let capsule = projectile_mesh("c".into(), &spec(ProjectileShape::Capsule));
        assert!(
            close(extent(&capsule), [0.2, 0.4, 0.2]),
            "{:?}",
            extent(&capsule)
        );
        let cylinder = projectile_mesh("c".into(), &spec(ProjectileShape::Cylinder));
        assert!(
            close(extent(&cylinder), [0.4, 0.4, 0.4]),
            "{:?}",
            extent(&cylinder)
        );
        let custom = ProjectileShape::Custom(vec![DVec3::ZERO, DVec3::new(1.0, 2.0, 0.5)]);
        let custom = projectile_mesh("c".into(), &spec(custom));
        assert!(
            close(extent(&custom), [0.4, 0.8, 0.2]),
            "{:?}",
            extent(&custom)
        );
    }
}
