//! The app's bridge to the simulation, without a window: the commands the panels send
//! reach the real `shatter-sim` world and have the effects the user expects.
#![allow(clippy::unwrap_used)]

use glam::Vec3;
use shatter_app::commands::{
    BondModel, FractureSource, MaterialPreset, MethodKind, ObjectId, ObjectSpec, Pattern,
    ProjectileSpec, Shape, SimCommand,
};
use shatter_app::sim_bridge::{
    PieceOwner, SandboxWorld, ShatterWorld, check_custom_mesh, load_projectile,
};
use shatter_app::ui::forms::AddObjectForm;
use shatter_sim::FractureParams;

fn steps(b: &mut ShatterWorld, n: usize) {
    for _ in 0..n {
        assert!(b.step_once(), "the world should be running");
    }
}

/// The params of a shape cut into `pieces` uniform Voronoi cells.
fn voronoi(pieces: u32) -> FractureParams {
    FractureParams {
        method: Some(MethodKind::Voronoi),
        pattern: Some(Pattern::Uniform),
        pieces,
        ..FractureParams::default()
    }
}

fn cube_spec(position: Vec3) -> ObjectSpec {
    ObjectSpec {
        break_force: Some(500.0),
        color: [0.2, 0.5, 0.8],
        material: MaterialPreset::Stone.material(),
        position,
        ..ObjectSpec::new(
            "cube",
            FractureSource::Shape {
                shape: Shape::Cube,
                params: voronoi(12),
            },
        )
    }
}

fn empty_world() -> ShatterWorld {
    ShatterWorld::sandbox(shatter_sim::World::new(Default::default()))
}

fn fire_at_wall(b: &mut ShatterWorld, speed: f32) {
    b.apply(SimCommand::Fire(ProjectileSpec {
        speed,
        from: Vec3::new(0.3, 1.2, 6.0),
        to: Vec3::new(0.3, 1.2, 0.0),
        ..ProjectileSpec::default()
    }))
    .unwrap();
}

#[test]
fn default_scene_is_the_bundled_file_with_every_object() {
    let b = ShatterWorld::default_scene();
    let s = b.stats();
    // Wall 16×10×2 bricks, bird 40 radial cells, glass pane 30 radial cells (the tiny
    // cells at the impact point merge into neighbours), crate 4×4×4.
    let ids = b.world().object_ids();
    assert_eq!(ids.len(), 4);
    let count = |i: usize| b.world().object_fracture(ids[i]).unwrap().fragments.len();
    assert_eq!(count(0), 320);
    assert!((20..=40).contains(&count(1)), "bird: {}", count(1));
    assert!((15..=30).contains(&count(2)), "pane: {}", count(2));
    assert_eq!(count(3), 64);
    assert_eq!(s.fragments, (0..4).map(count).sum::<usize>());
    assert!(s.bonds_total > 1000, "{s:?}");
    assert_eq!(s.bonds_broken, 0);
    assert!(!s.running);
    // Every piece has a mesh.
    let poses = b.poses();
    assert_eq!(poses.len(), s.fragments);
    for p in poses.iter().step_by(37) {
        let parts = b.piece_parts(p.key).unwrap();
        assert_eq!(parts.len(), 1, "a built-in shape is drawn in one part");
        let mesh = &parts[0].mesh;
        assert!(!mesh.positions.is_empty());
        assert_eq!(mesh.positions.len() % 3, 0);
        assert_eq!(mesh.positions.len(), mesh.colors.len());
    }
}

