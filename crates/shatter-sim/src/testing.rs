//! Fractures built without the fracture algorithms: a grid of box fragments ("bricks").
//!
//! Used by the tests and benchmarks, and by scenes through the `grid` method.

use shatter_geom::fracture::{Bond, Fracture, Fragment, interior_material};
use shatter_geom::model::Material;
use shatter_geom::{DMat3, DVec3, TriMesh};

/// A box of `size` (full extents, centred on the origin) cut into `cells[0] × cells[1] ×
/// cells[2]` equal boxes, bonded across every shared face.
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
pub fn box_grid_fracture(cells: [u32; 3], size: DVec3) -> Fracture {
    let [nx, ny, nz] = cells.map(|c| c.max(1));
    let cell = size / DVec3::new(nx as f64, ny as f64, nz as f64);
    let origin = -size / 2.0;
    let index = |x: u32, y: u32, z: u32| x + nx * (y + ny * z);
    let mut fragments = Vec::with_capacity((nx * ny * nz) as usize);
    for z in 0..nz {
        for y in 0..ny {
            for x in 0..nx {
                let lo = origin + cell * DVec3::new(x as f64, y as f64, z as f64);
                let on_boundary = [
                    x == 0,
                    x == nx - 1,
                    y == 0,
                    y == ny - 1,
                    z == 0,
                    z == nz - 1,
                ];
                fragments.push(box_fragment(lo, lo + cell, on_boundary));
            }
        }
    }
    let mut bonds = Vec::new();
    for z in 0..nz {
        for y in 0..ny {
            for x in 0..nx {
                let a = index(x, y, z);
                let centre = fragments[a as usize].centroid;
                let mut push = |b: u32, axis: DVec3, area: f64| {
                    bonds.push(Bond {
                        a,
                        b,
                        area,
                        centroid: centre + axis * (cell * 0.5),
                        normal: axis,
                    });
                };
                if x + 1 < nx {
                    push(index(x + 1, y, z), DVec3::X, cell.y * cell.z);
                }
                if y + 1 < ny {
                    push(index(x, y + 1, z), DVec3::Y, cell.x * cell.z);
                }
                if z + 1 < nz {
                    push(index(x, y, z + 1), DVec3::Z, cell.x * cell.y);
                }
            }
        }
    }
    Fracture {
        fragments,
        bonds,
        // Material 0 on the surface, 1 (interior) on the cut faces.
        materials: vec![Material::default(), interior_material()],
        ..Default::default()
    }
}

/// [`box_grid_fracture`] without the cells inside any of `voids` (boxes of cells
/// `[x0, y0, z0, x1, y1, z1]`, `x0 <= x < x1` and so on). Fragments keep the grid order
/// (renumbered without the gaps); bonds to a left-out cell are gone.
///
/// ```
/// use shatter_sim::testing::box_grid_fracture_with_voids;
/// // A 5 × 3 × 1 bridge: the span's lower two rows between the end columns left out.
/// let f = box_grid_fracture_with_voids([5, 3, 1], [5.0, 3.0, 1.0].into(), &[[1, 0, 0, 4, 2, 1]]);
/// assert_eq!(f.fragments.len(), 15 - 6);
/// ```
pub fn box_grid_fracture_with_voids(cells: [u32; 3], size: DVec3, voids: &[[u32; 6]]) -> Fracture {
    let full = box_grid_fracture(cells, size);
    if voids.is_empty() {
        return full;
    }
    let [nx, ny, _] = cells.map(|c| c.max(1));
    let inside = |i: u32| {
        let (x, y, z) = (i % nx, (i / nx) % ny, i / (nx * ny));
        voids.iter().any(|v| {
            (v[0]..v[3]).contains(&x) && (v[1]..v[4]).contains(&y) && (v[2]..v[5]).contains(&z)
        })
    };
    let mut index = vec![u32::MAX; full.fragments.len()];
    let mut fragments = Vec::new();
    for (i, f) in full.fragments.into_iter().enumerate() {
        if !inside(i as u32) {
            index[i] = fragments.len() as u32;
            fragments.push(f);
        }
    }
    let bonds = full
        .bonds
        .into_iter()
        .filter_map(|b| {
            let (a, c) = (index[b.a as usize], index[b.b as usize]);
            (a != u32::MAX && c != u32::MAX).then_some(Bond { a, b: c, ..b })
        })
        .collect();
    // Faces that now border a left-out cell are on the surface: mark them so (two
    // triangles per face, faces −x, +x, −y, +y, −z, +z as in `box_fragment`).
    let nz = cells[2].max(1);
    for (i, old) in index.iter().enumerate() {
        if *old == u32::MAX {
            continue;
        }
        let i = i as u32;
        let (x, y, z) = (i % nx, (i / nx) % ny, i / (nx * ny));
        let at = |dx: i64, dy: i64, dz: i64| {
            let (a, b, c) = (x as i64 + dx, y as i64 + dy, z as i64 + dz);
            let within =
                a >= 0 && b >= 0 && c >= 0 && a < nx as i64 && b < ny as i64 && c < nz as i64;
            within && !inside((a + nx as i64 * (b + ny as i64 * c)) as u32)
        };
        let neighbours = [
            at(-1, 0, 0),
            at(1, 0, 0),
            at(0, -1, 0),
            at(0, 1, 0),
            at(0, 0, -1),
            at(0, 0, 1),
        ];
        let frag = &mut fragments[*old as usize];
        for (face, n) in neighbours.iter().enumerate() {
            frag.interior[2 * face] = *n;
            frag.interior[2 * face + 1] = *n;
        }
    }
    Fracture {
        fragments,
        bonds,
        ..Default::default()
    }
}

