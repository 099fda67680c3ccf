//! The indexed triangle mesh type.

use glam::DVec3;

use crate::fracture::normalize::{Frame, ldexp};

/// An indexed triangle mesh.
///
/// Convention: triangles are wound counter-clockwise when seen from outside, so the
/// right-hand normal `(b - a) × (c - a)` points out of a closed, outward mesh and its
/// signed volume is positive.
///
/// Indices are trusted: [`check`](TriMesh::check), [`welded`](TriMesh::welded) and
/// [`validate_solid`](TriMesh::validate_solid) accept any input, but the geometric
/// queries (volume, inertia, winding number, …) index `positions` directly and panic on an
/// out-of-range index. Meshes from [`crate::io`] and [`crate::shapes`] are always in
/// range; validate meshes built by hand from user data first.
///
/// ```
/// use shatter_geom::{DVec3, TriMesh};
/// // A unit right tetrahedron, wound outward.
/// let mesh = TriMesh::new(
///     vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z],
///     vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]],
/// );
/// assert!((mesh.signed_volume() - 1.0 / 6.0).abs() < 1e-12);
/// ```
#[derive(Debug, Clone, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct TriMesh {
    /// Vertex positions.
    pub positions: Vec<DVec3>,
    /// Triangles as three indices into `positions`.
    pub triangles: Vec<[u32; 3]>,
    /// Set on a fragment the fracture made (see [`SolidMark`]); never serialised, not
    /// compared.
    #[serde(skip)]
    solid: SolidMark,
}

/// The fracture's note on a fragment mesh it made: the fingerprint of its positions and
/// triangles as they were made. A fragment is cut exactly from a solid that passed
/// [`TriMesh::validate_solid`], so it cannot cross itself; a fracture of it skips the
/// exact self-intersection search (the costliest check) while the mesh is unchanged —
/// any change to `positions` or `triangles` changes the fingerprint, and the mesh is
/// then checked in full. A mesh from anywhere else (built by hand, read from a file,
/// deserialised) has no mark.
#[derive(Clone, Copy, Default)]
struct SolidMark(Option<u64>);

impl PartialEq for SolidMark {
    /// Always equal: the mark is a cache of a check, not part of the mesh.
    fn eq(&self, _: &SolidMark) -> bool {
        true
    }
}

impl std::fmt::Debug for SolidMark {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(if self.0.is_some() { "marked" } else { "-" })
    }
}

impl TriMesh {
    /// A mesh from positions and triangles (not validated; see the checks in this module).
    pub fn new(positions: Vec<DVec3>, triangles: Vec<[u32; 3]>) -> Self {
        Self {
            positions,
            triangles,
            solid: SolidMark::default(),
        }
    }

    /// Marks the mesh as a fragment the fracture made (see [`SolidMark`]).
    pub(crate) fn mark_solid(&mut self) {
        self.solid = SolidMark(Some(self.fingerprint()));
    }

    /// Whether the fracture made this mesh as it is now (see `SolidMark`): `false` for
    /// any mesh built or read elsewhere, and for a fragment changed since.
    ///
    /// ```
    /// use shatter_geom::fracture::{fracture, FractureParams, Method, Seeds};
    /// use shatter_geom::{shapes, DVec3};
    ///
    /// assert!(!shapes::cube().is_fracture_fragment());
    /// let params = FractureParams { method: Method::Voronoi { seeds: Seeds::count(4) }, seed: 1 };
    /// let mut mesh = fracture(&shapes::cube(), &params)?.fragments[0].mesh.clone();
    /// assert!(mesh.is_fracture_fragment());
    /// mesh.positions[0] += DVec3::X;
    /// assert!(!mesh.is_fracture_fragment());
    /// # Ok::<(), shatter_geom::fracture::FractureError>(())
    /// ```
    pub fn is_fracture_fragment(&self) -> bool {
        self.solid.0.is_some_and(|f| f == self.fingerprint())
    }

    /// A 64-bit fingerprint of the positions' bits and the triangles (a multiply-fold
    /// hash, as in wyhash: any change alters it but by a 2⁻⁶⁴ chance).
    fn fingerprint(&self) -> u64 {
        const K0: u64 = 0xa076_1d64_78bd_642f;
        const K1: u64 = 0xe703_7ed1_a0b4_28db;
        let step = |h: u64, w: u64| {
            let r = u128::from(h ^ K0) * u128::from(w ^ K1);
            ((r as u64) ^ ((r >> 64) as u64)).wrapping_add(h.rotate_left(23))
        };
        let mut h = step(self.positions.len() as u64, self.triangles.len() as u64);
        for p in &self.positions {
            h = step(h, p.x.to_bits());
            h = step(h, p.y.to_bits());
            h = step(h, p.z.to_bits());
        }
        for t in &self.triangles {
            h = step(h, u64::from(t[0]) | (u64::from(t[1]) << 32));
            h = step(h, u64::from(t[2]));
        }
        h
    }