#[test]
fn a_fast_shot_breaks_the_wall_and_a_slow_one_does_not() {
    let mut slow = ShatterWorld::default_scene();
    slow.apply(SimCommand::Start).unwrap();
    steps(&mut slow, 10);
    fire_at_wall(&mut slow, 2.0);
    steps(&mut slow, 120);
    assert_eq!(slow.stats().bonds_broken, 0, "{:?}", slow.stats());

    let mut fast = ShatterWorld::default_scene();
    fast.apply(SimCommand::Start).unwrap();
    steps(&mut fast, 10);
    fire_at_wall(&mut fast, 40.0);
    // The projectile is drawn.
    assert!(
        fast.poses()
            .iter()
            .any(|p| matches!(p.key.owner, PieceOwner::Projectile(_)))
    );
    steps(&mut fast, 30);
    let s = fast.stats();
    assert!(s.bonds_broken > 0, "{s:?}");
    assert!(s.bodies > 5, "the wall split into several bodies: {s:?}");
}

#[test]
fn reset_puts_everything_back_and_replaces_the_meshes() {
    let mut b = ShatterWorld::default_scene();
    let initial: Vec<_> = b
        .poses()
        .iter()
        .map(|p| (p.translation, p.rotation))
        .collect();
    let key = b.poses()[0].key;
    b.apply(SimCommand::Start).unwrap();
    fire_at_wall(&mut b, 40.0);
    steps(&mut b, 40);
    assert!(b.stats().bonds_broken > 0);
    b.apply(SimCommand::Reset).unwrap();
    let s = b.stats();
    assert_eq!(s.bonds_broken, 0);
    assert_eq!(s.time, 0.0);
    assert!(!s.running);
    let after: Vec<_> = b
        .poses()
        .iter()
        .map(|p| (p.translation, p.rotation))
        .collect();
    assert_eq!(initial, after, "reset restores every fragment exactly");
    // Meshes of the old build are stale (projectile keys are reused after a reset).
    assert!(b.piece_parts(key).is_none());
    assert!(b.piece_parts(b.poses()[0].key).is_some());
}

#[test]
fn pause_holds_time_and_resume_continues() {
    let mut b = ShatterWorld::default_scene();
    b.apply(SimCommand::Start).unwrap();
    steps(&mut b, 5);
    b.apply(SimCommand::TogglePause).unwrap();
    assert!(b.stats().paused);
    let t = b.stats().time;
    assert!(!b.step_once());
    b.advance(1.0);
    assert_eq!(b.stats().time, t);
    b.apply(SimCommand::TogglePause).unwrap();
    b.advance(1.0 / 30.0);
    assert!(b.stats().time > t);
}

#[test]
fn advance_runs_fixed_steps_and_never_more_than_the_cap_per_frame() {
    let mut b = ShatterWorld::default_scene();
    b.apply(SimCommand::Start).unwrap();
    b.advance(0.05);
    // 1/60 s steps: three fit in 0.05 s.
    assert_eq!(b.world().stats().steps, 3);
    b.advance(10.0);
    assert_eq!(
        b.world().stats().steps,
        3 + shatter_app::sim_bridge::MAX_STEPS_PER_FRAME as u64
    );
}

#[test]
fn add_edit_delete_and_clean_change_the_world() {
    let mut b = ShatterWorld::default_scene();
    let before = b.stats().fragments;
    let id = b
        .apply(SimCommand::AddObject(Box::new(cube_spec(Vec3::new(
            5.0, 0.5, 0.0,
        )))))
        .unwrap()
        .unwrap();
    let added = b.stats().fragments - before;
    assert!(added >= 12, "12 Voronoi cells: {added}");
    let spec = b.world().object_spec(id).unwrap().clone();
    assert_eq!(spec.source.params().unwrap().pieces, 12);
    assert_eq!(spec.position, Vec3::new(5.0, 0.5, 0.0));
    assert_eq!(
        MaterialPreset::of(&spec.material),
        Some(MaterialPreset::Stone)
    );

    // Edit: 30 tetra random points instead.
    let edited = ObjectSpec {
        source: FractureSource::Shape {
            shape: Shape::Cube,
            params: FractureParams {
                method: Some(MethodKind::Tetra),
                random_vertices: 30,
                ..voronoi(12)
            },
        },
        ..spec
    };
    b.apply(SimCommand::EditObject(id, Box::new(edited)))
        .unwrap();
    let params = b.world().object_spec(id).unwrap().source.params().cloned();
    assert_eq!(params.unwrap().method, Some(MethodKind::Tetra));
    assert_ne!(b.stats().fragments - before, added);

    b.apply(SimCommand::DeleteObject(id)).unwrap();
    assert_eq!(b.stats().fragments, before);
    assert!(b.apply(SimCommand::DeleteObject(id)).is_err());

    b.apply(SimCommand::Clean).unwrap();
    assert_eq!(b.stats().fragments, 0);
    assert!(b.poses().is_empty());
}

