//! The flat interior regions of a finished fracture and the bonds between them: per
//! fragment, the connected groups of coplanar interior triangles, and the pairs of such
//! regions (in two fragments) that are the two sides of one shared cap.
//!
//! Two regions are the two sides of a cap when they are in the two fragments of a bond,
//! face each other and have the same centroid and area (up to rounding: the two sides
//! are cut separately, so their vertices may differ in the last bits, and one side may
//! have a vertex on an edge the other has not). A region that matches no other (a cap
//! shared with two neighbours after a merge) is left alone: it stays flat.

use std::collections::BTreeMap;

use glam::DVec3;

use super::super::types::{Bond, Fragment};
use crate::util::{FastMap, FastSet, UnionFind};

/// Two triangles are coplanar when their unit normals agree to this (1 − cos).
const NORMAL_TOL: f64 = 1e-8;
/// ... and the other's corners are within this fraction of the fragment's size of the
/// plane.
const PLANE_TOL: f64 = 1e-9;

/// One flat region of interior triangles of a fragment.
#[derive(Debug, Clone)]
pub(crate) struct Region {
    /// The fragment.
    pub fragment: usize,
    /// Its triangles (indices into the fragment's mesh), in order.
    pub tris: Vec<u32>,
    /// Unit normal, out of the fragment (area-weighted).
    pub normal: DVec3,
    /// The area-weighted centroid (a point of the plane).
    pub point: DVec3,
    /// The area.
    pub area: f64,
    /// Directed boundary edges (vertex indices of the fragment), in triangle order.
    pub boundary: Vec<(u32, u32)>,
}

/// The directed edges of a mesh by the welded indices (`canon`, equal positions one
/// index) of their ends: edge → triangle.
fn edge_map(mesh: &crate::TriMesh, canon: &[u32]) -> FastMap<(u32, u32), u32> {
    let mut map = FastMap::default();
    for (t, tri) in mesh.triangles.iter().enumerate() {
        let k = tri.map(|i| canon[i as usize]);
        for e in 0..3 {
            map.insert((k[e], k[(e + 1) % 3]), t as u32);
        }
    }
    map
}

/// The flat interior regions of fragment `index`.
pub(crate) fn regions_of(index: usize, f: &Fragment) -> Vec<Region> {
    let mesh = &f.mesh;
    let pos = &mesh.positions;
    let n = mesh.triangles.len();
    let (lo, hi) = crate::util::bounds(pos);
    let tol = PLANE_TOL * (hi - lo).length().max(f64::MIN_POSITIVE);
    let unit = |t: usize| mesh.triangle_normal(t);
    let (canon, _) = mesh.weld_map();
    let edges = edge_map(mesh, &canon);
    let key = |i: u32| canon[i as usize];
    let mut uf = UnionFind::new(n);
    for t in 0..n {
        if !f.interior.get(t).copied().unwrap_or(false) {
            continue;
        }
        let tri = mesh.triangles[t];
        let nt = unit(t);
        for e in 0..3 {
            let (a, b) = (tri[e], tri[(e + 1) % 3]);
            let Some(&s) = edges.get(&(key(b), key(a))) else {
                continue;
            };
            let s = s as usize;
            if s == t || !f.interior.get(s).copied().unwrap_or(false) {
                continue;
            }
            let coplanar = nt.dot(unit(s)) > 1.0 - NORMAL_TOL
                && mesh.triangles[s]
                    .iter()
                    .all(|&i| (pos[i as usize] - pos[a as usize]).dot(nt).abs() <= tol);
            if coplanar {
                uf.union(t, s);
            }
        }
    }
    let mut groups: BTreeMap<usize, Vec<u32>> = BTreeMap::new();
    for t in 0..n {
        if f.interior.get(t).copied().unwrap_or(false) {
            groups.entry(uf.find(t)).or_default().push(t as u32);
        }
    }
    let mut out: Vec<Region> = groups
        .into_values()
        .filter_map(|tris| region(index, mesh, &canon, tris))
        .collect();
    out.sort_by_key(|r| r.tris[0]);
    out
}

/// A region from its triangles: normal, centroid and boundary (`None` when its area is
/// zero).
fn region(fragment: usize, mesh: &crate::TriMesh, canon: &[u32], tris: Vec<u32>) -> Option<Region> {
    let mut area_normal = DVec3::ZERO;
    let mut moment = DVec3::ZERO;
    let mut area = 0.0;
    let mut inside: FastSet<(u32, u32)> = FastSet::default();
    for &t in &tris {
        let [a, b, c] = mesh.triangle(t as usize);
        let an = (b - a).cross(c - a);
        area_normal += an;
        area += an.length();
        moment += an.length() * (a + b + c) / 3.0;
        let k = mesh.triangles[t as usize].map(|i| canon[i as usize]);
        for e in 0..3 {
            inside.insert((k[e], k[(e + 1) % 3]));
        }
    }
    let normal = area_normal.try_normalize()?;
    if !(area > 0.0 && area.is_finite()) {
        return None;
    }
    let mut boundary = Vec::new();
    for &t in &tris {
        let tri = mesh.triangles[t as usize];
        for e in 0..3 {
            let (a, b) = (tri[e], tri[(e + 1) % 3]);
            if !inside.contains(&(canon[b as usize], canon[a as usize])) {
                boundary.push((a, b));
            }
        }
    }
    Some(Region {
        fragment,
        tris,
        normal,
        point: moment / area,
        area: area / 2.0,
        boundary,
    })
}

/// Pairs `(i, j)` of regions (indices into `regions`, sorted by fragment then
/// triangle) that are the two sides of one cap of a bond: in the bond's two fragments,
/// with opposite normals, and the same centroid (within `tol`) and area (relative
/// 1e-9). In order of `i`; a region is in at most one pair.
pub(crate) fn shared_caps(bonds: &[Bond], regions: &[Region], tol: f64) -> Vec<(usize, usize)> {
    let mut of_fragment: BTreeMap<usize, Vec<usize>> = BTreeMap::new();
    for (i, r) in regions.iter().enumerate() {
        of_fragment.entry(r.fragment).or_default().push(i);
    }
    let none = Vec::new();
    let mut used = vec![false; regions.len()];
    let mut pairs = Vec::new();
    for bond in bonds {
        let ra = of_fragment.get(&(bond.a as usize)).unwrap_or(&none);
        let rb = of_fragment.get(&(bond.b as usize)).unwrap_or(&none);
        for &i in ra {
            for &j in rb {
                let (p, q) = (&regions[i], &regions[j]);
                let same = !used[i]
                    && !used[j]
                    && p.normal.dot(q.normal) < -0.999
                    && (p.point - q.point).length() <= tol
                    && (p.area - q.area).abs() <= 1e-9 * p.area.max(q.area);
                if same {
                    used[i] = true;
                    used[j] = true;
                    pairs.push((i, j));
                }
            }
        }
    }
    pairs.sort_unstable();
    pairs
}
