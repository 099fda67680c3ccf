//! The sequential driver: order the points, find a first tetrahedron, insert every point.

use glam::DVec3;
use robust::Coord;

use super::insert::{Inserted, Location};
use super::order::brio_order;
use super::output::{Names, finish};
use super::packed::{Medium, Narrow, Store, Tets, Wide, with_store};
use super::predicates::orient;
use super::storage::{Mesh, Points, points_in_order, reserve_for};
use super::types::{DelaunayError, Tetrahedralization};

/// The layout a construction starts in.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Start {
    /// 24-byte records.
    Narrow,
    /// 27-byte records.
    Medium,
    /// 32-byte records.
    Wide,
}

/// How a sequential construction stores its work: the layout it starts in, how many
/// records that layout may hold before the construction moves to the wide one, and
/// whether the points are read in place rather than copied in insertion order.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct StorePlan {
    pub start: Start,
    pub limit: usize,
    pub in_place: bool,
}

impl StorePlan {
    /// What `n` points get: up to [`Narrow::MAX_POINTS`] (about two million) the narrow
    /// records and the points copied in insertion order (the copy keeps each insertion's
    /// reads close together); beyond, the points read in place (the copy would take the
    /// peak past 200 bytes per point), in the medium records up to their
    /// [`Medium::MAX_POINTS`], then in the wide ones.
    pub(crate) fn for_points(n: usize) -> Self {
        let (start, in_place) = if n <= <Narrow>::MAX_POINTS {
            (Start::Narrow, false)
        } else if n <= Medium::MAX_POINTS {
            (Start::Medium, true)
        } else {
            (Start::Wide, true)
        };
        Self {
            start,
            limit: usize::MAX,
            in_place,
        }
    }
}

/// The tetrahedralization of `points` (checked by the caller) by one insertion after the
/// other, stored as `plan` says.
pub(super) fn sequential(
    points: &[DVec3],
    plan: StorePlan,
) -> Result<Tetrahedralization, DelaunayError> {
    let n = points.len();
    if n < 4 {
        return Err(DelaunayError::TooFewPoints {
            distinct: count_distinct(points),
        });
    }
    let order = brio_order(points);
    let copy = if plan.in_place {
        Vec::new()
    } else {
        points_in_order(points, &order)
    };
    // Merged duplicates as (internal slot, internal vertex it coincides with).
    let mut dups: Vec<(u32, u32)> = Vec::new();
    let tets = {
        let pts = if plan.in_place {
            Points::in_place(points, &order)
        } else {
            Points::copied(&copy)
        };
        let first = first_simplex(pts).ok_or_else(|| {
            let distinct = count_distinct(points);
            if distinct < 4 {
                DelaunayError::TooFewPoints { distinct }
            } else {
                DelaunayError::AllCoplanar { distinct }
            }
        })?;
        let cap = reserve_for(n);
        let empty: Tets = match plan.start {
            Start::Narrow => Narrow::with_capacity(cap).into(),
            Start::Medium => Medium::with_capacity(cap).into(),
            Start::Wide => Wide::with_capacity(cap).into(),
        };
        with_store!(empty, tets => build(pts, tets, plan, first, &mut dups))
            .ok_or(DelaunayError::TooLarge { points: n })?
    };
    drop(copy);
    let names = if plan.in_place {
        drop(order);
        Names::InPlace { points: n }
    } else {
        Names::Order(order)
    };
    Ok(with_store!(tets, s => finish(s, names, &dups)))
}

/// Inserts every point of `pts` into the empty records `tets`, moving to the wide layout
/// when they are full (at `plan.limit` records, or their layout's most). `None` when even
/// the wide layout cannot hold the tetrahedra.
fn build<S: Store>(
    pts: Points<'_>,
    tets: S,
    plan: StorePlan,
    first: [u32; 4],
    dups: &mut Vec<(u32, u32)>,
) -> Option<Tets>
where
    Tets: From<S>,
{
    let mut mesh = Mesh::new(pts, tets, plan.limit);
    start(&mut mesh, first);
    match insert_from(&mut mesh, (1, None), first, dups) {
        None => Some(mesh.tets.into()),
        Some(full) => {
            let mut wide = mesh.into_wide();
            insert_from(&mut wide, full, first, dups)
                .is_none()
                .then(|| wide.tets.into())
        }
    }
}

/// Builds the first tetrahedron from the four points `first`, positively oriented.
pub(super) fn start<S: Store>(mesh: &mut Mesh<'_, S>, first: [u32; 4]) {
    let [a, b, c, d] = first;
    let p = |k: u32| &mesh.pts[k as usize];
    if orient(p(a), p(b), p(c), p(d)) > 0.0 {
        mesh.init(a, b, c, d);
    } else {
        mesh.init(a, b, d, c);
    }
}

/// Inserts the vertices inserted `from`-th to last (except `first`, already in), where
/// the `from`-th may come with the conflicting tetrahedron already found for it; merged
/// duplicates go to `dups`. Returns the position of the vertex that did not fit the
/// storage, with its conflicting tetrahedron, so that the insertion resumes exactly where
/// it stopped.
pub(super) fn insert_from<S: Store>(
    mesh: &mut Mesh<'_, S>,
    (from, found): (usize, Option<u32>),
    first: [u32; 4],
    dups: &mut Vec<(u32, u32)>,
) -> Option<(usize, Option<u32>)> {
    let n = mesh.pts.len();
    let mut found = found;
    for k in from..=n {
        let s = mesh.pts.inserted(k);
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
            return Some((k, Some(t)));
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

/// Four affinely independent points (internal vertices), in insertion order: the first
/// point, the first one distinct from it, the first one off their line and the first one
/// off their plane.
pub(super) fn first_simplex(pts: Points<'_>) -> Option<[u32; 4]> {
    let n = pts.len();
    let at = |k: usize| &pts[pts.inserted(k) as usize];
    let a = 1;
    let b = (2..=n).find(|&k| at(k) != at(a))?;
    let c = (b + 1..=n).find(|&k| !collinear(at(a), at(b), at(k)))?;
    let d = (c + 1..=n).find(|&k| orient(at(a), at(b), at(c), at(k)) != 0.0)?;
    Some([a, b, c, d].map(|k| pts.inserted(k)))
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
