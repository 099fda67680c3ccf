//! `skip_held_contacts`: joints-model fragments held within three bonds of each other do
//! not collide; once their bonds break, they do.
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
