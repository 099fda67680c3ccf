//! Tests of caps kept as polygons ([`super::piece::Face`]) through a sequence of cuts,
//! against caps triangulated at every cut: the same solids, with fewer triangles.

use std::collections::HashMap;

use glam::DVec3;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

use super::clip::{clip, clip_keeping_faces};
use super::fast_path_tests::closed;
use super::{Piece, Plane};
use crate::fracture::methods::voronoi::delaunay_neighbours;
use crate::shapes;

fn plane(n: DVec3, p: DVec3, tag: u64) -> Plane {
    Plane {
        n,
        d: n.dot(p),
        tag,
    }
}

/// `piece` cut by every plane in turn, its caps triangulated at each cut (`faces` false)
/// or kept as faces and triangulated at the end; `None` when nothing is left.
fn cut_all(piece: &Piece, planes: &[Plane], faces: bool) -> Option<Piece> {
    let mut current = piece.clone();
    for p in planes {
        let next = if faces {
            clip_keeping_faces(&current, p, 1e-10)
        } else {
            clip(&current, p, 1e-10)
        };
        if let Some(next) = next {
            if next.is_empty() {
                return None;
            }
            current = next;
        }
    }
    current.close_faces();
    Some(current)
}

/// Area of the triangles of each tag.
fn area_by_tag(p: &Piece) -> HashMap<u64, f64> {
    let mut out = HashMap::new();
    for (t, &tag) in p.tris.iter().zip(&p.tags) {
        let [a, b, c] = t.map(|i| p.pos[i as usize]);
        *out.entry(tag).or_insert(0.0) += (b - a).cross(c - a).length() / 2.0;
    }
    out
}

/// The same solid: closed both, equal volumes and equal areas per tag.
fn assert_same_solid(faces: &Piece, caps: &Piece, what: &str) {
    assert!(closed(faces), "{what}: the faces' result is not closed");
    assert!(closed(caps), "{what}: the caps' result is not closed");
    let (vf, vc) = (faces.volume(), caps.volume());
    assert!(
        vf > 0.0 && (vf - vc).abs() <= 1e-9 * vc,
        "{what}: volume {vf} vs {vc}"
    );
    let (af, ac) = (area_by_tag(faces), area_by_tag(caps));
    assert_eq!(
        af.keys().collect::<std::collections::BTreeSet<_>>(),
        ac.keys().collect::<std::collections::BTreeSet<_>>(),
        "{what}: different tags"
    );
    for (tag, a) in &af {
        let b = ac[tag];
        assert!(
            (a - b).abs() <= 1e-9 * b.max(1e-6),
            "{what}: tag {tag} area {a} vs {b}"
        );
    }
}

#[test]
fn a_cut_across_a_holed_face_keeps_it_one_polygon() {
    let torus = Piece::from_mesh_welded(&shapes::torus(1.0, 0.4, 32, 16));
    // The lower half (the torus goes round the y axis): its cap is a ring, one face
    // with a hole.
    let half = clip_keeping_faces(&torus, &plane(DVec3::Y, DVec3::splat(0.0131), 1), 1e-10)
        .expect("the plane cuts the torus");
    assert_eq!(half.faces.len(), 1);
    assert!(half.tags.iter().all(|&t| t != 1));
    // Across the ring: the line crosses it four times, the hole between.
    let across = plane(DVec3::X, DVec3::splat(0.0123), 2);
    let quarter = clip_keeping_faces(&half, &across, 1e-10).expect("the plane cuts");
    assert_eq!(quarter.faces.len(), 2, "the ring stays a polygon");
    assert!(quarter.tags.iter().all(|&t| t != 1 && t != 2));
    let ring = quarter
        .faces
        .iter()
        .find(|f| f.plane.tag == 1)
        .expect("the ring");
    // Its half: each loop's half and two closing edges along the line.
    let full = half.faces[0].edges.len();
    assert!(
        ring.edges.len() < full && ring.edges.len() > full / 2,
        "{} of {full} edges",
        ring.edges.len()
    );

    let mut faces = quarter;
    faces.close_faces();
    let planes = [plane(DVec3::Y, DVec3::splat(0.0131), 1), across];
    let caps = cut_all(&torus, &planes, false).expect("something is left");
    assert_same_solid(&faces, &caps, "torus quarter");
    // The triangulated caps carry the cut points of the ring's diagonals.
    assert!(faces.pos.len() < caps.pos.len());
}

