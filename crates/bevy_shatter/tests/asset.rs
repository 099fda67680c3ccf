//! Pre-fractured assets: a GLB with the `SHATTER_fracture` extension, written by the
//! library as `shatter fracture --out X.glb` writes it, loads through the plugin's
//! `AssetLoader` into the same fracture, and a bad file is a `FractureFailed` message.

#![allow(clippy::unwrap_used)]

use std::time::Duration;

use avian3d::prelude::*;
use bevy::prelude::*;
use bevy::time::TimeUpdateStrategy;
use bevy_shatter::{
    Breakable, BreakableError, FractureAsset, FractureFailed, Fractured, ShatterObject,
    ShatterPlugin, ShatterSystems,
};
use shatter_geom::fracture::{FractureParams, Method, Seeds, fracture};
use shatter_geom::io::{
    BreakThresholds, ExportObject, FractureAssetMeta, read_fracture, save_fracture_glb, save_glb,
};
use shatter_geom::shapes;

#[derive(Resource, Default)]
struct Log {
    fractured: Vec<Fractured>,
    failed: Vec<FractureFailed>,
}

fn collect(
    mut log: ResMut<Log>,
    mut f: MessageReader<Fractured>,
    mut e: MessageReader<FractureFailed>,
) {
    log.fractured.extend(f.read().cloned());
    log.failed.extend(e.read().cloned());
}

fn app(dir: &std::path::Path) -> App {
    let mut app = App::new();
    app.add_plugins((
        MinimalPlugins,
        TransformPlugin,
        AssetPlugin {
            file_path: dir.display().to_string(),
            ..AssetPlugin::default()
        },
        PhysicsPlugins::default(),
        ShatterPlugin::default(),
    ))
    .init_asset::<Mesh>()
    .init_asset::<StandardMaterial>()
    .init_resource::<Log>()
    .insert_resource(TimeUpdateStrategy::ManualDuration(Duration::from_secs_f64(
        1.0 / 64.0,
    )))
    .add_systems(FixedUpdate, collect.after(ShatterSystems::Break));
    app.finish();
    app.cleanup();
    app
}

/// Loads `file` as a pre-fractured breakable and updates until it is fractured or
/// refused (a bounded number of updates; file loading runs on Bevy's IO pool).
fn load(app: &mut App, file: &str) -> Entity {
    let handle: Handle<FractureAsset> =
        app.world().resource::<AssetServer>().load(file.to_string());
    let e = app
        .world_mut()
        .spawn((
            Transform::from_xyz(0.0, 2.0, 0.0),
            Breakable::prefractured(handle),
        ))
        .id();
    for _ in 0..3000 {
        app.update();
        let log = app.world().resource::<Log>();
        if !log.fractured.is_empty() || !log.failed.is_empty() {
            return e;
        }
        std::thread::sleep(Duration::from_millis(1));
    }
    panic!("{file} was neither loaded nor refused");
}

#[test]
fn a_prefractured_glb_loads_with_its_bonds_anchors_and_break_force() {
    let dir = tempfile::tempdir().unwrap();
    let params = FractureParams {
        method: Method::Voronoi {
            seeds: Seeds::count(16),
        },
        seed: 5,
    };
    let made = fracture(&shapes::cube(), &params).unwrap();
    let meta = FractureAssetMeta {
        anchors: made.lowest_fragments(),
        material: Some("stone".into()),
        thresholds: Some(BreakThresholds {
            strength: 12_345.0,
            compression: 1e8,
            tension: 6e6,
            shear: 1.2e7,
            wear: 0.0,
        }),
    };
    assert!(!meta.anchors.is_empty() && meta.anchors.len() < made.fragments.len());
    let path = dir.path().join("wall.glb");
    save_fracture_glb(&path, &made, &meta).unwrap();
    // What the library (and `shatter inspect`) reads from the file.
    let (read, _) = read_fracture(&path).unwrap();

    let mut app = app(dir.path());
    let e = load(&mut app, "wall.glb");
    let log = app.world().resource::<Log>();
    assert!(log.failed.is_empty(), "{:?}", log.failed);
    assert_eq!(log.fractured[0].object, e);
    assert_eq!(log.fractured[0].bonds, made.bonds.len());
    assert_eq!(log.fractured[0].fragments, made.fragments.len());
    app.update();
    let object = app.world().get::<ShatterObject>(e).unwrap();
    assert_eq!(object.fracture.bonds, read.bonds);
    assert_eq!(object.fracture.fragments.len(), made.fragments.len());
    let anchored: Vec<u32> = (0..object.anchored.len() as u32)
        .filter(|&f| object.anchored[f as usize])
        .collect();
    assert_eq!(anchored, meta.anchors, "the file's anchors hold the object");
    assert_eq!(object.state.strength, 12_345.0, "the file's break force");
    // Anchored: the body is static and stays where it was put.
    let body = object.body_of[0].unwrap();
    assert_eq!(app.world().get::<RigidBody>(body), Some(&RigidBody::Static));
    for _ in 0..30 {
        app.update();
    }
    let y = app.world().get::<Transform>(body).unwrap().translation.y;
    assert!(
        (y - 2.0).abs() < 1e-6,
        "the anchored object moved to y = {y}"
    );
}

#[test]
fn a_glb_without_the_extension_or_a_broken_file_is_a_message_not_a_panic() {
    let dir = tempfile::tempdir().unwrap();
    // An ordinary GLB (no SHATTER_fracture) and a file that is no GLB at all.
    let cube = shapes::cube();
    save_glb(
        dir.path().join("plain.glb"),
        &[ExportObject::new("cube", &cube)],
    )
    .unwrap();
    std::fs::write(dir.path().join("junk.glb"), b"glTF but not really").unwrap();
    for (file, needle) in [("plain.glb", "SHATTER_fracture"), ("junk.glb", "junk.glb")] {
        let mut app = app(dir.path());
        let e = load(&mut app, file);
        let log = app.world().resource::<Log>();
        assert!(log.fractured.is_empty(), "{file} was fractured");
        assert_eq!(log.failed[0].object, e);
        match &log.failed[0].error {
            BreakableError::Asset(msg) => assert!(msg.contains(needle), "{file}: {msg}"),
            other => panic!("{file}: {other:?}"),
        }
        assert!(app.world().get::<ShatterObject>(e).is_none());
    }
}
