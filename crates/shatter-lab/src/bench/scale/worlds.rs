//! The scale benchmark's worlds, built with `shatter_sim`'s public API: brick grids of
//! about N fragments (`FractureParams { method: Grid, .. }` on the cube), as an anchored
//! wall hit by shots, an anchored wall with an explosion in it or blown apart by one, or a
//! block of weakly bonded bricks dropped from 4 m.

use glam::Vec3;
use shatter_sim::{
    BondModel, ExplosionSpec, FractureParams, FractureSource, MethodKind, ObjectId, ObjectSpec,
    ProjectileSpec, Shape, World, WorldSettings,
};

use crate::error::{LabError, ResultExt};

/// What happens to the bricks in a scale run.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum ScaleCase {
    /// An anchored wall (bricks 0.1 × 0.1 × 0.2 m, two deep, 20 kN bonds) hit by a
    /// 0.3 m steel ball at 40 m/s every 0.25 s from 0.25 s on, across its face.
    Shots,
    /// The same wall with an explosion (radius 1 m, 1,500 N·s) 0.3 m in front of its
    /// middle at 0.25 s.
    Explosion,
    /// A block of 0.1 m bricks with weak bonds (2 kN) dropped from 4 m (its bottom),
    /// shattering on landing at about 0.9 s.
    Landing,
    /// The same wall blown apart: the explosion of [`ScaleCase::Explosion`] with a radius
    /// of half the wall's diagonal, so it reaches every brick (about half of them come
    /// loose: 10,000 free bodies from 20,000 bricks).
    Blast,
}

impl ScaleCase {
    /// Every case, in the order `--cases` lists them by default.
    pub const ALL: &'static [ScaleCase] = &[
        ScaleCase::Shots,
        ScaleCase::Explosion,
        ScaleCase::Landing,
        ScaleCase::Blast,
    ];
    /// The words of [`Self::ALL`], in the same order.
    pub const NAMES: &'static [&'static str] = &["shots", "explosion", "landing", "blast"];

    /// The case's word.
    pub fn name(self) -> &'static str {
        match self {
            ScaleCase::Shots => "shots",
            ScaleCase::Explosion => "explosion",
            ScaleCase::Landing => "landing",
            ScaleCase::Blast => "blast",
        }
    }
}

impl std::fmt::Display for ScaleCase {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// Edge of a brick (m); the walls' bricks are twice as deep.
const BRICK: f32 = 0.1;
/// Break force of the walls' bonds (N), as the 2,000-brick benchmark wall.
const WALL_BREAK_FORCE: f32 = 20_000.0;
/// Break force of the landing block's bonds (N): weak, so that the landing shatters it.
const LANDING_BREAK_FORCE: f32 = 2_000.0;
/// Height of the landing block's bottom above the ground (m).
const DROP_HEIGHT: f32 = 4.0;
/// Width over height of the walls (the 2,000-brick wall's 40 × 25).
const WALL_ASPECT: f64 = 1.6;
/// First shot and the time between shots (s).
const SHOT_START: f64 = 0.25;
const SHOT_EVERY: f64 = 0.25;
/// Where the shots hit, as fractions of the wall's width and height, in turn.
const SHOT_TARGETS: [(f32, f32); 8] = [
    (0.5, 0.5),
    (0.25, 0.3),
    (0.75, 0.7),
    (0.3, 0.75),
    (0.7, 0.25),
    (0.5, 0.2),
    (0.5, 0.8),
    (0.15, 0.5),
];

/// The grid of cells for about `n` bricks in `case` (the count is rounded to a grid:
/// the report gives the fragments actually built).
pub fn grid_for(case: ScaleCase, n: usize) -> [u32; 3] {
    let n = n.max(1) as f64;
    match case {
        ScaleCase::Shots | ScaleCase::Explosion | ScaleCase::Blast => {
            // Two bricks deep, width : height about 1.6.
            let face = (n / 2.0).max(1.0);
            let rows = (face / WALL_ASPECT).sqrt().round().max(1.0);
            let columns = (face / rows).round().max(1.0);
            [columns as u32, rows as u32, 2]
        }
        ScaleCase::Landing => {
            let side = n.cbrt().round().max(1.0);
            let depth = (n / (side * side)).round().max(1.0);
            [side as u32, side as u32, depth as u32]
        }
    }
}

/// Bricks of a grid.
pub fn bricks(grid: [u32; 3]) -> usize {
    grid.iter().map(|&c| c as usize).product()
}

/// The world settings a scale run may change from the defaults.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Speedups {
    /// [`WorldSettings::box_colliders`].
    pub box_colliders: bool,
    /// [`WorldSettings::skip_held_contacts`].
    pub skip_held_contacts: bool,
    /// [`WorldSettings::enclosed_colliders`].
    pub enclosed_colliders: bool,
    /// [`WorldSettings::contact_speed_cap`] turned off.
    pub no_contact_speed_cap: bool,
}

