//! The thesis's method: a Delaunay tetrahedralization of surface vertices and random
//! points; every tetrahedron, clipped exactly to the mesh ([`cells`]), is a fragment (or
//! several, where the surface cuts it in parts), slivers merged into a neighbour
//! ([`assemble`]).

mod assemble;
mod cells;

use glam::DVec3;
use rand::Rng;
use rand_chacha::ChaCha8Rng;

use crate::delaunay::tetrahedralize;
use crate::fracture::bonds::caps::cap_bonds;
use crate::fracture::kernel::convex::tet_volume;
use crate::fracture::kernel::{Piece, mesh_scale};
use crate::fracture::seeds::inside::{InsideSampler, InsideTester};
use crate::fracture::{Bond, FractureError, Fragment, Placement};
use crate::mesh::mass_properties;

/// A tetrahedron (or group) below this fraction of the object's volume is a sliver.
pub const SLIVER_VOLUME_FRACTION: f64 = 1e-4;
/// A lone tetrahedron whose quality `6√2·V / L³` (1 for a regular tetrahedron, `L` its
/// longest edge) is below this is a sliver.
pub const SLIVER_QUALITY: f64 = 1e-2;

/// Options of the tetra method.
pub(crate) struct TetraOptions {
    pub random_vertices: usize,
    pub skip: usize,
    pub center: bool,
    pub placement: Placement,
    /// Clip the tetrahedra to the mesh (false in a per-axis frame, where the mesh has
    /// features far below the cut tolerance: then tetrahedra are kept whole by their
    /// centroid, and a result that misses the volume is refused by the caller).
    pub exact: bool,
}

/// The point set of the thesis: every `(skip + 1)`-th surface vertex, the random points,
/// then the centre if asked.
pub(crate) fn tetra_points(mesh: &Piece, opt: &TetraOptions, rng: &mut ChaCha8Rng) -> Vec<DVec3> {
    let mut pts: Vec<DVec3> = mesh.pos.iter().step_by(opt.skip + 1).copied().collect();
    let centre = mass_properties(&mesh.pos, &mesh.tris).1;
    match opt.placement {
        Placement::Interior => {
            let sampler = InsideSampler::new(mesh);
            for _ in 0..opt.random_vertices {
                pts.push(sampler.uniform(rng));
            }
        }
        Placement::Thesis => {
            // The thesis's scheme, except that a point it puts outside the mesh (which
            // happens for concave or asymmetric meshes) is redrawn, a bounded number of
            // times, so no fragment pokes out of the object.
            let tester = InsideTester::new(mesh);
            for _ in 0..opt.random_vertices {
                for _ in 0..64 {
                    let p = pts[rng.random_range(0..pts.len())];
                    let d = rng.random_range(0.0..=1.0) * (p - centre).length();
                    let q = centre + (centre - p).normalize_or_zero() * d;
                    if tester.contains(q) {
                        pts.push(q);
                        break;
                    }
                }
            }
        }
    }
    if opt.center {
        pts.push(centre);
    }
    pts
}

/// Tetra fracture of `mesh` (welded, outward, volume `mesh_volume`; `eps` the cuts'
/// on-plane tolerance): the fragments, each triangle's kernel tag, and the bonds.
///
/// Bonds are the overlaps of the caps two pieces have on a shared tetrahedron face, as
/// for Voronoi cells; merged fragments are unions of pieces, so every fragment is a
/// closed 2-manifold, and the volumes add up to the part of the mesh inside the points'
/// hull (all of it when no surface vertex is skipped).
pub(crate) fn tetra(
    mesh: &Piece,
    mesh_volume: f64,
    opt: &TetraOptions,
    eps: f64,
    rng: &mut ChaCha8Rng,
    warnings: &mut Vec<String>,
) -> Result<TetraResult, FractureError> {
    let pts = tetra_points(mesh, opt, rng);
    let del = tetrahedralize(&pts)?;
    let cells = cells::cells(mesh, mesh_volume, &del, &pts, eps, opt.exact);
    let plane_of = |tag: u64| {
        let p = cells::own_plane(&del, &pts, (tag / 4) as usize, (tag % 4) as usize);
        let n = p.n.normalize_or_zero();
        (n, p.n * (p.d / p.n.length_squared()))
    };
    let scale = mesh_scale(mesh);
    let bonds = cap_bonds(&cells.pieces, plane_of, 1e-12 * scale * scale);
    Ok(assemble::assemble(
        cells,
        bonds,
        &del,
        &pts,
        mesh_volume,
        eps,
        warnings,
    ))
}

/// The tetra method's fragments, each one's triangle tags, and the bonds.
pub(crate) type TetraResult = (Vec<Fragment>, Vec<Vec<u64>>, Vec<Bond>);

/// Quality `6√2·V / L³` of a tetrahedron (1 when regular, 0 when flat).
pub(crate) fn quality(c: [DVec3; 4]) -> f64 {
    let mut l2: f64 = 0.0;
    for i in 0..4 {
        for j in i + 1..4 {
            l2 = l2.max((c[i] - c[j]).length_squared());
        }
    }
    if l2 == 0.0 {
        return 0.0;
    }
    6.0 * std::f64::consts::SQRT_2 * tet_volume(c) / (l2 * l2.sqrt())
}

#[cfg(test)]
mod tests;
