//! `shatter shape`, end to end through the real binary.
#![allow(clippy::unwrap_used)]

mod common;

use common::{reimport, rel, shatter};
use shatter_geom::shapes;

#[test]
fn every_shape_round_trips_through_obj_and_glb_with_its_volume() {
    let dir = tempfile::tempdir().unwrap();
    for name in shapes::NAMES {
        let expected = shapes::by_name(name).unwrap().signed_volume();
        for ext in ["obj", "glb"] {
            let file = format!("{name}.{ext}");
            let run = shatter(dir.path(), &["shape", name, "--out", &file]).ok();
            assert!(run.stdout.contains(&file), "{}", run.stdout);
            let mesh = reimport(&dir.path().join(&file));
            assert!(
                mesh.check().is_solid(),
                "{file} is not a closed outward solid"
            );
            let v = mesh.signed_volume();
            assert!(
                rel(v, expected) < 1e-6,
                "{file}: volume {v}, expected {expected}"
            );
        }
    }
}

#[test]
fn scale_multiplies_the_volume() {
    let dir = tempfile::tempdir().unwrap();
    shatter(
        dir.path(),
        &["shape", "bird", "--out", "b.glb", "--scale", "2,1,3"],
    )
    .ok();
    let expected = 6.0 * shapes::bird().signed_volume();
    let v = reimport(&dir.path().join("b.glb")).signed_volume();
    assert!(rel(v, expected) < 1e-6, "volume {v}, expected {expected}");
}

#[test]
fn bad_scales_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    shatter(
        dir.path(),
        &["shape", "cube", "--out", "c.obj", "--scale", "1,2"],
    )
    .bad_input(&[
        "--scale",
        "expected 3 comma-separated numbers X,Y,Z, found 2",
    ]);
    shatter(
        dir.path(),
        &["shape", "cube", "--out", "c.obj", "--scale", "1,0,1"],
    )
    .bad_input(&["--scale 1,0,1", "greater than 0"]);
    shatter(
        dir.path(),
        &["shape", "cube", "--out", "c.obj", "--scale", "-1,1,1"],
    )
    .bad_input(&["--scale -1,1,1", "greater than 0"]);
    shatter(
        dir.path(),
        &["shape", "cube", "--out", "c.obj", "--scale", "1,x,1"],
    )
    .bad_input(&["'x' is not a number"]);
    assert!(!dir.path().join("c.obj").exists());
}

#[test]
fn unknown_shape_and_outputs_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    shatter(dir.path(), &["shape", "teapot", "--out", "t.obj"]).bad_input(&["teapot"]);
    shatter(dir.path(), &["shape", "cube", "--out", "c.stl"])
        .bad_input(&["c.stl", "unknown output format"]);
    shatter(dir.path(), &["shape", "cube", "--out", "nowhere/c.obj"])
        .bad_input(&["nowhere/c.obj", "does not exist"]);
    shatter(dir.path(), &["shape", "cube"]).bad_input(&["--out"]);
}
