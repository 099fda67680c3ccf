//! Bonds between cut fragments: cap faces of two fragments on the same cutting plane,
//! facing each other, matched by the exact area of their 2D overlap.

use std::collections::BTreeMap;

use glam::{DVec2, DVec3};
use rayon::prelude::*;

use super::cap::plane_frame;
use super::piece::{Piece, SURFACE};
use super::types::Bond;

/// The cap triangles on one plane, by fragment.
type FragmentCaps = BTreeMap<usize, Vec<[DVec3; 3]>>;

/// One fragment's caps on a plane: fragment, 2D triangles, 2D bounds.
type CapSide = (usize, Vec<[DVec2; 3]>, (DVec2, DVec2));

/// Bonds between `pieces` (the fragments, in order) through their cap triangles.
///
/// `plane_of(tag)` gives a unit normal and a point of the plane of a cap tag. Two
/// fragments are bonded when caps with the same tag face each other and overlap by
/// more than `min_area`; the bond's area, centroid and normal (a → b) are those of the
/// overlap.
pub(crate) fn cap_bonds(
    pieces: &[Piece],
    plane_of: impl Fn(u64) -> (DVec3, DVec3) + Sync,
    min_area: f64,
) -> Vec<Bond> {
    // tag -> fragment -> triangles
    // Each piece's caps grouped by tag (in parallel), then gathered by tag.
    let per_piece: Vec<Vec<(u64, Vec<[DVec3; 3]>)>> = pieces
        .par_iter()
        .map(|p| {
            let mut caps: Vec<(u64, usize)> = p
                .tags
                .iter()
                .enumerate()
                .filter(|&(_, &tag)| tag != SURFACE)
                .map(|(t, &tag)| (tag, t))
                .collect();
            caps.sort_unstable();
            let mut out: Vec<(u64, Vec<[DVec3; 3]>)> = Vec::new();
            for (tag, t) in caps {
                let tri = p.tris[t].map(|i| p.pos[i as usize]);
                match out.last_mut() {
                    Some((last, tris)) if *last == tag => tris.push(tri),
                    _ => out.push((tag, vec![tri])),
                }
            }
            out
        })
        .collect();
    let mut by_tag: BTreeMap<u64, FragmentCaps> = BTreeMap::new();
    for (f, caps) in per_piece.into_iter().enumerate() {
        for (tag, tris) in caps {
            by_tag.entry(tag).or_default().insert(f, tris);
        }
    }
    // The planes are independent: their overlaps in parallel, summed in tag order (so
    // the result does not depend on the threads).
    let tags: Vec<(&u64, &FragmentCaps)> = by_tag
        .iter()
        .filter(|(_, frags)| frags.len() >= 2)
        .collect();
    let per_tag: Vec<Vec<Contact>> = tags
        .into_par_iter()
        .map(|(tag, frags)| plane_contacts(*tag, frags, &plane_of, min_area))
        .collect();
    let mut acc: BTreeMap<(u32, u32), (f64, DVec3, DVec3)> = BTreeMap::new();
    for (pair, area, centroid, normal) in per_tag.into_iter().flatten() {
        let e = acc.entry(pair).or_insert((0.0, DVec3::ZERO, DVec3::ZERO));
        e.0 += area;
        e.1 += centroid * area;
        e.2 += normal * area;
    }
    acc.into_iter()
        .map(|((a, b), (area, c, n))| Bond {
            a,
            b,
            area,
            centroid: c / area,
            normal: n.normalize_or_zero(),
        })
        .collect()
}

/// One contact through a plane: the fragment pair `(a, b)`, `a < b`, the overlap's
/// area and centroid, and the normal from `a` to `b`.
type Contact = ((u32, u32), f64, DVec3, DVec3);

