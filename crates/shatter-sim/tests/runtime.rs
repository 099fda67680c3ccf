//! Runtime fracture: an `on_impact` object starts as one intact body and is cut where a
//! hard hit lands; fragments are cut again down to `depth`; reset brings the intact body
//! back. Outcomes only: bodies, fragments, where the loose pieces are, momentum.

#![allow(clippy::unwrap_used)]

use glam::Vec3;
use shatter_sim::runtime::{FractureTiming, RuntimeFracture};
use shatter_sim::scene::Scene;
use shatter_sim::{
    FractureParams, FractureSource, ObjectId, ObjectSpec, ProjectileSpec, Shape, SimEvent, World,
    WorldSettings,
};

/// A 2 × 2 × 0.3 m slab standing free in space (no gravity, no ground), cut on impact
/// into `pieces`.
fn slab(pieces: u32, runtime: RuntimeFracture) -> ObjectSpec {
    let mut spec = ObjectSpec::from_fracture(Default::default(), Vec3::ZERO);
    spec.source = FractureSource::Shape {
        shape: Shape::Cube,
        params: FractureParams {
            pieces,
            seed: 5,
            ..Default::default()
        },
    };
    spec.scale = Vec3::new(2.0, 2.0, 0.3);
    spec.break_force = Some(2000.0);
    spec.runtime = runtime;
    spec
}

fn space() -> WorldSettings {
    WorldSettings {
        gravity: Vec3::ZERO,
        ground: false,
        ..WorldSettings::default()
    }
}

fn on_impact() -> RuntimeFracture {
    RuntimeFracture {
        timing: FractureTiming::OnImpact,
        ..RuntimeFracture::default()
    }
}

/// A ball at `speed` m/s flying along −z at the slab's face point (0.5, 0.4).
fn ball(speed: f32) -> ProjectileSpec {
    ProjectileSpec {
        from: Vec3::new(0.5, 0.4, 3.0),
        to: Vec3::new(0.5, 0.4, 0.0),
        speed,
        size: 0.2,
        ..ProjectileSpec::default()
    }
}

fn run(world: &mut World, steps: usize) -> Vec<SimEvent> {
    let mut events = Vec::new();
    for _ in 0..steps {
        world.step();
        events.extend(world.take_events());
    }
    events
}

/// The objects cut from `id`.
fn children(world: &World, id: ObjectId) -> Vec<ObjectId> {
    world
        .object_ids()
        .into_iter()
        .filter(|c| world.spawned_from(*c) == Some(id))
        .collect()
}

#[test]
fn an_on_impact_object_is_one_intact_body_until_a_hard_hit_cuts_it_near_the_impact() {
    let mut world = World::new(space());
    let mut spec = slab(40, on_impact());
    // Strong enough that the hit breaks the bonds of the cells it lands on, not the slab.
    spec.break_force = Some(20_000.0);
    let id = world.add_object(spec).unwrap();
    assert_eq!(world.stats().fragments, 1, "one intact fragment");
    assert_eq!(world.object_bodies(id).len(), 1);
    assert_eq!(world.object_level(id), Some(0));
    world.start();
    world.fire(ball(15.0));
    let events = run(&mut world, 60);
    assert_eq!(world.stats().runtime_fractures, 1, "{events:?}");
    let cut = children(&world, id);
    assert_eq!(cut.len(), 1);
    let cut = cut[0];
    assert_eq!(world.object_level(cut), Some(1));
    assert!(
        world.fragment_poses(id).is_empty(),
        "the intact body is gone"
    );
    let fracture = world.object_fracture(cut).unwrap();
    assert!(
        fracture.fragments.len() >= 20,
        "{} pieces",
        fracture.fragments.len()
    );
    assert!(events.iter().any(|e| matches!(
        e,
        SimEvent::Fractured { object, into, level: 1, .. } if *object == id.0 && *into == cut.0
    )));
    // The hit broke bonds, and the pieces that came loose are the small ones near where it
    // landed; the far part of the slab is still one body.
    assert!(world.stats().bonds_broken > 0);
    let impact = glam::DVec3::new(0.25, 0.2, 0.15); // (0.5, 0.4) on the scaled slab's face
    assert!(
        world.object_bodies(cut).len() >= 2,
        "the hit split the cut slab"
    );
    let mut loose = Vec::new();
    let mut largest = (0usize, 0.0f64);
    let poses = world.fragment_poses(cut);
    // Group fragments by body through their poses (fragments of one body share a pose).
    let mut groups: Vec<(shatter_sim::Pose, Vec<u32>)> = Vec::new();
    for (f, pose) in poses {
        match groups.iter_mut().find(|(p, _)| *p == pose) {
            Some((_, list)) => list.push(f),
            None => groups.push((pose, vec![f])),
        }
    }
    for (_, list) in &groups {
        let volume: f64 = list
            .iter()
            .map(|&f| fracture.fragments[f as usize].volume)
            .sum();
        if volume > largest.1 {
            largest = (list.len(), volume);
        }
        if list.len() <= 2 {
            loose.extend(list.iter().copied());
        }
    }
    let total: f64 = fracture.fragments.iter().map(|f| f.volume).sum();
    assert!(
        largest.1 > 0.5 * total,
        "most of the slab stays one body: {} of {total}",
        largest.1
    );
    assert!(!loose.is_empty());
    // The slab is 2 m wide (diagonal 2.8 m): every loose piece is within 1.2 m of the hit.
    for f in &loose {
        let d = fracture.fragments[*f as usize]
            .centroid
            .distance(impact * 2.0);
        assert!(d < 1.2, "loose fragment {f} is {d} m from the impact");
    }
}

