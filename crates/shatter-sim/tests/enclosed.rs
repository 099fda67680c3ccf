//! Enclosed fragments (every face a bonded cut face) of cluster objects have no colliders
//! until a bond of theirs breaks; their bodies keep the mass, and a split conserves
//! momentum either way.
#![allow(clippy::unwrap_used, missing_docs)]

use glam::Vec3;
use shatter_sim::object::prepare::prepare;
use shatter_sim::testing::box_grid_fracture;
use shatter_sim::{BondModel, ObjectId, ObjectSpec, World, WorldSettings};

/// Bricks per side of the test block.
const N: u32 = 4;

fn rel(a: Vec3, b: Vec3) -> f32 {
    (a - b).length() / a.length().max(b.length())
}

/// Grid cell of fragment `i` (`i = x + N·(y + N·z)`, see [`box_grid_fracture`]).
fn cell(i: usize) -> [u32; 3] {
    let i = i as u32;
    [i % N, (i / N) % N, i / (N * N)]
}

fn inside(c: [u32; 3]) -> bool {
    c.iter().all(|&k| k > 0 && k < N - 1)
}

/// A world with a 4 × 4 × 4 block of 0.25 m bricks whose centre is at `centre`.
fn block(enclosed_colliders: bool, centre: Vec3) -> (World, ObjectId) {
    let mut world = World::new(WorldSettings {
        bond_model: BondModel::Clusters,
        enclosed_colliders,
        ..WorldSettings::default()
    });
    let mut spec = ObjectSpec::from_fracture(box_grid_fracture([N; 3], [1.0; 3].into()), centre);
    spec.rotation = glam::Quat::from_euler(glam::EulerRot::XYZ, 0.2, 0.5, -0.3);
    let id = world.add_object(spec).unwrap();
    (world, id)
}

#[test]
fn prepared_marks_exactly_the_bricks_inside_a_block_enclosed() {
    for n in [1, 2, 3, 5] {
        let fracture = box_grid_fracture([n, n, n], [1.0; 3].into());
        let prepared = prepare(&fracture, Vec3::new(2.0, 0.5, 1.0), 1000.0, false);
        let expected: Vec<bool> = (0..n * n * n)
            .map(|i| {
                let c = [i % n, (i / n) % n, i / (n * n)];
                c.iter().all(|&k| k > 0 && k + 1 < n)
            })
            .collect();
        assert_eq!(prepared.enclosed, expected, "{n}³ bricks");
    }
    // A cell left out of the grid opens its neighbours: none of the 3³'s bricks then has
    // all six faces bonded, so none is enclosed.
    let holed = shatter_sim::testing::box_grid_fracture_with_voids(
        [3, 3, 3],
        [1.0; 3].into(),
        &[[1, 1, 1, 2, 2, 2]],
    );
    let prepared = prepare(&holed, Vec3::ONE, 1000.0, false);
    assert_eq!(prepared.enclosed.len(), 26);
    assert!(prepared.enclosed.iter().all(|e| !e));
}

#[test]
fn enclosed_bricks_have_no_colliders_unless_the_setting_asks_for_them() {
    let (world, id) = block(false, Vec3::new(0.0, 5.0, 0.0));
    let colliders = world.fragment_colliders(id);
    assert_eq!(colliders.len(), (N * N * N) as usize);
    for (i, &n) in colliders.iter().enumerate() {
        let want = if inside(cell(i)) { 0 } else { 1 };
        assert_eq!(n, want, "brick {i} at {:?}", cell(i));
    }
    // Every brick is still on the block's one body.
    assert_eq!(world.object_bodies(id).len(), 1);
    assert_eq!(world.fragment_poses(id).len(), colliders.len());

    let (world, id) = block(true, Vec3::new(0.0, 5.0, 0.0));
    assert!(world.fragment_colliders(id).iter().all(|&n| n == 1));
}

