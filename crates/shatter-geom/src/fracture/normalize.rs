//! The fracture's working frame: the input moved and scaled to about a unit box, so the
//! fracture sees the same numbers at any magnitude, and the results mapped back.
//!
//! The map is exact. Per axis, `local = (p − t) · 2⁻ᵏ`:
//! - the translation `t` is 0 when the origin is near the box (|centre| < 2 · half
//!   extent), and otherwise the box centre, so every coordinate is within a factor of two
//!   of `t` and `p − t` is exact (Sterbenz);
//! - the scale is a power of two, so it only changes exponents.
//!
//! The input's vertices therefore come back bit for bit, exact predicates decide the
//! same as on the input, and only new points (cut vertices) are rounded on the way back.
//!
//! **Isotropic or per axis.** Normally one power of two serves all axes (a similarity:
//! every method behaves exactly as at unit size). When the thinnest extent is below
//! [`ANISOTROPY`] of the largest (e.g. `--scale 1e200,1,1`), one scale would leave the
//! thin axes far below the cut tolerance or underflow their products, so each axis gets
//! its own power of two. The Voronoi cells are then cut under the metric that makes
//! local distances equal the input's ([`Frame::metric`]), so the cells are the input's
//! Euclidean cells; slice planes map to planes; a tetrahedralization is Delaunay in the
//! local frame (it still tiles the mesh exactly). Seed patterns other than uniform
//! (clustered, radial) and random slice planes are then drawn in the local frame.
//!
//! **Range.** Volumes, inertia tensors and bond areas grow with size³, size⁵ and size²;
//! where the input's size puts one beyond `f64` (inf, or below the smallest full-precision
//! value `f64::MIN_POSITIVE`), the fracture is refused with
//! [`FractureError::OutOfRange`] naming the quantity and its magnitude.

use glam::{DMat3, DVec3};
use rayon::prelude::*;

use super::error::FractureError;
use super::types::{Bond, Fracture, Fragment};
use crate::TriMesh;
use crate::util::bounds;

/// Below this ratio of the thinnest to the largest extent, each axis is scaled on its
/// own (2⁻²⁰ ≈ 1e-6; the cut tolerance is 1e-10 of the size).
pub const ANISOTROPY: f64 = 1.0 / (1u64 << 20) as f64;

/// How far a given point (a seed, a plane's point, an impact point) may lie from the
/// mesh, per coordinate in the local frame, where the mesh's largest half extent is
/// about 1: 2^64 ≈ 1.8e19 times the mesh's size. A bisector's offset is the product of
/// two such coordinates, and the exact predicates multiply up to five, so beyond this
/// the cut's arithmetic heads for overflow (at 1e300 a bisector's offset is infinite and
/// a cell swallows the whole mesh); a point that far is refused by name
/// ([`FractureError::TooFar`]).
pub const FAR_LIMIT: f64 = 18_446_744_073_709_551_616.0;

/// `x · 2^e`, exact whenever the result is a normal number (in steps, so `2^e` itself
/// need not be representable).
pub(crate) fn ldexp(mut x: f64, mut e: i32) -> f64 {
    while e > 1000 {
        x *= 2f64.powi(1000);
        e -= 1000;
    }
    while e < -1000 {
        x *= 2f64.powi(-1000);
        e += 1000;
    }
    x * 2f64.powi(e)
}

/// The exponent `k` with `2^(k-1) < h ≤ 2^k` (`h > 0`, finite).
fn exponent_above(h: f64) -> i32 {
    let mut k = h.log2().ceil() as i32;
    // log2 may be off by one at the boundaries; settle it exactly.
    while ldexp(1.0, k) < h {
        k += 1;
    }
    while ldexp(1.0, k - 1) >= h {
        k -= 1;
    }
    k
}

/// `log10(|x| · 2^e)` for reporting a magnitude that `f64` cannot hold.
fn log10_of(x: f64, e: i32) -> f64 {
    x.abs().log10() + f64::from(e) * std::f64::consts::LOG10_2
}

