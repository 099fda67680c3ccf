//! Hole filling (after Liepa 2003, "Filling holes in meshes"): each boundary loop of a
//! consistently wound shell is triangulated by dynamic programming over the loop's
//! vertices, minimising first the largest dihedral angle (between patch triangles and
//! with the mesh around the hole) and then the area, so the patch continues the
//! surface; loops too long for the cubic search are ear-clipped on their best-fit plane.
//! The patch is then refined (centroid splits where its triangles are larger than the
//! edges around the hole, with Delaunay edge flips) and faired (umbrella smoothing of
//! the new vertices, the loop held fixed), giving a membrane over the hole.
//!
//! Patch corners take the UVs and colours of the mesh corners around the hole
//! (interpolated at new vertices), flat normals, and the material most of the
//! triangles around the hole have.

use std::collections::HashMap;

use glam::DVec3;

use super::refine::refine_and_fair;
use super::soup::{Corner, Soup};
use crate::io::Triangulator;

/// Loops longer than this are ear-clipped instead of searched (the search is cubic).
const MAX_SEARCH_LOOP: usize = 120;

/// One boundary loop: vertices in the order the patch walks them, and per loop edge
/// `v[i] → v[i+1]` the mesh triangle on its other side.
#[derive(Debug, Clone)]
pub(super) struct Loop {
    pub verts: Vec<u32>,
    pub outside: Vec<usize>,
}

/// The boundary loops of a consistently wound shell (`tris`: its triangles). A loop
/// that touches itself at a vertex is split there into simple loops; edges that close
/// no loop are counted in the second value.
pub(super) fn boundary_loops(soup: &Soup, tris: &[u32]) -> (Vec<Loop>, usize) {
    let mut count: HashMap<(u32, u32), i32> = HashMap::with_capacity(tris.len() * 3);
    let mut owner: HashMap<(u32, u32), usize> = HashMap::with_capacity(tris.len() * 3);
    for &t in tris {
        let tri = soup.tris[t as usize];
        for k in 0..3 {
            let (a, b) = (tri[k], tri[(k + 1) % 3]);
            *count.entry((a, b)).or_default() += 1;
            *count.entry((b, a)).or_default() -= 1;
            owner.insert((a, b), t as usize);
        }
    }
    // A mesh edge a→b with no partner: the patch walks b→a.
    let mut next: HashMap<u32, Vec<(u32, usize)>> = HashMap::new();
    let mut edges = 0usize;
    let mut keys: Vec<(&(u32, u32), &i32)> = count.iter().filter(|&(_, &n)| n > 0).collect();
    keys.sort_unstable();
    for (&(a, b), &n) in keys {
        for _ in 0..n {
            next.entry(b).or_default().push((a, owner[&(a, b)]));
            edges += 1;
        }
    }
    let mut loops = Vec::new();
    let mut starts: Vec<u32> = next.keys().copied().collect();
    starts.sort_unstable();
    let mut used_edges = 0;
    for start in starts {
        while let Some((first, tri)) = next.get_mut(&start).and_then(Vec::pop) {
            let mut path = vec![start];
            let mut outside = vec![tri];
            let mut at = first;
            let mut index: HashMap<u32, usize> = HashMap::from([(start, 0)]);
            loop {
                if let Some(&j) = index.get(&at) {
                    // The path closes at `at`: `path[j..]` is a loop (the whole path, or
                    // a pinched part of it); the walk goes on from `at`.
                    let verts = path.split_off(j);
                    let out = outside.split_off(j);
                    for v in &verts {
                        index.remove(v);
                    }
                    used_edges += verts.len();
                    if verts.len() >= 3 {
                        loops.push(Loop {
                            verts,
                            outside: out,
                        });
                    }
                    if path.is_empty() {
                        break;
                    }
                }
                let Some((step, tri)) = next.get_mut(&at).and_then(Vec::pop) else {
                    break;
                };
                index.insert(at, path.len());
                path.push(at);
                outside.push(tri);
                at = step;
            }
        }
    }
    (loops, edges.saturating_sub(used_edges))
}

/// A patch for one loop: new positions (appended after the soup's), triangles over the
/// soup's indices (new positions numbered from `soup.pos.len()` on) and per triangle its
/// corners' attributes.
pub(super) struct Patch {
    pub new_pos: Vec<DVec3>,
    pub tris: Vec<[u32; 3]>,
    pub corners: Vec<[Corner; 3]>,
    pub material: u32,
    pub area: f64,
}

