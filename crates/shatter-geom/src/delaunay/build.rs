//! The entry: validate the input, then triangulate it in two halves on two threads when it
//! is large (`split`), else by one sequential insertion (`sequential`).

use glam::DVec3;

use super::predicates::{MAX_MAGNITUDE, MIN_MAGNITUDE};
use super::sequential::{StorePlan, count_distinct, sequential};
use super::split::{SPLIT_MIN_POINTS, tetrahedralize_split};
use super::types::{DelaunayError, Tetrahedralization};

/// Delaunay tetrahedralization of `points`.
///
/// Exact for every input whose coordinates are zero or of magnitude in `[1e-40, 1e40]`:
/// coplanar and cospherical configurations (grids, points on a sphere) are resolved by
/// symbolic perturbation, so no tetrahedron is flat. Duplicates are merged into their
/// first occurrence and listed in [`Tetrahedralization::duplicates`].
///
/// ```
/// use shatter_geom::{DVec3, delaunay::tetrahedralize};
/// let mut pts = Vec::new();
/// for i in 0..8 {
///     pts.push(DVec3::new((i & 1) as f64, ((i >> 1) & 1) as f64, (i >> 2) as f64));
/// }
/// pts.push(DVec3::ZERO); // a duplicate of point 0
/// let t = tetrahedralize(&pts).expect("a cube");
/// assert_eq!(t.unique_points, 8);
/// assert_eq!(t.representative[8], 0);
/// assert!((t.volume(&pts) - 1.0).abs() < 1e-12);
/// ```
pub fn tetrahedralize(points: &[DVec3]) -> Result<Tetrahedralization, DelaunayError> {
    tetrahedralize_with(points, None)
}

/// [`tetrahedralize`] stored as `plan` says, sequentially; `None`: as the points' number
/// says, in two halves when there are enough. Tests choose a plan to exercise every
/// layout, the move to the wide one and the points read in place on small inputs.
pub(crate) fn tetrahedralize_with(
    points: &[DVec3],
    plan: Option<StorePlan>,
) -> Result<Tetrahedralization, DelaunayError> {
    check_input(points)?;
    let n = points.len();
    if n >= (1 << 30) - 2 {
        return Err(DelaunayError::TooLarge { points: n });
    }
    if n < 4 {
        return Err(DelaunayError::TooFewPoints {
            distinct: count_distinct(points),
        });
    }
    // Large inputs on two cores, unless a test asks for a plan.
    if n >= SPLIT_MIN_POINTS
        && plan.is_none()
        && let Some(t) = tetrahedralize_split(points)
    {
        return Ok(t);
    }
    sequential(points, plan.unwrap_or_else(|| StorePlan::for_points(n)))
}

/// Rejects non-finite coordinates and magnitudes where the predicates would not be exact.
fn check_input(points: &[DVec3]) -> Result<(), DelaunayError> {
    for (index, p) in points.iter().enumerate() {
        for value in p.to_array() {
            if !value.is_finite() {
                return Err(DelaunayError::NonFinite { index });
            }
            let m = value.abs();
            if m > MAX_MAGNITUDE || (m != 0.0 && m < MIN_MAGNITUDE) {
                return Err(DelaunayError::OutOfRange { index, value });
            }
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::super::packed::{Medium, Narrow, Tets};
    use super::super::sequential::Start;
    use super::*;
    use crate::sampling::{Distribution, sample};

    fn same(a: &Tetrahedralization, b: &Tetrahedralization) -> bool {
        a.len() == b.len()
            && (0..a.len())
                .all(|t| a.tetrahedron(t) == b.tetrahedron(t) && a.neighbors(t) == b.neighbors(t))
            && a.representative == b.representative
    }

    /// Every layout from the start, the narrow and medium ones moving to the wide one part
    /// way (their limit set low), and the points copied or read in place, build the same
    /// valid tetrahedralization.
    #[test]
    fn every_layout_the_move_to_wide_and_both_point_readings_agree() {
        let mut sets: Vec<Vec<DVec3>> = [
            Distribution::Uniform,
            Distribution::Sphere,
            Distribution::Grid,
            Distribution::Gaussian,
        ]
        .into_iter()
        .map(|d| sample(d, 3000, 7))
        .collect();
        let mut dups = sample(Distribution::Ball, 500, 2);
        dups.extend_from_within(..250);
        // Duplicates of later points too, so that a duplicate's first occurrence is
        // sometimes inserted after it.
        dups.extend_from_within(600..700);
        dups.rotate_right(40);
        sets.push(dups);
        for p in &sets {
            let auto = tetrahedralize_with(p, None).expect("auto");
            auto.validate(p).expect("auto is Delaunay");
            assert!(matches!(auto.tets, Tets::Narrow(_)));
            let half = auto.len() / 2;
            for (start, limit, in_place, layout) in [
                (Start::Narrow, usize::MAX, true, "narrow"),
                (Start::Medium, usize::MAX, false, "medium"),
                (Start::Medium, usize::MAX, true, "medium"),
                (Start::Wide, usize::MAX, false, "wide"),
                (Start::Wide, usize::MAX, true, "wide"),
                (Start::Narrow, 100, false, "wide"),
                (Start::Narrow, half, true, "wide"),
                (Start::Medium, 100, true, "wide"),
                (Start::Medium, half, false, "wide"),
            ] {
                let plan = StorePlan {
                    start,
                    limit,
                    in_place,
                };
                let other = tetrahedralize_with(p, Some(plan)).expect("planned");
                let got = match other.tets {
                    Tets::Narrow(_) => "narrow",
                    Tets::Medium(_) => "medium",
                    Tets::Wide(_) => "wide",
                };
                assert_eq!(got, layout, "{plan:?}");
                other.validate(p).expect("Delaunay");
                assert!(same(&auto, &other), "{plan:?}");
            }
        }
    }

    /// The plan the number of points gets: narrow records and a copy up to about two
    /// million points, then the points in place, medium records up to about 16.7
    /// million, wide ones beyond.
    #[test]
    fn large_inputs_read_their_points_in_place_in_larger_records() {
        let plan = |n| {
            let p = StorePlan::for_points(n);
            (p.start, p.in_place)
        };
        let narrow = <Narrow>::MAX_POINTS;
        assert_eq!(plan(1000), (Start::Narrow, false));
        assert_eq!(plan(narrow), (Start::Narrow, false));
        assert_eq!(plan(narrow + 1), (Start::Medium, true));
        assert_eq!(plan(10_000_000), (Start::Medium, true));
        assert_eq!(plan(Medium::MAX_POINTS), (Start::Medium, true));
        assert_eq!(plan(Medium::MAX_POINTS + 1), (Start::Wide, true));
        assert!(narrow > 2_000_000 && Medium::MAX_POINTS > 16_000_000);
    }
}
