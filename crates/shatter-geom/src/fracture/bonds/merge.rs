//! Merging fragments below the sliver threshold into a bonded neighbour, so that no
//! tiny piece reaches the physics.

use std::collections::BTreeMap;

use glam::DVec3;

use crate::fracture::Bond;
use crate::fracture::kernel::Piece;
use crate::util::UnionFind;

/// Merges every piece whose volume is below `min_volume` into the bonded neighbour it
/// shares the largest area with (repeatedly, smallest first), or, with no bonded
/// neighbour, into the piece nearest to it. A merged fragment is the union of its
/// closed shells (each still closed and outward; the faces they share are kept, back to
/// back). Returns the new pieces, bonds (remapped, each pair once) and the number of
/// small pieces left (only when there is no other piece to merge into).
pub(crate) fn merge_small(
    pieces: Vec<Piece>,
    bonds: Vec<Bond>,
    min_volume: f64,
) -> (Vec<Piece>, Vec<Bond>, usize) {
    let n = pieces.len();
    let mut vol: Vec<f64> = pieces.iter().map(Piece::volume).collect();
    if vol.iter().all(|&v| v >= min_volume) {
        return (pieces, bonds, 0);
    }
    let mut uf = UnionFind::new(n);
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by(|&a, &b| vol[a].total_cmp(&vol[b]).then(a.cmp(&b)));
    loop {
        let mut changed = false;
        for &i in &order {
            let g = uf.find(i);
            if vol[g] >= min_volume {
                continue;
            }
            // Largest total bond area from group g to another group.
            let mut area_to: BTreeMap<usize, f64> = BTreeMap::new();
            for b in &bonds {
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
                let v = vol[g] + vol[h];
                uf.union(g, h);
                vol[uf.find(g)] = v;
                changed = true;
            }
        }
        if !changed {
            break;
        }
    }
    // Small groups with no bonded neighbour: their faces with the rest are below the
    // bonds' area threshold (a sliver cut off where a cell grazes the surface). Each is
    // merged into the group with the vertex nearest its centroid, which it touches or
    // nearly, so that nothing below the threshold reaches the physics.
    for &i in &order {
        let g = uf.find(i);
        if vol[g] >= min_volume {
            continue;
        }
        let (mut sum, mut count) = (DVec3::ZERO, 0usize);
        for (j, p) in pieces.iter().enumerate() {
            if uf.find(j) == g {
                sum += p.pos.iter().copied().sum::<DVec3>();
                count += p.pos.len();
            }
        }
        let centroid = sum / count.max(1) as f64;
        let mut nearest: Option<(f64, usize)> = None;
        for (j, p) in pieces.iter().enumerate() {
            let h = uf.find(j);
            if h == g {
                continue;
            }
            for q in &p.pos {
                let d2 = q.distance_squared(centroid);
                if nearest.is_none_or(|(best, _)| d2 < best) {
                    nearest = Some((d2, h));
                }
            }
        }
        if let Some((_, h)) = nearest {
            let v = vol[g] + vol[h];
            uf.union(g, h);
            vol[uf.find(g)] = v;
        }
    }
    let mut lonely = 0;
    let mut new_id = vec![u32::MAX; n];
    let mut out: Vec<Piece> = Vec::new();
    let mut slot = vec![usize::MAX; n];
    for (i, piece) in pieces.into_iter().enumerate() {
        let r = uf.find(i);
        if slot[r] == usize::MAX {
            slot[r] = out.len();
            out.push(Piece::default());
            if r == i && vol[r] < min_volume {
                lonely += 1;
            }
        }
        let target = &mut out[slot[r]];
        let base = target.pos.len() as u32;
        target.pos.extend(piece.pos);
        target
            .tris
            .extend(piece.tris.iter().map(|t| t.map(|k| k + base)));
        target.tags.extend(piece.tags);
        new_id[i] = slot[r] as u32;
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
    (out, bonds, lonely)
}
