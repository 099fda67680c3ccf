//! The animated GLB re-imports with the `gltf` crate: right node, mesh, animation channel
//! and keyframe counts, and the keyframe values that were written.
#![allow(clippy::unwrap_used)]

use gltf::animation::util::ReadOutputs;
use shatter_report::export::{AnimatedNode, AnimatedScene, FragmentMesh, Pose, animated_glb_bytes};
use shatter_report::record::RunRecorder;

fn tetra(name: &str, interior_faces: bool) -> FragmentMesh {
    let mut m = FragmentMesh::new(
        name,
        vec![[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
        vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]],
        [0.8, 0.3, 0.2],
    );
    if interior_faces {
        m.interior = vec![false, false, true, true];
    }
    m
}

/// Node `k` falls from height `k` and turns about y.
fn pose(k: usize, t: f32) -> Pose {
    let half = 0.5 * t;
    Pose::new(
        [k as f32, k as f32 - 4.9 * t * t, 0.0],
        [0.0, half.sin(), 0.0, half.cos()],
    )
}

fn scene(nodes: usize, times: usize) -> AnimatedScene {
    let times: Vec<f32> = (0..times).map(|i| i as f32 / 30.0).collect();
    AnimatedScene {
        meshes: vec![tetra("surface only", false), tetra("with cut faces", true)],
        nodes: (0..nodes)
            .map(|k| AnimatedNode {
                name: format!("fragment_{k}"),
                mesh: k % 2,
                poses: times.iter().map(|&t| pose(k, t)).collect(),
                // The last node vanishes half-way.
                visible: if k + 1 == nodes {
                    (0..times.len()).map(|i| i < times.len() / 2).collect()
                } else {
                    vec![]
                },
            })
            .collect(),
        times,
    }
}

#[test]
fn the_glb_reimports_with_its_nodes_channels_and_keyframes() {
    let (nodes, times) = (5, 12);
    let scene = scene(nodes, times);
    let bytes = animated_glb_bytes(&scene).unwrap();
    let (doc, buffers, _) = gltf::import_slice(&bytes).unwrap();

    assert_eq!(doc.nodes().count(), nodes);
    assert_eq!(doc.meshes().count(), 2);
    assert_eq!(doc.scenes().next().unwrap().nodes().count(), nodes);
    let names: Vec<&str> = doc.nodes().map(|n| n.name().unwrap()).collect();
    assert_eq!(names[3], "fragment_3");

    let animations: Vec<_> = doc.animations().collect();
    assert_eq!(animations.len(), 1);
    let channels: Vec<_> = animations[0].channels().collect();
    // Translation and rotation per node, plus scale for the node that vanishes.
    assert_eq!(channels.len(), 2 * nodes + 1);

    for channel in &channels {
        let node = channel.target().node().index();
        let reader = channel.reader(|b| Some(&buffers[b.index()]));
        let inputs: Vec<f32> = reader.read_inputs().unwrap().collect();
        assert_eq!(inputs, scene.times, "node {node} keyframe times");
        match reader.read_outputs().unwrap() {
            ReadOutputs::Translations(it) => {
                let v: Vec<[f32; 3]> = it.collect();
                assert_eq!(v.len(), times);
                for (i, t) in v.iter().enumerate() {
                    assert_eq!(*t, scene.nodes[node].poses[i].translation);
                }
            }
            ReadOutputs::Rotations(r) => {
                let v: Vec<[f32; 4]> = r.into_f32().collect();
                assert_eq!(v.len(), times);
                for (i, q) in v.iter().enumerate() {
                    let expected = scene.nodes[node].poses[i].rotation;
                    let dot: f32 = (0..4).map(|c| q[c] * expected[c]).sum();
                    assert!((dot.abs() - 1.0).abs() < 1e-5, "node {node} rotation {i}");
                }
            }
            ReadOutputs::Scales(it) => {
                assert_eq!(node, nodes - 1);
                let v: Vec<[f32; 3]> = it.collect();
                assert_eq!(v.len(), times);
                assert_eq!(v[0], [1.0; 3]);
                assert_eq!(v[times - 1], [0.0; 3]);
                assert_eq!(
                    channel.sampler().interpolation(),
                    gltf::animation::Interpolation::Step
                );
            }
            ReadOutputs::MorphTargetWeights(_) => panic!("no morph targets were written"),
        }
    }
}

#[test]
fn meshes_keep_their_triangles_and_interior_faces_get_their_own_material() {
    let bytes = animated_glb_bytes(&scene(2, 3)).unwrap();
    let (doc, buffers, _) = gltf::import_slice(&bytes).unwrap();
    let meshes: Vec<_> = doc.meshes().collect();
    assert_eq!(meshes[0].primitives().count(), 1);
    let cut: Vec<_> = meshes[1].primitives().collect();
    assert_eq!(cut.len(), 2);
    assert_ne!(cut[0].material().index(), cut[1].material().index());
    let mut triangles = 0;
    for p in meshes[1].primitives() {
        let reader = p.reader(|b| Some(&buffers[b.index()]));
        let positions: Vec<[f32; 3]> = reader.read_positions().unwrap().collect();
        let indices: Vec<u32> = reader.read_indices().unwrap().into_u32().collect();
        // Flat faces without normals of their own: no NORMAL (a viewer computes flat
        // normals), and each of the tetrahedron's corners is one vertex.
        assert!(reader.read_normals().is_none());
        assert!(positions.len() <= 4);
        assert!(indices.iter().all(|&i| (i as usize) < positions.len()));
        assert_eq!(indices.len() % 3, 0);
        triangles += indices.len() / 3;
    }
    assert_eq!(triangles, 4);
}

#[test]
fn a_recorded_run_exports_one_node_per_fragment_and_a_keyframe_per_sample() {
    let mut rec = RunRecorder::new().with_keyframe_rate(30.0);
    let mesh = rec.add_mesh(tetra("t", true));
    let nodes: Vec<usize> = (0..7)
        .map(|k| rec.add_node(format!("fragment_{k}"), mesh).unwrap())
        .collect();
    for step in 0..90 {
        let t = step as f64 / 60.0;
        let poses = nodes.iter().map(|&k| (k, pose(k, t as f32)));
        rec.record_poses(t, poses).unwrap();
    }
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("run.glb");
    rec.write_glb(&path).unwrap();
    let (doc, buffers, _) = gltf::import(&path).unwrap();
    assert_eq!(doc.nodes().count(), 7);
    let animation = doc.animations().next().unwrap();
    assert_eq!(animation.channels().count(), 14);
    for channel in animation.channels() {
        let reader = channel.reader(|b| Some(&buffers[b.index()]));
        assert_eq!(reader.read_inputs().unwrap().count(), 45);
    }
}

#[test]
fn an_invalid_scene_is_refused_before_writing() {
    let mut s = scene(2, 3);
    s.nodes[1].poses.pop();
    let err = animated_glb_bytes(&s).unwrap_err();
    assert!(
        err.to_string()
            .contains("node 1 'fragment_1' has 2 poses for 3 times")
    );
}
