//! Merging fragments below the sliver threshold into a bonded neighbour, so that no
//! tiny piece reaches the physics.

use std::collections::{BTreeMap, BTreeSet};

use glam::DVec3;

use crate::fracture::Bond;
use crate::fracture::kernel::Piece;
use crate::fracture::kernel::union::union;
use crate::util::UnionFind;

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
/// bonds (remapped, each pair once) and what was left unmerged.
pub(crate) fn merge_small(
    pieces: Vec<Piece>,
    bonds: Vec<Bond>,
    min_volume: f64,
    eps: f64,
) -> (Vec<Piece>, Vec<Bond>, Merged) {
    let (pieces, bonds, merged, _) = merge_small_with(pieces, bonds, min_volume, &[], eps);
    (pieces, bonds, merged)
}

/// [`merge_small`], where a piece marked in `poor` (missing marks are `false`) is also
/// small while it is alone in its group (a sliver tetrahedron of any volume); also
/// returns each input piece's new piece.
pub(crate) fn merge_small_with(
    pieces: Vec<Piece>,
    bonds: Vec<Bond>,
    min_volume: f64,
    poor: &[bool],
    eps: f64,
) -> (Vec<Piece>, Vec<Bond>, Merged, Vec<u32>) {
    let n = pieces.len();
    let mut vol: Vec<f64> = pieces.iter().map(Piece::volume).collect();
    // Members per group (held by its root): a poor piece is small while alone.
    let mut count: Vec<usize> = vec![1; n];
    let small = |g: usize, vol: &[f64], count: &[usize]| {
        vol[g] < min_volume || (count[g] == 1 && poor.get(g).copied().unwrap_or(false))
    };
    if (0..n).all(|i| !small(i, &vol, &count)) {
        return (pieces, bonds, Merged::default(), (0..n as u32).collect());
    }
    let mut uf = UnionFind::new(n);
    // Each group's surface, held by its root.
    let mut geometry: Vec<Option<Piece>> = pieces.into_iter().map(Some).collect();
    // Pairs of groups (by their pieces' ids at the time) whose union failed.
    let mut refused: BTreeSet<(usize, usize)> = BTreeSet::new();
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by(|&a, &b| vol[a].total_cmp(&vol[b]).then(a.cmp(&b)));
    // Each piece's bonds, and each group's pieces (held by its root), so a group's
    // neighbours are found from its own bonds, not by a scan of them all.
    let mut incident: Vec<Vec<u32>> = vec![Vec::new(); n];
    for (k, b) in bonds.iter().enumerate() {
        incident[b.a as usize].push(k as u32);
        incident[b.b as usize].push(k as u32);
    }
    let mut members: Vec<Vec<usize>> = (0..n).map(|i| vec![i]).collect();
    let join = |g: usize,
                h: usize,
                uf: &mut UnionFind,
                geometry: &mut Vec<Option<Piece>>,
                vol: &mut Vec<f64>,
                count: &mut Vec<usize>,
                members: &mut Vec<Vec<usize>>,
                refused: &mut BTreeSet<(usize, usize)>|
     -> bool {
        let key = (g.min(h), g.max(h));
        if refused.contains(&key) {
            return false;
        }
        let (Some(pg), Some(ph)) = (geometry[g].as_ref(), geometry[h].as_ref()) else {
            return false;
        };
        match union(&[ph, pg], eps) {
            Ok(joined) => {
                let (v, c) = (vol[g] + vol[h], count[g] + count[h]);
                geometry[g] = None;
                geometry[h] = None;
                uf.union(g, h);
                let r = uf.find(g);
                vol[r] = v;
                count[r] = c;
                geometry[r] = Some(joined);
                let other = if r == g { h } else { g };
                let moved = std::mem::take(&mut members[other]);
                members[r].extend(moved);
                true
            }
            Err(_) => {
                refused.insert(key);
                false
            }
        }
    };
    loop {
        let mut changed = false;
        for &i in &order {
            let g = uf.find(i);
            if !small(g, &vol, &count) {
                continue;
            }
            // Total bond area from group g to each other group, largest first.
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
            let mut candidates: Vec<(usize, f64)> = area_to.into_iter().collect();
            candidates.sort_by(|a, b| b.1.total_cmp(&a.1).then(a.0.cmp(&b.0)));
            for (h, _) in candidates {
                if join(
                    g,
                    h,
                    &mut uf,
                    &mut geometry,
                    &mut vol,
                    &mut count,
                    &mut members,
                    &mut refused,
                ) {
                    changed = true;
                    break;
                }
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
    for &i in &order {
        let g = uf.find(i);
        if !small(g, &vol, &count) || geometry[g].is_none() {
            continue;
        }
        let Some(pg) = geometry[g].as_ref() else {
            continue;
        };
        let centroid = pg.pos.iter().copied().sum::<DVec3>() / pg.pos.len().max(1) as f64;
        let mut nearest: Option<(f64, usize)> = None;
        for (h, ph) in geometry.iter().enumerate() {
            let Some(ph) = ph else { continue };
            if h == g {
                continue;
            }
            for q in &ph.pos {
                let d2 = q.distance_squared(centroid);
                if nearest.is_none_or(|(best, _)| d2 < best) {
                    nearest = Some((d2, h));
                }
            }
        }
        match nearest {
            None => merged.lonely += 1,
            Some((_, h)) => {
                if !join(
                    g,
                    h,
                    &mut uf,
                    &mut geometry,
                    &mut vol,
                    &mut count,
                    &mut members,
                    &mut refused,
                ) {
                    merged.unjoined += 1;
                }
            }
        }
    }
    let mut new_id = vec![u32::MAX; n];
    let mut slot = vec![usize::MAX; n];
    let mut out: Vec<Piece> = Vec::new();
    for (i, id) in new_id.iter_mut().enumerate() {
        let r = uf.find(i);
        if slot[r] == usize::MAX {
            slot[r] = out.len();
            out.push(geometry[r].take().unwrap_or_default());
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
