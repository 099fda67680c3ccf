//! The entry: validate the input, then triangulate it in two halves on two threads when it
//! is large (`split`), else by one sequential insertion (`sequential`).

use glam::DVec3;

use super::predicates::{MAX_MAGNITUDE, MIN_MAGNITUDE};
use super::sequential::{count_distinct, sequential};
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
    tetrahedralize_within(points, usize::MAX)
}

/// [`tetrahedralize`] with at most `narrow_limit` tetrahedra in the narrow layout before
/// moving to the wide one (below 5: wide from the start). Tests lower it to exercise both
/// layouts and the move on small inputs.
pub(crate) fn tetrahedralize_within(
    points: &[DVec3],
    narrow_limit: usize,
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
    // Large inputs on two cores; `narrow_limit` is lowered by tests of the sequential
    // path alone.
    if n >= SPLIT_MIN_POINTS
        && narrow_limit == usize::MAX
        && let Some(t) = tetrahedralize_split(points)
    {
        return Ok(t);
    }
    sequential(points, narrow_limit)
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
    use super::*;
    use crate::sampling::{Distribution, sample};

    fn same(a: &Tetrahedralization, b: &Tetrahedralization) -> bool {
        a.len() == b.len()
            && (0..a.len())
                .all(|t| a.tetrahedron(t) == b.tetrahedron(t) && a.neighbors(t) == b.neighbors(t))
            && a.representative == b.representative
    }

    /// The narrow layout, the wide one from the start, and a move from narrow to wide part
    /// way (the narrow limit set low) build the same valid tetrahedralization.
    #[test]
    fn both_layouts_and_the_move_between_them_agree() {
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
        sets.push(dups);
        for p in &sets {
            let narrow = tetrahedralize_within(p, usize::MAX).expect("narrow");
            narrow.validate(p).expect("narrow is Delaunay");
            assert!(matches!(narrow.tets, super::super::packed::Tets::Narrow(_)));
            for limit in [0, 100, narrow.len() / 2] {
                let other = tetrahedralize_within(p, limit).expect("wide");
                assert!(matches!(other.tets, super::super::packed::Tets::Wide(_)));
                other.validate(p).expect("wide is Delaunay");
                assert!(same(&narrow, &other), "limit {limit}");
            }
        }
    }
}