/// The contacts through the plane of `tag` between the fragments with caps on it.
fn plane_contacts(
    tag: u64,
    frags: &FragmentCaps,
    plane_of: &impl Fn(u64) -> (DVec3, DVec3),
    min_area: f64,
) -> Vec<Contact> {
    let mut out = Vec::new();
    let (n, o) = plane_of(tag);
    let (u, v) = plane_frame(n);
    let to2 = |p: DVec3| DVec2::new((p - o).dot(u), (p - o).dot(v));
    // Split the fragments by the side their caps face.
    let mut front: Vec<CapSide> = Vec::new();
    let mut back = Vec::new();
    for (&f, tris) in frags {
        let normal_sum: DVec3 = tris.iter().map(|[a, b, c]| (*b - *a).cross(*c - *a)).sum();
        let t2: Vec<[DVec2; 3]> = tris.iter().map(|t| t.map(to2)).collect();
        let bb = t2.iter().flatten().fold(
            (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY)),
            |(lo, hi), &p| (lo.min(p), hi.max(p)),
        );
        if normal_sum.dot(n) > 0.0 {
            front.push((f, t2, bb));
        } else {
            back.push((f, t2, bb));
        }
    }
    for (fa, ta, ba) in &front {
        for (fb, tb, bb) in &back {
            if ba.0.cmpgt(bb.1).any() || bb.0.cmpgt(ba.1).any() {
                continue;
            }
            let (area, c2) = if front.len() == 1 && back.len() == 1 {
                // One fragment on each side: both caps are the whole section of the
                // solid by this plane (the fronts' caps together cover it, and so
                // do the backs'), so the overlap is either cap; the smaller area
                // of the two (equal up to rounding) and the front's centroid.
                let (aa, ca) = triangles_area_centroid(ta);
                let (ab, _) = triangles_area_centroid(tb);
                (aa.min(ab), ca)
            } else {
                overlap(ta, tb)
            };
            if area <= min_area {
                continue;
            }
            let centroid = o + u * c2.x + v * c2.y;
            // `fa`'s cap faces +n, so +n points from fa to fb.
            let (a, b, normal) = if fa < fb {
                (*fa, *fb, n)
            } else {
                (*fb, *fa, -n)
            };
            out.push(((a as u32, b as u32), area, centroid, normal));
        }
    }
    out
}

/// Area and centroid of the overlap of two sets of 2D triangles (each set without
/// self-overlap).
fn overlap(a: &[[DVec2; 3]], b: &[[DVec2; 3]]) -> (f64, DVec2) {
    let mut area = 0.0;
    let mut moment = DVec2::ZERO;
    let bbox = |t: &[DVec2; 3]| (t[0].min(t[1]).min(t[2]), t[0].max(t[1]).max(t[2]));
    let bb: Vec<_> = b.iter().map(bbox).collect();
    for ta in a {
        let ba = bbox(ta);
        for (tb, bbb) in b.iter().zip(&bb) {
            if ba.0.cmpgt(bbb.1).any() || bbb.0.cmpgt(ba.1).any() {
                continue;
            }
            let poly = clip_triangle(ta, tb);
            let (ar, c) = polygon_area_centroid(&poly);
            area += ar;
            moment += c * ar;
        }
    }
    if area > 0.0 {
        (area, moment / area)
    } else {
        (0.0, DVec2::ZERO)
    }
}

/// Total area and centroid of 2D triangles that do not overlap (either winding).
fn triangles_area_centroid(tris: &[[DVec2; 3]]) -> (f64, DVec2) {
    let mut area = 0.0;
    let mut moment = DVec2::ZERO;
    for [a, b, c] in tris {
        let ar = ((*b - *a).perp_dot(*c - *a) * 0.5).abs();
        area += ar;
        moment += (*a + *b + *c) / 3.0 * ar;
    }
    if area > 0.0 {
        (area, moment / area)
    } else {
        (0.0, DVec2::ZERO)
    }
}

/// Counter-clockwise copy of a triangle.
fn ccw(t: &[DVec2; 3]) -> [DVec2; 3] {
    if (t[1] - t[0]).perp_dot(t[2] - t[0]) < 0.0 {
        [t[0], t[2], t[1]]
    } else {
        *t
    }
}

/// Intersection of two triangles as a convex polygon (Sutherland–Hodgman).
fn clip_triangle(a: &[DVec2; 3], b: &[DVec2; 3]) -> Vec<DVec2> {
    let mut poly: Vec<DVec2> = ccw(a).to_vec();
    let b = ccw(b);
    for k in 0..3 {
        let (p, q) = (b[k], b[(k + 1) % 3]);
        let side = |x: DVec2| (q - p).perp_dot(x - p);
        let mut next = Vec::with_capacity(poly.len() + 1);
        for i in 0..poly.len() {
            let (x, y) = (poly[i], poly[(i + 1) % poly.len()]);
            let (sx, sy) = (side(x), side(y));
            if sx >= 0.0 {
                next.push(x);
            }
            if (sx >= 0.0) != (sy >= 0.0) {
                let t = sx / (sx - sy);
                next.push(x + (y - x) * t);
            }
        }
        poly = next;
        if poly.len() < 3 {
            return Vec::new();
        }
    }
    poly
}

/// Area (positive for counter-clockwise) and centroid of a polygon.
fn polygon_area_centroid(poly: &[DVec2]) -> (f64, DVec2) {
    if poly.len() < 3 {
        return (0.0, DVec2::ZERO);
    }
    let o = poly[0];
    let mut area2 = 0.0;
    let mut c = DVec2::ZERO;
    for i in 1..poly.len() - 1 {
        let (p, q) = (poly[i] - o, poly[i + 1] - o);
        let a2 = p.perp_dot(q);
        area2 += a2;
        c += (p + q) * a2 / 3.0;
    }
    if area2 == 0.0 {
        return (0.0, o);
    }
    (area2 / 2.0, o + c / area2)
}
