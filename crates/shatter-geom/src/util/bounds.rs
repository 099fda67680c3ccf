//! Axis-aligned bounds of point sets.

use glam::DVec3;

/// Axis-aligned bounds `(min, max)` of a non-empty point set (infinite for an empty one).
pub(crate) fn bounds(pos: &[DVec3]) -> (DVec3, DVec3) {
    pos.iter().fold(
        (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
        |(lo, hi), &p| (lo.min(p), hi.max(p)),
    )
}

/// The eight corners of the box `lo..hi`: corner `i` takes `hi` along x where bit 0 of
/// `i` is set, along y where bit 1 is, along z where bit 2 is.
///
/// ```
/// use shatter_geom::DVec3;
/// use shatter_geom::util::box_corners;
/// let c = box_corners(DVec3::ZERO, DVec3::new(1.0, 2.0, 3.0));
/// assert_eq!(c.len(), 8);
/// assert_eq!(c[0], DVec3::ZERO);
/// assert_eq!(c[5], DVec3::new(1.0, 0.0, 3.0));
/// ```
pub fn box_corners(lo: DVec3, hi: DVec3) -> Vec<DVec3> {
    (0..8)
        .map(|i| {
            DVec3::new(
                if i & 1 == 0 { lo.x } else { hi.x },
                if i & 2 == 0 { lo.y } else { hi.y },
                if i & 4 == 0 { lo.z } else { hi.z },
            )
        })
        .collect()
}
