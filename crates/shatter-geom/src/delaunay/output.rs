//! From the working storage to the public result: drop the infinite and free tetrahedra,
//! renumber in place, translate internal vertices to input indices.

use super::packed::{Store, Tets};
use super::storage::INF;
use super::types::Tetrahedralization;
use crate::util::FastMap;

/// How the construction numbered the input points (see `storage::Points`).
pub(crate) enum Names {
    /// Internal vertex `k + 1` is input point `order[k]` (the points were copied in
    /// insertion order).
    Order(Vec<u32>),
    /// Internal vertex `v` is input point `v - 1` (the points were read in place); there
    /// are `points` of them.
    InPlace { points: usize },
}

/// Builds the result from the construction's records `tets`, whose points are numbered
/// as `names` says; `dups` lists merged duplicates as (internal slot, internal vertex).
pub(crate) fn finish<S: Store>(tets: S, names: Names, dups: &[(u32, u32)]) -> Tetrahedralization
where
    Tets: From<S>,
{
    match names {
        Names::Order(order) => {
            let n = order.len();
            let name = vertex_names(&order, dups);
            let mut representative = vec![0u32; n];
            fill_representative(&mut representative, &order, dups, &name);
            drop(order);
            assemble(tets, representative, |v| name[v as usize])
        }
        Names::InPlace { points } => {
            // A vertex's name is its own index unless a later duplicate of it has a
            // smaller one.
            let mut first: FastMap<u32, u32> = FastMap::default();
            for &(s, w) in dups {
                let e = first.entry(w).or_insert(w - 1);
                *e = (*e).min(s - 1);
            }
            let name = |v: u32| first.get(&v).copied().unwrap_or(v - 1);
            let mut representative: Vec<u32> = (0..points as u32).collect();
            for &(s, w) in dups {
                representative[s as usize - 1] = name(w);
                representative[w as usize - 1] = name(w);
            }
            assemble(tets, representative, name)
        }
    }
}

/// Drops the infinite and free tetrahedra of `tets` and renumbers the rest in place,
/// naming internal vertex `v` by `name(v)`.
fn assemble<S: Store>(
    mut tets: S,
    representative: Vec<u32>,
    name: impl Fn(u32) -> u32,
) -> Tetrahedralization
where
    Tets: From<S>,
{
    let (duplicates, unique_points) = duplicates_of(&representative);
    let total = tets.len();
    let dead = tets.vertex_marker();
    let keep = Rank::new(total, |t| {
        let v = tets.verts(t);
        v[0] != dead && !v.contains(&INF)
    });

    // In place, in the same records: the new index of a kept tetrahedron never exceeds its
    // old one. Vertices become input indices, adjacency fields the neighbour's new index
    // (the marker on the hull).
    let none = tets.adjacency_marker();
    let mut out = 0u32;
    for t in 0..total as u32 {
        if !keep.has(t) {
            continue;
        }
        let v = tets.verts(t).map(&name);
        let a = tets.adjs(t).map(|x| {
            let nb = x >> 2;
            if keep.has(nb) { keep.rank(nb) } else { none }
        });
        tets.write(out, v, a);
        out += 1;
    }
    tets.truncate(out as usize);
    Tetrahedralization::from_parts(tets.into(), representative, unique_points, duplicates)
}

/// `name[v]`: the output index of internal vertex `v` (`name[0]` is unused), the smallest
/// input index at its position. `order[k]` is the input index of internal vertex `k + 1`;
/// `dups` lists merged duplicates as (internal slot, internal vertex).
pub(crate) fn vertex_names(order: &[u32], dups: &[(u32, u32)]) -> Vec<u32> {
    let mut name: Vec<u32> = Vec::with_capacity(order.len() + 1);
    name.push(u32::MAX);
    name.extend_from_slice(order);
    for &(s, w) in dups {
        let i = order[s as usize - 1];
        if i < name[w as usize] {
            name[w as usize] = i;
        }
    }
    name
}

/// Sets `representative[i]` for every input index `i` that `order` lists.
pub(crate) fn fill_representative(
    representative: &mut [u32],
    order: &[u32],
    dups: &[(u32, u32)],
    name: &[u32],
) {
    for (k, &i) in order.iter().enumerate() {
        representative[i as usize] = name[k + 1];
    }
    for &(s, w) in dups {
        representative[order[s as usize - 1] as usize] = name[w as usize];
    }
}

/// The merged duplicates `[index, first occurrence]` in increasing index, and the number
/// of distinct points.
pub(crate) fn duplicates_of(representative: &[u32]) -> (Vec<[u32; 2]>, usize) {
    let duplicates: Vec<[u32; 2]> = representative
        .iter()
        .enumerate()
        .filter(|&(i, &r)| i as u32 != r)
        .map(|(i, &r)| [i as u32, r])
        .collect();
    let unique = representative.len() - duplicates.len();
    (duplicates, unique)
}

/// A chosen subset of `0..total`, with each member's rank among them: a bit per index and
/// a prefix count per 64.
pub(crate) struct Rank {
    bits: Vec<u64>,
    before: Vec<u32>,
}

impl Rank {
    /// The indices below `total` for which `keep` holds.
    pub(crate) fn new(total: usize, mut keep: impl FnMut(u32) -> bool) -> Self {
        let words = total.div_ceil(64);
        let mut bits = vec![0u64; words];
        for t in 0..total {
            if keep(t as u32) {
                bits[t / 64] |= 1 << (t % 64);
            }
        }
        let mut before = Vec::with_capacity(words);
        let mut acc = 0u32;
        for w in &bits {
            before.push(acc);
            acc += w.count_ones();
        }
        Self { bits, before }
    }

    /// Whether `t` is a member.
    #[inline(always)]
    pub(crate) fn has(&self, t: u32) -> bool {
        let t = t as usize;
        self.bits[t / 64] >> (t % 64) & 1 != 0
    }

    /// Number of members below `t`.
    #[inline(always)]
    pub(crate) fn rank(&self, t: u32) -> u32 {
        let t = t as usize;
        self.before[t / 64] + (self.bits[t / 64] & ((1u64 << (t % 64)) - 1)).count_ones()
    }
}
