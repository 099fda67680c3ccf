//! A tetrahedron's cell by an exact boolean, for the cells the clipper cannot close.
//!
//! The clipper cuts with floating-point planes and an on-plane tolerance. Where a CAD
//! model's faces lie in a tetrahedron's face plane, or its united parts leave sheets a
//! hair apart (Khronos' 2CylinderEngine: 107 of 257,109 cells), every cut order can
//! leave the cell open, and its volume is then lost to the fracture (the engine's
//! fragments added up to 0.999988 of its volume and the result was refused). Such a
//! cell is computed here instead as the intersection of the piece and the tetrahedron
//! by `manifold-rust`'s robust engine (the crate the repair's union already uses: exact
//! predicates and rational constructions, the arrangement of both surfaces, winding
//! numbers per cell), which has no tolerance to fail on. It is far slower than the
//! clipper, so it is the last resort, not the rule.
//!
//! Each triangle of the result lies on a triangle of the piece or a face of the
//! tetrahedron (its face id): it takes that triangle's tag, or the face plane's.

use glam::DVec3;
use manifold_rust::manifold::Manifold;
use manifold_rust::types::{BooleanEngine, Error as ManifoldStatus, MeshGL64, OpType};

use crate::fracture::kernel::convex::{TET_FACES, tet_volume};
use crate::fracture::kernel::{Piece, Plane};
use crate::mesh::repair::retreat_pinches;

/// How far the copies of a pinched vertex retreat, as a fraction of their edges' mean
/// length: well above the rounding-length edges a later weld collapses (1e-13 of a
/// piece), well below anything the volumes would show.
const PINCH_RETREAT: f64 = 1e-9;

/// The part of the closed `piece` inside the tetrahedron `corners` (whose face `f` is
/// [`TET_FACES`]`[f]`, on `planes[f]`), as one piece: surface triangles keep their tags,
/// the tetrahedron's faces carry their planes' tags. `None` when the boolean fails or
/// gives a triangle of neither (the caller then keeps what the clipper gave).
pub(super) fn clip_exactly(piece: &Piece, planes: &[Plane], corners: [DVec3; 4]) -> Option<Piece> {
    if planes.len() != 4 {
        return None;
    }
    let mut piece = piece.clone();
    piece.close_faces();
    piece.compact();
    // A panic inside the crate on some input must not take the fracture down.
    std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
        intersection(&piece, planes, corners)
    }))
    .ok()
    .flatten()
}

fn intersection(piece: &Piece, planes: &[Plane], corners: [DVec3; 4]) -> Option<Piece> {
    let n = piece.tris.len();
    let solid = Manifold::from_mesh_gl64_robust(&MeshGL64 {
        num_prop: 3,
        vert_properties: piece.pos.iter().flat_map(|p| p.to_array()).collect(),
        tri_verts: piece.tris.iter().flat_map(|t| t.map(u64::from)).collect(),
        face_id: (0..n as u64).collect(),
        ..MeshGL64::default()
    });
    // The tetrahedron wound outward (its faces as the planes see them when its volume is
    // positive, reversed otherwise).
    let outward = tet_volume(corners) > 0.0;
    let tet = Manifold::from_mesh_gl64_robust(&MeshGL64 {
        num_prop: 3,
        vert_properties: corners.iter().flat_map(|p| p.to_array()).collect(),
        tri_verts: TET_FACES
            .iter()
            .flat_map(|f| {
                let [a, b, c] = f.map(|i| i as u64);
                if outward { [a, b, c] } else { [a, c, b] }
            })
            .collect(),
        face_id: (n as u64..n as u64 + 4).collect(),
        ..MeshGL64::default()
    });
    if solid.status() != ManifoldStatus::NoError || tet.status() != ManifoldStatus::NoError {
        return None;
    }
    let cell = solid.boolean_with_engine(&tet, OpType::Intersect, BooleanEngine::Robust);
    if cell.status() != ManifoldStatus::NoError {
        return None;
    }
    let out = cell.get_mesh_gl64(-1);
    let np = (out.num_prop as usize).max(3);
    let pos: Vec<DVec3> = out
        .vert_properties
        .chunks_exact(np)
        .map(|v| DVec3::new(v[0], v[1], v[2]))
        .collect();
    if out.face_id.len() * 3 != out.tri_verts.len() {
        return None;
    }
    let mut tris = Vec::with_capacity(out.face_id.len());
    let mut tags = Vec::with_capacity(out.face_id.len());
    for (tri, &id) in out.tri_verts.chunks_exact(3).zip(&out.face_id) {
        let tri = [tri[0], tri[1], tri[2]].map(|v| v as u32);
        if tri.iter().any(|&v| v as usize >= pos.len()) {
            return None;
        }
        let id = id as usize;
        let tag = if id < n {
            piece.tags[id]
        } else {
            planes.get(id - n)?.tag
        };
        tris.push(tri);
        tags.push(tag);
    }
    let mut cell = Piece {
        pos,
        tris,
        tags,
        faces: Vec::new(),
    };
    // The crate keeps a solid that touches itself along an edge manifold by giving the
    // edge's ends a copy per side; a fragment is checked by position, where that is an
    // edge of four triangles. The copies retreat a hair into their own sides, as the
    // repair's union does with the same crate's pinches, but by less: the cell's
    // volume is to add up with its neighbours' (a millionth of the edges, the union's
    // step, lost 7e-9 of regr01.obj's volume).
    retreat_pinches(&mut cell.pos, &cell.tris, PINCH_RETREAT);
    Some(cell)
}

