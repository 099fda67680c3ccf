//! Caps of one plane from different pieces that meet in the union, joined into one
//! region and triangulated again.

use glam::DVec3;

use crate::fracture::kernel::cap::triangulate_cap;
use crate::fracture::kernel::{Piece, Plane, is_surface};
use crate::util::{FastMap, FastSet, UnionFind};

/// Caps of one plane from different pieces that share an edge are one region now:
/// each such region is triangulated again as one polygon (its rim vertices kept, so
/// its neighbours still meet it edge to edge). A region whose new triangulation would
/// not cover the same area is left as it was.
pub(super) fn join_coplanar_caps(p: &mut Piece, member: &[u32]) {
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
