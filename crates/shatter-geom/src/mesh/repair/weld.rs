//! Welding: first vertices at exactly equal positions, then the vertices of boundary
//! edges within a tolerance, so that the cracks CAD exporters leave between patches
//! (two rows of vertices a rounding error apart) close.
//!
//! Only boundary vertices take part in the tolerance weld: a closed surface is never
//! changed by it, and two separate closed parts a hair apart are not glued into a
//! non-manifold vertex.

use std::collections::HashMap;

use glam::DVec3;

use super::soup::{Soup, edge_key};
use crate::mesh::position_key;
use crate::util::UnionFind;

/// Merges vertices at exactly equal positions; returns how many vertices went.
pub(super) fn exact(soup: &mut Soup) -> usize {
    let mut seen: HashMap<[u64; 3], u32> = HashMap::with_capacity(soup.pos.len());
    let mut map = Vec::with_capacity(soup.pos.len());
    let mut pos = Vec::new();
    for &p in &soup.pos {
        let next = pos.len() as u32;
        let k = *seen.entry(position_key(p)).or_insert(next);
        if k == next {
            pos.push(p);
        }
        map.push(k);
    }
    let merged = soup.pos.len() - pos.len();
    remap(soup, pos, &map);
    merged
}

/// Merges boundary vertices closer than `tol` to each other (each cluster takes its
/// first vertex's position); returns how many vertices went.
pub(super) fn boundary(soup: &mut Soup, tol: f64) -> usize {
    if tol <= 0.0 || !tol.is_finite() {
        return 0;
    }
    let mut uses: HashMap<u64, u32> = HashMap::with_capacity(soup.tris.len() * 3 / 2);
    for t in &soup.tris {
        for k in 0..3 {
            *uses.entry(edge_key(t[k], t[(k + 1) % 3])).or_default() += 1;
        }
    }
    let mut on_boundary = vec![false; soup.pos.len()];
    for (&e, &n) in &uses {
        if n == 1 {
            on_boundary[(e >> 32) as usize] = true;
            on_boundary[(e & 0xffff_ffff) as usize] = true;
        }
    }
    let cell = |p: DVec3| (p / tol).floor().as_i64vec3().to_array();
    let mut grid: HashMap<[i64; 3], Vec<u32>> = HashMap::new();
    for (v, &b) in on_boundary.iter().enumerate() {
        if b {
            grid.entry(cell(soup.pos[v])).or_default().push(v as u32);
        }
    }
    if grid.is_empty() {
        return 0;
    }
    let mut sets = UnionFind::new(soup.pos.len());
    for (v, &b) in on_boundary.iter().enumerate() {
        if !b {
            continue;
        }
        let p = soup.pos[v];
        let [x, y, z] = cell(p);
        for dx in -1..=1 {
            for dy in -1..=1 {
                for dz in -1..=1 {
                    let Some(list) = grid.get(&[x + dx, y + dy, z + dz]) else {
                        continue;
                    };
                    for &w in list {
                        if (w as usize) > v && soup.pos[w as usize].distance(p) <= tol {
                            sets.union(v, w as usize);
                        }
                    }
                }
            }
        }
    }
    let mut map = Vec::with_capacity(soup.pos.len());
    let mut pos = Vec::new();
    let mut new_index = vec![u32::MAX; soup.pos.len()];
    for v in 0..soup.pos.len() {
        let root = sets.find(v);
        if new_index[root] == u32::MAX {
            new_index[root] = pos.len() as u32;
            pos.push(soup.pos[root]);
        }
        map.push(new_index[root]);
    }
    let merged = soup.pos.len() - pos.len();
    if merged > 0 {
        remap(soup, pos, &map);
    }
    merged
}

fn remap(soup: &mut Soup, pos: Vec<DVec3>, map: &[u32]) {
    soup.pos = pos;
    for t in &mut soup.tris {
        *t = t.map(|i| map[i as usize]);
    }
}

/// Snaps each coordinate axis on its own: the positions' `x` values (then `y`, then `z`)
/// in order, values less than `tol` from the previous one joined into a run (a run spans
/// at most `4·tol`), every value of a run set to the run's first. Faces of separate parts
/// that a file puts a rounding error apart on one axis-aligned plane (a 32-bit
/// coordinate through a node's transform) then lie on exactly one plane, which the union
/// settles exactly; left a hair apart, they give it slivers that rounding crosses.
/// Returns how many coordinates changed.
pub(super) fn coordinates(soup: &mut Soup, tol: f64) -> usize {
    if tol <= 0.0 || !tol.is_finite() {
        return 0;
    }
    let mut changed = 0;
    let mut order: Vec<usize> = (0..soup.pos.len()).collect();
    for axis in 0..3 {
        order.sort_by(|&a, &b| soup.pos[a][axis].total_cmp(&soup.pos[b][axis]));
        let mut start = 0;
        for i in 1..=order.len() {
            let ends = i == order.len() || {
                let (v, prev, first) = (
                    soup.pos[order[i]][axis],
                    soup.pos[order[i - 1]][axis],
                    soup.pos[order[start]][axis],
                );
                v - prev > tol || v - first > 4.0 * tol
            };
            if ends {
                let value = soup.pos[order[start]][axis];
                for &k in &order[start..i] {
                    if soup.pos[k][axis] != value {
                        soup.pos[k][axis] = value;
                        changed += 1;
                    }
                }
                start = i;
            }
        }
    }
    changed
}