#[cfg(test)]
mod tests {
    use glam::DVec3;

    use super::super::corner_plane;
    use super::clip_exactly;
    use crate::fracture::kernel::convex::tet_volume;
    use crate::fracture::kernel::{Piece, Plane, is_surface};
    use crate::shapes;

    /// A tetrahedron with a corner at the centre of the unit cube and three at its
    /// corners, one face on the cube's face `z = 0.5`: the cut is the part of the
    /// tetrahedron in the cube, closed, with the volume computed by hand, the cube's
    /// triangles keeping their tags and the caps carrying their planes'.
    #[test]
    fn a_cell_is_the_exact_intersection_even_on_a_face_of_the_mesh() {
        let cube = Piece::from_mesh_welded(&shapes::cube());
        // Three corners on the top face (z = 0.5), one far below the bottom face.
        let mut c = [
            DVec3::new(-0.5, -0.5, 0.5),
            DVec3::new(0.5, -0.5, 0.5),
            DVec3::new(-0.5, 0.5, 0.5),
            DVec3::new(-0.5, -0.5, -1.5),
        ];
        if tet_volume(c) < 0.0 {
            c.swap(0, 1);
        }
        let planes: Vec<Plane> = (0..4).map(|f| corner_plane(c, f, 40 + f as u64)).collect();
        let cell = clip_exactly(&cube, &planes, c).expect("the boolean succeeds");
        assert!(cell.is_closed());
        // The tetrahedron is a right-angled corner: legs 1, 1 (on top) and 2 (down);
        // the cube keeps it down to z = -0.5, a frustum: the whole (1·1·2/6) less the
        // tip beyond (half the size: 1/8 of it).
        let whole = 2.0 / 6.0;
        let expected = whole - whole / 8.0;
        assert!(
            (cell.volume() - expected).abs() < 1e-12,
            "{} vs {expected}",
            cell.volume()
        );
        // Every triangle is the cube's or lies on a face of the tetrahedron; the bottom
        // (z = -0.5) is on no face of the tetrahedron, so it is the cube's.
        assert!(
            cell.tags
                .iter()
                .all(|&t| is_surface(t) || (40..44).contains(&t))
        );
        assert!(cell.tags.iter().any(|&t| is_surface(t)));
        for (tri, &t) in cell.tris.iter().zip(&cell.tags) {
            if tri.iter().all(|&v| cell.pos[v as usize].z == -0.5) {
                assert!(is_surface(t), "the bottom is the cube's face");
            }
        }
    }
}
