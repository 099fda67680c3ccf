//! Merging fragments below the sliver threshold into a bonded neighbour, so that no
//! tiny piece reaches the physics.

use std::collections::{BTreeMap, BTreeSet};

use glam::DVec3;
use rayon::prelude::*;

use crate::fracture::Bond;
use crate::fracture::kernel::Piece;
use crate::fracture::kernel::union::union;
use crate::mesh::is_degenerate;
use crate::util::{FastMap, UnionFind};

/// What merging did beyond the plain case.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub(crate) struct Merged {
    /// Small pieces left as they are: no other piece to merge into.
    pub lonely: usize,
    /// Small pieces left as they are because no union with a neighbour is a closed
    /// 2-manifold (they touch it along an edge only, or their caps overlap in part).
    pub unjoined: usize,
}

/// Merges every piece whose volume is below `min_volume` into the bonded neighbour it
/// shares the largest area with (repeatedly, smallest first), or, with no bonded
/// neighbour, into the piece nearest to it. A merged fragment is the [`union`] of its
/// pieces: the caps they share cancel, so it is a closed 2-manifold again. A union
/// that would not be one is not made; the next neighbour is tried, and a piece no
/// neighbour takes is kept as it is (counted in [`Merged`]). Returns the new pieces,
/// bonds (remapped, each pair once), what was left unmerged, and each input piece's new
/// piece.
///
/// A piece marked in `poor` (missing marks are `false`) is also small while it is alone
/// in its group (a sliver tetrahedron of any volume).
pub(crate) fn merge_small_with(
    pieces: Vec<Piece>,
    bonds: Vec<Bond>,
    min_volume: f64,
    poor: &[bool],
    eps: f64,
) -> (Vec<Piece>, Vec<Bond>, Merged, Vec<u32>) {
    let n = pieces.len();
    let vol: Vec<f64> = pieces.iter().map(Piece::volume).collect();
    // A group is small below the volume, or while it is one poor piece.
    let is_small = |g: usize, vol: f64, count: usize| {
        vol < min_volume || (count == 1 && poor.get(g).copied().unwrap_or(false))
    };
    if (0..n).all(|i| !is_small(i, vol[i], 1)) {
        return (pieces, bonds, Merged::default(), (0..n as u32).collect());
    }
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by(|&a, &b| vol[a].total_cmp(&vol[b]).then(a.cmp(&b)));
    // The groups are planned first, as if every union closed, and each is made by one
    // union of all its pieces, the groups in parallel. Joined one piece at a time, a
    // group of m pieces costs m unions of a growing surface: on a dense mesh, where
    // nearly every tetrahedron is a sliver, that was most of the time. A planned group
    // whose union does not close is left in pieces, which the loop below then joins one
    // at a time, as before.
    let planned = plan(&order, &vol, &bonds, is_small);
    let mut groups = Groups::new(pieces, vol, &bonds);
    groups.make(planned, &bonds, eps);
    let small = |g: usize, groups: &Groups| is_small(g, groups.vol[g], groups.count[g]);
    loop {
        let mut changed = false;
        for &i in &order {
            let g = groups.uf.find(i);
            if !small(g, &groups) {
                continue;
            }
            // Total bond area from group g to each other group, largest first.
            let mut area_to: BTreeMap<usize, f64> = BTreeMap::new();
            for &k in groups.members[g].iter().flat_map(|&p| &groups.incident[p]) {
                let b = &bonds[k as usize];
                let (ga, gb) = (groups.uf.find(b.a as usize), groups.uf.find(b.b as usize));
                if ga == gb {
                    continue;
                }
                if ga == g {
                    *area_to.entry(gb).or_default() += b.area;
                } else if gb == g {
                    *area_to.entry(ga).or_default() += b.area;
                }
            }
            let mut candidates: Vec<(usize, f64)> = area_to.into_iter().collect();
            candidates.sort_by(|a, b| b.1.total_cmp(&a.1).then(a.0.cmp(&b.0)));
            if candidates.into_iter().any(|(h, _)| groups.join(g, h, eps)) {
                changed = true;
            }
        }
        if !changed {
            break;
        }
    }
    // Small groups with no bonded neighbour that takes them: their faces with the rest
    // are below the bonds' area threshold (a sliver cut off where a cell grazes the
    // surface). Each is joined to the group with the vertex nearest its centroid, which
    // it touches or nearly, if their union is closed.
    let mut merged = Merged::default();
    // Every group's vertices on a grid, made when first needed (a scan of them all per
    // small group was quadratic, most of the time on a dense mesh's thousands of
    // slivers).
    let mut grid: Option<VertexGrid> = None;
    for &i in &order {
        let g = groups.uf.find(i);
        if !small(g, &groups) {
            continue;
        }
        let Some(pg) = groups.geometry[g].as_ref() else {
            continue;
        };
        let centroid = pg.pos.iter().copied().sum::<DVec3>() / pg.pos.len().max(1) as f64;
        let grid = grid.get_or_insert_with(|| VertexGrid::new(&groups.geometry));
        let nearest = grid.nearest(centroid, |h| {
            let r = groups.uf.find(h as usize);
            (r != g && groups.geometry[r].is_some()).then_some(r)
        });
        match nearest {
            None => merged.lonely += 1,
            Some(h) => {
                if !groups.join(g, h, eps) {
                    merged.unjoined += 1;
                }
            }
        }
    }
    let mut new_id = vec![u32::MAX; n];
    let mut slot = vec![usize::MAX; n];
    let mut out: Vec<Piece> = Vec::new();
    for (i, id) in new_id.iter_mut().enumerate() {
        let r = groups.uf.find(i);
        if slot[r] == usize::MAX {
            slot[r] = out.len();
            out.push(groups.geometry[r].take().unwrap_or_default());
        }
        *id = slot[r] as u32;
    }
    let mut acc: BTreeMap<(u32, u32), (f64, DVec3, DVec3)> = BTreeMap::new();
    for b in bonds {
        let (a, c) = (new_id[b.a as usize], new_id[b.b as usize]);
        if a == c {
            continue;
        }
        let (lo, hi, normal) = if a < c {
            (a, c, b.normal)
        } else {
            (c, a, -b.normal)
        };
        let e = acc
            .entry((lo, hi))
            .or_insert((0.0, DVec3::ZERO, DVec3::ZERO));
        e.0 += b.area;
        e.1 += b.centroid * b.area;
        e.2 += normal * b.area;
    }
    let bonds = acc
        .into_iter()
        .map(|((a, b), (area, c, nrm))| Bond {
            a,
            b,
            area,
            centroid: c / area,
            normal: nrm.normalize_or_zero(),
        })
        .collect();
    (out, bonds, merged, new_id)
}

