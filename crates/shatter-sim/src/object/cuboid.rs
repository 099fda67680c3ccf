//! Which convex pieces are boxes: a piece that is an axis-aligned box in its object's
//! frame (a grid's brick) can collide as Rapier's cuboid
//! ([`WorldSettings::box_colliders`](crate::WorldSettings::box_colliders)).

use glam::Vec3;
use shatter_geom::DVec3;

/// Relative tolerance of [`axis_aligned_box`]: a point may be this far (times the box's
/// largest edge) from the box's corner, about the rounding of a scaled brick's corners.
/// Only which collision shape a piece can get depends on it.
const BOX_TOLERANCE: f64 = 1e-6;

/// The centre and half extents (scaled by `scale`) of `points` when they are the eight
/// corners of an axis-aligned box with edges of positive length, else `None`.
pub(crate) fn axis_aligned_box(points: &[DVec3], scale: DVec3) -> Option<(Vec3, Vec3)> {
    if points.len() != 8 {
        return None;
    }
    let (mut lo, mut hi) = (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY));
    for p in points {
        lo = lo.min(*p * scale);
        hi = hi.max(*p * scale);
    }
    let edge = hi - lo;
    if !(edge.min_element() > 0.0 && edge.max_element().is_finite()) {
        return None;
    }
    let tol = BOX_TOLERANCE * edge.max_element();
    let mut seen = 0u8;
    for p in points {
        let p = *p * scale;
        let mut corner = 0u8;
        for axis in 0..3 {
            if (p[axis] - hi[axis]).abs() <= tol {
                corner |= 1 << axis;
            } else if (p[axis] - lo[axis]).abs() > tol {
                return None;
            }
        }
        if seen & (1 << corner) != 0 {
            return None;
        }
        seen |= 1 << corner;
    }
    Some((((lo + hi) / 2.0).as_vec3(), (edge / 2.0).as_vec3()))
}

#[cfg(test)]
mod tests {
    use super::*;

    use shatter_geom::util::box_corners as corners;

    #[test]
    fn a_brick_s_corners_are_a_box_at_scale() {
        let points = corners(DVec3::new(0.0, -1.0, 2.0), DVec3::new(1.0, 1.0, 3.0));
        let (centre, half) = axis_aligned_box(&points, DVec3::new(2.0, 1.0, 0.5)).unwrap();
        assert_eq!(centre, Vec3::new(1.0, 0.0, 1.25));
        assert_eq!(half, Vec3::new(1.0, 1.0, 0.25));
    }

    #[test]
    fn other_pieces_are_not_boxes() {
        let mut points = corners(DVec3::ZERO, DVec3::ONE);
        // A corner twice (a wedge of 7 distinct points and one repeated).
        let mut twice = points.clone();
        twice[7] = twice[6];
        assert!(axis_aligned_box(&twice, DVec3::ONE).is_none());
        // A corner moved inside: not a box.
        points[7] = DVec3::splat(0.9);
        assert!(axis_aligned_box(&points, DVec3::ONE).is_none());
        // Flat, or too few points.
        let flat = corners(DVec3::ZERO, DVec3::new(1.0, 0.0, 1.0));
        assert!(axis_aligned_box(&flat, DVec3::ONE).is_none());
        assert!(axis_aligned_box(&points[..4], DVec3::ONE).is_none());
    }
}