#[test]
fn a_face_with_a_corner_on_the_plane_is_cut_as_triangles() {
    let cube = Piece::from_mesh_welded(&shapes::cube());
    let slab = clip_keeping_faces(&cube, &plane(DVec3::X, DVec3::splat(0.1), 1), 1e-10)
        .expect("the plane cuts the cube");
    assert_eq!(slab.faces.len(), 1);
    // y + z = 0 runs through two corners of the square face at x = 0.1.
    let diagonal = plane(DVec3::new(0.0, 1.0, 1.0), DVec3::ZERO, 2);
    let mut wedge = clip_keeping_faces(&slab, &diagonal, 1e-10).expect("the plane cuts");
    assert!(
        wedge.faces.iter().all(|f| f.plane.tag != 1),
        "the square was triangulated"
    );
    assert!(wedge.tags.contains(&1));
    wedge.close_faces();
    assert!(closed(&wedge));
    assert!(
        (wedge.volume() - 0.3).abs() <= 1e-12,
        "volume {}",
        wedge.volume()
    );
}

#[test]
fn voronoi_cells_are_the_same_solids_with_faces_as_with_caps() {
    let mut rng = ChaCha8Rng::seed_from_u64(11);
    let meshes = [
        ("bird", Piece::from_mesh_welded(&shapes::bird())),
        (
            "torus",
            Piece::from_mesh_welded(&shapes::torus(1.0, 0.4, 24, 12)),
        ),
    ];
    for (name, mesh) in &meshes {
        let (lo, hi) = crate::util::bounds(&mesh.pos);
        let seeds: Vec<DVec3> = (0..40)
            .map(|_| lo + (hi - lo) * DVec3::new(rng.random(), rng.random(), rng.random()))
            .collect();
        let (adjacent, _) =
            delaunay_neighbours(&seeds, DVec3::ONE).expect("seeds in general position");
        let (mut volume, mut tris_faces, mut tris_caps) = (0.0, 0, 0);
        for (i, si) in seeds.iter().enumerate() {
            let planes: Vec<Plane> = adjacent[i]
                .iter()
                .map(|&j| {
                    let sj = seeds[j as usize];
                    plane(sj - *si, (*si + sj) * 0.5, u64::from(j))
                })
                .collect();
            let faces = cut_all(mesh, &planes, true);
            let caps = cut_all(mesh, &planes, false);
            match (faces, caps) {
                (Some(f), Some(c)) => {
                    assert_same_solid(&f, &c, &format!("{name} cell {i}"));
                    volume += f.volume();
                    tris_faces += f.tris.len();
                    tris_caps += c.tris.len();
                }
                (None, None) => {}
                _ => panic!("{name} cell {i}: one way left nothing"),
            }
        }
        let total = mesh.volume();
        assert!(
            (volume - total).abs() <= 1e-9 * total,
            "{name}: cells {volume} vs {total}"
        );
        assert!(
            tris_faces < tris_caps,
            "{name}: {tris_faces} vs {tris_caps} triangles"
        );
    }
}

/// Every directed edge of the triangles and faces has its reverse exactly once.
fn closed_with_faces(p: &Piece) -> bool {
    let mut count = HashMap::new();
    let tri_edges = p
        .tris
        .iter()
        .flat_map(|t| [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])]);
    let face_edges = p.faces.iter().flat_map(|f| f.edges.iter().copied());
    for e in tri_edges.chain(face_edges) {
        *count.entry(e).or_insert(0i32) += 1;
    }
    count
        .iter()
        .all(|(&(a, b), &n)| a != b && n == 1 && count.get(&(b, a)) == Some(&1))
}

#[test]
fn convex_decomposition_parts_with_faces_are_closed_and_add_up() {
    let bird = Piece::from_mesh_welded(&shapes::bird());
    let mut rng = ChaCha8Rng::seed_from_u64(4);
    let (lo, hi) = crate::util::bounds(&bird.pos);
    let seeds: Vec<DVec3> = (0..40)
        .map(|_| lo + (hi - lo) * DVec3::new(rng.random(), rng.random(), rng.random()))
        .collect();
    let (cells, _) = crate::fracture::methods::voronoi::voronoi(&bird, &seeds, DVec3::ONE, 1e-10);
    let mut decomposed = 0;
    for (i, cell) in cells.iter().enumerate() {
        let parts = super::convex::decomposition_parts(cell).unwrap_or_else(|| vec![cell.clone()]);
        if parts.len() > 1 {
            decomposed += 1;
            assert!(
                parts.iter().any(|p| !p.faces.is_empty()),
                "cell {i}: no faces"
            );
        }
        for (k, p) in parts.iter().enumerate() {
            assert!(closed_with_faces(p), "cell {i} part {k} is not closed");
            assert!(p.volume() > 0.0, "cell {i} part {k}: volume {}", p.volume());
            // One solid (triangulated, its parts cannot hide behind a shared face).
            let mut whole = p.clone();
            whole.close_faces();
            assert_eq!(
                whole.components().len(),
                1,
                "cell {i} part {k} is in pieces"
            );
        }
        let sum: f64 = parts.iter().map(Piece::volume).sum();
        let whole = cell.volume();
        assert!(
            (sum - whole).abs() <= 1e-9 * whole,
            "cell {i}: parts {sum} vs {whole}"
        );
    }
    assert!(decomposed >= 5, "only {decomposed} cells were decomposed");
}