    /// The three corner positions of triangle `t`.
    pub fn triangle(&self, t: usize) -> [DVec3; 3] {
        let [a, b, c] = self.triangles[t];
        [
            self.positions[a as usize],
            self.positions[b as usize],
            self.positions[c as usize],
        ]
    }

    /// Signed volume enclosed by the mesh (positive for a closed outward mesh). At any
    /// magnitude: a mesh far from unit size is measured in an exactly rescaled frame, so
    /// the result is infinite or zero only when the volume itself is beyond `f64` (see
    /// [`signed_volume_exp2`](TriMesh::signed_volume_exp2) for those).
    pub fn signed_volume(&self) -> f64 {
        let (m, e) = self.signed_volume_exp2();
        ldexp(m, e)
    }

    /// The signed volume as `m · 2^e`, so that a volume beyond `f64` (a cube of side
    /// 1e300 has volume 1e900) is still known. Non-finite coordinates give `(NaN or the
    /// plain sum, 0)`.
    ///
    /// ```
    /// use shatter_geom::{DVec3, shapes};
    /// let huge = shapes::cube().transformed(DVec3::splat(1e300), DVec3::ZERO);
    /// let (m, e) = huge.signed_volume_exp2();
    /// let log10 = m.log10() + e as f64 * std::f64::consts::LOG10_2;
    /// assert!((log10 - 900.0).abs() < 1e-9);
    /// assert_eq!(huge.signed_volume(), f64::INFINITY);
    /// ```
    pub fn signed_volume_exp2(&self) -> (f64, i32) {
        if !self.positions.is_empty() && self.positions.iter().all(|p| p.is_finite()) {
            let frame = Frame::of(self);
            if !frame.is_plain() {
                let local = frame.mesh_to_local(self);
                return (local.signed_volume_here(), frame.volume_exp2());
            }
        }
        (self.signed_volume_here(), 0)
    }

    /// [`signed_volume`](TriMesh::signed_volume) computed on the coordinates as they are.
    fn signed_volume_here(&self) -> f64 {
        // Sum of signed tetrahedra (origin shifted to the first vertex for precision).
        let Some(&o) = self.positions.first() else {
            return 0.0;
        };
        let mut v = 0.0;
        for t in 0..self.triangles.len() {
            let [a, b, c] = self.triangle(t);
            v += (a - o).dot((b - o).cross(c - o));
        }
        v / 6.0
    }

    /// Centroid of the enclosed solid (of a closed mesh). Falls back to the vertex mean
    /// when the volume is zero.
    pub fn centroid(&self) -> DVec3 {
        let Some(&o) = self.positions.first() else {
            return DVec3::ZERO;
        };
        let mut v6 = 0.0;
        let mut acc = DVec3::ZERO;
        for t in 0..self.triangles.len() {
            let [a, b, c] = self.triangle(t);
            let d = (a - o).dot((b - o).cross(c - o));
            v6 += d;
            acc += d * (a + b + c - 3.0 * o) / 4.0;
        }
        if v6.abs() > 0.0 {
            o + acc / v6
        } else {
            self.positions.iter().copied().sum::<DVec3>() / self.positions.len() as f64
        }
    }

    /// Axis-aligned bounds `(min, max)`, or `None` for a mesh without vertices.
    pub fn bounds(&self) -> Option<(DVec3, DVec3)> {
        let first = *self.positions.first()?;
        Some(
            self.positions
                .iter()
                .fold((first, first), |(lo, hi), &p| (lo.min(p), hi.max(p))),
        )
    }

    /// Unit normal of triangle `t` by the right-hand rule (outward for an outward mesh), or
    /// [`DVec3::ZERO`] for a zero-area triangle.
    ///
    /// ```
    /// use shatter_geom::{DVec3, TriMesh};
    /// let m = TriMesh::new(vec![DVec3::ZERO, DVec3::X, DVec3::Y], vec![[0, 1, 2]]);
    /// assert_eq!(m.triangle_normal(0), DVec3::Z);
    /// ```
    pub fn triangle_normal(&self, t: usize) -> DVec3 {
        let [a, b, c] = self.triangle(t);
        (b - a).cross(c - a).normalize_or_zero()
    }

    /// Area of triangle `t`.
    pub fn triangle_area(&self, t: usize) -> f64 {
        let [a, b, c] = self.triangle(t);
        0.5 * (b - a).cross(c - a).length()
    }

    /// Total area of the triangles.
    ///
    /// ```
    /// use shatter_geom::shapes;
    /// assert!((shapes::cube().surface_area() - 6.0).abs() < 1e-12);
    /// ```
    pub fn surface_area(&self) -> f64 {
        (0..self.triangles.len())
            .map(|t| self.triangle_area(t))
            .sum()
    }