#[test]
fn a_slow_hit_does_not_cut() {
    let mut world = World::new(space());
    let id = world.add_object(slab(40, on_impact())).unwrap();
    world.start();
    world.fire(ball(0.5));
    run(&mut world, 90);
    assert_eq!(world.stats().runtime_fractures, 0);
    assert!(children(&world, id).is_empty());
    assert_eq!(world.stats().fragments, 1);
}

#[test]
fn a_cut_keeps_the_momentum_and_spin_the_body_had() {
    let mut world = World::new(space());
    let id = world.add_object(slab(30, on_impact())).unwrap();
    let centre = Vec3::ZERO;
    world.set_object_velocity(
        id,
        centre,
        Vec3::new(1.5, -0.5, 2.0),
        Vec3::new(0.3, 1.2, -0.7),
    );
    let point = Vec3::new(0.3, 0.2, 0.1);
    let (p0, l0) = world.object_momentum(id, point);
    let cut = world.cut_now(id, 0, Vec3::new(0.9, 0.9, 0.15)).unwrap();
    let (p1, l1) = world.object_momentum(cut, point);
    let (pe, le) = (
        (p1 - p0).length() / p0.length(),
        (l1 - l0).length() / l0.length(),
    );
    assert!(
        pe < 1e-4,
        "linear momentum {p0} -> {p1} (relative error {pe})"
    );
    assert!(
        le < 1e-4,
        "angular momentum {l0} -> {l1} (relative error {le})"
    );
    // Breaking every bond of the cut keeps it too (each piece moves as its material did).
    let bonds = world.object_fracture(cut).unwrap().bonds.len() as u32;
    world.break_bonds(cut, &(0..bonds).collect::<Vec<_>>());
    assert_eq!(
        world.object_bodies(cut).len(),
        world.object_fracture(cut).unwrap().fragments.len()
    );
    // One Split event names every part: each fragment alone, each once.
    let parts: Vec<Vec<u32>> = world
        .take_events()
        .into_iter()
        .filter_map(|e| match e {
            SimEvent::Split { object, parts } if object == cut.0 => Some(parts),
            _ => None,
        })
        .flatten()
        .collect();
    let n = world.object_fracture(cut).unwrap().fragments.len();
    assert_eq!(parts.len(), n, "{parts:?}");
    let mut all: Vec<u32> = parts.iter().flatten().copied().collect();
    all.sort_unstable();
    assert_eq!(all, (0..n as u32).collect::<Vec<_>>());
    let (p2, l2) = world.object_momentum(cut, point);
    assert!((p2 - p0).length() / p0.length() < 1e-4, "{p0} -> {p2}");
    assert!((l2 - l0).length() / l0.length() < 1e-4, "{l0} -> {l2}");
}

#[test]
fn a_cut_bird_inherits_convex_pieces_with_hulls_and_keeps_its_momentum() {
    let mut spec = slab(50, on_impact());
    spec.source = FractureSource::Shape {
        shape: Shape::Bird,
        params: FractureParams {
            pieces: 50,
            seed: 2,
            ..Default::default()
        },
    };
    spec.scale = Vec3::ONE;
    let mut world = World::new(space());
    let id = world.add_object(spec).unwrap();
    let whole = world.object_fracture(id).unwrap();
    assert!(whole.fragments[0].convex_pieces.len() > 16);
    world.set_object_velocity(id, Vec3::ZERO, Vec3::new(0.5, 1.0, -2.0), Vec3::Y);
    let point = Vec3::new(0.1, 0.2, 0.3);
    let (p0, l0) = world.object_momentum(id, point);
    let cut = world.cut_now(id, 0, Vec3::new(0.0, 0.0, 1.5)).unwrap();
    let fracture = world.object_fracture(cut).unwrap();
    assert!(fracture.fragments.len() >= 50);
    for (i, f) in fracture.fragments.iter().enumerate() {
        assert!(!f.convex_pieces.is_empty(), "fragment {i}");
        assert_eq!(f.convex_hulls.len(), f.convex_pieces.len(), "fragment {i}");
    }
    let (p1, l1) = world.object_momentum(cut, point);
    assert!((p1 - p0).length() / p0.length() < 1e-4, "{p0} -> {p1}");
    assert!((l1 - l0).length() / l0.length() < 1e-4, "{l0} -> {l1}");
}

