//! From the working storage to the public result: drop the infinite and free tetrahedra,
//! renumber in place, translate internal vertices to input indices.

use super::packed::{Store, Tets};
use super::storage::{INF, Mesh};
use super::types::Tetrahedralization;

/// Builds the result. `order[k]` is the input index of internal vertex `k + 1`; `dups`
/// lists merged duplicates as (internal slot, internal vertex).
pub(crate) fn finish<S: Store>(
    mesh: Mesh<S>,
    order: Vec<u32>,
    dups: &[(u32, u32)],
) -> Tetrahedralization
where
    Tets: From<S>,
{
    let Mesh { pts, mut tets, .. } = mesh;
    drop(pts);
    let n = order.len();
    // name[v]: the output index of internal vertex v — the smallest input index at its position.
    let mut name: Vec<u32> = Vec::with_capacity(n + 1);
    name.push(u32::MAX);
    name.extend_from_slice(&order);
    for &(s, w) in dups {
        let i = order[s as usize - 1];
        if i < name[w as usize] {
            name[w as usize] = i;
        }
    }
    let mut representative = vec![0u32; n];
    for (k, &i) in order.iter().enumerate() {
        representative[i as usize] = name[k + 1];
    }
    for &(s, w) in dups {
        representative[order[s as usize - 1] as usize] = name[w as usize];
    }
    drop(order);
    let duplicates: Vec<[u32; 2]> = representative
        .iter()
        .enumerate()
        .filter(|&(i, &r)| i as u32 != r)
        .map(|(i, &r)| [i as u32, r])
        .collect();
    let unique_points = n - duplicates.len();

    // Rank structure over kept tetrahedra: a bit per tetrahedron, a prefix count per word.
    let total = tets.len();
    let dead = tets.vertex_marker();
    let words = total.div_ceil(64);
    let mut bits = vec![0u64; words];
    for t in 0..total {
        let v = tets.verts(t as u32);
        if v[0] != dead && !v.contains(&INF) {
            bits[t / 64] |= 1 << (t % 64);
        }
    }
    let mut before = Vec::with_capacity(words);
    let mut acc = 0u32;
    for w in &bits {
        before.push(acc);
        acc += w.count_ones();
    }
    let kept = |t: usize| bits[t / 64] >> (t % 64) & 1 != 0;
    let rank = |t: usize| before[t / 64] + (bits[t / 64] & ((1u64 << (t % 64)) - 1)).count_ones();

    // In place, in the same records: the new index of a kept tetrahedron never exceeds its
    // old one. Vertices become input indices, adjacency fields the neighbour's new index
    // (the marker on the hull).
    let none = tets.adjacency_marker();
    let mut out = 0u32;
    for t in 0..total {
        if !kept(t) {
            continue;
        }
        let v = tets.verts(t as u32).map(|x| name[x as usize]);
        let a = tets.adjs(t as u32).map(|x| {
            let nb = (x >> 2) as usize;
            if kept(nb) { rank(nb) } else { none }
        });
        tets.write(out, v, a);
        out += 1;
    }
    tets.truncate(out as usize);
    Tetrahedralization::from_parts(tets.into(), representative, unique_points, duplicates)
}
