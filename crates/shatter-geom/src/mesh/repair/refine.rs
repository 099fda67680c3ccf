//! Refinement and fairing of a hole patch (Liepa 2003, sections 3.2–3.3, simplified):
//! a patch triangle whose centroid is farther from its corners than the local edge
//! length around the hole (times √2) is split at its centroid; edges inside the patch are
//! then flipped to the Delaunay choice; this repeats until nothing splits. The new
//! vertices are finally moved to the mean of their neighbours (umbrella smoothing with
//! the loop fixed), which makes the patch a membrane over the hole.

use std::collections::HashMap;

use glam::DVec3;

use super::soup::Corner;

/// Rounds of splitting.
const ROUNDS: usize = 8;
/// Rounds of umbrella smoothing.
const FAIRING: usize = 40;

/// A refined patch: the loop's positions first (unchanged), then the new ones.
pub(super) struct Refined {
    pub pos: Vec<DVec3>,
    pub attrs: Vec<Corner>,
    pub tris: Vec<[usize; 3]>,
}

/// Refines and fairs the triangulation `tris` of the loop `p` (see the module docs).
pub(super) fn refine_and_fair(
    mut pos: Vec<DVec3>,
    mut attrs: Vec<Corner>,
    mut tris: Vec<[usize; 3]>,
) -> Refined {
    let n = pos.len();
    let mut sigma: Vec<f64> = (0..n)
        .map(|i| 0.5 * (pos[i].distance(pos[(i + 1) % n]) + pos[i].distance(pos[(i + n - 1) % n])))
        .collect();
    let cap = 8 * n + 64;
    let alpha = std::f64::consts::SQRT_2;
    for _ in 0..ROUNDS {
        let mut split = false;
        let mut out = Vec::with_capacity(tris.len());
        for &t in &tris {
            let c = (pos[t[0]] + pos[t[1]] + pos[t[2]]) / 3.0;
            let sc = (sigma[t[0]] + sigma[t[1]] + sigma[t[2]]) / 3.0;
            let large = t.iter().all(|&m| {
                let d = alpha * c.distance(pos[m]);
                d > sc && d > sigma[m]
            });
            if large && pos.len() < n + cap {
                let v = pos.len();
                pos.push(c);
                sigma.push(sc);
                let third = 1.0 / 3.0;
                attrs.push(Corner::mix(&[
                    (third, attrs[t[0]]),
                    (third, attrs[t[1]]),
                    (third, attrs[t[2]]),
                ]));
                out.push([t[0], t[1], v]);
                out.push([t[1], t[2], v]);
                out.push([t[2], t[0], v]);
                split = true;
            } else {
                out.push(t);
            }
        }
        tris = out;
        if !split {
            break;
        }
        flip_to_delaunay(&pos, &mut tris);
    }
    fair(&mut pos, n, &tris);
    Refined { pos, attrs, tris }
}

/// Angle at `c` in triangle `a b c`.
fn angle_at(a: DVec3, b: DVec3, c: DVec3) -> f64 {
    let (u, v) = (a - c, b - c);
    u.cross(v).length().atan2(u.dot(v))
}

/// Flips edges shared by two patch triangles whose opposite angles add up to more
/// than π, when the flip keeps both triangles facing the way the pair did.
fn flip_to_delaunay(pos: &[DVec3], tris: &mut [[usize; 3]]) {
    let mut directed: HashMap<(usize, usize), usize> = HashMap::with_capacity(3 * tris.len());
    for (i, t) in tris.iter().enumerate() {
        for k in 0..3 {
            directed.insert((t[k], t[(k + 1) % 3]), i);
        }
    }
    for _pass in 0..64 {
        let mut flipped = false;
        for i in 0..tris.len() {
            for k in 0..3 {
                let t1 = tris[i];
                let (a, b, c) = (t1[k], t1[(k + 1) % 3], t1[(k + 2) % 3]);
                let Some(&j) = directed.get(&(b, a)) else {
                    continue;
                };
                if j == i {
                    continue;
                }
                let t2 = tris[j];
                let Some(d) = t2.iter().copied().find(|&v| v != a && v != b) else {
                    continue;
                };
                if c == d || directed.contains_key(&(c, d)) || directed.contains_key(&(d, c)) {
                    continue;
                }
                let (pa, pb, pc, pd) = (pos[a], pos[b], pos[c], pos[d]);
                if angle_at(pa, pb, pc) + angle_at(pb, pa, pd) <= std::f64::consts::PI + 1e-12 {
                    continue;
                }
                let before = (pb - pa).cross(pc - pa) + (pa - pb).cross(pd - pb);
                let n1 = (pa - pc).cross(pd - pc);
                let n2 = (pb - pd).cross(pc - pd);
                if n1.dot(before) <= 0.0 || n2.dot(before) <= 0.0 {
                    continue;
                }
                for t in [t1, t2] {
                    for m in 0..3 {
                        directed.remove(&(t[m], t[(m + 1) % 3]));
                    }
                }
                tris[i] = [c, a, d];
                tris[j] = [d, b, c];
                for (idx, t) in [(i, tris[i]), (j, tris[j])] {
                    for m in 0..3 {
                        directed.insert((t[m], t[(m + 1) % 3]), idx);
                    }
                }
                flipped = true;
                break;
            }
        }
        if !flipped {
            return;
        }
    }
}

/// Umbrella smoothing of the vertices from `fixed` on (the loop's stay).
fn fair(pos: &mut [DVec3], fixed: usize, tris: &[[usize; 3]]) {
    if pos.len() <= fixed {
        return;
    }
    let mut neighbours: Vec<Vec<usize>> = vec![Vec::new(); pos.len()];
    for t in tris {
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            if !neighbours[a].contains(&b) {
                neighbours[a].push(b);
            }
            if !neighbours[b].contains(&a) {
                neighbours[b].push(a);
            }
        }
    }
    for _ in 0..FAIRING {
        let old = pos.to_vec();
        for (v, list) in neighbours.iter().enumerate().skip(fixed) {
            if !list.is_empty() {
                pos[v] = list.iter().map(|&w| old[w]).sum::<DVec3>() / list.len() as f64;
            }
        }
    }
}
