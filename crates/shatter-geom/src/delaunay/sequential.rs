//! The sequential driver: order the points, find a first tetrahedron, insert every point.

use glam::DVec3;
use robust::Coord;

use super::insert::{Inserted, Location};
use super::order::brio_order;
use super::output::finish;
use super::packed::{Narrow, Store, Wide};
use super::predicates::orient;
use super::storage::{Mesh, points_in_order, reserve_for};
use super::types::{DelaunayError, Tetrahedralization};

/// The tetrahedralization of `points` (checked by the caller) by one insertion after the
/// other, with at most `narrow_limit` tetrahedra in the narrow layout before moving to the
/// wide one (below 5: wide from the start).
pub(super) fn sequential(
    points: &[DVec3],
    narrow_limit: usize,
) -> Result<Tetrahedralization, DelaunayError> {
    let n = points.len();
    if n < 4 {
        return Err(DelaunayError::TooFewPoints {
            distinct: count_distinct(points),
        });
    }
    let order = brio_order(points);
    let pts = points_in_order(points, &order);
    let first = first_simplex(&pts).ok_or_else(|| {
        let distinct = count_distinct(points);
        if distinct < 4 {
            DelaunayError::TooFewPoints { distinct }
        } else {
            DelaunayError::AllCoplanar { distinct }
        }
    })?;
    // Merged duplicates as (internal slot, internal vertex it coincides with).
    let mut dups: Vec<(u32, u32)> = Vec::new();
    // Narrow records when the points allow it; wide ones from the start, or from the
    // insertion that no longer fitted the narrow ones.
    let (mut mesh, from) = if n <= <Narrow>::MAX_POINTS && narrow_limit >= 5 {
        let tets = Narrow::with_capacity(reserve_for(n));
        let mut mesh = Mesh::new(pts, tets, narrow_limit);
        start(&mut mesh, first);
        match insert_from(&mut mesh, (1, None), first, &mut dups) {
            None => return Ok(finish(mesh, order, &dups)),
            Some(full) => (mesh.into_wide(), full),
        }
    } else {
        let tets = Wide::with_capacity(reserve_for(n));
        let mut mesh = Mesh::new(pts, tets, usize::MAX);
        start(&mut mesh, first);
        (mesh, (1, None))
    };
    match insert_from(&mut mesh, from, first, &mut dups) {
        None => Ok(finish(mesh, order, &dups)),
        Some(_) => Err(DelaunayError::TooLarge { points: n }),
    }
}

/// Builds the first tetrahedron from the four points `first`, positively oriented.
pub(super) fn start<S: Store>(mesh: &mut Mesh<S>, first: [u32; 4]) {
    let [a, b, c, d] = first;
    let p = |k: u32| &mesh.pts[k as usize];
    if orient(p(a), p(b), p(c), p(d)) > 0.0 {
        mesh.init(a, b, c, d);
    } else {
        mesh.init(a, b, d, c);
    }
}

/// Inserts internal vertices `from..=n` (except `first`, already in), where `from` may come
/// with the conflicting tetrahedron already found for it; merged duplicates go to `dups`.
/// Returns the vertex that did not fit the storage, with its conflicting tetrahedron, so
/// that the insertion resumes exactly where it stopped.
pub(super) fn insert_from<S: Store>(
    mesh: &mut Mesh<S>,
    (from, found): (u32, Option<u32>),
    first: [u32; 4],
    dups: &mut Vec<(u32, u32)>,
) -> Option<(u32, Option<u32>)> {
    let n = mesh.pts.len() - 1;
    let mut found = found;
    for s in from..=n as u32 {
        if first.contains(&s) {
            continue;
        }
        let q = mesh.pts[s as usize];
        let t = match found.take() {
            Some(t) => t,
            None => match mesh.locate(&q) {
                Location::Duplicate(w) => {
                    dups.push((s, w));
                    continue;
                }
                Location::Conflict(t) => t,
            },
        };
        if mesh.insert(s, t) == Inserted::Full {
            return Some((s, Some(t)));
        }
    }
    None
}

/// Number of distinct points (exact comparison; `-0.0 == 0.0`).
pub(super) fn count_distinct(points: &[DVec3]) -> usize {
    let mut v: Vec<[f64; 3]> = points
        .iter()
        .map(|p| (*p + DVec3::ZERO).to_array())
        .collect();
    v.sort_unstable_by(|a, b| {
        a[0].total_cmp(&b[0])
            .then(a[1].total_cmp(&b[1]))
            .then(a[2].total_cmp(&b[2]))
    });
    v.dedup();
    v.len()
}

/// Four affinely independent points, in insertion order: the first point, the first one
/// distinct from it, the first one off their line and the first one off their plane.
pub(super) fn first_simplex(pts: &[[f64; 3]]) -> Option<[u32; 4]> {
    let n = pts.len();
    let a = 1;
    let b = (2..n).find(|&s| pts[s] != pts[a])?;
    let c = (b + 1..n).find(|&s| !collinear(&pts[a], &pts[b], &pts[s]))?;
    let d = (c + 1..n).find(|&s| orient(&pts[a], &pts[b], &pts[c], &pts[s]) != 0.0)?;
    Some([a as u32, b as u32, c as u32, d as u32])
}

/// Exact collinearity: all three coordinate-plane projections are degenerate.
fn collinear(a: &[f64; 3], b: &[f64; 3], c: &[f64; 3]) -> bool {
    let o = |i: usize, j: usize| {
        robust::orient2d(
            Coord { x: a[i], y: a[j] },
            Coord { x: b[i], y: b[j] },
            Coord { x: c[i], y: c[j] },
        )
    };
    o(0, 1) == 0.0 && o(1, 2) == 0.0 && o(0, 2) == 0.0
}
