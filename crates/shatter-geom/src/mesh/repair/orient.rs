//! Shells and their orientation.
//!
//! Shells are the edge-connected parts of the surface, where two triangles are
//! connected through an edge that exactly two triangles use (an edge of three or more
//! triangles joins nothing: two boxes sharing an edge are two shells). Each shell is
//! wound consistently by a breadth-first walk (a neighbour wound the same way as its
//! predecessor across their edge is flipped); once closed, a shell with a negative
//! volume is flipped whole; and a shell inside an odd number of others is a cavity,
//! wound inward.

use std::collections::{HashMap, VecDeque};

use glam::DVec3;

use super::soup::{Soup, edge_key};
use crate::mesh::winding::winding_number;

/// One edge-connected shell.
#[derive(Debug, Clone)]
pub(super) struct Shell {
    /// Its triangles.
    pub tris: Vec<u32>,
    /// Edges across which no consistent winding exists (a Möbius-like surface).
    pub conflicts: usize,
}

/// Splits the soup into shells and winds each consistently; returns the shells and the
/// number of triangles flipped.
pub(super) fn shells_wound(soup: &mut Soup) -> (Vec<Shell>, usize) {
    let n = soup.tris.len();
    let mut uses: HashMap<u64, Vec<u32>> = HashMap::with_capacity(3 * n / 2);
    for (t, tri) in soup.tris.iter().enumerate() {
        for k in 0..3 {
            uses.entry(edge_key(tri[k], tri[(k + 1) % 3]))
                .or_default()
                .push(t as u32);
        }
    }
    // Whether triangle t walks edge (a, b) from a to b.
    let walks =
        |tri: [u32; 3], a: u32, b: u32| (0..3).any(|k| tri[k] == a && tri[(k + 1) % 3] == b);
    let mut seen = vec![false; n];
    let mut flip = vec![false; n];
    let mut shells = Vec::new();
    for start in 0..n {
        if seen[start] {
            continue;
        }
        seen[start] = true;
        let mut queue = VecDeque::from([start]);
        let mut tris = Vec::new();
        let mut conflicts = 0;
        while let Some(t) = queue.pop_front() {
            tris.push(t as u32);
            let tri = soup.tris[t];
            for k in 0..3 {
                let (a, b) = (tri[k], tri[(k + 1) % 3]);
                let users = &uses[&edge_key(a, b)];
                if users.len() != 2 {
                    continue;
                }
                let o = if users[0] as usize == t {
                    users[1]
                } else {
                    users[0]
                } as usize;
                if o == t {
                    continue;
                }
                // t (after its flip) walks a→b iff flip[t] is false; o must walk it the
                // other way after its own flip.
                let o_walks_ab = walks(soup.tris[o], a, b);
                let want_flip = o_walks_ab != flip[t];
                if seen[o] {
                    if flip[o] != want_flip {
                        conflicts += 1;
                    }
                } else {
                    seen[o] = true;
                    flip[o] = want_flip;
                    queue.push_back(o);
                }
            }
        }
        // Keep the winding most of the shell already has.
        let flipped = tris.iter().filter(|&&t| flip[t as usize]).count();
        if 2 * flipped > tris.len() {
            for &t in &tris {
                flip[t as usize] = !flip[t as usize];
            }
        }
        shells.push(Shell {
            tris,
            conflicts: conflicts / 2,
        });
    }
    let mut count = 0;
    for (t, &f) in flip.iter().enumerate() {
        if f {
            soup.flip(t);
            count += 1;
        }
    }
    (shells, count)
}

/// Flips every triangle of `shell`.
pub(super) fn flip_shell(soup: &mut Soup, shell: &Shell) {
    for &t in &shell.tris {
        soup.flip(t as usize);
    }
}

/// Signed volume of a closed shell.
pub(super) fn volume(soup: &Soup, shell: &Shell) -> f64 {
    let origin = shell.tris.first().map_or(DVec3::ZERO, |&t| {
        soup.pos[soup.tris[t as usize][0] as usize]
    });
    soup.volume_of(&shell.tris, origin)
}

/// Bounds of a shell.
fn bounds(soup: &Soup, shell: &Shell) -> (DVec3, DVec3) {
    let mut lo = DVec3::splat(f64::INFINITY);
    let mut hi = DVec3::splat(f64::NEG_INFINITY);
    for &t in &shell.tris {
        for &v in &soup.tris[t as usize] {
            lo = lo.min(soup.pos[v as usize]);
            hi = hi.max(soup.pos[v as usize]);
        }
    }
    (lo, hi)
}

/// How many probe vertices decide whether a shell is inside another.
const PROBES: usize = 8;

/// For closed shells wound outward: which are cavities (inside an odd number of the
/// others). A shell counts as inside another when its bounds are, and every one of a few
/// of its triangles' centroids spread over it has a winding number of at least ½ with respect to
/// the other (a shell that only crosses another is not inside it).
pub(super) fn cavities(soup: &Soup, shells: &[Shell]) -> Vec<bool> {
    let boxes: Vec<(DVec3, DVec3)> = shells.iter().map(|s| bounds(soup, s)).collect();
    let tri_lists: Vec<Vec<[u32; 3]>> = shells
        .iter()
        .map(|s| s.tris.iter().map(|&t| soup.tris[t as usize]).collect())
        .collect();
    (0..shells.len())
        .map(|i| {
            let (lo, hi) = boxes[i];
            let probes: Vec<DVec3> = {
                let s = &shells[i];
                let step = (s.tris.len() / PROBES).max(1);
                s.tris
                    .iter()
                    .step_by(step)
                    .take(PROBES)
                    .map(|&t| {
                        // Triangle centroids: a vertex may be shared with the other
                        // shell, where its winding number says nothing.
                        let [a, b, c] = soup.tris[t as usize].map(|v| soup.pos[v as usize]);
                        (a + b + c) / 3.0
                    })
                    .collect()
            };
            let depth = (0..shells.len())
                .filter(|&j| {
                    let (olo, ohi) = boxes[j];
                    j != i
                        && (lo.cmpge(olo) & hi.cmple(ohi)).all()
                        && probes
                            .iter()
                            .all(|&p| winding_number(&soup.pos, &tri_lists[j], p) >= 0.5)
                })
                .count();
            depth % 2 == 1
        })
        .collect()
}