#[test]
fn editing_a_scene_object_keeps_what_the_panels_do_not_show() {
    let mut b = ShatterWorld::default_scene();
    // Object 0 is the anchored brick wall, edited through the panels as a user would.
    let wall = b.world().object_spec(ObjectId(0)).unwrap().clone();
    let (mut form, transform) = AddObjectForm::from_spec(&wall);
    assert_eq!(form.method, MethodKind::Grid);
    assert_eq!(form.random_vertices, "16");
    form.color = ["1".into(), "0".into(), "0".into()];
    let edited = form.validate(&transform, &|_| Ok(()), Some(&wall)).unwrap();
    let bricks = b.stats().fragments;
    b.apply(SimCommand::EditObject(ObjectId(0), Box::new(edited)))
        .unwrap();
    assert_eq!(b.stats().fragments, bricks, "same grid");
    let sim = b.world().object_spec(ObjectId(0)).unwrap();
    assert!(sim.anchored, "still anchored");
    assert_eq!(sim.color, [1.0, 0.0, 0.0]);
}

#[test]
fn a_refused_object_changes_nothing_and_says_why() {
    let mut b = ShatterWorld::default_scene();
    let before = b.stats();
    // A mesh file that does not exist: the message names it.
    let err = b
        .apply(SimCommand::AddObject(Box::new(ObjectSpec {
            source: FractureSource::MeshFile {
                path: "no/such/mesh.obj".into(),
                params: voronoi(12),
            },
            ..cube_spec(Vec3::ZERO)
        })))
        .unwrap_err();
    assert!(err.to_string().contains("no/such/mesh.obj"), "{err}");
    assert_eq!(b.stats(), before);
    // A grid of the bird is its cells clipped to it, not a refusal.
    let added = b.apply(SimCommand::AddObject(Box::new(ObjectSpec {
        source: FractureSource::Shape {
            shape: Shape::Bird,
            params: FractureParams {
                method: Some(MethodKind::Grid),
                ..voronoi(12)
            },
        },
        ..cube_spec(Vec3::new(0.0, 3.0, 0.0))
    })));
    assert!(matches!(added, Ok(Some(_))), "{added:?}");
    assert!(b.stats().fragments > before.fragments);
    // An explosion with a negative radius is refused.
    assert!(
        b.apply(SimCommand::Explode {
            position: Vec3::ZERO,
            radius: -1.0,
            power: 10.0
        })
        .unwrap_err()
        .to_string()
        .contains("radius")
    );
}

#[test]
fn an_explosion_breaks_bonds_near_it() {
    let mut b = ShatterWorld::default_scene();
    b.apply(SimCommand::Start).unwrap();
    steps(&mut b, 5);
    // Next to the glass pane at (3, 0.02, 2).
    b.apply(SimCommand::Explode {
        position: Vec3::new(3.0, 0.3, 2.0),
        radius: 2.0,
        power: 800.0,
    })
    .unwrap();
    steps(&mut b, 10);
    assert!(b.stats().bonds_broken > 0, "{:?}", b.stats());
}

#[test]
fn bond_model_choice_applies_to_new_objects() {
    let mut b = ShatterWorld::default_scene();
    b.apply(SimCommand::SetBondModel(BondModel::Joints))
        .unwrap();
    let id = b
        .apply(SimCommand::AddObject(Box::new(cube_spec(Vec3::new(
            5.0, 0.5, 0.0,
        )))))
        .unwrap()
        .unwrap();
    let model = b.world().object_bond_model(id).unwrap();
    assert_eq!(model, shatter_sim::BondModel::Joints);
}

