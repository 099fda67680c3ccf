//! Axis-aligned bounds of point sets.

use glam::DVec3;

/// Axis-aligned bounds `(min, max)` of a non-empty point set (infinite for an empty one).
pub(crate) fn bounds(pos: &[DVec3]) -> (DVec3, DVec3) {
    pos.iter().fold(
        (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
        |(lo, hi), &p| (lo.min(p), hi.max(p)),
    )
}
