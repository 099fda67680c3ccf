//! Ready-made fractures and worlds for the tests and benchmarks: a box cut into a grid of
//! bricks (shatter-geom's [`Method::Grid`]) and the 2,000-brick benchmark wall.

use shatter_geom::fracture::{Fracture, FractureParams, Method, fracture};
use shatter_geom::{DVec3, shapes};

/// A box of `size` (full extents, centred on the origin) cut into `cells[0] × cells[1] ×
/// cells[2]` equal boxes, bonded across every shared face: [`Method::Grid`] on a box.
///
/// Fragment `i` sits at grid cell `(x, y, z)` with `i = x + nx·(y + ny·z)`. Bonds are
/// sorted by `(a, b)` with `a < b`, normals point from `a` to `b`.
///
/// ```
/// use shatter_sim::testing::box_grid_fracture;
/// let f = box_grid_fracture([20, 10, 10], [4.0, 2.0, 2.0].into());
/// assert_eq!(f.fragments.len(), 2000);
/// // 19·10·10 + 20·9·10 + 20·10·9 shared faces.
/// assert_eq!(f.bonds.len(), 1900 + 1800 + 1800);
/// ```
///
/// # Panics
/// When a cell count is 0 or `size` is not positive and finite (a test's own mistake).
pub fn box_grid_fracture(cells: [u32; 3], size: DVec3) -> Fracture {
    box_grid_fracture_with_voids(cells, size, &[])
}

/// [`box_grid_fracture`] without the cells inside any of `voids` (boxes of cells
/// `[x0, y0, z0, x1, y1, z1]`, `x0 <= x < x1` and so on): fragments in grid order
/// without the gaps, no bond to a left-out cell, the faces on one surface.
///
/// ```
/// use shatter_sim::testing::box_grid_fracture_with_voids;
/// // A 5 × 3 × 1 bridge: the span's lower two rows between the end columns left out.
/// let f = box_grid_fracture_with_voids([5, 3, 1], [5.0, 3.0, 1.0].into(), &[[1, 0, 0, 4, 2, 1]]);
/// assert_eq!(f.fragments.len(), 15 - 6);
/// ```
///
/// # Panics
/// As [`box_grid_fracture`], and when the voids leave no cell.
pub fn box_grid_fracture_with_voids(cells: [u32; 3], size: DVec3, voids: &[[u32; 6]]) -> Fracture {
    let params = FractureParams {
        method: Method::Grid {
            cells,
            voids: voids.to_vec(),
        },
        seed: 0,
    };
    fracture(&shapes::cube().transformed(size, DVec3::ZERO), &params)
        .expect("a grid of a box with positive cells and size")
}

/// The benchmark wall of `assets/scenes/wall.toml`, built in code: 40 × 25 × 2 = 2,000
/// anchored stone bricks (4 m × 2.5 m × 0.4 m, break force 20 kN) and a 0.3 m steel ball
/// at 40 m/s fired 0.5 s in.
pub fn wall_benchmark_world(model: crate::BondModel) -> crate::World {
    use glam::Vec3;
    let mut world = crate::World::new(crate::WorldSettings {
        bond_model: model,
        ..crate::WorldSettings::default()
    });
    let mut spec = crate::ObjectSpec::from_fracture(
        box_grid_fracture([40, 25, 2], DVec3::ONE),
        Vec3::new(0.0, 1.25, 0.0),
    );
    spec.name = "wall".to_string();
    spec.scale = Vec3::new(4.0, 2.5, 0.4);
    spec.break_force = Some(20_000.0);
    spec.anchored = true;
    world
        .add_object(spec)
        .expect("the benchmark wall is a valid object");
    world.schedule_projectile(
        0.5,
        crate::ProjectileSpec {
            size: 0.3,
            speed: 40.0,
            from: Vec3::new(0.2, 1.2, 6.0),
            to: Vec3::new(0.2, 1.2, 0.0),
            ..crate::ProjectileSpec::default()
        },
    );
    world
}