#[test]
fn save_and_load_round_trip_and_a_bad_file_keeps_the_scene() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("scene.toml");
    let mut b = ShatterWorld::default_scene();
    b.apply(SimCommand::AddObject(Box::new(cube_spec(Vec3::new(
        5.0, 0.5, 0.0,
    )))))
    .unwrap();
    let stats = b.stats();
    b.apply(SimCommand::SaveScene(path.clone())).unwrap();

    let mut other = empty_world();
    other.apply(SimCommand::LoadScene(path)).unwrap();
    assert_eq!(other.world().object_ids().len(), 5);
    assert_eq!(other.stats().fragments, stats.fragments);
    assert_eq!(other.stats().bonds_total, stats.bonds_total);

    let bad = dir.path().join("bad.toml");
    std::fs::write(&bad, "[world]\ngravty = 1\n").unwrap();
    let err = other.apply(SimCommand::LoadScene(bad)).unwrap_err();
    assert!(err.to_string().contains("gravty"), "{err}");
    assert_eq!(other.world().object_ids().len(), 5, "the scene stayed");
}

#[test]
fn custom_projectile_and_custom_mesh_checks() {
    let dir = tempfile::tempdir().unwrap();
    let good = dir.path().join("rock.obj");
    std::fs::write(
        &good,
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n",
    )
    .unwrap();
    assert!(check_custom_mesh(&good).is_ok());
    let broken = dir.path().join("broken.obj");
    std::fs::write(&broken, "v 0 0 0\nf 1 2 3\n").unwrap();
    assert!(
        check_custom_mesh(&broken).is_err(),
        "a face with missing vertices"
    );
    assert!(check_custom_mesh(&dir.path().join("none.stl")).is_err());

    let mut b = ShatterWorld::default_scene();
    b.apply(SimCommand::Start).unwrap();
    b.apply(SimCommand::Fire(ProjectileSpec {
        shape: load_projectile(&good).unwrap(),
        from: Vec3::new(8.0, 3.0, 8.0),
        to: Vec3::new(8.0, 3.0, 0.0),
        ..ProjectileSpec::default()
    }))
    .unwrap();
    let key = b
        .poses()
        .into_iter()
        .find(|p| matches!(p.key.owner, PieceOwner::Projectile(_)))
        .unwrap()
        .key;
    // The drawn hull of the tetrahedron: 4 triangles.
    assert_eq!(b.piece_parts(key).unwrap()[0].mesh.positions.len(), 12);
    assert!(load_projectile(&broken).is_err());
}

#[test]
fn keyboard_shortcuts_are_the_scene_controls_and_leave_the_camera_keys_alone() {
    use bevy::prelude::KeyCode;
    use shatter_app::input::shortcut;
    assert_eq!(shortcut(KeyCode::Enter), Some(SimCommand::Start));
    assert_eq!(shortcut(KeyCode::KeyP), Some(SimCommand::TogglePause));
    assert_eq!(shortcut(KeyCode::KeyR), Some(SimCommand::Reset));
    for camera_key in [KeyCode::KeyW, KeyCode::KeyA, KeyCode::KeyS, KeyCode::KeyD] {
        assert_eq!(shortcut(camera_key), None);
    }
}

#[test]
fn the_state_line_the_web_page_reads_is_json_with_the_counts() {
    let mut b = ShatterWorld::default_scene();
    b.apply(SimCommand::Start).unwrap();
    fire_at_wall(&mut b, 40.0);
    steps(&mut b, 30);
    let line = shatter_app::state_log::state_line(&b, 7);
    let json: serde_json::Value =
        serde_json::from_str(line.strip_prefix("SHATTER_STATE ").unwrap()).unwrap();
    let s = b.stats();
    assert_eq!(json["frames"], 7);
    assert_eq!(json["bonds_broken"], s.bonds_broken as u64);
    assert_eq!(json["fragments"], s.fragments as u64);
    assert_eq!(json["running"], true);
}

