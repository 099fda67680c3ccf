//! Scene files: parse errors name key and line; validation; the shipped scenes load.
#![allow(clippy::unwrap_used, missing_docs)]

use std::path::Path;

use shatter_sim::SimError;
use shatter_sim::scene::Scene;

fn err(text: &str) -> String {
    Scene::parse(text).unwrap_err().to_string()
}

#[test]
fn unknown_keys_and_wrong_types_name_key_and_line() {
    let e = err("[world]\ndt = 0.01\n\n[[objects]]\nshape = \"cube\"\ncolour = [1, 0, 0]\n");
    assert!(e.contains("line 6") && e.contains("colour"), "{e}");
    let e = err("[[objects]]\nshape = \"cube\"\nbreak_force = \"strong\"\n");
    assert!(e.contains("line 3") && e.contains("break_force"), "{e}");
    let e = err("[[objects]]\nshape = \"cube\"\nskip = 1.5\n");
    assert!(e.contains("line 3"), "{e}");
}

#[test]
fn invalid_values_name_the_key() {
    let e = err("[[explosions]]\nposition = [0, 0, 0]\nradius = -1.0\npower = 5.0\n");
    assert!(
        e.contains("explosions[0].radius") && e.contains("line 3"),
        "{e}"
    );
    let e = err("[[objects]]\nshape = \"cube\"\npieces = 0\n");
    assert!(
        e.contains("objects[0].pieces") && e.contains("line 3"),
        "{e}"
    );
    let e = err("[[objects]]\nshape = \"cube\"\n\nmaterial = \"cheese\"\n");
    assert!(
        e.contains("objects[0].material") && e.contains("cheese") && e.contains("line 4"),
        "{e}"
    );
    let e = err("[[objects]]\nshape = \"teapot\"\n");
    assert!(
        e.contains("objects[0].shape") && e.contains("teapot"),
        "{e}"
    );
    for bad in ["0", "-3", "2.5", "\"all\""] {
        let e = err(&format!("[world]\nstress_budget = {bad}\n"));
        assert!(
            e.contains("world.stress_budget") && e.contains("line 2") && e.contains("none"),
            "{bad}: {e}"
        );
    }
    for bad in ["-1", "2.5", "\"all\""] {
        let e = err(&format!("[world]\nmax_debris = {bad}\n"));
        assert!(
            e.contains("world.max_debris") && e.contains("line 2") && e.contains("none"),
            "{bad}: {e}"
        );
    }
    for bad in ["-0.1", "nan", "inf", "\"small\""] {
        let e = err(&format!("[world]\ntiny_debris = {bad}\n"));
        assert!(
            e.contains("tiny_debris") && e.contains("line 2"),
            "{bad}: {e}"
        );
    }
    for bad in ["0", "-5", "nan", "inf"] {
        let e = err(&format!("[world]\nmax_launch_speed = {bad}\n"));
        assert!(
            e.contains("world.max_launch_speed") && e.contains("line 2"),
            "{bad}: {e}"
        );
    }
    let e = err("[[projectiles]]\nshape = \"banana\"\nfrom = [0, 0, 1]\nto = [0, 0, 0]\n");
    assert!(e.contains("projectiles[0].shape"), "{e}");
    assert!(matches!(
        Scene::parse("[world\n"),
        Err(SimError::SceneSyntax { line: 1, .. })
    ));
}

fn scenes_dir() -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../assets/scenes")
}

#[test]
fn the_wall_scene_has_two_thousand_fragments_and_a_timed_shot() {
    let scene = Scene::load(&scenes_dir().join("wall.toml")).unwrap();
    assert_eq!(scene.projectiles.len(), 1);
    assert!((scene.projectiles[0].0 - 0.5).abs() < 1e-9);
    let world = scene.build(None).unwrap();
    assert!(world.stats().fragments >= 2000);
}

#[test]
fn every_shipped_scene_builds() {
    for entry in std::fs::read_dir(scenes_dir()).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "toml") {
            let scene = Scene::load(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
            scene
                .build(None)
                .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        }
    }
}

