//! Materials with rough cut faces: a stone object's precomputed fragments have displaced
//! interior faces, still add up to the object's volume, and repeat with the same seed;
//! glass stays flat and grids stay square.

#![allow(clippy::unwrap_used)]

use glam::Vec3;
use shatter_geom::fracture::Roughness;
use shatter_sim::{
    FractureParams, FractureSource, MaterialPreset, MethodKind, ObjectSpec, Pattern, Shape, World,
    WorldSettings,
};

fn object(preset: MaterialPreset, method: MethodKind, seed: u64) -> ObjectSpec {
    let mut spec = ObjectSpec::from_fracture(Default::default(), Vec3::new(0.0, 2.0, 0.0));
    spec.material = preset.material();
    spec.scale = Vec3::splat(1.5);
    spec.source = FractureSource::Shape {
        shape: Shape::Cube,
        params: FractureParams {
            method: Some(method),
            // One pattern for every material (glass's own is radial).
            pattern: Some(Pattern::Uniform),
            pieces: 12,
            grid: [2, 2, 2],
            seed,
            ..FractureParams::default()
        },
    };
    spec
}

fn vertices(world: &World) -> usize {
    let id = world.object_ids()[0];
    let f = world.object_fracture(id).unwrap();
    f.fragments.iter().map(|f| f.mesh.positions.len()).sum()
}

fn volume(world: &World) -> f64 {
    let id = world.object_ids()[0];
    world.object_fracture(id).unwrap().total_volume()
}

fn world_of(spec: ObjectSpec) -> World {
    let mut world = World::new(WorldSettings::default());
    world.add_object(spec).unwrap();
    world
}

#[test]
fn stone_is_rough_glass_and_grids_are_flat_and_volumes_add_up() {
    let mut flat_stone = object(MaterialPreset::Stone, MethodKind::Voronoi, 3);
    flat_stone.material.roughness = Roughness::OFF;
    let flat = world_of(flat_stone);
    let stone = world_of(object(MaterialPreset::Stone, MethodKind::Voronoi, 3));
    assert!(
        vertices(&stone) > vertices(&flat) * 2,
        "stone's cut faces get inner vertices: {} against {} flat",
        vertices(&stone),
        vertices(&flat)
    );
    let exact = 1.5f64.powi(3);
    assert!(
        (volume(&stone) - exact).abs() < 1e-6 * exact,
        "{}",
        volume(&stone)
    );
    assert!((volume(&flat) - exact).abs() < 1e-6 * exact);
    // Glass has no roughness: the same cut as flat stone.
    let glass = world_of(object(MaterialPreset::Glass, MethodKind::Voronoi, 3));
    assert_eq!(vertices(&glass), vertices(&flat));
    // A stone grid stays a grid of boxes (8 corners each).
    let grid = world_of(object(MaterialPreset::Stone, MethodKind::Grid, 3));
    assert_eq!(vertices(&grid), 8 * 8);
    // Same seed, same faces; another seed, others.
    let again = world_of(object(MaterialPreset::Stone, MethodKind::Voronoi, 3));
    let id = again.object_ids()[0];
    assert_eq!(
        again.object_fracture(id).unwrap().fragments,
        stone.object_fracture(id).unwrap().fragments
    );
}

#[test]
fn a_bad_roughness_is_an_error_naming_it() {
    let mut spec = object(MaterialPreset::Stone, MethodKind::Voronoi, 1);
    spec.material.roughness.octaves = 0;
    let mut world = World::new(WorldSettings::default());
    let err = world.add_object(spec).unwrap_err().to_string();
    assert!(err.contains("material.roughness"), "{err}");
}