/// The exact map between the input's frame and the fracture's local frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Frame {
    /// Translation (per axis 0 or the box centre).
    t: DVec3,
    /// Per-axis exponents: `local = (p − t) · 2^(−k)`.
    k: [i32; 3],
    /// Each axis scaled on its own.
    per_axis: bool,
    /// Half extents of the input's box.
    half: DVec3,
}

impl Frame {
    /// The frame of `mesh` (finite coordinates, at least one vertex).
    pub(crate) fn of(mesh: &TriMesh) -> Self {
        let (lo, hi) = bounds(&mesh.positions);
        // Halves first: no overflow near f64::MAX.
        let half = hi * 0.5 - lo * 0.5;
        let centre = lo * 0.5 + hi * 0.5;
        let largest = half.max_element();
        let smallest = half.min_element();
        let per_axis = largest > 0.0 && smallest < ANISOTROPY * largest;
        let mut t = DVec3::ZERO;
        let mut k = [0i32; 3];
        for a in 0..3 {
            if centre[a].abs() >= 2.0 * half[a] {
                t[a] = centre[a];
            }
            let h = if per_axis { half[a] } else { largest };
            k[a] = if h > 0.0 { exponent_above(h) } else { 0 };
        }
        Frame {
            t,
            k,
            per_axis,
            half,
        }
    }

    /// Whether each axis has its own scale.
    pub(crate) fn is_per_axis(&self) -> bool {
        self.per_axis
    }

    /// Half extents of the input's bounding box (input units).
    pub(crate) fn half_extents(&self) -> DVec3 {
        self.half
    }

    /// Whether the frame is a plain one: one scale for all axes, within 2^±100 of unit
    /// size, where computing on the input's own coordinates is as good.
    pub(crate) fn is_plain(&self) -> bool {
        !self.per_axis && self.k.iter().all(|k| k.abs() <= 100)
    }

    /// The exponent a local volume is multiplied by (`2^(kx+ky+kz)`).
    pub(crate) fn volume_exp2(&self) -> i32 {
        self.ksum()
    }

    fn kmax(&self) -> i32 {
        self.k[0].max(self.k[1]).max(self.k[2])
    }

    fn ksum(&self) -> i32 {
        self.k[0] + self.k[1] + self.k[2]
    }

    /// A point of the input frame in the local frame (`None` if it is too far from the
    /// mesh for the local frame to hold it: a coordinate beyond [`FAR_LIMIT`]).
    pub(crate) fn point_to_local(&self, p: DVec3) -> Option<DVec3> {
        let mut q = DVec3::ZERO;
        for a in 0..3 {
            let d = p[a] - self.t[a];
            q[a] = if d.is_finite() {
                ldexp(d, -self.k[a])
            } else {
                ldexp(p[a] * 0.5 - self.t[a] * 0.5, 1 - self.k[a])
            };
        }
        (q.is_finite() && q.abs().max_element() <= FAR_LIMIT).then_some(q)
    }

    /// A point of the local frame in the input frame.
    pub(crate) fn point_to_world(&self, q: DVec3) -> DVec3 {
        let mut p = DVec3::ZERO;
        for a in 0..3 {
            p[a] = ldexp(q[a], self.k[a]) + self.t[a];
        }
        p
    }

    /// A plane normal of the input frame in the local frame (a direction `n` with
    /// `n · (p − q) = 0` keeps that form), unnormalised; `None` if it vanishes.
    pub(crate) fn normal_to_local(&self, n: DVec3) -> Option<DVec3> {
        let m = n.abs().max_element();
        if !(m > 0.0 && m.is_finite()) {
            return None;
        }
        let kmax = self.kmax();
        let mut v = DVec3::ZERO;
        for a in 0..3 {
            v[a] = ldexp(n[a] / m, self.k[a] - kmax);
        }
        (v != DVec3::ZERO).then_some(v)
    }