#[test]
fn every_example_scene_loads_and_the_runtime_one_starts_whole() {
    let mut b = ShatterWorld::default_scene();
    for (name, _) in shatter_app::sim_bridge::EXAMPLE_SCENES {
        b.apply(SimCommand::LoadExample((*name).to_owned()))
            .unwrap_or_else(|e| panic!("{name}: {e}"));
        assert!(b.stats().fragments > 0, "{name} has no fragments");
    }
    b.apply(SimCommand::LoadExample("runtime".into())).unwrap();
    assert_eq!(b.stats().fragments, 2, "the bird and the pane start whole");
    b.apply(SimCommand::Start).unwrap();
    steps(&mut b, 110);
    let s = b.stats();
    assert!(s.runtime_fractures >= 2, "{s:?}");
    assert!(s.fragments > 20);
    let err = b.apply(SimCommand::LoadExample("nope".into())).unwrap_err();
    assert!(
        err.to_string().contains("no example scene `nope`") && err.to_string().contains("runtime"),
        "{err}"
    );
}

/// Issue 13: a Custom object made from a textured file is drawn as the file looks: its
/// fragments come in parts per material, the surface with the file's texture and UVs,
/// the cut faces with the interior material.
#[test]
fn a_textured_custom_object_keeps_its_texture_and_uvs() {
    let mut b = ShatterWorld::default_scene();
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../tests/corpus/gltf/BoxTextured.glb");
    let id = b
        .apply(SimCommand::AddObject(Box::new(ObjectSpec {
            source: FractureSource::MeshFile {
                path: path.display().to_string(),
                params: voronoi(12),
            },
            material: MaterialPreset::Ceramic.material(),
            ..cube_spec(Vec3::new(0.0, 3.0, 4.0))
        })))
        .unwrap()
        .unwrap();
    let keys: Vec<_> = b
        .poses()
        .into_iter()
        .filter(|p| p.key.owner == PieceOwner::Object(id))
        .map(|p| p.key)
        .collect();
    assert!(keys.len() >= 8, "{} fragments", keys.len());
    let (mut textured, mut interior) = (0, 0);
    for key in keys {
        for part in b.piece_parts(key).unwrap() {
            let (_, material) = part.material.expect("a file's fragment names its material");
            let n = part.mesh.positions.len();
            assert_eq!(part.mesh.uvs.len(), n, "every vertex has a UV");
            assert!(part.mesh.uvs.iter().flatten().all(|x| x.is_finite()));
            if material.base_color_texture.is_some() {
                textured += 1;
            } else if material.name == "interior" {
                interior += 1;
            }
        }
    }
    assert!(textured >= 8, "{textured} textured parts");
    assert!(interior >= 8, "{interior} interior parts");
}

#[test]
fn the_textured_example_brings_its_files_and_draws_them_textured() {
    let mut b = ShatterWorld::default_scene();
    b.load_example("textured").unwrap();
    // The files come with the app, under the paths the scene names (the web page has no
    // disk to read them from).
    let files = shatter_app::picked_files::picked_files();
    for (path, bytes) in shatter_app::sim_bridge::EXAMPLE_FILES {
        assert_eq!(files.get(path).as_deref(), Some(*bytes), "{path}");
    }
    let objects: std::collections::BTreeSet<_> =
        b.poses().into_iter().map(|p| p.key.owner).collect();
    assert_eq!(objects.len(), 2, "the spider and the box");
    let mut textured = std::collections::BTreeSet::new();
    for pose in b.poses() {
        for part in b.piece_parts(pose.key).unwrap() {
            if part
                .material
                .as_ref()
                .is_some_and(|(_, m)| m.base_color_texture.is_some())
            {
                textured.insert(pose.key.owner);
            }
        }
    }
    assert_eq!(
        textured, objects,
        "both models are drawn with their textures"
    );
}