#[test]
fn a_saved_world_loads_back_into_the_same_initial_state() {
    let scene = Scene::load(&scenes_dir().join("thesis_joints.toml")).unwrap();
    let world = scene.build(None).unwrap();
    let text = world.to_scene_toml().unwrap();
    let again = Scene::parse(&text).unwrap_or_else(|e| panic!("{e}\n{text}"));
    let mut world2 = again.build(None).unwrap();
    assert_eq!(world.digest(), world2.digest());
    let mut world = world;
    for w in [&mut world, &mut world2] {
        w.start();
        for _ in 0..40 {
            w.step();
        }
    }
    assert_eq!(world.digest(), world2.digest(), "same scene, same run");
    assert!(world.stats().bonds_broken > 0);
}

/// A saved scene kept its objects' densities but not their presets: the default scene's
/// glass pane, ceramic bird and wooden crate came back as stone (stone's strengths, wear
/// and rough cut faces).
#[test]
fn a_saved_scene_keeps_each_objects_material() {
    let scene = Scene::load(&scenes_dir().join("default.toml")).unwrap();
    let world = scene.build(None).unwrap();
    let text = world.to_scene_toml().unwrap();
    let again = Scene::parse(&text)
        .unwrap_or_else(|e| panic!("{e}\n{text}"))
        .build(None)
        .unwrap();
    let ids = world.object_ids();
    assert_eq!(ids.len(), 4);
    for id in ids {
        let (a, b) = (
            world.object_spec(id).unwrap(),
            again.object_spec(id).unwrap(),
        );
        assert_eq!(a.material, b.material, "{}", a.name);
    }
}

/// Triangles of object 0's fragments in a one-object scene.
fn triangles_of(object: &str) -> usize {
    let text = format!("[world]\nground = false\n\n[[objects]]\n{object}\n");
    let world = Scene::parse(&text)
        .unwrap_or_else(|e| panic!("{e}\n{text}"))
        .build(None)
        .unwrap();
    let id = world.object_ids()[0];
    let fracture = world.object_fracture(id).unwrap();
    fracture
        .fragments
        .iter()
        .map(|f| f.mesh.triangles.len())
        .sum()
}

/// Issue 16: the cut faces' roughness is a scene setting of each object, over its
/// material's: glass made rough, stone made flat, and bad values named.
#[test]
fn roughness_keys_make_cut_faces_rough_or_flat() {
    let glass = "shape = \"cube\"\nmaterial = \"glass\"\npattern = \"uniform\"\npieces = 8";
    let stone = "shape = \"cube\"\nmaterial = \"stone\"\npieces = 8";
    let flat_glass = triangles_of(glass);
    let rough_glass = triangles_of(&format!("{glass}\nroughness = 0.02"));
    assert!(
        rough_glass > 2 * flat_glass,
        "{rough_glass} vs {flat_glass}"
    );
    let rough_stone = triangles_of(stone);
    let flat_stone = triangles_of(&format!("{stone}\nroughness = 0"));
    assert!(
        rough_stone > 2 * flat_stone,
        "{rough_stone} vs {flat_stone}"
    );
    // Finer noise, more octaves: more detail.
    let fine = triangles_of(&format!(
        "{glass}\nroughness = 0.02\nroughness_frequency = 20.0\nroughness_octaves = 6"
    ));
    assert!(fine != rough_glass, "frequency and octaves changed nothing");
    for (bad, what) in [
        ("roughness = -0.1", "objects[0].roughness"),
        (
            "roughness_frequency = 0.0",
            "objects[0].roughness_frequency",
        ),
        ("roughness_octaves = 9", "objects[0].roughness_octaves"),
    ] {
        let e = err(&format!("[[objects]]\n{stone}\n{bad}\n"));
        assert!(e.contains(what) && e.contains("line 5"), "{bad}: {e}");
    }
    // Saved and loaded, an object keeps its own roughness and its preset.
    let text = format!("[[objects]]\n{glass}\nroughness = 0.03\nroughness_octaves = 5\n");
    let world = Scene::parse(&text).unwrap().build(None).unwrap();
    let saved = world.to_scene_toml().unwrap();
    let again = Scene::parse(&saved).unwrap().build(None).unwrap();
    let id = world.object_ids()[0];
    let (a, b) = (
        world.object_spec(id).unwrap(),
        again.object_spec(id).unwrap(),
    );
    assert_eq!(a.material, b.material);
    assert_eq!(b.material.roughness.amplitude, f64::from(0.03f32));
    assert_eq!(b.material.roughness.octaves, 5);
}

