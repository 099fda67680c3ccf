//! A cluster split conserves linear and angular momentum.
#![allow(clippy::unwrap_used, missing_docs)]

use glam::Vec3;
use shatter_sim::testing::box_grid_fracture;
use shatter_sim::{BondModel, ObjectSpec, World, WorldSettings};

fn rel(a: Vec3, b: Vec3) -> f32 {
    (a - b).length() / a.length().max(b.length())
}

#[test]
fn a_split_of_a_spinning_moving_cluster_conserves_momentum() {
    let hulls = split_momentum(false);
    // Bricks as cuboids (offset from the object's frame) carry the same mass, centre and
    // inertia as their hulls.
    let boxes = split_momentum(true);
    assert!(rel(hulls.0, boxes.0) <= 1e-5, "{hulls:?} {boxes:?}");
    assert!(rel(hulls.1, boxes.1) <= 1e-5, "{hulls:?} {boxes:?}");
}

/// Sets the wall spinning and moving, splits it in three, checks that the split keeps
/// the momentum and returns it (linear, angular about a point).
fn split_momentum(box_colliders: bool) -> (Vec3, Vec3) {
    let mut world = World::new(WorldSettings {
        bond_model: BondModel::Clusters,
        box_colliders,
        ..WorldSettings::default()
    });
    let mut spec = ObjectSpec::from_fracture(
        box_grid_fracture([6, 3, 2], [3.0, 1.5, 1.0].into()),
        Vec3::new(1.0, 5.0, -2.0),
    );
    spec.rotation = glam::Quat::from_euler(glam::EulerRot::XYZ, 0.3, -0.7, 0.2);
    let id = world.add_object(spec).unwrap();
    let fracture = world.object_fracture(id).unwrap();
    let centre = Vec3::new(1.0, 5.0, -2.0);
    world.set_object_velocity(
        id,
        centre,
        Vec3::new(3.0, -1.0, 2.0),
        Vec3::new(0.5, 2.0, -1.5),
    );
    let point = Vec3::new(-4.0, 2.0, 7.0);
    let (p0, l0) = world.object_momentum(id, point);
    // Cut the wall between columns 1|2 and 3|4 (x bonds) and the top row off one side.
    let cut: Vec<u32> = fracture
        .bonds
        .iter()
        .enumerate()
        .filter(|(_, b)| {
            let x = b.centroid.x;
            (b.normal.x > 0.5 && ((x + 0.5).abs() < 1e-6 || (x - 0.5).abs() < 1e-6))
                || (b.normal.y > 0.5 && b.centroid.x > 0.5 && b.centroid.y > 0.0)
        })
        .map(|(i, _)| i as u32)
        .collect();
    assert!(!cut.is_empty());
    world.break_bonds(id, &cut);
    assert!(
        world.object_bodies(id).len() >= 3,
        "the cut should give at least 3 bodies"
    );
    let (p1, l1) = world.object_momentum(id, point);
    assert!(rel(p0, p1) <= 1e-4, "linear momentum {p0} -> {p1}");
    assert!(rel(l0, l1) <= 1e-4, "angular momentum {l0} -> {l1}");
    (p0, l0)
}
