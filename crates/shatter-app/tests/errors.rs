//! The app's errors are typed end to end: what the simulation, the scene store or a
//! custom mesh refused stays reachable through `std::error::Error::source`, while the
//! message the user sees is the one the panels always showed.
#![allow(clippy::unwrap_used)]

use std::error::Error;

use bevy_shatter::world::MeshFileError;
use glam::Vec3;
use shatter_app::commands::{FractureSource, ObjectId, ObjectSpec, SimCommand};
use shatter_app::error::AppError;
use shatter_app::scene_store::StoreError;
use shatter_app::sim_bridge::{SandboxWorld, ShatterWorld, load_projectile};
use shatter_app::ui::fields::FieldError;
use shatter_app::ui::forms::{AddObjectForm, FormError, SceneFileForm, TransformForm};
use shatter_app::ui::state::UiState;
use shatter_geom::io::MeshIoError;
use shatter_sim::SimError;

/// The Add Object panel's default object.
fn default_object() -> ObjectSpec {
    AddObjectForm::default()
        .validate(&TransformForm::default(), &|_| Ok(()), None)
        .unwrap()
}

fn empty_world() -> ShatterWorld {
    ShatterWorld::sandbox(shatter_sim::World::new(Default::default()))
}

#[test]
fn a_missing_object_mesh_is_a_sim_error_whose_source_is_the_readers() {
    let mut b = empty_world();
    let err = b
        .apply(SimCommand::AddObject(Box::new(ObjectSpec {
            source: FractureSource::MeshFile {
                path: "no/such/mesh.obj".into(),
                params: Default::default(),
            },
            ..default_object()
        })))
        .unwrap_err();
    assert!(
        matches!(err, AppError::Sim(SimError::Mesh { .. })),
        "{err:?}"
    );
    let sim = err.source().unwrap().downcast_ref::<SimError>().unwrap();
    assert_eq!(
        err.to_string(),
        sim.to_string(),
        "shown as the simulation says"
    );
    assert!(
        sim.source()
            .unwrap()
            .downcast_ref::<MeshIoError>()
            .is_some()
    );
}

#[test]
fn a_missing_projectile_mesh_keeps_the_readers_error() {
    let err = load_projectile("no/such/rock.obj".as_ref()).unwrap_err();
    assert!(
        matches!(err, AppError::MeshFile(MeshFileError::CannotRead { .. })),
        "{err:?}"
    );
    let io = err
        .source()
        .unwrap()
        .downcast_ref::<std::io::Error>()
        .unwrap();
    assert_eq!(
        err.to_string(),
        format!("cannot read 'no/such/rock.obj': {io}")
    );
    let dir = tempfile::tempdir().unwrap();
    let broken = dir.path().join("rock.obj");
    std::fs::write(&broken, "v 0 0 0\nf 1 2 3\n").unwrap();
    let err = load_projectile(&broken).unwrap_err();
    let reader = err.source().unwrap().downcast_ref::<MeshIoError>().unwrap();
    assert_eq!(err.to_string(), reader.to_string());
}

#[test]
fn scene_and_example_errors_keep_their_sources() {
    let mut b = empty_world();
    let err = b.apply(SimCommand::LoadExample("nope".into())).unwrap_err();
    assert!(matches!(&err, AppError::UnknownExample { name, .. } if name == "nope"));
    assert!(err.source().is_none());

    let dir = tempfile::tempdir().unwrap();
    let err = b
        .apply(SimCommand::SaveScene(dir.path().join("missing/s.toml")))
        .unwrap_err();
    assert!(
        matches!(err, AppError::Store(StoreError::Write { .. })),
        "{err:?}"
    );
    let store = err.source().unwrap().downcast_ref::<StoreError>().unwrap();
    assert!(
        store
            .source()
            .unwrap()
            .downcast_ref::<std::io::Error>()
            .is_some()
    );
    assert!(err.to_string().starts_with("cannot write '"), "{err}");

    let bad = dir.path().join("bad.toml");
    std::fs::write(&bad, "[world]\ngravty = 1\n").unwrap();
    let err = b.apply(SimCommand::LoadScene(bad)).unwrap_err();
    assert!(matches!(err, AppError::Sim(_)), "{err:?}");
}

#[test]
fn forms_keep_typed_errors_and_show_their_messages() {
    let form = AddObjectForm {
        random_vertices: "12.5".into(),
        ..Default::default()
    };
    let err = form
        .validate(&TransformForm::default(), &|_| Ok(()), None)
        .unwrap_err();
    assert_eq!(
        err.error("random_vertices"),
        Some(&FormError::Field(FieldError::NotAnInteger {
            text: "12.5".into()
        }))
    );
    assert_eq!(
        err.get("random_vertices").as_deref(),
        Some("'12.5' is not an integer")
    );

    let no_dir = SceneFileForm {
        path: "no/such/dir/s.toml".into(),
    };
    let err = no_dir.save().unwrap_err();
    assert!(
        matches!(err.error("path"), Some(FormError::Store(_))),
        "{err:?}"
    );
    assert_eq!(err.to_string(), "path: folder 'no/such/dir' does not exist");

    // A refused object: the typed error next to the fields, its message in the status.
    let mut s = UiState::default();
    let cmd = SimCommand::AddObject(Box::new(ObjectSpec {
        position: Vec3::ZERO,
        ..default_object()
    }));
    let refused = empty_world()
        .apply(SimCommand::DeleteObject(ObjectId(4)))
        .unwrap_err();
    let message = refused.to_string();
    assert!(message.contains('4'), "{message}");
    s.command_failed(&cmd, refused);
    assert_eq!(s.status, message);
    assert!(matches!(
        s.add_errors.error("object"),
        Some(FormError::App(_))
    ));
    assert_eq!(s.add_errors.get("object"), Some(message));
}

#[test]
fn the_error_stays_small() {
    // Clippy's `result_large_err` limit: every `Result<_, AppError>` would trip it.
    assert!(std::mem::size_of::<AppError>() < 128);
}