    /// The mesh in the local frame (same triangles).
    pub(crate) fn mesh_to_local(&self, mesh: &TriMesh) -> TriMesh {
        let positions = mesh
            .positions
            .iter()
            .map(|&p| {
                self.point_to_local(p)
                    .expect("a vertex inside the box maps into the local frame")
            })
            .collect();
        TriMesh::new(positions, mesh.triangles.clone())
    }

    /// The diagonal metric under which local distances are the input's distances (up to
    /// one common factor): all ones when isotropic. Weights are at least
    /// `f64::MIN_POSITIVE` (a bisector keeps a non-zero normal; what that adds is far
    /// below rounding once mapped back, unless the axes differ over 1e300-fold).
    pub(crate) fn metric(&self) -> DVec3 {
        let kmax = self.kmax();
        DVec3::from_array(
            self.k
                .map(|k| ldexp(1.0, 2 * (k - kmax)).max(f64::MIN_POSITIVE)),
        )
    }

    /// A volume of the local frame in the input frame, or the refusal naming `what`.
    pub(crate) fn volume_to_world(&self, v: f64, what: &'static str) -> Result<f64, FractureError> {
        let w = ldexp(v, self.ksum());
        if w.is_finite() && w.abs() >= f64::MIN_POSITIVE {
            Ok(w)
        } else {
            Err(out_of_range(what, log10_of(v, self.ksum())))
        }
    }

    /// An inertia tensor (about the centroid, unit density) of the local frame in the
    /// input frame. Isotropic: `I · 2^(5k)`. Per axis: through the second moment
    /// `S = tr(I)/2 · 1 − I`, which maps as `S'ᵢⱼ = Sᵢⱼ · 2^(kᵢ + kⱼ + Σk)`, then
    /// `I' = tr(S') · 1 − S'` with each diagonal the sum of the other two moments.
    pub(crate) fn inertia_to_world(
        &self,
        i: DMat3,
        what: &'static str,
    ) -> Result<DMat3, FractureError> {
        let k = self.k;
        let s = self.ksum();
        let m = i.to_cols_array_2d();
        let mut out = [[0.0; 3]; 3];
        if !self.per_axis {
            for (c, col) in m.iter().enumerate() {
                for (r, &x) in col.iter().enumerate() {
                    out[c][r] = ldexp(x, 2 * k[0] + s);
                }
            }
        } else {
            let tr = (m[0][0] + m[1][1] + m[2][2]) * 0.5;
            let moment = |c: usize, r: usize| {
                let x = if c == r { tr - m[c][r] } else { -m[c][r] };
                ldexp(x, k[c] + k[r] + s)
            };
            for (c, col) in out.iter_mut().enumerate() {
                for (r, x) in col.iter_mut().enumerate() {
                    *x = if c == r {
                        let (u, v) = ((c + 1) % 3, (c + 2) % 3);
                        moment(u, u) + moment(v, v)
                    } else {
                        -moment(c, r)
                    };
                }
            }
        }
        let diagonal = [out[0][0], out[1][1], out[2][2]];
        let finite = out.iter().flatten().all(|x| x.is_finite());
        let largest = diagonal.iter().fold(0.0f64, |a, &b| a.max(b));
        let local_largest = [m[0][0], m[1][1], m[2][2]]
            .iter()
            .fold(0.0f64, |a, &b| a.max(b));
        // Only a range problem is refused here: a tensor already zero in the local frame
        // (a degenerate solid) maps to zero.
        if finite && (largest >= f64::MIN_POSITIVE || local_largest <= 0.0) {
            return Ok(DMat3::from_cols_array_2d(&out));
        }
        // The magnitude of the largest diagonal entry, for the message.
        let local = [m[0][0], m[1][1], m[2][2]];
        let e = if self.per_axis {
            s + 2 * self.kmax()
        } else {
            s + 2 * k[0]
        };
        let big = local.iter().fold(0.0f64, |a, &b| a.max(b.abs()));
        Err(out_of_range(what, log10_of(big, e)))
    }

