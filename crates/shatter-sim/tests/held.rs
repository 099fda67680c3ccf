//! Contacts left out: joints-model fragments held within three bonds of each other
//! (`skip_held_contacts`; once their bonds break, they collide), and tiny debris with
//! tiny debris (`tiny_debris`).
#![allow(clippy::unwrap_used, missing_docs)]

mod common;
use common::*;
use shatter_sim::BondModel;

#[test]
fn fragments_held_by_joints_touch_only_when_their_bonds_break() {
    let touching = |skip: bool, break_one: bool| {
        let (mut world, id) = wall_world(BondModel::Joints, 1e9);
        let mut settings = *world.settings();
        settings.skip_held_contacts = skip;
        world.set_settings(settings);
        run(&mut world, 5);
        if break_one {
            // Every bond of the brick at the wall's top front corner.
            let fracture = world.object_fracture(id).unwrap();
            let corner = (0..fracture.fragments.len())
                .max_by(|&a, &b| {
                    let key = |f: usize| {
                        let c = fracture.fragments[f].centroid;
                        c.x + c.y + c.z
                    };
                    key(a).total_cmp(&key(b))
                })
                .unwrap() as u32;
            let bonds: Vec<u32> = (0..fracture.bonds.len() as u32)
                .filter(|&b| {
                    let bond = &fracture.bonds[b as usize];
                    bond.a == corner || bond.b == corner
                })
                .collect();
            world.break_bonds(id, &bonds);
            for _ in 0..5 {
                world.step();
            }
        }
        world.touching_pairs()
    };
    // The 8 × 4 × 2 anchored wall: bricks meet their edge and corner neighbours without
    // a bond, and those touch unless held.
    assert!(touching(false, false) > 0);
    assert_eq!(touching(true, false), 0, "held bricks touch");
    // The loose corner brick rests on its neighbours and touches them again.
    assert!(touching(true, true) > 0, "a loose brick touches nothing");
}

#[test]
fn tiny_debris_touches_the_ground_but_not_other_tiny_debris() {
    use glam::Vec3;
    use shatter_sim::testing::box_grid_fracture;
    use shatter_sim::{ObjectSpec, World, WorldSettings};
    // 18 bricks of 3 cm (6 cm across) in two layers, with bonds that break at once.
    let touching = |tiny_debris: f32| {
        let mut world = World::new(WorldSettings {
            bond_model: BondModel::Clusters,
            tiny_debris,
            ..WorldSettings::default()
        });
        let mut spec = ObjectSpec::from_fracture(
            box_grid_fracture([3, 2, 3], [0.09, 0.06, 0.09].into()),
            Vec3::new(0.0, 0.03, 0.0),
        );
        spec.break_force = Some(0.001);
        world.add_object(spec).unwrap();
        run(&mut world, 120);
        assert_eq!(world.stats().bodies, 18, "not all loose");
        world.touching_pairs()
    };
    // Every brick on the ground and nothing else: the upper layer fell through the lower.
    assert_eq!(touching(0.1), 18, "tiny debris pairs touch");
    // With the rule off, the upper layer rests on the lower one.
    let pairs = touching(0.0);
    assert!(pairs > 18, "{pairs}");
}
