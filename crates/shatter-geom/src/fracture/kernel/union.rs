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

use glam::DVec3;

use super::cap::triangulate_cap;
use super::{Piece, Plane, is_surface};
use crate::util::{FastMap, FastSet, UnionFind};

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
    let mut keep = 0;
    for t in 0..p.tris.len() {
        let tri = p.tris[t].map(|i| remap[i as usize]);
        if tri[0] != tri[1] && tri[1] != tri[2] && tri[0] != tri[2] {
            p.tris[keep] = tri;
            p.tags[keep] = p.tags[t];
            member[keep] = member[t];
            keep += 1;
        }
    }
    p.tris.truncate(keep);
    p.tags.truncate(keep);
    member.truncate(keep);
}

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
fn cancel_shared_caps(p: &mut Piece, member: &mut Vec<u32>, eps: f64) {
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
    let mut keep = 0;
    for t in 0..p.tris.len() {
        if !remove[t] {
            p.tris[keep] = p.tris[t];
            p.tags[keep] = p.tags[t];
            member[keep] = member[t];
            keep += 1;
        }
    }
    p.tris.truncate(keep);
    p.tags.truncate(keep);
    member.truncate(keep);
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
    let mut keep = 0;
    for t in 0..p.tris.len() {
        if !remove[t] {
            p.tris[keep] = p.tris[t];
            p.tags[keep] = p.tags[t];
            member[keep] = member[t];
            keep += 1;
        }
    }
    p.tris.truncate(keep);
    p.tags.truncate(keep);
    member.truncate(keep);
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

/// Splits every edge that has no reverse at the vertices of other such edges lying on
/// it (a fan from the triangle's opposite corner), until every edge has its reverse.
fn close_t_junctions(p: &mut Piece, member: &mut Vec<u32>, eps: f64) -> Result<(), UnionError> {
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
        let mut keep = 0;
        for t in 0..p.tris.len() {
            if !split_done[t] {
                p.tris[keep] = p.tris[t];
                p.tags[keep] = p.tags[t];
                member[keep] = member[t];
                keep += 1;
            }
        }
        p.tris.truncate(keep);
        p.tags.truncate(keep);
        member.truncate(keep);
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
fn check_closed(p: &Piece) -> Result<(), UnionError> {
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

/// Caps of one plane from different pieces that share an edge are one region now:
/// each such region is triangulated again as one polygon (its rim vertices kept, so
/// its neighbours still meet it edge to edge). A region whose new triangulation would
/// not cover the same area is left as it was.
fn join_coplanar_caps(p: &mut Piece, member: &[u32]) {
    // Regions by tag only (any piece), edge-connected.
    let n = p.tris.len();
    let mut uf = UnionFind::new(n);
    let mut owner: FastMap<(u64, u32, u32), usize> = FastMap::default();
    owner.reserve(3 * n);
    for (t, tri) in p.tris.iter().enumerate() {
        if is_surface(p.tags[t]) {
            continue;
        }
        for k in 0..3 {
            let (a, b) = (tri[k], tri[(k + 1) % 3]);
            let key = (p.tags[t], a.min(b), a.max(b));
            match owner.get(&key) {
                Some(&u) => uf.union(u, t),
                None => {
                    owner.insert(key, t);
                }
            }
        }
    }
    let mut groups: FastMap<usize, Vec<usize>> = FastMap::default();
    for t in 0..n {
        if !is_surface(p.tags[t]) {
            groups.entry(uf.find(t)).or_default().push(t);
        }
    }
    let mut roots: Vec<usize> = groups.keys().copied().collect();
    roots.sort_unstable();
    let mut replaced = vec![false; n];
    let mut added: Vec<([u32; 3], u64)> = Vec::new();
    for root in roots {
        let ts = &groups[&root];
        let first = member[ts[0]];
        if ts.iter().all(|&t| member[t] == first) {
            continue;
        }
        let Some(tris) = retriangulate(p, ts) else {
            continue;
        };
        for &t in ts {
            replaced[t] = true;
        }
        let tag = p.tags[ts[0]];
        added.extend(tris.into_iter().map(|tri| (tri, tag)));
    }
    if added.is_empty() {
        return;
    }
    let mut keep = 0;
    for (t, &gone) in replaced.iter().enumerate() {
        if !gone {
            p.tris[keep] = p.tris[t];
            p.tags[keep] = p.tags[t];
            keep += 1;
        }
    }
    p.tris.truncate(keep);
    p.tags.truncate(keep);
    for (tri, tag) in added {
        p.tris.push(tri);
        p.tags.push(tag);
    }
}

/// A new triangulation of the planar region made of triangles `ts`, or `None` when it
/// would not cover the same area the same way.
fn retriangulate(p: &Piece, ts: &[usize]) -> Option<Vec<[u32; 3]>> {
    let mut inner: FastSet<(u32, u32)> = FastSet::default();
    inner.reserve(3 * ts.len());
    for &t in ts {
        let tri = p.tris[t];
        for k in 0..3 {
            inner.insert((tri[k], tri[(k + 1) % 3]));
        }
    }
    // The rim as the solid's side sees it (reversed), as the cap triangulation takes it.
    let mut rim: Vec<(u32, u32)> = Vec::new();
    let mut area_vector = DVec3::ZERO;
    let mut area = 0.0;
    for &t in ts {
        let tri = p.tris[t];
        let [a, b, c] = tri.map(|i| p.pos[i as usize]);
        let cross = (b - a).cross(c - a) / 2.0;
        area_vector += cross;
        area += cross.length();
        for k in 0..3 {
            let (u, v) = (tri[k], tri[(k + 1) % 3]);
            if !inner.contains(&(v, u)) {
                rim.push((v, u));
            }
        }
    }
    let normal = area_vector.normalize_or_zero();
    if normal == DVec3::ZERO || area_vector.length() < (1.0 - 1e-9) * area {
        // Not flat (or not one side): leave it.
        return None;
    }
    let origin = p.pos[p.tris[ts[0]][0] as usize];
    let plane = Plane {
        n: normal,
        d: normal.dot(origin),
        tag: p.tags[ts[0]],
    };
    let tris = triangulate_cap(&p.pos, &rim, &plane);
    let mut new_vector = DVec3::ZERO;
    let mut new_area = 0.0;
    for tri in &tris {
        let [a, b, c] = tri.map(|i| p.pos[i as usize]);
        let cross = (b - a).cross(c - a) / 2.0;
        new_vector += cross;
        new_area += cross.length();
    }
    let tol = 1e-9 * area;
    ((new_vector - area_vector).length() <= tol
        && (new_area - area).abs() <= tol
        && tris.len() < ts.len())
    .then_some(tris)
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
