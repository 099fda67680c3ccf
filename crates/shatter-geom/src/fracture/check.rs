//! [`Fracture::validate`]: the invariants every fracture result must keep — closed,
//! 2-manifold, outward fragments with positive volumes that add up, and a well-formed
//! bond graph.

use glam::DVec3;
use rayon::prelude::*;

use super::error::InvalidFracture;
use super::normalize::Frame;
use super::types::Fracture;
use crate::TriMesh;
use crate::mesh::is_degenerate;
use crate::util::FastMap;

/// Relative tolerance of [`Fracture::validate`]'s volume checks.
pub const VOLUME_TOLERANCE: f64 = 1e-9;

/// A directed edge use: welded ends, walked from `lo` to `hi` or back.
type EdgeKey = (u32, u32);

impl Fracture {
    /// Checks the result's invariants; `mesh_volume`, when given, is the volume the
    /// fragments must add up to (relative [`VOLUME_TOLERANCE`]).
    ///
    /// Each fragment, welded by exact position, must be a closed 2-manifold per shell:
    /// no degenerate triangles, no two triangles on the same corners (equal or back to
    /// back), every undirected edge used by exactly two triangles walking it opposite
    /// ways; one `interior` flag per triangle; a positive volume equal to what its mesh
    /// encloses; the convex pieces' hulls, when given, one list per piece, naming only
    /// the piece's points. Bonds must be sorted by `(a, b)` with `a < b <` the fragment count, each
    /// pair once, with a positive finite area, a unit normal and a finite centroid.
    /// Works at any magnitude (volumes are measured in a rescaled frame).
    ///
    /// ```
    /// use shatter_geom::fracture::{fracture, FractureParams, InvalidFracture, Method};
    /// use shatter_geom::{DVec3, shapes};
    ///
    /// let cube = shapes::cube();
    /// let planes = vec![(DVec3::ZERO, DVec3::X), (DVec3::ZERO, DVec3::Y)];
    /// let params = FractureParams { method: Method::Slice { pieces: 0, planes: Some(planes) }, seed: 0 };
    /// let mut result = fracture(&cube, &params)?;
    /// assert_eq!(result.validate(Some(cube.volume())), Ok(()));
    ///
    /// // A fragment with a face removed has a hole.
    /// result.fragments[0].mesh.triangles.pop();
    /// result.fragments[0].interior.pop();
    /// assert!(matches!(result.validate(None), Err(InvalidFracture::EdgeUses { fragment: 0, uses: 1, .. })));
    /// # Ok::<(), shatter_geom::fracture::FractureError>(())
    /// ```
    pub fn validate(&self, mesh_volume: Option<f64>) -> Result<(), InvalidFracture> {
        if self.fragments.is_empty() {
            return Err(InvalidFracture::Empty);
        }
        // The fragments are independent, so they are checked in parallel; the error
        // reported is the first fragment's, as a loop in order would find it.
        if let Some(err) = self
            .fragments
            .par_iter()
            .enumerate()
            .with_max_len(1)
            .map(|(i, f)| check_fragment(i, f).err())
            .find_first(Option::is_some)
            .flatten()
        {
            return Err(err);
        }
        if let Some(expected) = mesh_volume {
            let total = self.total_volume();
            let err = (total - expected).abs();
            if err.is_nan() || err > VOLUME_TOLERANCE * expected.abs() {
                return Err(InvalidFracture::TotalVolume { total, expected });
            }
        }
        self.check_bonds()
    }

    fn check_bonds(&self) -> Result<(), InvalidFracture> {
        let n = self.fragments.len();
        for (k, b) in self.bonds.iter().enumerate() {
            let bad = |reason| InvalidFracture::Bond {
                bond: k,
                a: b.a,
                b: b.b,
                reason,
            };
            if b.a >= b.b {
                return Err(bad("a is not below b"));
            }
            if b.b as usize >= n {
                return Err(bad("fragment index out of range"));
            }
            if k > 0 && (self.bonds[k - 1].a, self.bonds[k - 1].b) >= (b.a, b.b) {
                return Err(bad(
                    "not after the previous bond in (a, b) order (unsorted or repeated)",
                ));
            }
            if !(b.area > 0.0 && b.area.is_finite()) {
                return Err(bad("area not positive and finite"));
            }
            let off = (b.normal.length() - 1.0).abs();
            if off.is_nan() || off > 1e-9 {
                return Err(bad("normal is not a unit vector"));
            }
            if !b.centroid.is_finite() {
                return Err(bad("centroid is not finite"));
            }
        }
        Ok(())
    }
}

