//! The grid method: bricks of a box (exact, in grid order), cells clipped to other
//! meshes, voids, attributes, bad grids.
#![allow(clippy::unwrap_used)]

#[path = "fracture_shapes.rs"]
mod shapes;

use shapes::*;
use shatter_geom::DVec3;
use shatter_geom::fracture::{
    Fracture, FractureError, FractureParams, Method, fracture, fracture_model,
};
use shatter_geom::model::Model;

fn grid(cells: [u32; 3], voids: Vec<[u32; 6]>) -> FractureParams {
    FractureParams {
        method: Method::Grid { cells, voids },
        seed: 0,
    }
}

/// Bonds of a full `nx × ny × nz` grid: the faces two cells share.
fn full_bonds([x, y, z]: [u32; 3]) -> usize {
    ((x - 1) * y * z + x * (y - 1) * z + x * y * (z - 1)) as usize
}

fn interior_triangles(f: &Fracture) -> usize {
    f.fragments
        .iter()
        .map(|g| g.interior.iter().filter(|&&i| i).count())
        .sum()
}

#[test]
fn a_box_becomes_bricks_in_grid_order_with_a_bond_per_shared_face() {
    let (lo, hi) = (DVec3::new(1.0, -2.0, 0.5), DVec3::new(4.0, 0.0, 2.5));
    let mesh = box24(lo, hi);
    let cells = [3, 4, 2];
    let f = fracture(&mesh, &grid(cells, Vec::new())).unwrap();
    check_fracture(&mesh, 12.0, &f, 1e-12, "box grid");
    assert_eq!(f.fragments.len(), 24);
    assert_eq!(f.bonds.len(), full_bonds(cells));
    let cell = (hi - lo) / DVec3::new(3.0, 4.0, 2.0);
    for (i, g) in f.fragments.iter().enumerate() {
        let (x, y, z) = (i % 3, (i / 3) % 4, i / 12);
        let centre = lo + cell * (DVec3::new(x as f64, y as f64, z as f64) + 0.5);
        assert!(
            (g.centroid - centre).length() < 1e-12,
            "brick {i} at {}",
            g.centroid
        );
        assert!(
            (g.volume - 0.5).abs() < 1e-12,
            "brick {i} volume {}",
            g.volume
        );
        assert_eq!(g.mesh.triangles.len(), 12, "brick {i}");
    }
    // Each shared face is two triangles on each side.
    assert_eq!(interior_triangles(&f), 4 * f.bonds.len());
    for b in &f.bonds {
        let d = f.fragments[b.b as usize].centroid - f.fragments[b.a as usize].centroid;
        assert!((d.normalize() - b.normal).length() < 1e-12);
        assert!((b.centroid - (f.fragments[b.a as usize].centroid + d / 2.0)).length() < 1e-12);
    }
}

#[test]
fn voids_leave_out_their_cells_and_their_walls_are_surface() {
    // A 5 × 3 × 1 bridge: the lower two rows between the end columns left out.
    let mesh = box24(DVec3::ZERO, DVec3::new(5.0, 3.0, 1.0));
    let f = fracture(&mesh, &grid([5, 3, 1], vec![[1, 0, 0, 4, 2, 1]])).unwrap();
    assert_eq!(f.fragments.len(), 9);
    // Pillars of 2 (1 bond each), the deck of 5 (4 bonds), the pillars' tops to the deck.
    assert_eq!(f.bonds.len(), 1 + 1 + 4 + 2);
    assert_eq!(interior_triangles(&f), 4 * f.bonds.len());
    let total: f64 = f.fragments.iter().map(|g| g.volume).sum();
    assert!((total - 9.0).abs() < 1e-12);
    for g in &f.fragments {
        assert_closed_outward(&g.mesh, "voided brick");
        assert!(g.centroid.y > 2.0 || g.centroid.x < 1.0 || g.centroid.x > 4.0);
    }
}

