//! Closing the union once its shared caps are gone: rim edges split at the vertices
//! the other side has on them (T-junctions), and the check that every directed edge
//! meets its reverse exactly once.

use glam::DVec3;

use super::{UnionError, retain_triangles};
use crate::fracture::kernel::Piece;
use crate::util::{FastMap, FastSet};

/// Splits every edge that has no reverse at the vertices of other such edges lying on
/// it (a fan from the triangle's opposite corner), until every edge has its reverse.
pub(super) fn close_t_junctions(
    p: &mut Piece,
    member: &mut Vec<u32>,
    eps: f64,
) -> Result<(), UnionError> {
    // Each pass splits every open edge at the open vertices on it; a split makes new
    // open edges only where the other side still has finer vertices, so a few passes
    // suffice. The bound guards against a loop on bad input.
    for _ in 0..16 {
        let open = open_edges(p);
        if open.is_empty() {
            return Ok(());
        }
        let mut verts: Vec<u32> = open.iter().flat_map(|&(_, _, a, b)| [a, b]).collect();
        verts.sort_unstable();
        verts.dedup();
        let grid = PointGrid::new(&p.pos, &verts);
        let mut split_done = vec![false; p.tris.len()];
        let mut new_tris: Vec<([u32; 3], u64, u32)> = Vec::new();
        let mut any = false;
        for &(t, k, a, b) in &open {
            if split_done[t] {
                continue;
            }
            let (pa, pb) = (p.pos[a as usize], p.pos[b as usize]);
            let d = pb - pa;
            let len2 = d.length_squared();
            if len2 == 0.0 {
                continue;
            }
            let mut on: Vec<(f64, u32)> = grid
                .near_segment(pa, pb, eps)
                .into_iter()
                .filter(|&v| v != a && v != b)
                .filter_map(|v| {
                    let q = p.pos[v as usize];
                    let s = (q - pa).dot(d) / len2;
                    let off = (pa + d * s).distance(q);
                    let margin = eps / len2.sqrt();
                    (s > margin && s < 1.0 - margin && off <= eps).then_some((s, v))
                })
                .collect();
            if on.is_empty() {
                continue;
            }
            on.sort_by(|x, y| x.0.total_cmp(&y.0));
            on.dedup_by_key(|x| x.1);
            let tri = p.tris[t];
            let c = tri[(k + 2) % 3];
            let mut chain = vec![a];
            chain.extend(on.iter().map(|&(_, v)| v));
            chain.push(b);
            for w in chain.windows(2) {
                new_tris.push(([w[0], w[1], c], p.tags[t], member[t]));
            }
            split_done[t] = true;
            any = true;
        }
        if !any {
            return Err(UnionError::Open);
        }
        retain_triangles(p, member, |t, _| !split_done[t]);
        for (tri, tag, m) in new_tris {
            p.tris.push(tri);
            p.tags.push(tag);
            member.push(m);
        }
    }
    Err(UnionError::Open)
}

/// Directed edges `(triangle, slot, from, to)` whose reverse is missing.
fn open_edges(p: &Piece) -> Vec<(usize, usize, u32, u32)> {
    let mut edges: FastSet<(u32, u32)> = FastSet::default();
    edges.reserve(3 * p.tris.len());
    for tri in &p.tris {
        for k in 0..3 {
            edges.insert((tri[k], tri[(k + 1) % 3]));
        }
    }
    let mut open = Vec::new();
    for (t, tri) in p.tris.iter().enumerate() {
        for k in 0..3 {
            let (a, b) = (tri[k], tri[(k + 1) % 3]);
            if !edges.contains(&(b, a)) {
                open.push((t, k, a, b));
            }
        }
    }
    open
}

/// Every directed edge once, with its reverse once: a closed 2-manifold by edges.
pub(super) fn check_closed(p: &Piece) -> Result<(), UnionError> {
    let mut count: FastMap<(u32, u32), u32> = FastMap::default();
    count.reserve(3 * p.tris.len());
    for tri in &p.tris {
        for k in 0..3 {
            let e = count.entry((tri[k], tri[(k + 1) % 3])).or_default();
            *e += 1;
            if *e > 1 {
                return Err(UnionError::NonManifold);
            }
        }
    }
    if count.keys().any(|&(a, b)| !count.contains_key(&(b, a))) {
        return Err(UnionError::Open);
    }
    Ok(())
}

/// A uniform grid over some of the points, to find those near a segment.
struct PointGrid {
    cell: f64,
    map: FastMap<glam::I64Vec3, Vec<u32>>,
    pos: Vec<(u32, DVec3)>,
}

impl PointGrid {
    fn new(all: &[DVec3], which: &[u32]) -> Self {
        let pts: Vec<(u32, DVec3)> = which.iter().map(|&i| (i, all[i as usize])).collect();
        if pts.is_empty() {
            return Self {
                cell: 1.0,
                map: FastMap::default(),
                pos: pts,
            };
        }
        let (lo, hi) = pts.iter().fold(
            (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
            |(l, h), &(_, q)| (l.min(q), h.max(q)),
        );
        // About one point per cell along the longest side's cube root.
        let extent = (hi - lo).max_element().max(f64::MIN_POSITIVE);
        let per_side = (pts.len() as f64).cbrt().ceil().max(1.0);
        let cell = extent / per_side;
        let mut map: FastMap<glam::I64Vec3, Vec<u32>> = FastMap::default();
        for (k, &(_, q)) in pts.iter().enumerate() {
            map.entry((q / cell).floor().as_i64vec3())
                .or_default()
                .push(k as u32);
        }
        Self {
            cell,
            map,
            pos: pts,
        }
    }

    /// Points within `eps` of the box of segment `a`–`b` (a superset of those near it).
    fn near_segment(&self, a: DVec3, b: DVec3, eps: f64) -> Vec<u32> {
        if self.pos.is_empty() {
            return Vec::new();
        }
        let lo = a.min(b) - DVec3::splat(eps);
        let hi = a.max(b) + DVec3::splat(eps);
        let (klo, khi) = (
            (lo / self.cell).floor().as_i64vec3(),
            (hi / self.cell).floor().as_i64vec3(),
        );
        let cells = (khi - klo + glam::I64Vec3::ONE).as_dvec3();
        let mut out = Vec::new();
        if cells.x * cells.y * cells.z > self.pos.len() as f64 {
            for &(i, q) in &self.pos {
                if q.cmpge(lo).all() && q.cmple(hi).all() {
                    out.push(i);
                }
            }
            return out;
        }
        for x in klo.x..=khi.x {
            for y in klo.y..=khi.y {
                for z in klo.z..=khi.z {
                    if let Some(list) = self.map.get(&glam::I64Vec3::new(x, y, z)) {
                        for &k in list {
                            let (i, q) = self.pos[k as usize];
                            if q.cmpge(lo).all() && q.cmple(hi).all() {
                                out.push(i);
                            }
                        }
                    }
                }
            }
        }
        out
    }
}
