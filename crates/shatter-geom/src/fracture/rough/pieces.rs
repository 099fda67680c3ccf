//! Collision pieces of a roughened fragment: each convex piece is cut by the plane of
//! every roughened cap of the fragment it reaches, moved inward by the cap's deepest
//! inward displacement, so the pieces stay convex and inside the rough fragment.

use glam::{DVec2, DVec3};

/// A half-space cut: keep `x` with `(x − point)·n ≤ 0`, for pieces whose projection on
/// the plane meets `lo..hi` (the cap's 2D bounds in `(u, v)`).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Cut {
    pub point: DVec3,
    pub n: DVec3,
    pub u: DVec3,
    pub v: DVec3,
    pub lo: DVec2,
    pub hi: DVec2,
}

/// The 2D convex hull (counter-clockwise, no collinear points) of `pts` (monotone
/// chain).
fn hull2(mut pts: Vec<DVec2>) -> Vec<DVec2> {
    pts.sort_unstable_by(|a, b| a.x.total_cmp(&b.x).then(a.y.total_cmp(&b.y)));
    pts.dedup();
    if pts.len() < 3 {
        return pts;
    }
    let cross = |o: DVec2, a: DVec2, b: DVec2| (a - o).perp_dot(b - o);
    let mut h: Vec<DVec2> = Vec::with_capacity(2 * pts.len());
    let n = pts.len();
    for pass in 0..2 {
        let start = h.len();
        for k in 0..n {
            let p = if pass == 0 { pts[k] } else { pts[n - 1 - k] };
            while h.len() >= start + 2 && cross(h[h.len() - 2], h[h.len() - 1], p) <= 0.0 {
                h.pop();
            }
            h.push(p);
        }
        h.pop();
    }
    h
}

/// Whether the hull of `pts` has a volume above `tol³` (four points spanning it).
fn has_volume(pts: &[DVec3], tol: f64) -> bool {
    let Some(&a) = pts.first() else {
        return false;
    };
    let far = |f: &dyn Fn(DVec3) -> f64| {
        pts.iter()
            .copied()
            .max_by(|p, q| f(*p).total_cmp(&f(*q)))
            .unwrap_or(a)
    };
    let b = far(&|p| (p - a).length());
    let ab = b - a;
    if ab.length() <= tol {
        return false;
    }
    let c = far(&|p| ab.cross(p - a).length());
    let n = ab.cross(c - a);
    if n.length() <= tol * ab.length() {
        return false;
    }
    let n = n.normalize();
    let d = far(&|p| (p - a).dot(n).abs());
    (d - a).dot(n).abs() > tol
}

/// The convex piece `pts` cut by `cut` (the kept part's corners: the points on the kept
/// side and the hull of the cross-section). `None` when nothing with a volume above
/// `tol³` is left; the piece itself when the cut does not reach it.
pub(crate) fn clip_piece(pts: &[DVec3], cut: &Cut, tol: f64) -> Option<Vec<DVec3>> {
    let side = |p: DVec3| (p - cut.point).dot(cut.n);
    if pts.iter().all(|&p| side(p) <= 0.0) {
        return Some(pts.to_vec());
    }
    // Only pieces over the cap's footprint are cut.
    let (mut lo, mut hi) = (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY));
    for &p in pts {
        let q = DVec2::new((p - cut.point).dot(cut.u), (p - cut.point).dot(cut.v));
        lo = lo.min(q);
        hi = hi.max(q);
    }
    if lo.cmpgt(cut.hi).any() || cut.lo.cmpgt(hi).any() {
        return Some(pts.to_vec());
    }
    let sides: Vec<f64> = pts.iter().map(|&p| side(p)).collect();
    let (kept, removed): (Vec<usize>, Vec<usize>) = (0..pts.len()).partition(|&k| sides[k] <= 0.0);
    let mut section = Vec::with_capacity(kept.len() * removed.len());
    for &i in &kept {
        for &j in &removed {
            let (p, q, sp, sq) = (pts[i], pts[j], sides[i], sides[j]);
            let x = p + (q - p) * (sp / (sp - sq));
            section.push(DVec2::new(
                (x - cut.point).dot(cut.u),
                (x - cut.point).dot(cut.v),
            ));
        }
    }
    let mut out: Vec<DVec3> = kept.iter().map(|&k| pts[k]).collect();
    out.extend(
        hull2(section)
            .into_iter()
            .map(|q| cut.point + cut.u * q.x + cut.v * q.y),
    );
    has_volume(&out, tol).then_some(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cube_points() -> Vec<DVec3> {
        (0..8)
            .map(|i| DVec3::new((i & 1) as f64, ((i >> 1) & 1) as f64, ((i >> 2) & 1) as f64))
            .collect()
    }

    fn cut_at(z: f64) -> Cut {
        Cut {
            point: DVec3::new(0.0, 0.0, z),
            n: DVec3::Z,
            u: DVec3::X,
            v: DVec3::Y,
            lo: DVec2::splat(-10.0),
            hi: DVec2::splat(10.0),
        }
    }

    #[test]
    fn a_cut_keeps_the_part_below_and_its_section() {
        let out = clip_piece(&cube_points(), &cut_at(0.25), 1e-9).unwrap();
        assert!(out.iter().all(|p| p.z <= 0.25 + 1e-15));
        // Four kept corners and the four corners of the section.
        assert_eq!(out.len(), 8);
        assert_eq!(out.iter().filter(|p| (p.z - 0.25).abs() < 1e-15).count(), 4);
    }

    #[test]
    fn a_cut_below_the_piece_leaves_nothing() {
        assert!(clip_piece(&cube_points(), &cut_at(-0.5), 1e-9).is_none());
    }

    #[test]
    fn a_cut_off_the_footprint_leaves_the_piece() {
        let mut cut = cut_at(0.25);
        cut.lo = DVec2::splat(5.0);
        assert_eq!(
            clip_piece(&cube_points(), &cut, 1e-9).unwrap(),
            cube_points()
        );
    }
}
