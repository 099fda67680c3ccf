//! The new tessellation of one shared cap, in two parts:
//!
//! - the **core**: a grid of points (about a quarter of the noise's period apart) kept
//!   at least 0.4 spacings inside the cap, triangulated once (spade's constrained
//!   Delaunay triangulation of the cap with the grid as Steiner points, its triangles
//!   with three grid corners). Its inner vertices are displaced along the cap's normal;
//!   its rim (the vertices on its boundary) stays in the plane. Both sides of the bond
//!   get the same core, bit for bit, one side wound the other way.
//! - a **collar** per side: the flat ring between the side's own cap boundary and the
//!   core's rim, triangulated for each side from its own boundary vertices (the two
//!   sides of a cap are cut separately and may differ by rounding or by a vertex on an
//!   edge). The collar is flat, so the two collars cover the same ring of the plane, and
//!   the cap's boundary keeps its vertices and edges: no T-junction with the rest of the
//!   fragment.
//!
//! ```text
//!   boundary ─────────────────────────     (the side's own vertices, untouched)
//!             \  collar (flat)  /  \
//!   rim  ──────●───────●───────●────        (core vertices in the plane)
//!              │ core: displaced │
//! ```

use glam::{DVec2, DVec3};

use super::Roughness;
use super::noise::fbm;
use super::regions::Region;
use crate::fracture::Fragment;
use crate::fracture::kernel::cap::constrained_triangulation;

/// Grid points closer than this many spacings to the cap's boundary are not used.
const MIN_CLEARANCE: f64 = 0.4;
/// At most this many grid points along a cap's longer side.
const MAX_PER_AXIS: f64 = 24.0;
/// The amplitude is at most this fraction of the taper's width.
const MAX_SLOPE: f64 = 0.4;
/// Ids of core points in a collar triangulation start here (below: fragment vertices).
pub(crate) const CORE_ID: u32 = 1 << 31;

/// A 2D frame of a cap's plane: `p = origin + x·u + y·v`, `u × v = n`.
#[derive(Debug, Clone, Copy)]
pub(crate) struct PlaneFrame {
    pub origin: DVec3,
    pub u: DVec3,
    pub v: DVec3,
    pub n: DVec3,
}

impl PlaneFrame {
    /// The frame of the plane through `origin` with unit normal `n`.
    pub fn new(origin: DVec3, n: DVec3) -> PlaneFrame {
        let u = n.any_orthonormal_vector();
        PlaneFrame {
            origin,
            u,
            v: n.cross(u),
            n,
        }
    }

    /// `p` in the frame (projected onto the plane).
    pub fn to2(&self, p: DVec3) -> DVec2 {
        let d = p - self.origin;
        DVec2::new(d.dot(self.u), d.dot(self.v))
    }

    /// The point of the plane at `q`.
    pub fn to3(&self, q: DVec2) -> DVec3 {
        self.origin + self.u * q.x + self.v * q.y
    }
}

/// The displaced inner part of a cap, shared by its two sides.
#[derive(Debug, Clone)]
pub(crate) struct Core {
    /// The frame (normal out of the first side's fragment).
    pub frame: PlaneFrame,
    /// The core's points in the frame.
    pub points: Vec<DVec2>,
    /// Their positions in the plane.
    pub flat: Vec<DVec3>,
    /// Triangles over `points`, counter-clockwise in the frame (normal `frame.n`).
    pub tris: Vec<[u32; 3]>,
    /// The core's boundary, directed as in `tris`.
    pub rim: Vec<(u32, u32)>,
    /// Per point: the unit-amplitude displacement (noise times taper; 0 on the rim).
    pub shape: Vec<f64>,
    /// The largest amplitude the cap allows (`MAX_SLOPE` times the taper's width).
    pub max_amplitude: f64,
}

/// The 2D triangles of a region (in `frame`), with their bounds.
pub(crate) fn region_triangles(f: &Fragment, r: &Region, frame: &PlaneFrame) -> Vec<[DVec2; 3]> {
    r.tris
        .iter()
        .map(|&t| f.mesh.triangle(t as usize).map(|p| frame.to2(p)))
        .collect()
}