#[test]
fn a_sphere_is_cut_into_cells_clipped_to_it() {
    let mesh = shatter_geom::shapes::sphere(24, 12);
    let volume = mesh.signed_volume();
    let cells = [4, 3, 5];
    let f = fracture(&mesh, &grid(cells, Vec::new())).unwrap();
    check_fracture(&mesh, volume, &f, 1e-9, "sphere grid");
    assert!(
        f.fragments.len() > 30 && f.fragments.len() <= 60,
        "{}",
        f.fragments.len()
    );
    // Every fragment lies in one cell of the sphere's box, in grid order.
    let (lo, hi) = mesh.bounds().unwrap();
    let cell = (hi - lo) / DVec3::new(4.0, 3.0, 5.0);
    let mut last = 0;
    for (i, g) in f.fragments.iter().enumerate() {
        let (a, b) = g.mesh.bounds().unwrap();
        let c = ((a + b) / 2.0 - lo) / cell;
        let c = c.floor();
        let (cl, ch) = (lo + cell * c, lo + cell * (c + 1.0));
        let tol = 1e-9;
        assert!(
            a.cmpge(cl - tol).all() && b.cmple(ch + tol).all(),
            "fragment {i} spans {a}..{b}, outside its cell {cl}..{ch}"
        );
        let index = (c.x + 4.0 * (c.y + 3.0 * c.z)) as usize;
        assert!(index >= last, "fragment {i} out of grid order");
        last = index;
    }
    // Every bond lies on one of the grid's planes.
    for b in &f.bonds {
        let axis = b.normal.abs().max_position();
        assert!(
            (b.normal.abs()[axis] - 1.0).abs() < 1e-12,
            "bond normal {}",
            b.normal
        );
        let k = (b.centroid[axis] - lo[axis]) / cell[axis];
        assert!(
            (k - k.round()).abs() < 1e-9,
            "bond off the grid's planes: {k}"
        );
    }
}

#[test]
fn a_torus_grid_with_a_void_keeps_it_closed_and_its_walls_on_the_surface() {
    let mesh = torus(1.0, 0.4, 32, 16);
    let volume = mesh.signed_volume();
    let void = [0, 0, 0, 2, 4, 1];
    let f = fracture(&mesh, &grid([4, 4, 1], vec![void])).unwrap();
    // Half the torus is left; the cut where the void begins is its surface.
    let total: f64 = f.fragments.iter().map(|g| g.volume).sum();
    assert!(
        (total - volume / 2.0).abs() < 1e-9 * volume,
        "{total} of {volume}"
    );
    let (lo, hi) = mesh.bounds().unwrap();
    let mid = (lo.x + hi.x) / 2.0;
    for (i, g) in f.fragments.iter().enumerate() {
        assert_closed_outward(&g.mesh, &format!("fragment {i}"));
        assert!(
            g.mesh.bounds().unwrap().0.x >= mid - 1e-9,
            "fragment {i} in the void"
        );
        // Interior faces are bonded faces: none lies on the void's wall x = mid.
        for t in 0..g.mesh.triangles.len() {
            let [a, b, c] = g.mesh.triangle(t);
            let on_wall = [a, b, c].iter().all(|p| (p.x - mid).abs() < 1e-9);
            assert!(
                !(on_wall && g.interior[t]),
                "fragment {i}: the void's wall is a cut"
            );
        }
    }
    let bonded: f64 = f.bonds.iter().map(|b| 2.0 * b.area).sum();
    let cut: f64 = f.fragments.iter().map(interior_area).sum();
    assert!((bonded - cut).abs() < 1e-9 * cut, "{bonded} vs {cut}");
}

#[test]
fn bricks_keep_the_models_uvs_on_the_surface() {
    let mut model = Model::from_mesh(shatter_geom::shapes::cube());
    // u = x + ½, v = y + ½ on every face of the cube (−½..½).
    model.corners.uv = Some(corner_uvs(&model.mesh, |p| {
        [(p.x + 0.5) as f32, (p.y + 0.5) as f32]
    }));
    let f = fracture_model(&model, &grid([2, 2, 2], Vec::new())).unwrap();
    assert_eq!(f.fragments.len(), 8);
    assert_eq!(f.materials.last().unwrap().name, "interior");
    for g in &f.fragments {
        let uv = g.corners.uv.as_ref().unwrap();
        for (t, tri) in g.mesh.triangles.iter().enumerate() {
            if g.interior[t] {
                assert_eq!(g.material[t] as usize, f.materials.len() - 1);
                continue;
            }
            for k in 0..3 {
                let p = g.mesh.positions[tri[k] as usize];
                assert!((uv[t][k][0] as f64 - (p.x + 0.5)).abs() < 1e-6);
                assert!((uv[t][k][1] as f64 - (p.y + 0.5)).abs() < 1e-6);
            }
        }
    }
}

#[test]
fn a_grid_without_cells_is_refused() {
    let mesh = box24(DVec3::ZERO, DVec3::ONE);
    for cells in [[0, 2, 2], [u32::MAX, u32::MAX, 2]] {
        let e = fracture(&mesh, &grid(cells, Vec::new())).unwrap_err();
        assert_eq!(e, FractureError::BadGrid { cells });
        assert!(e.to_string().contains("at least 1 cell"), "{e}");
    }
    // Voids that leave nothing: no fragment, an error rather than an empty result.
    let e = fracture(&mesh, &grid([2, 2, 2], vec![[0, 0, 0, 2, 2, 2]])).unwrap_err();
    assert_eq!(e, FractureError::NoFragments);
}