/// One axis-aligned box fragment from `lo` to `hi`. `on_boundary` flags the faces
/// −x, +x, −y, +y, −z, +z that lie on the object's surface.
pub fn box_fragment(lo: DVec3, hi: DVec3, on_boundary: [bool; 6]) -> Fragment {
    let corners: Vec<DVec3> = (0..8)
        .map(|i| {
            DVec3::new(
                if i & 1 == 0 { lo.x } else { hi.x },
                if i & 2 == 0 { lo.y } else { hi.y },
                if i & 4 == 0 { lo.z } else { hi.z },
            )
        })
        .collect();
    // Two outward triangles per face, faces in the order −x, +x, −y, +y, −z, +z.
    let faces: [[u32; 4]; 6] = [
        [0, 4, 6, 2],
        [1, 3, 7, 5],
        [0, 1, 5, 4],
        [2, 6, 7, 3],
        [0, 2, 3, 1],
        [4, 5, 7, 6],
    ];
    let mut triangles = Vec::with_capacity(12);
    let mut interior = Vec::with_capacity(12);
    for (face, [a, b, c, d]) in faces.iter().enumerate() {
        triangles.push([*a, *b, *c]);
        triangles.push([*a, *c, *d]);
        interior.extend([!on_boundary[face]; 2]);
    }
    let e = hi - lo;
    let volume = e.x * e.y * e.z;
    let inertia = DMat3::from_diagonal(
        DVec3::new(
            e.y * e.y + e.z * e.z,
            e.x * e.x + e.z * e.z,
            e.x * e.x + e.y * e.y,
        ) * (volume / 12.0),
    );
    let material = interior.iter().map(|&i| u32::from(i)).collect();
    Fragment {
        mesh: TriMesh::new(corners.clone(), triangles),
        interior,
        corners: Default::default(),
        material,
        convex_pieces: vec![corners],
        volume,
        centroid: (lo + hi) / 2.0,
        inertia,
    }
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn grid_fragments_are_outward_and_fill_the_box() {
        let f = box_grid_fracture([3, 2, 4], DVec3::new(3.0, 1.0, 2.0));
        let total: f64 = f.fragments.iter().map(|g| g.mesh.signed_volume()).sum();
        assert!((total - 6.0).abs() < 1e-12);
        for g in &f.fragments {
            assert!((g.mesh.signed_volume() - g.volume).abs() < 1e-12);
            assert!((g.mesh.centroid() - g.centroid).length() < 1e-12);
        }
        for b in &f.bonds {
            assert!(b.a < b.b);
            let d = f.fragments[b.b as usize].centroid - f.fragments[b.a as usize].centroid;
            assert!((d.normalize() - b.normal).length() < 1e-12);
        }
    }
}