/// The groups [`merge_small_with`] would make if every union closed: each small group
/// (smallest first, repeatedly) joined to the bonded group it shares the most area
/// with. Groups of more than one piece, each as its pieces in ascending order.
fn plan(
    order: &[usize],
    vol: &[f64],
    bonds: &[Bond],
    is_small: impl Fn(usize, f64, usize) -> bool,
) -> Vec<Vec<usize>> {
    let n = vol.len();
    let mut uf = UnionFind::new(n);
    let mut gvol = vol.to_vec();
    let mut count = vec![1usize; n];
    let mut members: Vec<Vec<usize>> = (0..n).map(|i| vec![i]).collect();
    let mut incident: Vec<Vec<u32>> = vec![Vec::new(); n];
    for (k, b) in bonds.iter().enumerate() {
        incident[b.a as usize].push(k as u32);
        incident[b.b as usize].push(k as u32);
    }
    loop {
        let mut changed = false;
        for &i in order {
            let g = uf.find(i);
            if !is_small(g, gvol[g], count[g]) {
                continue;
            }
            let mut area_to: BTreeMap<usize, f64> = BTreeMap::new();
            for &k in members[g].iter().flat_map(|&p| &incident[p]) {
                let b = &bonds[k as usize];
                let (ga, gb) = (uf.find(b.a as usize), uf.find(b.b as usize));
                if ga == gb {
                    continue;
                }
                if ga == g {
                    *area_to.entry(gb).or_default() += b.area;
                } else if gb == g {
                    *area_to.entry(ga).or_default() += b.area;
                }
            }
            let best = area_to
                .into_iter()
                .max_by(|a, b| a.1.total_cmp(&b.1).then(b.0.cmp(&a.0)));
            if let Some((h, _)) = best {
                let (v, c) = (gvol[g] + gvol[h], count[g] + count[h]);
                uf.union(g, h);
                let r = uf.find(g);
                gvol[r] = v;
                count[r] = c;
                let other = if r == g { h } else { g };
                let moved = std::mem::take(&mut members[other]);
                members[r].extend(moved);
                changed = true;
            }
        }
        if !changed {
            break;
        }
    }
    members
        .into_iter()
        .filter(|m| m.len() > 1)
        .map(|mut m| {
            m.sort_unstable();
            m
        })
        .collect()
}

/// The groups being merged: each piece's group, and per group (held by its root) its
/// surface, volume, member count and members; each piece's bonds; the pairs whose union
/// failed.
struct Groups {
    uf: UnionFind,
    geometry: Vec<Option<Piece>>,
    vol: Vec<f64>,
    count: Vec<usize>,
    members: Vec<Vec<usize>>,
    /// Each piece's bonds, so a group's neighbours are found from its own bonds, not by
    /// a scan of them all.
    incident: Vec<Vec<u32>>,
    /// Pairs of groups (by their roots at the time) whose union failed.
    refused: BTreeSet<(usize, usize)>,
}

