//! The caps the pieces share, removed: pairs of triangles wound opposite ways first,
//! then pairs of cap regions that cover the same part of one plane from its two sides.

use glam::DVec3;

use super::retain_triangles;
use crate::fracture::kernel::{Piece, is_surface};
use crate::util::{FastMap, UnionFind};

/// One piece's connected cap region on one plane: its triangles, area vector, area,
/// centroid and bounds.
struct Region {
    tag: u64,
    member: u32,
    tris: Vec<usize>,
    area_vector: DVec3,
    area: f64,
    centroid: DVec3,
    lo: DVec3,
    hi: DVec3,
}

/// Removes each pair of cap regions of two different pieces that cover the same part
/// of the same plane from opposite sides.
pub(super) fn cancel_shared_caps(p: &mut Piece, member: &mut Vec<u32>, eps: f64) {
    cancel_opposite_triangles(p, member);
    let regions = cap_regions(p, member);
    let mut by_tag: FastMap<u64, Vec<usize>> = FastMap::default();
    for (r, region) in regions.iter().enumerate() {
        by_tag.entry(region.tag).or_default().push(r);
    }
    let mut remove = vec![false; p.tris.len()];
    let mut used = vec![false; regions.len()];
    let mut tags: Vec<u64> = by_tag.keys().copied().collect();
    tags.sort_unstable();
    for tag in tags {
        let list = &by_tag[&tag];
        for (i, &r) in list.iter().enumerate() {
            for &s in &list[i + 1..] {
                if used[r] || used[s] {
                    continue;
                }
                if same_region_opposite(&regions[r], &regions[s], eps) {
                    used[r] = true;
                    used[s] = true;
                    for &t in regions[r].tris.iter().chain(&regions[s].tris) {
                        remove[t] = true;
                    }
                }
            }
        }
    }
    retain_triangles(p, member, |t, _| !remove[t]);
}

/// Removes each pair of cap triangles of two different pieces made of the same three
/// vertices wound opposite ways: where both pieces were cut alike, their shared caps
/// are the same triangles, and where they were not (a later cut that one side's
/// tolerance took as passing through a vertex), the triangles they do share still
/// cancel here, before the regions are compared.
fn cancel_opposite_triangles(p: &mut Piece, member: &mut Vec<u32>) {
    // A triangle's key: its vertices rotated to start at the smallest, and whether
    // that order is the reverse of the sorted one (its orientation).
    let key = |t: [u32; 3]| {
        let k = (0..3).min_by_key(|&k| t[k]).unwrap_or(0);
        let r = [t[k], t[(k + 1) % 3], t[(k + 2) % 3]];
        if r[1] < r[2] {
            ([r[0], r[1], r[2]], true)
        } else {
            ([r[0], r[2], r[1]], false)
        }
    };
    let mut seen: FastMap<[u32; 3], Vec<usize>> = FastMap::default();
    seen.reserve(p.tris.len());
    let mut remove = vec![false; p.tris.len()];
    let mut any = false;
    for (t, &tri) in p.tris.iter().enumerate() {
        if is_surface(p.tags[t]) {
            continue;
        }
        let (k, up) = key(tri);
        let list = seen.entry(k).or_default();
        let partner = list.iter().position(|&u| {
            !remove[u] && key(p.tris[u]).1 != up && member[u] != member[t] && p.tags[u] == p.tags[t]
        });
        match partner {
            Some(i) => {
                remove[list[i]] = true;
                remove[t] = true;
                list.swap_remove(i);
                any = true;
            }
            None => list.push(t),
        }
    }
    if !any {
        return;
    }
    retain_triangles(p, member, |t, _| !remove[t]);
}

/// The edge-connected regions of cap triangles per (tag, piece).
fn cap_regions(p: &Piece, member: &[u32]) -> Vec<Region> {
    let n = p.tris.len();
    let mut uf = UnionFind::new(n);
    let mut owner: FastMap<(u64, u32, u32, u32), usize> = FastMap::default();
    owner.reserve(3 * n);
    for (t, tri) in p.tris.iter().enumerate() {
        if is_surface(p.tags[t]) {
            continue;
        }
        for k in 0..3 {
            let (a, b) = (tri[k], tri[(k + 1) % 3]);
            let key = (p.tags[t], member[t], a.min(b), a.max(b));
            match owner.get(&key) {
                Some(&u) => uf.union(u, t),
                None => {
                    owner.insert(key, t);
                }
            }
        }
    }
    // Region of each root triangle.
    let mut slot: Vec<usize> = vec![usize::MAX; n];
    let mut regions: Vec<Region> = Vec::new();
    for (t, tri) in p.tris.iter().enumerate() {
        if is_surface(p.tags[t]) {
            continue;
        }
        let root = uf.find(t);
        if slot[root] == usize::MAX {
            slot[root] = regions.len();
            regions.push(Region {
                tag: p.tags[t],
                member: member[t],
                tris: Vec::new(),
                area_vector: DVec3::ZERO,
                area: 0.0,
                centroid: DVec3::ZERO,
                lo: DVec3::splat(f64::INFINITY),
                hi: DVec3::splat(f64::NEG_INFINITY),
            });
        }
        let r = slot[root];
        let [a, b, c] = tri.map(|i| p.pos[i as usize]);
        let cross = (b - a).cross(c - a) / 2.0;
        let area = cross.length();
        let region = &mut regions[r];
        region.tris.push(t);
        region.area_vector += cross;
        region.area += area;
        region.centroid += (a + b + c) / 3.0 * area;
        region.lo = region.lo.min(a.min(b).min(c));
        region.hi = region.hi.max(a.max(b).max(c));
    }
    for region in &mut regions {
        if region.area > 0.0 {
            region.centroid /= region.area;
        }
    }
    regions
}

/// Whether two regions of one plane, of different pieces, are the same region seen
/// from its two sides: opposite area vectors of equal size, the same centroid and
/// bounds (within rounding).
fn same_region_opposite(r: &Region, s: &Region, eps: f64) -> bool {
    if r.member == s.member {
        return false;
    }
    let area_tol = 1e-9 * (r.area + s.area) + eps * eps;
    let size = (r.hi - r.lo).max_element().max((s.hi - s.lo).max_element());
    let len_tol = 1e-9 * size + 4.0 * eps;
    (r.area - s.area).abs() <= area_tol
        && (r.area_vector + s.area_vector).length() <= area_tol
        && r.centroid.distance(s.centroid) <= len_tol
        && (r.lo - s.lo).abs().max_element() <= len_tol
        && (r.hi - s.hi).abs().max_element() <= len_tol
}
