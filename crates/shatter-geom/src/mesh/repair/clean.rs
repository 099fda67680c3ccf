//! Degenerate and duplicate triangles.
//!
//! - A triangle with a repeated vertex is dropped (its two real edges cancel).
//! - A triangle with three distinct collinear corners (decided exactly) is a T-junction
//!   in disguise: its middle corner lies on its long edge. It is dropped and the
//!   neighbour across the long edge is split at the middle corner, so the surface
//!   stays closed where it was closed.
//! - Triangles on the same three vertices: copies wound the same way are one triangle;
//!   a pair wound opposite ways is a zero-thickness wall and both go.

use std::collections::HashMap;

use super::soup::{Corner, Soup};
use crate::mesh::check::is_degenerate;

/// What [`degenerate`] did.
#[derive(Debug, Default, Clone, Copy, PartialEq, Eq)]
pub(super) struct Degenerate {
    /// Triangles dropped.
    pub dropped: usize,
    /// Neighbours split at a collinear triangle's middle corner.
    pub split: usize,
}

/// Drops degenerate triangles (see the module docs).
pub(super) fn degenerate(soup: &mut Soup) -> Degenerate {
    let mut out = Degenerate::default();
    let n = soup.tris.len();
    let mut keep = vec![true; n];
    let mut collinear = Vec::new();
    for (t, tri) in soup.tris.iter().enumerate() {
        let [a, b, c] = *tri;
        if a == b || b == c || c == a {
            keep[t] = false;
            out.dropped += 1;
        } else if is_degenerate(
            soup.pos[a as usize],
            soup.pos[b as usize],
            soup.pos[c as usize],
        ) {
            collinear.push(t);
        }
    }
    if !collinear.is_empty() {
        let mut directed: HashMap<(u32, u32), usize> = HashMap::with_capacity(3 * n);
        for (t, tri) in soup.tris.iter().enumerate() {
            if keep[t] {
                for k in 0..3 {
                    directed.insert((tri[k], tri[(k + 1) % 3]), t);
                }
            }
        }
        let mut is_collinear = vec![false; n];
        for &t in &collinear {
            is_collinear[t] = true;
        }
        for &t in &collinear {
            keep[t] = false;
            out.dropped += 1;
            let tri = soup.tris[t];
            for k in 0..3 {
                if directed.get(&(tri[k], tri[(k + 1) % 3])) == Some(&t) {
                    directed.remove(&(tri[k], tri[(k + 1) % 3]));
                }
            }
            // The long edge p→q is the one opposite the middle corner m.
            let m_at = middle_corner(soup, tri);
            let m = tri[m_at];
            let (p, q) = (tri[(m_at + 1) % 3], tri[(m_at + 2) % 3]);
            let Some(&nb) = directed.get(&(q, p)) else {
                continue;
            };
            if is_collinear[nb] || !keep[nb] {
                continue;
            }
            split_at(soup, nb, q, p, m, &mut directed);
            keep.push(true);
            is_collinear.push(false);
            out.split += 1;
        }
    }
    soup.retain(&keep);
    out
}

/// Which corner of a collinear triangle lies between the other two.
fn middle_corner(soup: &Soup, tri: [u32; 3]) -> usize {
    let p = tri.map(|i| soup.pos[i as usize]);
    (0..3)
        .max_by(|&i, &j| {
            let len = |k: usize| p[(k + 1) % 3].distance_squared(p[(k + 2) % 3]);
            len(i).total_cmp(&len(j))
        })
        .unwrap_or(0)
}

/// Splits triangle `nb`, which walks `q → p`, at vertex `m` on that edge: `nb` becomes
/// `q m r` and a new triangle `m p r` is appended (attributes interpolated at `m`).
fn split_at(
    soup: &mut Soup,
    nb: usize,
    q: u32,
    p: u32,
    m: u32,
    directed: &mut HashMap<(u32, u32), usize>,
) {
    let tri = soup.tris[nb];
    let kq = (0..3).find(|&k| tri[k] == q).unwrap_or(0);
    let (kp, kr) = ((kq + 1) % 3, (kq + 2) % 3);
    let r = tri[kr];
    let (cq, cp, cr) = (
        soup.corner(nb, kq),
        soup.corner(nb, kp),
        soup.corner(nb, kr),
    );
    let (pq, pp, pm) = (
        soup.pos[q as usize],
        soup.pos[p as usize],
        soup.pos[m as usize],
    );
    let len = pq.distance(pp);
    let s = if len > 0.0 {
        (pm.distance(pq) / len).clamp(0.0, 1.0)
    } else {
        0.5
    };
    let cm = Corner::mix(&[(1.0 - s, cq), (s, cp)]);
    let material = soup.material[nb];
    // Rewrite nb in place as q m r (its corner order rotated to start at q).
    soup.tris[nb] = [q, m, r];
    set_corners(soup, nb, [cq, cm, cr]);
    soup.push([m, p, r], [cm, cp, cr], material);
    let new = soup.tris.len() - 1;
    directed.remove(&(q, p));
    directed.insert((q, m), nb);
    directed.insert((m, r), nb);
    directed.insert((r, q), nb);
    directed.insert((m, p), new);
    directed.insert((p, r), new);
    directed.insert((r, m), new);
}

/// Overwrites triangle `t`'s corner attributes.
fn set_corners(soup: &mut Soup, t: usize, c: [Corner; 3]) {
    if let Some(v) = &mut soup.corners.uv {
        v[t] = c.map(|c| c.uv);
    }
    if let Some(v) = &mut soup.corners.normal {
        v[t] = c.map(|c| c.normal);
    }
    if let Some(v) = &mut soup.corners.color {
        v[t] = c.map(|c| c.color);
    }
}

/// What [`duplicates`] did.
#[derive(Debug, Default, Clone, Copy, PartialEq, Eq)]
pub(super) struct Duplicates {
    /// Extra copies of a triangle wound the same way, dropped.
    pub copies: usize,
    /// Triangles dropped in pairs wound opposite ways (zero-thickness walls).
    pub opposite: usize,
}

/// Drops duplicate triangles (see the module docs).
pub(super) fn duplicates(soup: &mut Soup) -> Duplicates {
    let mut out = Duplicates::default();
    let mut groups: HashMap<[u32; 3], Vec<(usize, bool)>> = HashMap::new();
    for (t, &[a, b, c]) in soup.tris.iter().enumerate() {
        // Rotate the smallest index first; `forward` tells the cyclic order.
        let r = if a < b && a < c {
            [a, b, c]
        } else if b < c {
            [b, c, a]
        } else {
            [c, a, b]
        };
        let forward = r[1] < r[2];
        let key = if forward { r } else { [r[0], r[2], r[1]] };
        groups.entry(key).or_default().push((t, forward));
    }
    let mut keep = vec![true; soup.tris.len()];
    for group in groups.values().filter(|g| g.len() > 1) {
        let f: Vec<usize> = group.iter().filter(|g| g.1).map(|g| g.0).collect();
        let b: Vec<usize> = group.iter().filter(|g| !g.1).map(|g| g.0).collect();
        let pairs = f.len().min(b.len());
        out.opposite += 2 * pairs;
        // Keep one triangle of the winding that has more copies, or none.
        let (more, less) = if f.len() >= b.len() { (f, b) } else { (b, f) };
        for &t in &less {
            keep[t] = false;
        }
        for (i, &t) in more.iter().enumerate() {
            if i >= more.len() - pairs || i > 0 {
                keep[t] = false;
            }
        }
        if more.len() > pairs {
            out.copies += more.len() - pairs - 1;
        }
    }
    soup.retain(&keep);
    out
}