#[test]
fn a_block_without_its_inner_colliders_has_the_same_mass_centre_and_inertia() {
    let centre = Vec3::new(1.0, 6.0, -2.0);
    let point = Vec3::new(-4.0, 2.0, 7.0);
    let momentum = |enclosed_colliders: bool| {
        let (mut world, id) = block(enclosed_colliders, centre);
        world.set_object_velocity(
            id,
            centre,
            Vec3::new(3.0, -1.0, 2.0),
            Vec3::new(0.5, 2.0, -1.5),
        );
        world.object_momentum(id, point)
    };
    let (p_all, l_all) = momentum(true);
    let (p_hidden, l_hidden) = momentum(false);
    assert!(rel(p_all, p_hidden) <= 1e-5, "{p_all} against {p_hidden}");
    assert!(rel(l_all, l_hidden) <= 1e-5, "{l_all} against {l_hidden}");
}

#[test]
fn a_broken_bond_gives_an_enclosed_brick_its_colliders_and_the_split_keeps_momentum() {
    let centre = Vec3::new(0.0, 6.0, 0.0);
    let (mut world, id) = block(false, centre);
    world.set_object_velocity(
        id,
        centre,
        Vec3::new(1.0, 2.0, -3.0),
        Vec3::new(-1.0, 0.5, 2.0),
    );
    let point = Vec3::new(3.0, -1.0, 2.0);
    let (p0, l0) = world.object_momentum(id, point);
    // Free the inner brick (1, 1, 1): break its six bonds.
    let inner = 1 + N * (1 + N);
    let fracture = world.object_fracture(id).unwrap();
    let cut: Vec<u32> = fracture
        .bonds
        .iter()
        .enumerate()
        .filter(|(_, b)| b.a == inner || b.b == inner)
        .map(|(i, _)| i as u32)
        .collect();
    assert_eq!(cut.len(), 6);
    world.break_bonds(id, &cut);
    assert_eq!(world.object_bodies(id).len(), 2, "the brick comes loose");
    let colliders = world.fragment_colliders(id);
    // The freed brick, and its three inner neighbours (whose bonds to it broke), now
    // collide; the other four inner bricks are still enclosed.
    for (i, &n) in colliders.iter().enumerate() {
        let c = cell(i);
        let touched = cut.iter().any(|&b| {
            let bond = &fracture.bonds[b as usize];
            bond.a as usize == i || bond.b as usize == i
        });
        let want = if !inside(c) || touched { 1 } else { 0 };
        assert_eq!(n, want, "brick {i} at {c:?}");
    }
    let (p1, l1) = world.object_momentum(id, point);
    assert!(rel(p0, p1) <= 1e-4, "linear momentum {p0} -> {p1}");
    assert!(rel(l0, l1) <= 1e-4, "angular momentum {l0} -> {l1}");
}

#[test]
fn a_block_that_shatters_on_landing_exposes_every_brick_with_a_broken_bond() {
    let mut world = World::new(WorldSettings {
        bond_model: BondModel::Clusters,
        ..WorldSettings::default()
    });
    let mut spec = ObjectSpec::from_fracture(
        box_grid_fracture([6, 6, 6], [0.6; 3].into()),
        Vec3::new(0.0, 4.0, 0.0),
    );
    spec.break_force = Some(300.0);
    let id = world.add_object(spec).unwrap();
    assert_eq!(
        world
            .fragment_colliders(id)
            .iter()
            .filter(|&&n| n == 0)
            .count(),
        64,
        "the 4³ inner bricks start without colliders"
    );
    world.start();
    for _ in 0..120 {
        world.step();
    }
    let broken = world.bond_states(id).unwrap();
    assert!(
        broken.iter().filter(|b| **b).count() > 50,
        "the landing should break bonds"
    );
    let fracture = world.object_fracture(id).unwrap();
    let colliders = world.fragment_colliders(id);
    let mut exposed = 0;
    for (i, &n) in colliders.iter().enumerate() {
        let has_broken = fracture
            .bonds
            .iter()
            .zip(&broken)
            .any(|(b, &x)| x && (b.a as usize == i || b.b as usize == i));
        if has_broken {
            assert!(n > 0, "brick {i} has a broken bond and no collider");
        }
        if n > 0 && fracture.fragments[i].interior.iter().all(|&c| c) {
            exposed += 1;
        }
    }
    assert!(exposed > 0, "some inner brick should have come loose");
    // Nothing went through the ground: every brick's centre is above it.
    for (f, pose) in world.fragment_poses(id) {
        let c = pose.transform_point(fracture.fragments[f as usize].centroid.as_vec3());
        assert!(c.y > 0.0, "brick {f} at {c}");
    }
}