/// Barycentric coordinates of `q` in the 2D triangle `t` (`None` if degenerate).
pub(crate) fn barycentric2(t: &[DVec2; 3], q: DVec2) -> Option<[f64; 3]> {
    let [a, b, c] = *t;
    let den = (b - a).perp_dot(c - a);
    if den == 0.0 || !den.is_finite() {
        return None;
    }
    let wb = (q - a).perp_dot(c - a) / den;
    let wc = (b - a).perp_dot(q - a) / den;
    Some([1.0 - wb - wc, wb, wc])
}

/// Distance from `q` to the segment `ab`.
fn segment_distance(q: DVec2, a: DVec2, b: DVec2) -> f64 {
    let ab = b - a;
    let len2 = ab.length_squared();
    let t = if len2 > 0.0 {
        ((q - a).dot(ab) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (q - (a + ab * t)).length()
}

/// A small deterministic jitter in `[-0.5, 0.5)²` for grid point `(i, j)`, so the
/// grid is not cocircular everywhere (its Delaunay triangulation then has no ties).
fn jitter(i: i64, j: i64) -> DVec2 {
    let h = |x: u64| {
        let mut z = x.wrapping_add(0x9e37_79b9_7f4a_7c15);
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64 - 0.5
    };
    let k = (i as u64).wrapping_mul(0x1000_0000_01b3) ^ (j as u64);
    DVec2::new(h(k), h(k ^ 0x5555_5555_5555_5555))
}

/// The core of the cap whose first side is region `r` of fragment `f`; `None` when the
/// cap is too small to hold an inner (displaceable) core vertex.
pub(crate) fn build_core(f: &Fragment, r: &Region, rough: &Roughness) -> Option<Core> {
    let frame = PlaneFrame::new(r.point, r.normal);
    let tris2 = region_triangles(f, r, &frame);
    let boundary2: Vec<(DVec2, DVec2)> = r
        .boundary
        .iter()
        .map(|&(a, b)| {
            (
                frame.to2(f.mesh.positions[a as usize]),
                frame.to2(f.mesh.positions[b as usize]),
            )
        })
        .collect();
    let (mut lo, mut hi) = (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY));
    for t in &tris2 {
        for &p in t {
            lo = lo.min(p);
            hi = hi.max(p);
        }
    }
    let extent = (hi - lo).max_element();
    if !(extent > 0.0 && extent.is_finite()) {
        return None;
    }
    // A quarter of the noise's period, at most an eighth of the cap and half its
    // inradius (about area over half the perimeter), at least 1/24 of the cap.
    let area: f64 = tris2
        .iter()
        .map(|t| 0.5 * (t[1] - t[0]).perp_dot(t[2] - t[0]).abs())
        .sum();
    let perimeter: f64 = boundary2.iter().map(|(a, b)| (*b - *a).length()).sum();
    let inradius = 2.0 * area / perimeter.max(f64::MIN_POSITIVE);
    let spacing = (0.25 / rough.frequency)
        .min(extent / 8.0)
        .min(inradius / 2.0)
        .max(extent / MAX_PER_AXIS);
    let dist = |q: DVec2| {
        boundary2
            .iter()
            .map(|&(a, b)| segment_distance(q, a, b))
            .fold(f64::INFINITY, f64::min)
    };
    let inside = |q: DVec2| {
        tris2
            .iter()
            .any(|t| barycentric2(t, q).is_some_and(|w| w.iter().all(|&x| x >= 0.0)))
    };
    // The grid, jittered, strictly inside with a clearance.
    let (ni, nj) = (
        ((hi.x - lo.x) / spacing).ceil() as i64,
        ((hi.y - lo.y) / spacing).ceil() as i64,
    );
    let mut grid = Vec::new();
    for i in 0..=ni {
        for j in 0..=nj {
            let q = lo + (DVec2::new(i as f64, j as f64) + 0.2 * jitter(i, j)) * spacing;
            if inside(q) && dist(q) >= MIN_CLEARANCE * spacing {
                grid.push(q);
            }
        }
    }
    if grid.len() < 4 {
        return None;
    }
    // The master triangulation: the cap's boundary and the grid.
    let nb = f.mesh.positions.len() as u32;
    let mut points: Vec<(u32, DVec2)> = Vec::new();
    for &(a, _) in &r.boundary {
        points.push((a, frame.to2(f.mesh.positions[a as usize])));
    }
    for (k, &q) in grid.iter().enumerate() {
        points.push((nb + k as u32, q));
    }
    let all = constrained_triangulation(&points, &r.boundary);
    let core_all: Vec<[u32; 3]> = all
        .into_iter()
        .filter(|t| t.iter().all(|&i| i >= nb))
        .map(|t| t.map(|i| i - nb))
        .collect();
    // Keep the grid points the core uses, renumbered in grid order.
    let mut new_id = vec![u32::MAX; grid.len()];
    let mut kept = Vec::new();
    for t in &core_all {
        for &k in t {
            if new_id[k as usize] == u32::MAX {
                new_id[k as usize] = 0;
            }
        }
    }
    for (k, id) in new_id.iter_mut().enumerate() {
        if *id == 0 {
            *id = kept.len() as u32;
            kept.push(grid[k]);
        }
    }
    let tris: Vec<[u32; 3]> = core_all
        .iter()
        .map(|t| t.map(|k| new_id[k as usize]))
        .collect();
    let mut directed = crate::util::FastSet::default();
    for t in &tris {
        for e in 0..3 {
            directed.insert((t[e], t[(e + 1) % 3]));
        }
    }
    let mut rim = Vec::new();
    let mut on_rim = vec![false; kept.len()];
    for t in &tris {
        for e in 0..3 {
            let (a, b) = (t[e], t[(e + 1) % 3]);
            if !directed.contains(&(b, a)) {
                rim.push((a, b));
                on_rim[a as usize] = true;
                on_rim[b as usize] = true;
            }
        }
    }
    if on_rim.iter().all(|&x| x) {
        return None;
    }
    // Unit-amplitude shape: noise at the flat world position, times a taper that rises
    // from 0 at the cap's boundary over `width` (two spacings or the core's depth).
    let flat: Vec<DVec3> = kept.iter().map(|&q| frame.to3(q)).collect();
    let depth: Vec<f64> = kept.iter().map(|&q| dist(q)).collect();
    let deepest = depth.iter().copied().fold(0.0, f64::max);
    let width = (2.0 * spacing).min(deepest).max(f64::MIN_POSITIVE);
    let shape = (0..kept.len())
        .map(|k| {
            if on_rim[k] {
                return 0.0;
            }
            let t = (depth[k] / width).clamp(0.0, 1.0);
            let taper = t * t * (3.0 - 2.0 * t);
            fbm(flat[k], rough.frequency, rough.octaves, rough.seed) * taper
        })
        .collect();
    Some(Core {
        frame,
        points: kept,
        flat,
        tris,
        rim,
        shape,
        max_amplitude: MAX_SLOPE * width,
    })
}

/// The collar of one side: triangles between the side's boundary (region `r` of `f`,
/// fragment vertex ids) and the core's rim (ids `CORE_ID + k`), counter-clockwise in
/// the core's frame. `None` when the triangulation does not cover the ring exactly (its
/// area differs from the side's cap minus the core by more than rounding).
pub(crate) fn collar(f: &Fragment, r: &Region, core: &Core) -> Option<Vec<[u32; 3]>> {
    let frame = &core.frame;
    let mut points: Vec<(u32, DVec2)> = r
        .boundary
        .iter()
        .map(|&(a, _)| (a, frame.to2(f.mesh.positions[a as usize])))
        .collect();
    let mut constraints = r.boundary.clone();
    for &(a, b) in &core.rim {
        points.push((CORE_ID + a, core.points[a as usize]));
        constraints.push((CORE_ID + a, CORE_ID + b));
    }
    let tris = constrained_triangulation(&points, &constraints);
    let at = |i: u32| {
        if i >= CORE_ID {
            core.points[(i - CORE_ID) as usize]
        } else {
            frame.to2(f.mesh.positions[i as usize])
        }
    };
    let area = |t: [DVec2; 3]| 0.5 * (t[1] - t[0]).perp_dot(t[2] - t[0]);
    let collar_area: f64 = tris.iter().map(|t| area(t.map(at))).sum();
    let core_area: f64 = core
        .tris
        .iter()
        .map(|t| area(t.map(|k| core.points[k as usize])))
        .sum();
    let cap_area: f64 = region_triangles(f, r, frame)
        .into_iter()
        .map(|t| area(t).abs())
        .sum();
    let covered = collar_area + core_area;
    ((covered - cap_area).abs() <= 1e-9 * cap_area).then_some(tris)
}

impl Core {
    /// Per core point, its displacement along `frame.n` for `amplitude` (already
    /// limited by the caller).
    pub fn heights(&self, amplitude: f64) -> Vec<f64> {
        self.shape.iter().map(|s| s * amplitude).collect()
    }
}
