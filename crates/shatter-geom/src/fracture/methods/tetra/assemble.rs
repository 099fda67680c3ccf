//! The tetra method's fragments from its pieces: slivers merged into neighbours by the
//! union-based merge, lone tetrahedra as they are.

use glam::DVec3;
use rayon::prelude::*;

use super::cells::Cells;
use super::{SLIVER_QUALITY, SLIVER_VOLUME_FRACTION, quality};
use crate::TriMesh;
use crate::delaunay::Tetrahedralization;
use crate::fracture::bonds::merge::merge_small_with;
use crate::fracture::kernel::convex::{TET_FACES, convex_pieces};
use crate::fracture::kernel::{Piece, is_surface};
use crate::fracture::{Bond, Fragment};
use crate::mesh::mass_properties;

/// Fragments (with each triangle's kernel tag) and bonds of the tetra method: pieces
/// below the sliver volume, and lone tetrahedra (or parts of one) of poor shape, are
/// merged into the neighbour they share the most area with.
pub(super) fn assemble(
    cells: Cells,
    bonds: Vec<Bond>,
    del: &Tetrahedralization,
    pts: &[DVec3],
    mesh_volume: f64,
    eps: f64,
    warnings: &mut Vec<String>,
) -> (Vec<Fragment>, Vec<Vec<u64>>, Vec<Bond>) {
    let vmin = SLIVER_VOLUME_FRACTION * mesh_volume;
    let corners = |t: usize| del.tetrahedron(t).map(|i| pts[i as usize]);
    let poor: Vec<bool> = cells
        .tet
        .iter()
        .map(|&t| quality(corners(t)) < SLIVER_QUALITY)
        .collect();
    let Cells { pieces, tet, whole } = cells;
    let originals = pieces.clone();
    let (merged, bonds, info, group) = merge_small_with(pieces, bonds, vmin, &poor, eps);
    if info.lonely > 0 {
        warnings.push(format!(
            "{} tetra fragments below the sliver threshold had no other fragment to merge \
             into",
            info.lonely
        ));
    }
    if info.unjoined > 0 {
        warnings.push(format!(
            "{} tetra fragments below the sliver threshold were kept apart: joining them to \
             a neighbour would not give a closed surface",
            info.unjoined
        ));
    }
    let mut members: Vec<Vec<usize>> = vec![Vec::new(); merged.len()];
    for (i, &g) in group.iter().enumerate() {
        members[g as usize].push(i);
    }
    let built: Vec<(Fragment, Vec<u64>)> = merged
        .into_par_iter()
        .zip(members)
        .with_max_len(1)
        .map(|(p, ms)| {
            if let [i] = ms[..]
                && whole[i]
            {
                return lone_tetrahedron(&originals[i], corners(tet[i]));
            }
            group_fragment(p, &ms, &originals, &whole, vmin)
        })
        .collect();
    let (fragments, tags) = built.into_iter().unzip();
    (fragments, tags, bonds)
}

/// A lone whole tetrahedron: four vertices and four triangles, so that its surface is
/// closed by index as every other fragment's is (the thesis split the vertices per face
/// for flat shading; here flat normals are per corner, in [`Fragment::corners`], or the
/// renderer's); its collision piece is itself.
fn lone_tetrahedron(p: &Piece, c: [DVec3; 4]) -> (Fragment, Vec<u64>) {
    let triangles = TET_FACES.map(|f| f.map(|i| i as u32)).to_vec();
    let mesh = TriMesh::new(c.to_vec(), triangles);
    let (volume, centroid, inertia) = mass_properties(&mesh.positions, &mesh.triangles);
    let fragment = Fragment {
        mesh,
        interior: p.tags.iter().map(|&t| !is_surface(t)).collect(),
        // Set at the end, from the tags (see `attributes`).
        corners: Default::default(),
        material: Vec::new(),
        convex_pieces: vec![c.to_vec()],
        convex_hulls: Vec::new(),
        volume,
        centroid,
        inertia,
    };
    (fragment, p.tags.clone())
}

/// A fragment of one clipped piece or of a merged group (`p`, the union of the pieces
/// `members`). Its collision pieces are its members' (whole tetrahedra as they are,
/// clipped ones decomposed), the negligible ones left out: the hull of a merged group
/// can be larger than the group and would overlap its neighbours.
fn group_fragment(
    mut p: Piece,
    members: &[usize],
    originals: &[Piece],
    whole: &[bool],
    vmin: f64,
) -> (Fragment, Vec<u64>) {
    p.weld();
    let (volume, centroid, inertia) = mass_properties(&p.pos, &p.tris);
    let mut pieces: Vec<Vec<DVec3>> = Vec::new();
    let all_whole = members.iter().all(|&i| whole[i]);
    if members.len() > 1 {
        for &i in members {
            let m = &originals[i];
            if m.volume() < vmin {
                continue;
            }
            if whole[i] {
                pieces.push(m.pos.clone());
            } else {
                pieces.extend(convex_pieces(m));
            }
        }
    }
    if pieces.is_empty() {
        if all_whole {
            // Only slivers (merged up to the volume threshold): their common hull.
            let mut pts: Vec<DVec3> = members
                .iter()
                .flat_map(|&i| originals[i].pos.iter().copied())
                .collect();
            pts.sort_by(|a, b| {
                a.to_array()
                    .partial_cmp(&b.to_array())
                    .unwrap_or(std::cmp::Ordering::Equal)
            });
            pts.dedup();
            pieces.push(pts);
        } else {
            pieces = convex_pieces(&p);
        }
    }
    let fragment = Fragment {
        mesh: TriMesh::new(p.pos.clone(), p.tris.clone()),
        interior: p.tags.iter().map(|&t| !is_surface(t)).collect(),
        corners: Default::default(),
        material: Vec::new(),
        convex_pieces: pieces,
        convex_hulls: Vec::new(),
        volume,
        centroid,
        inertia,
    };
    (fragment, p.tags)
}