    /// A fracture of the local frame in the input frame, or the refusal naming the first
    /// quantity beyond `f64`.
    pub(crate) fn fracture_to_world(&self, f: Fracture) -> Result<Fracture, FractureError> {
        // Per fragment in parallel; the error returned is the first fragment's.
        let fragments = f
            .fragments
            .into_par_iter()
            .with_max_len(1)
            .map(|g| self.fragment_to_world(g))
            .collect::<Vec<_>>()
            .into_iter()
            .collect::<Result<Vec<_>, _>>()?;
        let bonds = f
            .bonds
            .into_iter()
            .map(|b| self.bond_to_world(b))
            .collect::<Result<Vec<_>, _>>()?;
        Ok(Fracture {
            fragments,
            bonds,
            materials: f.materials,
            warnings: f.warnings,
        })
    }

    fn positions_to_world(&self, pos: &[DVec3]) -> Result<Vec<DVec3>, FractureError> {
        let out: Vec<DVec3> = pos.iter().map(|&q| self.point_to_world(q)).collect();
        if let Some(p) = out.iter().find(|p| !p.is_finite()) {
            let big = p.abs().max_element();
            return Err(out_of_range("a fragment vertex coordinate", big.log10()));
        }
        Ok(out)
    }

    fn fragment_to_world(&self, g: Fragment) -> Result<Fragment, FractureError> {
        let positions = self.positions_to_world(&g.mesh.positions)?;
        let convex_pieces = g
            .convex_pieces
            .iter()
            .map(|p| self.positions_to_world(p))
            .collect::<Result<Vec<_>, _>>()?;
        Ok(Fragment {
            mesh: TriMesh::new(positions, g.mesh.triangles),
            interior: g.interior,
            convex_pieces,
            convex_hulls: g.convex_hulls,
            volume: self.volume_to_world(g.volume, "a fragment's volume")?,
            centroid: self.point_to_world(g.centroid),
            inertia: self.inertia_to_world(g.inertia, "a fragment's inertia tensor")?,
            // Attributes are attached after the fracture is back in the world frame.
            corners: g.corners,
            material: g.material,
        })
    }

    fn bond_to_world(&self, b: Bond) -> Result<Bond, FractureError> {
        // The area vector `area · n` maps component-wise by 2^(Σk − kᵢ).
        let s = self.ksum();
        let mut v = DVec3::ZERO;
        for a in 0..3 {
            v[a] = ldexp(b.area * b.normal[a], s - self.k[a]);
        }
        let m = v.abs().max_element();
        let area = m * (v / m).length();
        let refuse = || {
            let e = (0..3).map(|a| s - self.k[a]).max().unwrap_or(s);
            out_of_range("a bond's area", log10_of(b.area, e))
        };
        if !(area.is_finite() && area >= f64::MIN_POSITIVE) {
            return Err(refuse());
        }
        let normal = v / m / (v / m).length();
        Ok(Bond {
            a: b.a,
            b: b.b,
            area,
            centroid: self.point_to_world(b.centroid),
            normal,
        })
    }
}

/// Above this ratio of the signed tetrahedra's absolute sum to their sum, a mesh's
/// volume is refused as lost in rounding (its relative error could pass 1e-10).
pub const CANCELLATION_LIMIT: f64 = 1e6;

/// Refuses a mesh whose volume `f64` cannot compute: the signed tetrahedra (apex at the
/// first vertex, as the mass properties use) cancel so much that rounding swamps the
/// result — a part of the mesh vastly larger than the rest, e.g. one vertex moved 1e33
/// away into a flat fin.
pub(crate) fn check_cancellation(pos: &[DVec3], tris: &[[u32; 3]]) -> Result<(), FractureError> {
    let Some(&o) = pos.first() else {
        return Ok(());
    };
    let (mut sum, mut abs) = (0.0f64, 0.0f64);
    for t in tris {
        let [a, b, c] = t.map(|i| pos[i as usize] - o);
        let d = a.dot(b.cross(c));
        sum += d;
        abs += d.abs();
    }
    if abs <= CANCELLATION_LIMIT * sum.abs() {
        return Ok(());
    }
    let ratio = abs / sum.abs();
    Err(FractureError::VolumeLost {
        log10: if ratio.is_finite() {
            ratio.log10().round() as i32
        } else {
            308
        },
    })
}

