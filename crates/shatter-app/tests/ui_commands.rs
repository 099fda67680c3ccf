//! Each panel's fields validate input and produce the right simulation commands —
//! without a window.
#![allow(clippy::unwrap_used)]

use std::path::{Path, PathBuf};

use glam::Vec3;
use shatter_app::commands::{
    BondModel, FractureSource, MaterialPreset, MethodKind, ObjectId, Pattern, ProjectileShape,
    ProjectileSpec, Shape, SimCommand,
};
use shatter_app::error::AppError;
use shatter_app::sim_bridge::check_custom_mesh;
use shatter_app::ui::forms::{
    AddObjectForm, FireForm, ForceForm, SceneFileForm, ShapeKind, TransformForm,
};
use shatter_app::ui::state::{AddObjectPage, ClickOutcome, UiState, ground_hit};

fn any_mesh(_: &Path) -> Result<(), AppError> {
    Ok(())
}

fn any_projectile(_: &Path) -> Result<ProjectileShape, AppError> {
    Ok(ProjectileShape::Custom(vec![
        glam::DVec3::ZERO,
        glam::DVec3::ONE,
    ]))
}

fn temp_dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("shatter-app-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

#[test]
fn add_object_defaults_follow_the_thesis() {
    let spec = AddObjectForm::default()
        .validate(&TransformForm::default(), &any_mesh, None)
        .unwrap();
    assert_eq!(spec.position, Vec3::new(0.0, 10.0, 0.0));
    assert_eq!(spec.scale, Vec3::ONE);
    assert!(matches!(
        spec.source,
        FractureSource::Shape {
            shape: Shape::Cube,
            ..
        }
    ));
    assert_eq!(spec.last, None);
    assert_eq!(spec.material, MaterialPreset::Stone.material());
    assert_eq!(spec.break_force, Some(20000.0));
}

#[test]
fn non_integer_random_vertices_is_reported_next_to_the_field() {
    let form = AddObjectForm {
        random_vertices: "12.5".into(),
        ..Default::default()
    };
    let err = form
        .validate(&TransformForm::default(), &any_mesh, None)
        .unwrap_err();
    assert!(
        err.get("random_vertices")
            .unwrap()
            .contains("not an integer")
    );
    assert_eq!(err.0.len(), 1, "only the bad field is flagged: {err:?}");
}

#[test]
fn every_bad_field_is_reported_at_once() {
    let form = AddObjectForm {
        break_force: "-5".into(),
        skip: "x".into(),
        last: "0".into(),
        color: ["1".into(), "1.5".into(), "0".into()],
        ..Default::default()
    };
    let transform = TransformForm {
        position: ["0".into(), "ten".into(), "0".into()],
        scale: ["1".into(), "0".into(), "1".into()],
    };
    let err = form.validate(&transform, &any_mesh, None).unwrap_err();
    for field in ["break_force", "skip", "last", "color", "position", "scale"] {
        assert!(err.get(field).is_some(), "{field} not flagged: {err:?}");
    }
    assert!(err.get("color").unwrap().starts_with("G:"));
    assert!(err.get("position").unwrap().starts_with("y:"));
}

#[test]
fn unreadable_custom_mesh_is_refused() {
    let dir = temp_dir("mesh");
    let missing = dir.join("nope.obj");
    let form = AddObjectForm {
        shape: ShapeKind::Custom,
        custom_path: missing.display().to_string(),
        ..Default::default()
    };
    let err = form
        .validate(&TransformForm::default(), &check_custom_mesh, None)
        .unwrap_err();
    assert!(err.get("shape").unwrap().contains("cannot read"), "{err:?}");

    let wrong_kind = dir.join("notes.txt");
    std::fs::write(&wrong_kind, "hello").unwrap();
    let form = AddObjectForm {
        shape: ShapeKind::Custom,
        custom_path: wrong_kind.display().to_string(),
        ..Default::default()
    };
    let err = form
        .validate(&TransformForm::default(), &check_custom_mesh, None)
        .unwrap_err();
    assert!(err.get("shape").unwrap().contains(".obj"), "{err:?}");

    let empty_path = AddObjectForm {
        shape: ShapeKind::Custom,
        ..Default::default()
    };
    assert!(
        empty_path
            .validate(&TransformForm::default(), &any_mesh, None)
            .unwrap_err()
            .get("shape")
            .is_some()
    );
}

#[test]
fn voronoi_needs_at_least_one_piece() {
    let form = AddObjectForm {
        method: MethodKind::Voronoi,
        random_vertices: "0".into(),
        ..Default::default()
    };
    assert!(
        form.validate(&TransformForm::default(), &any_mesh, None)
            .unwrap_err()
            .get("random_vertices")
            .is_some()
    );
}

#[test]
fn draw_adds_then_edits_the_same_object_and_apply_closes() {
    let mut s = UiState::default();
    s.open_add_panel();
    s.next_page(&any_mesh);
    assert_eq!(s.add_page, AddObjectPage::Transform);
    s.transform.position = ["1".into(), "2".into(), "3".into()];
    let first = s.draw(&any_mesh).unwrap();
    let SimCommand::AddObject(spec) = first else {
        panic!("first Draw should add, got {first:?}");
    };
    assert_eq!(spec.position, Vec3::new(1.0, 2.0, 3.0));
    s.object_added(ObjectId(7));
    s.transform.scale = ["2".into(), "2".into(), "2".into()];
    let second = s.draw(&any_mesh).unwrap();
    match second {
        SimCommand::EditObject(ObjectId(7), spec) => assert_eq!(spec.scale, Vec3::splat(2.0)),
        other => panic!("second Draw should rebuild object 7, got {other:?}"),
    }
    assert!(matches!(
        s.apply(&any_mesh),
        Some(SimCommand::EditObject(ObjectId(7), _))
    ));
    assert_eq!(s.add_page, AddObjectPage::Closed);
    assert_eq!(s.target, None);
}

#[test]
fn invalid_transform_produces_no_command_and_keeps_the_panel() {
    let mut s = UiState::default();
    s.open_add_panel();
    s.next_page(&any_mesh);
    s.transform.scale = ["1".into(), "-1".into(), "1".into()];
    assert_eq!(s.draw(&any_mesh), None);
    assert_eq!(s.apply(&any_mesh), None);
    assert_eq!(s.add_page, AddObjectPage::Transform);
    assert!(s.add_errors.get("scale").is_some());
    s.back();
    assert_eq!(s.add_page, AddObjectPage::Parameters);
}

#[test]
fn next_page_stays_on_parameters_when_invalid() {
    let mut s = UiState::default();
    s.open_add_panel();
    s.add.random_vertices = "many".into();
    s.next_page(&any_mesh);
    assert_eq!(s.add_page, AddObjectPage::Parameters);
    assert!(s.add_errors.get("random_vertices").is_some());
}

#[test]
fn fire_ok_sets_the_projectile_only_when_valid() {
    let mut s = UiState::default();
    let before = s.projectile.clone();
    s.fire.speed = "-3".into();
    assert!(!s.fire_ok(&any_projectile));
    assert_eq!(s.projectile, before);
    assert!(s.fire_errors.get("speed").is_some());
    s.fire = FireForm {
        shape: ShapeKind::Builtin(Shape::Cube),
        speed: "75".into(),
        last: "4".into(),
        ..Default::default()
    };
    assert!(s.fire_ok(&any_projectile));
    assert_eq!(s.projectile.shape, ProjectileShape::Cube);
    assert_eq!(s.projectile.speed, 75.0);
    assert_eq!(s.projectile.last, Some(4.0));
    // A custom shape is the file's points, read by the loader the panel is given.
    s.fire.shape = ShapeKind::Custom;
    assert!(!s.fire_ok(&any_projectile), "no path given");
    assert!(s.fire_errors.get("shape").is_some());
    s.fire.custom_path = "rock.obj".into();
    assert!(s.fire_ok(&any_projectile));
    assert_eq!(s.projectile.shape, any_projectile(Path::new("")).unwrap());
}

#[test]
fn negative_radius_keeps_the_previous_explosion() {
    let mut s = UiState {
        force_form: ForceForm {
            enabled: true,
            radius: "3".into(),
            power: "100".into(),
        },
        ..Default::default()
    };
    s.update_force();
    assert_eq!(s.force.radius, 3.0);
    s.force_form.radius = "-2".into();
    s.update_force();
    assert!(
        s.force_errors
            .get("radius")
            .unwrap()
            .contains("greater than 0")
    );
    assert_eq!(s.force.radius, 3.0);
    assert!(s.force.enabled);
}

#[test]
fn click_fires_from_the_camera_at_the_hit_point() {
    let s = UiState::default();
    let eye = Vec3::new(0.0, 5.0, 20.0);
    let dir = Vec3::new(0.0, 0.0, -1.0);
    let hit = Some((ObjectId(3), Vec3::new(0.0, 5.0, 0.3)));
    match s.click(eye, dir, hit) {
        ClickOutcome::Command(SimCommand::Fire(spec)) => {
            assert_eq!(spec.to, Vec3::new(0.0, 5.0, 0.3));
            assert!(spec.from.distance(eye) < 1.5);
            assert_eq!(
                spec,
                ProjectileSpec {
                    from: spec.from,
                    to: spec.to,
                    ..s.projectile.clone()
                }
            );
        }
        other => panic!("expected Fire, got {other:?}"),
    }
    // A miss aims at a far point along the ray.
    match s.click(eye, Vec3::Y, None) {
        ClickOutcome::Command(SimCommand::Fire(spec)) => assert!(spec.to.y > 100.0),
        other => panic!("expected Fire, got {other:?}"),
    }
}

#[test]
fn click_explodes_when_add_force_is_on() {
    let mut s = UiState::default();
    s.force_form.enabled = true;
    s.force_form.radius = "6".into();
    s.force_form.power = "250".into();
    s.update_force();
    let eye = Vec3::new(0.0, 10.0, 10.0);
    let dir = Vec3::new(0.0, -1.0, -1.0).normalize();
    match s.click(eye, dir, None) {
        ClickOutcome::Command(SimCommand::Explode {
            position,
            radius,
            power,
        }) => {
            // No object hit: the explosion goes where the ray meets the ground.
            assert!(position.distance(Vec3::new(0.0, 0.0, 0.0)) < 1e-4);
            assert_eq!((radius, power), (6.0, 250.0));
        }
        other => panic!("expected Explode, got {other:?}"),
    }
    assert_eq!(s.click(eye, Vec3::Y, None), ClickOutcome::Nothing);
}

#[test]
fn edit_and_delete_act_on_the_clicked_object_and_exclude_each_other() {
    let mut s = UiState::default();
    let eye = Vec3::ZERO;
    let hit = Some((ObjectId(5), Vec3::X));
    s.toggle_delete();
    assert_eq!(
        s.click(eye, Vec3::X, hit),
        ClickOutcome::Command(SimCommand::DeleteObject(ObjectId(5)))
    );
    assert_eq!(s.click(eye, Vec3::X, None), ClickOutcome::Nothing);
    s.toggle_edit();
    assert!(!s.delete_mode);
    assert_eq!(s.click(eye, Vec3::X, hit), ClickOutcome::Edit(ObjectId(5)));
}

#[test]
fn edit_fills_the_panel_with_the_object_and_draw_rebuilds_it() {
    let spec = AddObjectForm {
        shape: ShapeKind::Builtin(Shape::Capsule),
        random_vertices: "77".into(),
        last: "12".into(),
        ..Default::default()
    }
    .validate(&TransformForm::default(), &any_mesh, None)
    .unwrap();
    // What the panels do not show is kept through an edit.
    let spec = shatter_app::commands::ObjectSpec {
        anchored: true,
        rotation: glam::Quat::from_rotation_y(0.5),
        ..spec
    };
    let mut s = UiState::default();
    s.edit_object(ObjectId(9), &spec);
    assert_eq!(s.add.shape, ShapeKind::Builtin(Shape::Capsule));
    assert_eq!(s.add.random_vertices, "77");
    assert_eq!(s.transform.position[1], "10");
    s.next_page(&any_mesh);
    assert_eq!(
        s.draw(&any_mesh),
        Some(SimCommand::EditObject(ObjectId(9), Box::new(spec.clone())))
    );
    s.add.random_vertices = "20".into();
    match s.draw(&any_mesh) {
        Some(SimCommand::EditObject(ObjectId(9), edited)) => {
            assert!(edited.anchored && edited.rotation == spec.rotation);
            assert_eq!(edited.source.params().unwrap().random_vertices, 20);
        }
        other => panic!("expected an edit, got {other:?}"),
    }
}

#[test]
fn scene_file_save_and_load_check_the_path() {
    let dir = temp_dir("scene");
    let file = dir.join("s.toml");
    let form = SceneFileForm {
        path: file.display().to_string(),
    };
    assert_eq!(form.save().unwrap(), SimCommand::SaveScene(file.clone()));
    assert!(
        form.load()
            .unwrap_err()
            .get("path")
            .unwrap()
            .contains("no file")
    );
    std::fs::write(&file, "").unwrap();
    assert_eq!(form.load().unwrap(), SimCommand::LoadScene(file));
    let bad = SceneFileForm {
        path: dir.join("s.txt").display().to_string(),
    };
    assert!(bad.save().is_err());
    let no_dir = SceneFileForm {
        path: dir.join("missing/s.toml").display().to_string(),
    };
    assert!(
        no_dir
            .save()
            .unwrap_err()
            .get("path")
            .unwrap()
            .contains("does not exist")
    );
}

#[test]
fn ground_hit_only_in_front_of_the_eye() {
    assert_eq!(
        ground_hit(Vec3::new(1.0, 2.0, 0.0), Vec3::NEG_Y),
        Some(Vec3::new(1.0, 0.0, 0.0))
    );
    assert_eq!(ground_hit(Vec3::new(0.0, 2.0, 0.0), Vec3::Y), None);
}

#[test]
fn the_shape_lists_come_from_the_vocabulary() {
    let object = ShapeKind::object_options();
    let builtin: Vec<Shape> = object
        .iter()
        .filter_map(|k| match k {
            ShapeKind::Builtin(s) => Some(*s),
            ShapeKind::Custom => None,
        })
        .collect();
    assert_eq!(builtin, Shape::ALL);
    assert_eq!(object.last(), Some(&ShapeKind::Custom));
    assert_eq!(
        ShapeKind::projectile_options(),
        [Shape::Cube, Shape::Capsule, Shape::Cylinder, Shape::Sphere]
            .map(ShapeKind::Builtin)
            .into_iter()
            .chain([ShapeKind::Custom])
            .collect::<Vec<_>>()
    );
    assert_eq!(ShapeKind::Builtin(Shape::Bird).label(), "Bird");
    // Every other panel list iterates a vocabulary's ALL: the words are the library's.
    assert_eq!(MethodKind::ALL.len(), 4);
    assert_eq!(Pattern::ALL.len(), 4);
    assert!(MaterialPreset::ALL.contains(&MaterialPreset::Brick));
    assert_eq!(BondModel::ALL[0], BondModel::default());
}

#[test]
fn the_fire_panel_defaults_are_the_simulators() {
    // The panel's fields, validated untouched, are the simulator's projectile.
    let validated = FireForm::default().validate(&any_projectile).unwrap();
    assert_eq!(validated, ProjectileSpec::default());
    assert_eq!(UiState::default().projectile, ProjectileSpec::default());
}
