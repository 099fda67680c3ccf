//! The union of fragments that share faces: what merging a small piece into its
//! neighbour makes of their two closed surfaces.
//!
//! Two pieces of one cut touch where each has a cap on the same plane (the same tag),
//! facing the other: a Voronoi face between two cells, a slice plane between its two
//! sides. Both caps cover the same region of the plane (the mesh's section by the cut,
//! bounded by the same other cuts), so in the union they cancel: both are removed. What
//! is left is closed except along the rim of the removed region, where one side may
//! have vertices the other lacks (its own cut points, its triangulation's diagonals): a
//! T-junction. Each rim edge is split at the other side's vertices lying on it, which
//! closes the union exactly. Last, caps of one plane from different pieces that now meet
//! (a later slice plane that crossed both) are joined into one region and triangulated
//! again.
//!
//! The result is checked: every directed edge must meet its reverse exactly once. A
//! union that cannot be closed (caps that only partly overlap, pieces touching along
//! an edge only) is refused, and the caller keeps the pieces apart.

mod cancel;
mod close;
mod join;

use glam::DVec3;

use super::Piece;
use crate::util::FastMap;
use cancel::cancel_shared_caps;
use close::{check_closed, close_t_junctions};
use join::join_coplanar_caps;

/// Why two pieces could not be joined into one closed 2-manifold.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum UnionError {
    /// An edge is left without its reverse (caps that overlap only in part).
    Open,
    /// An edge is used twice in one direction or by more than two triangles (the
    /// pieces touch along an edge or overlap).
    NonManifold,
}

/// The union of `pieces` (closed, outward, triangles only; vertices of different
/// pieces within `eps` are taken as one). See the module documentation.
pub(crate) fn union(pieces: &[&Piece], eps: f64) -> Result<Piece, UnionError> {
    let mut out = Piece::default();
    let mut member: Vec<u32> = Vec::new();
    for (m, p) in pieces.iter().enumerate() {
        debug_assert!(p.faces.is_empty(), "union of closed pieces");
        let base = out.pos.len() as u32;
        out.pos.extend_from_slice(&p.pos);
        out.tris.extend(p.tris.iter().map(|t| t.map(|i| i + base)));
        out.tags.extend_from_slice(&p.tags);
        member.extend(std::iter::repeat_n(m as u32, p.tris.len()));
    }
    weld_within(&mut out, &mut member, eps);
    cancel_shared_caps(&mut out, &mut member, eps);
    close_t_junctions(&mut out, &mut member, eps)?;
    check_closed(&out)?;
    join_coplanar_caps(&mut out, &member);
    out.compact();
    Ok(out)
}

/// Merges vertices closer than `eps` (the first one kept), then drops triangles that
/// repeat a vertex.
fn weld_within(p: &mut Piece, member: &mut Vec<u32>, eps: f64) {
    let cell = (2.0 * eps).max(f64::MIN_POSITIVE);
    let key = |q: DVec3| (q / cell).floor().as_i64vec3();
    let mut grid: FastMap<glam::I64Vec3, Vec<u32>> = FastMap::default();
    grid.reserve(p.pos.len());
    let mut pos: Vec<DVec3> = Vec::with_capacity(p.pos.len());
    let mut remap = Vec::with_capacity(p.pos.len());
    for &q in &p.pos {
        let k = key(q);
        let mut found = None;
        'search: for dx in -1..=1 {
            for dy in -1..=1 {
                for dz in -1..=1 {
                    if let Some(&i) =
                        grid.get(&(k + glam::I64Vec3::new(dx, dy, dz)))
                            .and_then(|list| {
                                list.iter()
                                    .find(|&&i| pos[i as usize].distance_squared(q) <= eps * eps)
                            })
                    {
                        found = Some(i);
                        break 'search;
                    }
                }
            }
        }
        let i = found.unwrap_or_else(|| {
            pos.push(q);
            let i = (pos.len() - 1) as u32;
            grid.entry(k).or_default().push(i);
            i
        });
        remap.push(i);
    }
    p.pos = pos;
    for tri in &mut p.tris {
        *tri = tri.map(|i| remap[i as usize]);
    }
    retain_triangles(p, member, |_, tri| {
        tri[0] != tri[1] && tri[1] != tri[2] && tri[0] != tri[2]
    });
}

/// Keeps the triangles `keep(index, triangle)` accepts, with their tags and members, in
/// order.
fn retain_triangles(p: &mut Piece, member: &mut Vec<u32>, keep: impl Fn(usize, [u32; 3]) -> bool) {
    let mut kept = 0;
    for t in 0..p.tris.len() {
        if keep(t, p.tris[t]) {
            p.tris[kept] = p.tris[t];
            p.tags[kept] = p.tags[t];
            member[kept] = member[t];
            kept += 1;
        }
    }
    p.tris.truncate(kept);
    p.tags.truncate(kept);
    member.truncate(kept);
}