/// A world of `case` with about `n` bricks bonded by `model`, and the object's id;
/// `seconds` is the length of the run (the shots are scheduled up to it); `speedups`
/// are the settings changed from the defaults.
pub fn build(
    case: ScaleCase,
    n: usize,
    model: BondModel,
    seconds: f64,
    speedups: Speedups,
) -> Result<(World, ObjectId), LabError> {
    let grid = grid_for(case, n);
    let mut world = World::new(WorldSettings {
        bond_model: model,
        box_colliders: speedups.box_colliders,
        skip_held_contacts: speedups.skip_held_contacts,
        enclosed_colliders: speedups.enclosed_colliders,
        contact_speed_cap: !speedups.no_contact_speed_cap,
        ..WorldSettings::default()
    });
    let cells = Vec3::new(grid[0] as f32, grid[1] as f32, grid[2] as f32);
    let mut spec = ObjectSpec::from_fracture(Default::default(), Vec3::ZERO);
    spec.source = FractureSource::Shape {
        shape: Shape::Cube,
        params: FractureParams {
            method: Some(MethodKind::Grid),
            grid,
            ..FractureParams::default()
        },
    };
    spec.name = case.name().to_string();
    let size = match case {
        ScaleCase::Shots | ScaleCase::Explosion | ScaleCase::Blast => {
            spec.anchored = true;
            spec.break_force = Some(WALL_BREAK_FORCE);
            let size = cells * Vec3::new(BRICK, BRICK, 2.0 * BRICK);
            spec.position = Vec3::new(0.0, size.y / 2.0, 0.0);
            size
        }
        ScaleCase::Landing => {
            spec.break_force = Some(LANDING_BREAK_FORCE);
            let size = cells * BRICK;
            spec.position = Vec3::new(0.0, DROP_HEIGHT + size.y / 2.0, 0.0);
            size
        }
    };
    spec.scale = size;
    let id = world.add_object(spec).internal_err(format!(
        "building the {case} world of {} bricks",
        bricks(grid)
    ))?;
    match case {
        ScaleCase::Shots => schedule_shots(&mut world, size, seconds),
        ScaleCase::Explosion | ScaleCase::Blast => world.schedule_explosion(
            SHOT_START,
            ExplosionSpec {
                position: Vec3::new(0.0, size.y / 2.0, size.z / 2.0 + 0.3),
                // The blast reaches the wall's corners from its middle.
                radius: if case == ScaleCase::Blast {
                    size.truncate().length() / 2.0
                } else {
                    1.0
                },
                power: 1500.0,
            },
        ),
        ScaleCase::Landing => {}
    }
    Ok((world, id))
}

/// One shot every [`SHOT_EVERY`] seconds from [`SHOT_START`] while `t < seconds`, at the
/// wall of `size` (standing on the ground, centred on x = 0, its face at z = size.z / 2).
fn schedule_shots(world: &mut World, size: Vec3, seconds: f64) {
    let mut k = 0usize;
    loop {
        let at = SHOT_START + SHOT_EVERY * k as f64;
        if at >= seconds {
            break;
        }
        let (fx, fy) = SHOT_TARGETS[k % SHOT_TARGETS.len()];
        let target = Vec3::new((fx - 0.5) * size.x, fy * size.y, 0.0);
        world.schedule_projectile(
            at,
            ProjectileSpec {
                size: 0.3,
                speed: 40.0,
                from: target + Vec3::new(0.0, 0.0, 6.0),
                to: target,
                ..ProjectileSpec::default()
            },
        );
        k += 1;
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;

    #[test]
    fn the_case_names_are_in_the_order_of_the_cases() {
        let names: Vec<&str> = ScaleCase::ALL.iter().map(|c| c.name()).collect();
        assert_eq!(names, ScaleCase::NAMES);
        assert_eq!(ScaleCase::Landing.to_string(), "landing");
    }

    #[test]
    fn the_default_sizes_round_to_grids_near_them() {
        // The 2,000-brick wall is the step benchmark's 40 × 25 × 2.
        assert_eq!(grid_for(ScaleCase::Shots, 2000), [40, 25, 2]);
        for case in ScaleCase::ALL.iter().copied() {
            for n in [200, 2000, 5000, 10_000, 20_000] {
                let got = bricks(grid_for(case, n)) as f64;
                assert!((got / n as f64 - 1.0).abs() < 0.1, "{case} {n}: {got}");
            }
        }
        assert_eq!(bricks(grid_for(ScaleCase::Landing, 1)), 1);
    }

    #[test]
    fn a_world_holds_the_grid_s_bricks_and_its_shots() {
        let (world, _) = build(
            ScaleCase::Shots,
            200,
            BondModel::Clusters,
            1.0,
            Speedups::default(),
        )
        .unwrap();
        assert_eq!(
            world.stats().fragments,
            bricks(grid_for(ScaleCase::Shots, 200))
        );
        // Shots at 0.25, 0.5 and 0.75 s: they exist once fired.
        let mut world = world;
        world.start();
        for _ in 0..50 {
            world.step();
        }
        assert_eq!(world.projectiles().len(), 3);
    }
}