/// Fragment `i`'s own invariants: its interior flags, a closed outward surface, its
/// hulls' indices, and its volume as its mesh encloses it.
fn check_fragment(i: usize, f: &super::types::Fragment) -> Result<(), InvalidFracture> {
    if f.interior.len() != f.mesh.triangles.len() {
        return Err(InvalidFracture::InteriorFlags {
            fragment: i,
            flags: f.interior.len(),
            triangles: f.mesh.triangles.len(),
        });
    }
    check_surface(i, &f.mesh)?;
    check_hulls(i, f)?;
    let mesh = enclosed_volume(&f.mesh);
    let agrees = (f.volume - mesh).abs() <= VOLUME_TOLERANCE * f.volume.abs();
    if !(f.volume > 0.0 && f.volume.is_finite() && agrees) {
        return Err(InvalidFracture::Volume {
            fragment: i,
            volume: f.volume,
            mesh,
        });
    }
    Ok(())
}

/// The convex pieces' hulls of fragment `i`: none, or one list per piece whose triangles
/// name the piece's points.
fn check_hulls(i: usize, f: &super::types::Fragment) -> Result<(), InvalidFracture> {
    if f.convex_hulls.is_empty() {
        return Ok(());
    }
    if f.convex_hulls.len() != f.convex_pieces.len() {
        return Err(InvalidFracture::ConvexHull {
            fragment: i,
            piece: f.convex_pieces.len(),
            reason: "lists do not match the pieces",
        });
    }
    for (k, (hull, piece)) in f.convex_hulls.iter().zip(&f.convex_pieces).enumerate() {
        if hull.iter().flatten().any(|&v| v as usize >= piece.len()) {
            return Err(InvalidFracture::ConvexHull {
                fragment: i,
                piece: k,
                reason: "names a point beyond the piece's",
            });
        }
    }
    Ok(())
}

/// The signed volume `mesh` encloses, measured in its own rescaled frame (so it neither
/// overflows nor underflows where the result itself fits in `f64`).
fn enclosed_volume(mesh: &TriMesh) -> f64 {
    if mesh.positions.is_empty() {
        return 0.0;
    }
    let frame = Frame::of(mesh);
    let local = frame.mesh_to_local(mesh).signed_volume();
    frame.volume_to_world(local, "").unwrap_or(0.0)
}

/// Closed, 2-manifold edges, no degenerate or repeated triangles, for fragment `i`.
fn check_surface(i: usize, mesh: &TriMesh) -> Result<(), InvalidFracture> {
    let n = mesh.positions.len();
    for (t, tri) in mesh.triangles.iter().enumerate() {
        if tri
            .iter()
            .any(|&v| v as usize >= n || !mesh.positions[v as usize].is_finite())
        {
            return Err(InvalidFracture::Malformed {
                fragment: i,
                triangle: t,
            });
        }
    }
    let (map, _) = mesh.weld_map();
    let welded: Vec<[u32; 3]> = mesh
        .triangles
        .iter()
        .map(|t| t.map(|v| map[v as usize]))
        .collect();
    // Welded index -> a position.
    let mut first = vec![DVec3::ZERO; n];
    for (v, &w) in map.iter().enumerate() {
        first[w as usize] = mesh.positions[v];
    }
    let pos = |w: u32| first[w as usize];
    let mut corners: FastMap<[u32; 3], usize> = FastMap::default();
    corners.reserve(welded.len());
    let mut uses: FastMap<EdgeKey, (usize, usize)> = FastMap::default();
    uses.reserve(3 * welded.len() / 2);
    for (t, w) in welded.iter().enumerate() {
        let [a, b, c] = mesh.triangles[t].map(|v| mesh.positions[v as usize]);
        if w[0] == w[1] || w[1] == w[2] || w[2] == w[0] || is_degenerate(a, b, c) {
            return Err(InvalidFracture::Degenerate {
                fragment: i,
                triangle: t,
            });
        }
        let mut sorted = *w;
        sorted.sort_unstable();
        if let Some(&first) = corners.get(&sorted) {
            // The same cyclic order (any rotation) is the same winding.
            let u = welded[first];
            let same = (0..3).any(|r| [w[r], w[(r + 1) % 3], w[(r + 2) % 3]] == u);
            return Err(InvalidFracture::DuplicateTriangles {
                fragment: i,
                first,
                second: t,
                opposite: !same,
            });
        }
        corners.insert(sorted, t);
        for k in 0..3 {
            let (u, v) = (w[k], w[(k + 1) % 3]);
            let e = uses.entry((u.min(v), u.max(v))).or_insert((0, 0));
            if u < v {
                e.0 += 1;
            } else {
                e.1 += 1;
            }
        }
    }
    // Report the first bad edge in a deterministic order.
    let mut bad: Vec<(EdgeKey, (usize, usize))> = uses
        .into_iter()
        .filter(|&(_, (f, b))| !(f == 1 && b == 1))
        .collect();
    bad.sort_unstable_by_key(|&(e, _)| e);
    if let Some(&((u, v), (f, b))) = bad.first() {
        let (a, b_pos) = (pos(u), pos(v));
        return Err(if f + b == 2 {
            InvalidFracture::Winding {
                fragment: i,
                a,
                b: b_pos,
            }
        } else {
            InvalidFracture::EdgeUses {
                fragment: i,
                a,
                b: b_pos,
                uses: f + b,
            }
        });
    }
    Ok(())
}