impl Groups {
    fn new(pieces: Vec<Piece>, vol: Vec<f64>, bonds: &[Bond]) -> Groups {
        let n = pieces.len();
        let mut incident: Vec<Vec<u32>> = vec![Vec::new(); n];
        for (k, b) in bonds.iter().enumerate() {
            incident[b.a as usize].push(k as u32);
            incident[b.b as usize].push(k as u32);
        }
        Groups {
            uf: UnionFind::new(n),
            geometry: pieces.into_iter().map(Some).collect(),
            vol,
            count: vec![1; n],
            members: (0..n).map(|i| vec![i]).collect(),
            incident,
            refused: BTreeSet::new(),
        }
    }

    /// Makes each planned group (pieces, each still alone) by one union of all its
    /// pieces, the groups in parallel. A group whose union does not close is halved
    /// along its bonds and each half made the same way, down to pairs; what is left
    /// apart, the loop of [`merge_small_with`] joins one group at a time.
    fn make(&mut self, planned: Vec<Vec<usize>>, bonds: &[Bond], eps: f64) {
        let (geometry, incident) = (&self.geometry, &self.incident);
        let made: Vec<(Vec<usize>, Piece)> = planned
            .into_par_iter()
            .with_max_len(1)
            .flat_map_iter(|m| {
                let mut out = Vec::new();
                make_group(m, geometry, incident, bonds, eps, &mut out);
                out
            })
            .collect();
        for (m, joined) in made {
            let (v, c): (f64, usize) = (m.iter().map(|&i| self.vol[i]).sum(), m.len());
            for &i in &m[1..] {
                self.uf.union(m[0], i);
            }
            for &i in &m {
                self.geometry[i] = None;
            }
            let r = self.uf.find(m[0]);
            self.vol[r] = v;
            self.count[r] = c;
            self.geometry[r] = Some(joined);
            for &i in &m {
                if i != r {
                    self.members[i].clear();
                }
            }
            self.members[r] = m;
        }
    }

    /// Joins groups `g` and `h` (roots) when the union of their surfaces is a closed
    /// 2-manifold; a refused pair is remembered and not tried again.
    fn join(&mut self, g: usize, h: usize, eps: f64) -> bool {
        let key = (g.min(h), g.max(h));
        if self.refused.contains(&key) {
            return false;
        }
        let (Some(pg), Some(ph)) = (self.geometry[g].as_ref(), self.geometry[h].as_ref()) else {
            return false;
        };
        match union_without_flat(&[ph, pg], eps) {
            Some(joined) => {
                let (v, c) = (self.vol[g] + self.vol[h], self.count[g] + self.count[h]);
                self.geometry[g] = None;
                self.geometry[h] = None;
                self.uf.union(g, h);
                let r = self.uf.find(g);
                self.vol[r] = v;
                self.count[r] = c;
                self.geometry[r] = Some(joined);
                let other = if r == g { h } else { g };
                let moved = std::mem::take(&mut self.members[other]);
                self.members[r].extend(moved);
                true
            }
            None => {
                self.refused.insert(key);
                false
            }
        }
    }
}

/// The union of the pieces `m` (bonded, each alone) pushed onto `out` when it closes
/// and has no flat triangle (the fragment check refuses those);
/// else `m` in breadth-first order along its bonds is halved (the first half connected,
/// the second as its connected parts) and each part made the same way.
fn make_group(
    m: Vec<usize>,
    geometry: &[Option<Piece>],
    incident: &[Vec<u32>],
    bonds: &[Bond],
    eps: f64,
    out: &mut Vec<(Vec<usize>, Piece)>,
) {
    if m.len() < 2 {
        return;
    }
    let parts: Vec<&Piece> = m.iter().filter_map(|&i| geometry[i].as_ref()).collect();
    if parts.len() != m.len() {
        return;
    }
    if let Some(joined) = union_without_flat(&parts, eps) {
        out.push((m, joined));
        return;
    }
    if m.len() == 2 {
        return;
    }
    let inside: BTreeSet<usize> = m.iter().copied().collect();
    let neighbours = |i: usize| {
        incident[i].iter().map(move |&k| {
            let b = &bonds[k as usize];
            if b.a as usize == i {
                b.b as usize
            } else {
                b.a as usize
            }
        })
    };
    // Connected parts of `set`, each in breadth-first order from its lowest piece.
    let parts_of = |set: &BTreeSet<usize>| -> Vec<Vec<usize>> {
        let mut seen: BTreeSet<usize> = BTreeSet::new();
        let mut parts = Vec::new();
        for &start in set {
            if !seen.insert(start) {
                continue;
            }
            let mut order = vec![start];
            let mut k = 0;
            while k < order.len() {
                for j in neighbours(order[k]) {
                    if set.contains(&j) && seen.insert(j) {
                        order.push(j);
                    }
                }
                k += 1;
            }
            parts.push(order);
        }
        parts
    };
    for part in parts_of(&inside) {
        if part.len() < m.len() {
            // Not connected after all: each part on its own.
            make_group(sorted(part), geometry, incident, bonds, eps, out);
            continue;
        }
        let half = part.len() / 2;
        let first: Vec<usize> = part[..half].to_vec();
        let rest: BTreeSet<usize> = part[half..].iter().copied().collect();
        make_group(sorted(first), geometry, incident, bonds, eps, out);
        for piece in parts_of(&rest) {
            make_group(sorted(piece), geometry, incident, bonds, eps, out);
        }
    }
}

