//! Bonds between cut fragments: cap faces of two fragments on the same cutting plane,
//! facing each other, matched by the exact area of their 2D overlap.

use std::collections::BTreeMap;

use glam::{DVec2, DVec3};
use rayon::prelude::*;

use crate::fracture::Bond;
use crate::fracture::kernel::cap::plane_frame;
use crate::fracture::kernel::{Piece, is_surface};

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
    // Each piece's caps grouped by tag, with their area, centroid and normal (in
    // parallel); then gathered by tag as small records.
    let per_piece: Vec<Vec<CapGroup>> = pieces.par_iter().map(cap_groups).collect();
    let mut by_tag: BTreeMap<u64, Vec<(usize, &CapGroup)>> = BTreeMap::new();
    for (f, groups) in per_piece.iter().enumerate() {
        for g in groups {
            by_tag.entry(g.tag).or_default().push((f, g));
        }
    }
    // The planes are independent: their contacts in parallel, summed in tag order (so
    // the result does not depend on the threads).
    let tags: Vec<(&u64, &Vec<(usize, &CapGroup)>)> =
        by_tag.iter().filter(|(_, caps)| caps.len() >= 2).collect();
    let per_tag: Vec<Vec<Contact>> = tags
        .into_par_iter()
        .map(|(tag, caps)| plane_contacts(*tag, caps, pieces, &plane_of, min_area))
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

/// One piece's cap triangles with one tag: their indices, total area, area-weighted
/// centroid and summed (area-weighted) normal.
struct CapGroup {
    tag: u64,
    tris: Vec<u32>,
    area: f64,
    centroid: DVec3,
    normal_sum: DVec3,
}

/// The caps of `p` grouped by tag, in tag order.
fn cap_groups(p: &Piece) -> Vec<CapGroup> {
    let mut caps: Vec<(u64, u32)> = p
        .tags
        .iter()
        .enumerate()
        .filter(|&(_, &tag)| !is_surface(tag))
        .map(|(t, &tag)| (tag, t as u32))
        .collect();
    caps.sort_unstable();
    let mut out: Vec<CapGroup> = Vec::new();
    for (tag, t) in caps {
        if out.last().is_none_or(|g| g.tag != tag) {
            out.push(CapGroup {
                tag,
                tris: Vec::new(),
                area: 0.0,
                centroid: DVec3::ZERO,
                normal_sum: DVec3::ZERO,
            });
        }
        let g = out.last_mut().expect("a group was just pushed");
        let [a, b, c] = p.tris[t as usize].map(|i| p.pos[i as usize]);
        let cross = (b - a).cross(c - a);
        let area = cross.length() / 2.0;
        g.tris.push(t);
        g.area += area;
        g.centroid += (a + b + c) / 3.0 * area;
        g.normal_sum += cross;
    }
    for g in &mut out {
        if g.area > 0.0 {
            g.centroid /= g.area;
        }
    }
    out
}

/// A fragment's cap group on a plane, as gathered by tag.
type CapRef<'a> = &'a (usize, &'a CapGroup);

/// One contact through a plane: the fragment pair `(a, b)`, `a < b`, the overlap's
/// area and centroid, and the normal from `a` to `b`.
type Contact = ((u32, u32), f64, DVec3, DVec3);

/// The contacts through the plane of `tag` between the fragments with caps on it.
fn plane_contacts(
    tag: u64,
    caps: &[(usize, &CapGroup)],
    pieces: &[Piece],
    plane_of: &impl Fn(u64) -> (DVec3, DVec3),
    min_area: f64,
) -> Vec<Contact> {
    let (n, o) = plane_of(tag);
    // Split the fragments by the side their caps face.
    let (front, back): (Vec<CapRef>, Vec<CapRef>) =
        caps.iter().partition(|(_, g)| g.normal_sum.dot(n) > 0.0);
    let contact = |fa: usize, fb: usize, area: f64, centroid: DVec3| {
        // `fa`'s cap faces +n, so +n points from fa to fb.
        let (a, b, normal) = if fa < fb { (fa, fb, n) } else { (fb, fa, -n) };
        ((a as u32, b as u32), area, centroid, normal)
    };
    if let ([(fa, ga)], [(fb, gb)]) = (front.as_slice(), back.as_slice()) {
        // One fragment on each side: both caps are the whole section of the solid by
        // this plane (the fronts' caps together cover it, and so do the backs'), so the
        // overlap is either cap: the smaller area of the two (equal up to rounding) and
        // the front's centroid.
        let area = ga.area.min(gb.area);
        return if area > min_area {
            vec![contact(*fa, *fb, area, ga.centroid)]
        } else {
            Vec::new()
        };
    }
    let (u, v) = plane_frame(n);
    let to2 = |p: DVec3| DVec2::new((p - o).dot(u), (p - o).dot(v));
    let flat = |&&(f, g): &CapRef| -> CapSide {
        let p = &pieces[f];
        let t2: Vec<[DVec2; 3]> = g
            .tris
            .iter()
            .map(|&t| p.tris[t as usize].map(|i| to2(p.pos[i as usize])))
            .collect();
        let bb = t2.iter().flatten().fold(
            (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY)),
            |(lo, hi), &q| (lo.min(q), hi.max(q)),
        );
        (f, t2, bb)
    };
    let front: Vec<CapSide> = front.iter().map(flat).collect();
    let back: Vec<CapSide> = back.iter().map(flat).collect();
    let mut out = Vec::new();
    for (fa, ta, ba) in &front {
        for (fb, tb, bb) in &back {
            if ba.0.cmpgt(bb.1).any() || bb.0.cmpgt(ba.1).any() {
                continue;
            }
            let (area, c2) = overlap(ta, tb);
            if area <= min_area {
                continue;
            }
            out.push(contact(*fa, *fb, area, o + u * c2.x + v * c2.y));
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