    /// The mesh scaled per axis about the origin, then translated. A scale with an odd
    /// number of negative components mirrors the mesh; the winding is then reversed so an
    /// outward mesh stays outward.
    ///
    /// A fragment the fracture made stays one ([`is_fracture_fragment`](Self::is_fracture_fragment))
    /// when the transform's rounding cannot make it cross itself: each coordinate moves
    /// by at most 2⁻⁵² of the largest magnitude it passes through, and that must stay
    /// below a thousandth of the crossings the checks accept (a fragment within about two
    /// hundred of its sizes of the origin, before and after). Any other result is checked
    /// in full when fractured.
    ///
    /// ```
    /// use shatter_geom::fracture::{fracture, FractureParams};
    /// use shatter_geom::{DVec3, shapes};
    /// let m = shapes::cube().transformed(DVec3::new(2.0, 1.0, 3.0), DVec3::new(0.0, 10.0, 0.0));
    /// assert!((m.volume() - 6.0).abs() < 1e-12);
    /// assert!((m.centroid() - DVec3::new(0.0, 10.0, 0.0)).length() < 1e-12);
    ///
    /// let fragment = &fracture(&shapes::cube(), &FractureParams::voronoi(4, 1))?.fragments[0].mesh;
    /// assert!(fragment.transformed(DVec3::new(0.3, 2.0, 7.0), DVec3::ZERO).is_fracture_fragment());
    /// // Far from the origin for its size: rounding could matter, so it is checked again.
    /// assert!(!fragment.transformed(DVec3::ONE, DVec3::splat(1e9)).is_fracture_fragment());
    /// # Ok::<(), shatter_geom::fracture::FractureError>(())
    /// ```
    pub fn transformed(&self, scale: DVec3, translate: DVec3) -> TriMesh {
        // (A zero translation adds nothing, not even to the sign of a zero.)
        let positions = if translate == DVec3::ZERO {
            self.positions.iter().map(|&p| p * scale).collect()
        } else {
            self.positions
                .iter()
                .map(|&p| p * scale + translate)
                .collect()
        };
        let mirrored = scale.x * scale.y * scale.z < 0.0;
        let triangles = if mirrored {
            self.triangles.iter().map(|&[a, b, c]| [a, c, b]).collect()
        } else {
            self.triangles.clone()
        };
        let mut out = TriMesh::new(positions, triangles);
        if self.is_fracture_fragment() && out.rounding_keeps_shape(self, scale, translate) {
            out.mark_solid();
        }
        out
    }

    /// Whether this mesh, `original` scaled by `scale` and translated by `translate`,
    /// is so close to the exact transform that the rounding cannot have made it cross
    /// itself (see [`transformed`](Self::transformed)): every coordinate moved by at most
    /// 2⁻⁵² of the largest magnitude it passed through (the scaled value, then the
    /// translated one), and that is below a thousandth of the crossing depth the checks
    /// accept for this mesh's size.
    fn rounding_keeps_shape(&self, original: &TriMesh, scale: DVec3, translate: DVec3) -> bool {
        let Some((lo, hi)) = self.bounds() else {
            return false;
        };
        let size = (hi - lo).length();
        let reach = original.positions.iter().fold(0.0f64, |m, &p| {
            let q = p * scale;
            m.max(q.abs().max_element())
                .max((q + translate).abs().max_element())
        });
        size > 0.0
            && size.is_finite()
            && reach.is_finite()
            && reach * 2.0 * f64::EPSILON <= 1e-3 * super::validate::CROSSING_TOLERANCE * size
    }

    /// The mesh with every triangle's winding reversed (normals point the other way).
    ///
    /// ```
    /// use shatter_geom::shapes;
    /// let cube = shapes::cube();
    /// assert!((cube.flipped().signed_volume() + 1.0).abs() < 1e-12);
    /// ```
    pub fn flipped(&self) -> TriMesh {
        TriMesh::new(
            self.positions.clone(),
            self.triangles.iter().map(|&[a, b, c]| [a, c, b]).collect(),
        )
    }

    /// All meshes in one: positions concatenated, indices offset. Triangle order follows
    /// the input order, so per-triangle data can be concatenated alongside.
    ///
    /// ```
    /// use shatter_geom::{DVec3, TriMesh, shapes};
    /// let a = shapes::cube();
    /// let b = a.transformed(DVec3::ONE, DVec3::new(3.0, 0.0, 0.0));
    /// let both = TriMesh::merge(&[a, b]);
    /// assert_eq!(both.triangles.len(), 24);
    /// assert_eq!(both.check().components, 2);
    /// ```
    pub fn merge(meshes: &[TriMesh]) -> TriMesh {
        let mut out = TriMesh::default();
        for m in meshes {
            let offset =
                u32::try_from(out.positions.len()).expect("merged mesh exceeds u32 vertices");
            out.positions.extend_from_slice(&m.positions);
            out.triangles
                .extend(m.triangles.iter().map(|t| t.map(|i| i + offset)));
        }
        out
    }
}