/// Triangulates, refines and fairs the patch over `hole`.
pub(super) fn patch(soup: &Soup, hole: &Loop) -> Option<Patch> {
    let n = hole.verts.len();
    let p: Vec<DVec3> = hole.verts.iter().map(|&v| soup.pos[v as usize]).collect();
    let outside_normal: Vec<DVec3> = hole
        .outside
        .iter()
        .map(|&t| soup.face_normal(t).normalize_or_zero())
        .collect();
    let local = if n <= MAX_SEARCH_LOOP {
        search(&p, &outside_normal)
    } else {
        Triangulator::new().triangulate(&p)?
    };
    // Attributes at each loop vertex, from the mesh triangle on the loop edge leaving it.
    let attrs: Vec<Corner> = (0..n)
        .map(|i| {
            let t = hole.outside[i];
            let v = hole.verts[i];
            let k = soup.tris[t].iter().position(|&w| w == v).unwrap_or(0);
            soup.corner(t, k)
        })
        .collect();
    let mut votes: HashMap<u32, usize> = HashMap::new();
    for &t in &hole.outside {
        *votes.entry(soup.material[t]).or_default() += 1;
    }
    let material = votes
        .into_iter()
        .max_by_key(|&(m, c)| (c, std::cmp::Reverse(m)))
        .map_or(0, |(m, _)| m);
    let refined = refine_and_fair(p, attrs, local);
    let base = soup.pos.len() as u32;
    let map = |i: usize| {
        if i < n {
            hole.verts[i]
        } else {
            base + (i - n) as u32
        }
    };
    let mut area = 0.0;
    let mut tris = Vec::with_capacity(refined.tris.len());
    let mut corners = Vec::with_capacity(refined.tris.len());
    for t in &refined.tris {
        let [a, b, c] = t.map(|i| refined.pos[i]);
        let normal = (b - a).cross(c - a);
        area += 0.5 * normal.length();
        let n32 = normal.normalize_or_zero().as_vec3().to_array();
        tris.push(t.map(map));
        corners.push(t.map(|i| Corner {
            normal: n32,
            ..refined.attrs[i]
        }));
    }
    Some(Patch {
        new_pos: refined.pos[n..].to_vec(),
        tris,
        corners,
        material,
        area,
    })
}

/// Liepa's search: the triangulation of the polygon `p` minimising (largest dihedral
/// angle, area), where `outside[i]` is the unit normal of the mesh triangle beyond edge
/// `p[i] → p[i+1]`. Triangles are `[i, m, k]` with `i < m < k`, wound like the loop.
fn search(p: &[DVec3], outside: &[DVec3]) -> Vec<[usize; 3]> {
    let n = p.len();
    if n == 3 {
        return vec![[0, 1, 2]];
    }
    let idx = |i: usize, k: usize| i * n + k;
    let mut angle = vec![0.0f64; n * n];
    let mut area = vec![0.0f64; n * n];
    let mut choice = vec![0usize; n * n];
    let normal = |i: usize, m: usize, k: usize| (p[m] - p[i]).cross(p[k] - p[i]);
    let dihedral = |a: DVec3, b: DVec3| {
        let (a, b) = (a.normalize_or_zero(), b.normalize_or_zero());
        if a == DVec3::ZERO || b == DVec3::ZERO {
            std::f64::consts::PI
        } else {
            a.dot(b).clamp(-1.0, 1.0).acos()
        }
    };
    // Normal of the triangle on the far side of edge (i, m) inside the subproblem.
    let beyond = |i: usize, m: usize, choice: &[usize]| {
        if m == i + 1 {
            outside[i]
        } else {
            normal(i, choice[idx(i, m)], m)
        }
    };
    for len in 2..n {
        for i in 0..n - len {
            let k = i + len;
            let mut best = (f64::INFINITY, f64::INFINITY, i + 1);
            for m in i + 1..k {
                let tri = normal(i, m, k);
                let a = angle[idx(i, m)]
                    .max(angle[idx(m, k)])
                    .max(dihedral(tri, beyond(i, m, &choice)))
                    .max(dihedral(tri, beyond(m, k, &choice)));
                let s = area[idx(i, m)] + area[idx(m, k)] + 0.5 * tri.length();
                let a = if len == n - 1 {
                    a.max(dihedral(tri, outside[n - 1]))
                } else {
                    a
                };
                if (a, s) < (best.0, best.1) {
                    best = (a, s, m);
                }
            }
            angle[idx(i, k)] = best.0;
            area[idx(i, k)] = best.1;
            choice[idx(i, k)] = best.2;
        }
    }
    let mut out = Vec::with_capacity(n - 2);
    let mut stack = vec![(0, n - 1)];
    while let Some((i, k)) = stack.pop() {
        if k < i + 2 {
            continue;
        }
        let m = choice[idx(i, k)];
        out.push([i, m, k]);
        stack.push((i, m));
        stack.push((m, k));
    }
    out
}