/// `v` in ascending order.
fn sorted(mut v: Vec<usize>) -> Vec<usize> {
    v.sort_unstable();
    v
}

/// The [`union`] of `parts` with its flat triangles split away
/// ([`Piece::split_flat_triangles`]); `None` when it does not close or a flat triangle
/// is left (the fragment check refuses those).
fn union_without_flat(parts: &[&Piece], eps: f64) -> Option<Piece> {
    let mut joined = union(parts, eps).ok()?;
    joined.split_flat_triangles();
    let flat = joined.tris.iter().any(|t| {
        let [a, b, c] = t.map(|i| joined.pos[i as usize]);
        is_degenerate(a, b, c)
    });
    (!flat).then_some(joined)
}

/// The vertices of a set of pieces bucketed on a uniform grid, each with its piece, for
/// the vertex nearest a point.
struct VertexGrid {
    lo: DVec3,
    cell: f64,
    /// Cells along each axis.
    dims: [i64; 3],
    buckets: FastMap<[i64; 3], Vec<(DVec3, u32)>>,
}

impl VertexGrid {
    fn new(pieces: &[Option<Piece>]) -> VertexGrid {
        let all = || {
            pieces
                .iter()
                .enumerate()
                .filter_map(|(h, p)| p.as_ref().map(|p| (h, p)))
                .flat_map(|(h, p)| p.pos.iter().map(move |&q| (q, h as u32)))
        };
        let (mut lo, mut hi, mut count) = (DVec3::INFINITY, DVec3::NEG_INFINITY, 0usize);
        for (q, _) in all() {
            lo = lo.min(q);
            hi = hi.max(q);
            count += 1;
        }
        let extent = (hi - lo).max(DVec3::ZERO);
        // About two vertices per cell, were they spread through the box (a flat box
        // counted a thousandth of its size thick).
        let thin = extent.max_element() * 1e-3;
        let volume = extent.max(DVec3::splat(thin)).element_product();
        let cell = (volume / (count.max(1) as f64 / 2.0))
            .cbrt()
            .max(extent.max_element() / 4096.0)
            .max(f64::MIN_POSITIVE);
        let dims = [0, 1, 2].map(|k| ((extent[k] / cell).floor() as i64 + 1).max(1));
        let mut grid = VertexGrid {
            lo,
            cell,
            dims,
            buckets: FastMap::default(),
        };
        for (q, h) in all() {
            let key = grid.key(q);
            grid.buckets.entry(key).or_default().push((q, h));
        }
        grid
    }

    fn key(&self, q: DVec3) -> [i64; 3] {
        let k = ((q - self.lo) / self.cell).floor();
        [0, 1, 2].map(|i| (k[i] as i64).clamp(0, self.dims[i] - 1))
    }

    /// The group (as `accept` maps a vertex's piece, `None` to skip it) of the vertex
    /// nearest `p`, searched in shells of cells outward until no nearer one can be left.
    fn nearest(&self, p: DVec3, mut accept: impl FnMut(u32) -> Option<usize>) -> Option<usize> {
        let c = self.key(p);
        let mut best: Option<(f64, usize)> = None;
        let reach = self.dims.iter().copied().max().unwrap_or(1);
        for r in 0..=reach {
            for dx in -r..=r {
                for dy in -r..=r {
                    for dz in -r..=r {
                        if dx.abs().max(dy.abs()).max(dz.abs()) != r {
                            continue;
                        }
                        let Some(bucket) = self.buckets.get(&[c[0] + dx, c[1] + dy, c[2] + dz])
                        else {
                            continue;
                        };
                        for &(q, h) in bucket {
                            let d2 = q.distance_squared(p);
                            if best.is_none_or(|(b, _)| d2 < b)
                                && let Some(g) = accept(h)
                            {
                                best = Some((d2, g));
                            }
                        }
                    }
                }
            }
            // Beyond shell r, every vertex is at least r cells away.
            if let Some((b, _)) = best
                && b <= (r as f64 * self.cell).powi(2)
            {
                break;
            }
        }
        best.map(|(_, g)| g)
    }
}