#[test]
fn a_hit_on_a_loose_fragment_cuts_it_again_only_below_the_depth() {
    for depth in [1u32, 2] {
        let mut world = World::new(space());
        let runtime = RuntimeFracture {
            depth,
            min_size: 0.01,
            ..on_impact()
        };
        let id = world.add_object(slab(8, runtime)).unwrap();
        let cut = world.cut_now(id, 0, Vec3::new(0.0, 0.0, 0.15)).unwrap();
        let n = world.object_fracture(cut).unwrap().bonds.len() as u32;
        world.break_bonds(cut, &(0..n).collect::<Vec<_>>());
        world.start();
        world.fire(ProjectileSpec {
            from: Vec3::new(0.0, 0.0, 3.0),
            to: Vec3::ZERO,
            speed: 60.0,
            size: 0.2,
            ..ProjectileSpec::default()
        });
        assert_eq!(world.stats().runtime_fractures, 1, "cut_now counts");
        let events = run(&mut world, 40);
        let max = world.stats().max_depth;
        if depth == 1 {
            assert_eq!(world.stats().runtime_fractures, 1, "{events:?}");
            assert_eq!(max, 1);
        } else {
            assert!(world.stats().runtime_fractures >= 2, "{events:?}");
            assert_eq!(max, 2);
        }
    }
}

#[test]
fn reset_brings_the_intact_body_back_and_a_run_repeats() {
    let mut world = World::new(space());
    let id = world.add_object(slab(30, on_impact())).unwrap();
    let first = {
        world.start();
        world.fire(ball(40.0));
        run(&mut world, 40);
        assert_eq!(world.stats().runtime_fractures, 1);
        world.digest()
    };
    world.reset();
    assert_eq!(world.object_ids(), vec![id], "cut objects go on reset");
    assert_eq!(world.stats().fragments, 1);
    world.start();
    world.fire(ball(40.0));
    run(&mut world, 40);
    assert_eq!(world.digest(), first, "the same hit cuts the same way");
}

#[test]
fn scenes_take_the_runtime_keys_and_name_bad_ones() {
    let text = |extra: &str| {
        format!(
            "[world]\ngravity = [0.0, 0.0, 0.0]\nground = false\n[[objects]]\nshape = \"cube\"\npieces = 20\nposition = [0.0, 0.0, 0.0]\n{extra}\n"
        )
    };
    let build = |t: &str| Scene::parse(t).and_then(|s| s.build(None));
    let world = build(&text(
        "fracture = \"on_impact\"\ndepth = 2\nmin_size = 0.2\nfracture_impulse = 50.0",
    ))
    .unwrap();
    let id = world.object_ids()[0];
    let spec = world.object_spec(id).unwrap();
    assert_eq!(spec.runtime.timing, FractureTiming::OnImpact);
    assert_eq!(spec.runtime.depth, 2);
    assert_eq!(spec.runtime.impulse, Some(50.0));
    assert_eq!(world.stats().fragments, 1);
    // The round trip through a saved scene keeps them.
    let saved = world.to_scene_toml().unwrap();
    let again = build(&saved).unwrap();
    assert_eq!(
        again.object_spec(again.object_ids()[0]).unwrap().runtime,
        spec.runtime
    );
    for (extra, key) in [
        ("fracture = \"later\"", "fracture"),
        ("fracture = \"on_impact\"\ndepth = 0", "depth"),
        ("fracture = \"on_impact\"\ndepth = 99", "depth"),
        ("fracture = \"on_impact\"\nmethod = \"tetra\"", "method"),
        ("fracture = \"on_impact\"\npattern = \"uniform\"", "pattern"),
        (
            "fracture = \"on_impact\"\nfracture_impulse = -3.0",
            "fracture_impulse",
        ),
        ("fracture = \"on_impact\"\nmin_size = -1.0", "min_size"),
        (
            "fracture = \"on_impact\"\nbond_model = \"joints\"",
            "fracture",
        ),
    ] {
        let err = match build(&text(extra)) {
            Ok(_) => panic!("`{extra}` was accepted"),
            Err(e) => e.to_string(),
        };
        assert!(err.contains(key), "`{extra}`: {err}");
    }
}

#[test]
fn the_runtime_scene_cuts_the_bird_and_the_pane_where_the_balls_land() {
    let path =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../assets/scenes/runtime.toml");
    let scene = Scene::load(&path).unwrap();
    let mut world = scene.build(None).unwrap();
    let (bird, pane) = (world.object_ids()[0], world.object_ids()[1]);
    assert_eq!(world.stats().fragments, 2, "both start whole");
    world.start();
    // Up to the first ball's arrival the bird only lands: not cut.
    let events = run(&mut world, 30);
    assert_eq!(world.stats().runtime_fractures, 0, "{events:?}");
    let events = run(&mut world, 150);
    let cut_from = |id: ObjectId| {
        events
            .iter()
            .any(|e| matches!(e, SimEvent::Fractured { object, level: 1, .. } if *object == id.0))
    };
    assert!(cut_from(bird), "the ball cuts the bird: {events:?}");
    assert!(cut_from(pane), "the ball cuts the pane: {events:?}");
    assert_eq!(world.stats().diverged, 0);
    assert!(world.stats().bonds_broken > 0);
}