#[test]
fn a_mesh_projectile_is_centred_and_its_largest_extent_is_its_size() {
    // A tetrahedron 4 m along x and 2 m along y and z, far from the origin.
    let dir = std::env::temp_dir().join(format!("shatter-mesh-shot-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let tet =
        "v 10 10 10\nv 14 10 10\nv 10 12 10\nv 10 10 12\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
    std::fs::write(dir.join("rock.obj"), tet).unwrap();
    let scene_path = dir.join("shot.toml");
    std::fs::write(
        &scene_path,
        "[[projectiles]]\nmesh = \"rock.obj\"\nsize = 0.5\nfrom = [0, 1, 5]\nto = [0, 1, 0]\n",
    )
    .unwrap();
    let scene = Scene::load(&scene_path).unwrap();
    let shatter_sim::ProjectileShape::Custom(points) = &scene.projectiles[0].1.shape else {
        panic!("a custom shape: {:?}", scene.projectiles[0].1.shape);
    };
    let (lo, hi) = points.iter().fold(
        (
            shatter_geom::DVec3::splat(f64::MAX),
            shatter_geom::DVec3::splat(f64::MIN),
        ),
        |(lo, hi), p| (lo.min(*p), hi.max(*p)),
    );
    assert!(((hi - lo).max_element() - 1.0).abs() < 1e-12, "{lo} {hi}");
    assert!(((lo + hi) * 0.5).length() < 1e-12, "centred: {lo} {hi}");
    assert_eq!(scene.projectiles[0].1.size, 0.5);
    // A mesh without extent is refused, naming the key.
    std::fs::write(dir.join("dot.obj"), "v 1 1 1\nv 1 1 1\nv 1 1 1\nf 1 2 3\n").unwrap();
    std::fs::write(
        &scene_path,
        "[[projectiles]]\nmesh = \"dot.obj\"\nfrom = [0, 1, 5]\nto = [0, 1, 0]\n",
    )
    .unwrap();
    let e = Scene::load(&scene_path).unwrap_err().to_string();
    assert!(e.contains("projectiles[0]"), "{e}");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn the_stress_budget_is_read_and_saved() {
    use shatter_sim::DEFAULT_STRESS_BUDGET;
    let budget = |text: &str| Scene::parse(text).unwrap().settings.stress_budget;
    assert_eq!(budget(""), Some(DEFAULT_STRESS_BUDGET));
    assert_eq!(budget("[world]\nstress_budget = 5\n"), Some(5));
    assert_eq!(budget("[world]\nstress_budget = \"none\"\n"), None);
    for text in [
        "[world]\nstress_budget = 5\n",
        "[world]\nstress_budget = \"none\"\n",
    ] {
        let world = Scene::parse(text).unwrap().build(None).unwrap();
        let saved = world.to_scene_toml().unwrap();
        assert_eq!(budget(&saved), budget(text), "{saved}");
    }
}

/// A `[world]` switch `key`: false by default, read when true, refused naming itself when
/// given `bad`, and saved so that it loads back true.
fn switch_reads_and_saves(key: &str, bad: &str, get: fn(&shatter_sim::WorldSettings) -> bool) {
    let read = |text: &str| get(&Scene::parse(text).unwrap().settings);
    let on = format!("[world]\n{key} = true\n");
    assert!(!read(""), "{key}");
    assert!(read(&on), "{key}");
    let e = err(&format!("[world]\n{key} = {bad}\n"));
    assert!(e.contains(key), "{e}");
    let world = Scene::parse(&on).unwrap().build(None).unwrap();
    assert!(read(&world.to_scene_toml().unwrap()), "{key}");
}

#[test]
fn the_debris_cap_and_the_launch_limit_are_read_and_saved() {
    use shatter_sim::{DEFAULT_MAX_DEBRIS, DEFAULT_MAX_LAUNCH_SPEED};
    let settings = |text: &str| {
        let s = Scene::parse(text).unwrap().settings;
        (s.max_debris, s.max_launch_speed)
    };
    assert_eq!(
        settings(""),
        (Some(DEFAULT_MAX_DEBRIS), DEFAULT_MAX_LAUNCH_SPEED)
    );
    assert_eq!(settings("[world]\nmax_debris = 0\n").0, Some(0));
    assert_eq!(settings("[world]\nmax_debris = 300\n").0, Some(300));
    assert_eq!(settings("[world]\nmax_debris = \"none\"\n").0, None);
    assert_eq!(settings("[world]\nmax_launch_speed = 40\n").1, 40.0);
    switch_reads_and_saves("box_colliders", "1", |s| s.box_colliders);
    switch_reads_and_saves("enclosed_colliders", "\"yes\"", |s| s.enclosed_colliders);
    let tiny = |text: &str| Scene::parse(text).unwrap().settings.tiny_debris;
    assert_eq!(tiny(""), shatter_sim::DEFAULT_TINY_DEBRIS);
    assert_eq!(tiny("[world]\ntiny_debris = 0\n"), 0.0);
    let world = Scene::parse("[world]\ntiny_debris = 0.125\n")
        .unwrap()
        .build(None)
        .unwrap();
    assert_eq!(tiny(&world.to_scene_toml().unwrap()), 0.125);
    switch_reads_and_saves("skip_held_contacts", "\"yes\"", |s| s.skip_held_contacts);
    // On by default: turned off, read and saved.
    let cap = |text: &str| Scene::parse(text).unwrap().settings.contact_speed_cap;
    assert!(cap(""));
    let off = "[world]\ncontact_speed_cap = false\n";
    assert!(!cap(off));
    let e = err("[world]\ncontact_speed_cap = 0\n");
    assert!(e.contains("contact_speed_cap"), "{e}");
    let world = Scene::parse(off).unwrap().build(None).unwrap();
    assert!(!cap(&world.to_scene_toml().unwrap()));
    for text in [
        "[world]\nmax_debris = 300\nmax_launch_speed = 40.5\n",
        "[world]\nmax_debris = \"none\"\n",
    ] {
        let world = Scene::parse(text).unwrap().build(None).unwrap();
        let saved = world.to_scene_toml().unwrap();
        assert_eq!(settings(&saved), settings(text), "{saved}");
    }
}

#[test]
fn the_stress_spring_budget_is_read_and_saved() {
    use shatter_sim::DEFAULT_STRESS_SPRING_BUDGET;
    let budget = |text: &str| Scene::parse(text).unwrap().settings.stress_spring_budget;
    assert_eq!(budget(""), Some(DEFAULT_STRESS_SPRING_BUDGET));
    assert_eq!(budget("[world]\nstress_spring_budget = 5000\n"), Some(5000));
    assert_eq!(budget("[world]\nstress_spring_budget = \"none\"\n"), None);
    for text in [
        "[world]\nstress_spring_budget = 5000\n",
        "[world]\nstress_spring_budget = \"none\"\n",
    ] {
        let world = Scene::parse(text).unwrap().build(None).unwrap();
        let saved = world.to_scene_toml().unwrap();
        assert_eq!(budget(&saved), budget(text), "{saved}");
    }
    let e = Scene::parse("[world]\nstress_spring_budget = 0\n")
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("world.stress_spring_budget") && e.contains("none"),
        "{e}"
    );
}