/// Relative tolerance of the check that a fracture's volumes add up.
pub const VOLUME_SUM_TOLERANCE: f64 = 1e-6;

/// Refuses a fracture (local frame) whose fragments' volumes do not add up to `volume`.
pub(crate) fn check_volume_sum(f: &Fracture, volume: f64) -> Result<(), FractureError> {
    let total = f.total_volume();
    if (total - volume).abs() <= VOLUME_SUM_TOLERANCE * volume {
        Ok(())
    } else {
        Err(FractureError::VolumeMismatch {
            ratio: total / volume,
        })
    }
}

fn out_of_range(what: &'static str, log10: f64) -> FractureError {
    FractureError::OutOfRange {
        what,
        log10: if log10.is_finite() {
            log10.round() as i32
        } else {
            0
        },
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn points_go_there_and_back_exactly() {
        let mesh = crate::shapes::bird().transformed(DVec3::new(1e200, 1.0, 3e-7), DVec3::ZERO);
        let f = Frame::of(&mesh);
        assert!(f.is_per_axis());
        for &p in &mesh.positions {
            let q = f.point_to_local(p).unwrap();
            assert!(q.abs().max_element() <= 3.0, "{q}");
            assert_eq!(f.point_to_world(q), p);
        }
    }

    #[test]
    fn far_mesh_is_moved_and_comes_back_exactly() {
        let mesh = crate::shapes::cube().transformed(DVec3::splat(1e-3), DVec3::splat(1e9));
        let f = Frame::of(&mesh);
        assert!(!f.is_per_axis());
        assert_eq!(f.t, DVec3::splat(1e9));
        for &p in &mesh.positions {
            let q = f.point_to_local(p).unwrap();
            // Half extent 5e-4 over 2^-10: about 0.51 (the corners are rounded at 1e9).
            assert!((q.abs().max_element() - 0.512).abs() < 1e-3, "{q}");
            assert_eq!(f.point_to_world(q), p);
        }
    }

    #[test]
    fn exponent_brackets_the_extent() {
        for h in [1e-310, 1e-200, 0.5, 1.0, 3.0, 1e300, f64::MAX] {
            let k = exponent_above(h);
            assert!(ldexp(1.0, k) >= h && ldexp(1.0, k - 1) < h, "{h} {k}");
        }
    }

    #[test]
    fn box_inertia_maps_per_axis() {
        // A unit cube's inertia (1/6 on the diagonal) stretched to a 2^40 × 1 × 2^-30 box.
        let mesh = crate::shapes::cube().transformed(
            DVec3::new(ldexp(1.0, 40), 1.0, ldexp(1.0, -30)),
            DVec3::ZERO,
        );
        let f = Frame::of(&mesh);
        assert!(f.is_per_axis());
        let local = f.mesh_to_local(&mesh);
        let i = f.inertia_to_world(local.inertia(), "x").unwrap();
        let (a, b, c) = (ldexp(1.0, 40), 1.0, ldexp(1.0, -30));
        let m = a * b * c;
        let want = DVec3::new(b * b + c * c, a * a + c * c, a * a + b * b) * (m / 12.0);
        let got = DVec3::new(i.x_axis.x, i.y_axis.y, i.z_axis.z);
        assert!(
            ((got - want) / want).abs().max_element() < 1e-12,
            "{got} {want}"
        );
        assert!(i.x_axis.y.abs() <= 1e-12 * want.x);
    }

    #[test]
    fn volume_beyond_f64_is_refused() {
        let mesh = crate::shapes::cube().transformed(DVec3::splat(1e300), DVec3::ZERO);
        let f = Frame::of(&mesh);
        let local = f.mesh_to_local(&mesh);
        let err = f.volume_to_world(local.signed_volume(), "the mesh's volume");
        assert_eq!(
            err,
            Err(FractureError::OutOfRange {
                what: "the mesh's volume",
                log10: 900
            })
        );
    }
}
