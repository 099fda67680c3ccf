//! Merging fragments below the sliver threshold into a bonded neighbour, so that no
//! tiny piece reaches the physics.

use std::collections::{BTreeMap, BTreeSet};

use glam::DVec3;

use crate::fracture::Bond;
use crate::fracture::kernel::Piece;
use crate::fracture::kernel::union::union;
use crate::util::{ShellGrid, UnionFind};

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
    let mut groups = Groups::new(pieces, vol, &bonds);
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
    // A group left as it is is counted once (through its first member), not once per
    // member.
    let mut seen = vec![false; n];
    for &i in &order {
        let g = groups.uf.find(i);
        if seen[g] || !small(g, &groups) {
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
            None => {
                merged.lonely += 1;
                seen[g] = true;
            }
            Some(h) => {
                if !groups.join(g, h, eps) {
                    merged.unjoined += 1;
                    seen[g] = true;
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

/// The [`union`] of `parts` with its flat triangles split away
/// ([`Piece::split_flat_triangles`]); `None` when it does not close or a flat triangle
/// is left (the fragment check refuses those).
fn union_without_flat(parts: &[&Piece], eps: f64) -> Option<Piece> {
    let mut joined = union(parts, eps).ok()?;
    joined.split_flat_triangles();
    (!joined.has_flat_triangle()).then_some(joined)
}

/// The vertices of a set of pieces on a [`ShellGrid`], each with its piece, for the vertex
/// nearest a point.
struct VertexGrid {
    /// Every vertex's position, and its piece.
    pos: Vec<DVec3>,
    piece: Vec<u32>,
    grid: ShellGrid,
}

impl VertexGrid {
    fn new(pieces: &[Option<Piece>]) -> VertexGrid {
        let (pos, piece): (Vec<DVec3>, Vec<u32>) = pieces
            .iter()
            .enumerate()
            .filter_map(|(h, p)| p.as_ref().map(|p| (h, p)))
            .flat_map(|(h, p)| p.pos.iter().map(move |&q| (q, h as u32)))
            .unzip();
        // About two vertices per cell.
        let mut grid = ShellGrid::over(&pos, pos.len() as f64 / 2.0);
        for (k, &q) in pos.iter().enumerate() {
            grid.insert(k as u32, q, q);
        }
        VertexGrid { pos, piece, grid }
    }

    /// The group (as `accept` maps a vertex's piece, `None` to skip it) of the vertex
    /// nearest `p` (the first of equals, in piece order).
    fn nearest(&self, p: DVec3, mut accept: impl FnMut(u32) -> Option<usize>) -> Option<usize> {
        let k = self.grid.nearest(p, |k| {
            accept(self.piece[k as usize]).map(|_| self.pos[k as usize].distance_squared(p))
        })?;
        accept(self.piece[k as usize])
    }
}
