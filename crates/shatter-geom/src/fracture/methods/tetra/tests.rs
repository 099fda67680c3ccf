//! The cells of the tetra method: a tetrahedron the surface cuts in two gives two
//! pieces, one wholly inside stays itself, one wholly outside is dropped.

use glam::DVec3;

use super::cells::cells;
use crate::delaunay::tetrahedralize;
use crate::fracture::kernel::convex::tet_volume;
use crate::fracture::kernel::{Piece, is_surface, source_triangle};
use crate::shapes;

fn torus() -> Piece {
    // Ring about the y axis in the xz plane: radii 0.3..0.7, |y| <= 0.2.
    Piece::from_mesh_welded(&shapes::torus(0.5, 0.2, 24, 12))
}

fn closed(p: &Piece) -> bool {
    let mut edges: Vec<(u32, u32)> = p
        .tris
        .iter()
        .flat_map(|t| (0..3).map(move |k| (t[k], t[(k + 1) % 3])))
        .collect();
    edges.sort_unstable();
    let unique = edges.windows(2).all(|w| w[0] != w[1]);
    unique
        && edges
            .iter()
            .all(|&(a, b)| edges.binary_search(&(b, a)).is_ok())
}

#[test]
fn a_tetrahedron_across_the_hole_gives_two_pieces() {
    let mesh = torus();
    let volume = mesh.volume();
    // A long thin tetrahedron along x through the hole: it passes through the ring on
    // both sides (|x| in 0.3..0.7), and through the hole (|x| < 0.3) between.
    let pts = vec![
        DVec3::new(-0.9, -0.1, -0.05),
        DVec3::new(-0.9, -0.1, 0.05),
        DVec3::new(0.9, -0.1, 0.0),
        DVec3::new(0.0, 0.1, 0.0),
    ];
    let del = tetrahedralize(&pts).unwrap();
    assert_eq!(del.len(), 1);
    let c = cells(&mesh, volume, &del, &pts, 1e-10, true);
    assert_eq!(c.pieces.len(), 2, "two parts of one tetrahedron");
    assert!(c.tet.iter().all(|&t| t == 0) && c.whole.iter().all(|&w| !w));
    let tet = tet_volume([pts[0], pts[1], pts[2], pts[3]]).abs();
    let mut sides = Vec::new();
    for p in &c.pieces {
        assert!(closed(p), "a closed 2-manifold");
        let v = p.volume();
        assert!(v > 0.0 && v < tet, "{v} of {tet}");
        // Inside the ring: no vertex in the hole or beyond the ring (up to rounding).
        for q in &p.pos {
            let r = (q.x * q.x + q.z * q.z).sqrt();
            assert!(r > 0.29 && r < 0.71 && q.y.abs() <= 0.2 + 1e-12, "{q}");
        }
        // Surface triangles of the torus, and the tetrahedron's faces (on the points'
        // hull here, so outer surface of no input triangle).
        assert!(p.tags.iter().any(|&t| source_triangle(t).is_some()));
        assert!(p.tags.iter().all(|&t| is_surface(t)));
        assert!(p.tags.iter().any(|&t| source_triangle(t).is_none()));
        let x = p.pos.iter().map(|q| q.x).sum::<f64>() / p.pos.len() as f64;
        sides.push(x.signum());
    }
    sides.sort_by(f64::total_cmp);
    assert_eq!(sides, vec![-1.0, 1.0], "one part on each side of the hole");
}

#[test]
fn a_tetrahedron_inside_stays_whole_and_one_outside_is_dropped() {
    let mesh = torus();
    let volume = mesh.volume();
    // A small tetrahedron in the ring, well inside the tube, and one in the hole.
    let inside = [
        DVec3::new(0.45, -0.05, -0.05),
        DVec3::new(0.55, -0.05, -0.05),
        DVec3::new(0.5, -0.05, 0.05),
        DVec3::new(0.5, 0.05, 0.0),
    ];
    let del = tetrahedralize(&inside).unwrap();
    let c = cells(&mesh, volume, &del, &inside, 1e-10, true);
    assert_eq!(c.pieces.len(), 1);
    let p = &c.pieces[0];
    // Clipped (its faces are on the points' hull) but unchanged: four caps-or-hull
    // faces, the tetrahedron's volume, its own corners up to rounding.
    let tet = tet_volume(inside).abs();
    assert!(
        (p.volume() - tet).abs() <= 1e-12 * tet,
        "{} vs {tet}",
        p.volume()
    );
    for q in &p.pos {
        assert!(inside.iter().any(|c| c.distance(*q) < 1e-12), "{q}");
    }
    let hole = inside.map(|q| q - DVec3::new(0.5, 0.0, 0.0));
    let del = tetrahedralize(&hole).unwrap();
    assert!(
        cells(&mesh, volume, &del, &hole, 1e-10, true)
            .pieces
            .is_empty()
    );
}
