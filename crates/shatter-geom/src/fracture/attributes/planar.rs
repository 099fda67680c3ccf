//! Planar UVs of interior faces: a basis per cap plane that depends on the plane alone
//! (not on which side sees it), and one world-space frame for the whole object.

use glam::DVec3;

use crate::fracture::Fragment;
use crate::fracture::kernel::is_surface;
use crate::util::FastMap;

/// Tag of an interior triangle whose plane is its own (the tetra method's faces): its
/// basis comes from its three corners, taken in a fixed order, so the two sides of a
/// shared face (the same corners, wound the other way) get the same one. Below the
/// surface tags and above any cap plane id the methods make.
pub(crate) const OWN_PLANE: u64 = (1 << 63) - 1;

/// Unit-normal components closer than this to the largest one tie with it.
pub(crate) const TIE: f64 = 1e-6;

/// The axis a unit normal is most along: the first whose component is within [`TIE`]
/// of the largest in magnitude.
fn dominant_axis(n: DVec3) -> usize {
    let a = n.abs();
    let top = a.max_element();
    (0..3).find(|&k| a[k] >= top - TIE).unwrap_or(0)
}

/// An orthonormal basis `(u, v, n)` of a plane, `n` its unit normal up to sign.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Basis {
    pub u: DVec3,
    pub v: DVec3,
    pub n: DVec3,
}

impl Basis {
    /// The canonical basis of the plane with normal `±normal`: `n` is the normal turned
    /// so that its largest component is positive, `u` the next axis (cyclically) made
    /// orthogonal to `n`, `v = n × u`. Both orientations of a plane give the same basis.
    ///
    /// Components within [`TIE`] of the largest count as equal and the first of them
    /// is taken, so two normals of one plane that differ by rounding (the two sides of
    /// a crack, or two cuts in nearly the same plane) pick the same axis even for a
    /// plane at 45° to two axes, where "the largest" alone would follow the rounding.
    pub fn canonical(normal: DVec3) -> Basis {
        let Some(n) = normal.try_normalize() else {
            return Basis {
                u: DVec3::X,
                v: DVec3::Y,
                n: DVec3::Z,
            };
        };
        let k = dominant_axis(n);
        let n = if n[k] < 0.0 { -n } else { n };
        // |n[k]| ≥ 1/√3, so the next axis is at least that far from n: no cancellation.
        let e = DVec3::AXES[(k + 1) % 3];
        let u = (e - n * n.dot(e)).normalize();
        Basis {
            u,
            v: n.cross(u),
            n,
        }
    }

    /// The box-projection basis for a surface of normal `normal`: the canonical basis of
    /// the coordinate axis `normal` is most along (the first of equals), so a texture is
    /// projected along that axis as a box mapping does, and nearby triangles facing the
    /// same way share one chart.
    pub fn boxed(normal: DVec3) -> Basis {
        let n = normal.normalize_or_zero();
        Basis::canonical(DVec3::AXES[dominant_axis(n)])
    }

    /// The canonical basis of a triangle's plane, from its corners sorted by position
    /// (so every winding of the same corners gives the same basis).
    pub fn of_triangle(p: [DVec3; 3]) -> Basis {
        let mut q = p;
        q.sort_by(|a, b| {
            a.x.total_cmp(&b.x)
                .then(a.y.total_cmp(&b.y))
                .then(a.z.total_cmp(&b.z))
        });
        Basis::canonical((q[1] - q[0]).cross(q[2] - q[0]))
    }
}

/// The object's frame for planar UVs: `uv = ((p − origin)·u, (p − origin)·v) · scale`,
/// with `origin` the low corner of the input's bounds and `scale` one over its largest
/// extent (a texture then spans the object once).
#[derive(Debug, Clone, Copy)]
pub(crate) struct UvFrame {
    origin: DVec3,
    scale: f64,
}

impl UvFrame {
    /// The frame of an object with these positions.
    pub fn of(positions: &[DVec3]) -> UvFrame {
        if positions.is_empty() {
            return UvFrame {
                origin: DVec3::ZERO,
                scale: 1.0,
            };
        }
        let (lo, hi) = crate::util::bounds(positions);
        let extent = (hi - lo).max_element();
        let scale = if extent > 0.0 && extent.is_finite() {
            1.0 / extent
        } else {
            1.0
        };
        UvFrame { origin: lo, scale }
    }

    /// The planar UV of `p` in `basis`.
    pub fn uv(&self, basis: &Basis, p: DVec3) -> [f32; 2] {
        let d = p - self.origin;
        [
            (d.dot(basis.u) * self.scale) as f32,
            (d.dot(basis.v) * self.scale) as f32,
        ]
    }
}

/// Cap planes whose unit normals are parallel up to this sine (0.06°) share one UV
/// basis. Two cuts in nearly the same plane (the faces on either side of a sliver, which
/// a CAD model's nearly coplanar points leave in the tetra method) can face each other
/// across a crack under different tags; a basis per tag alone would differ between them
/// by their angle (a UV step of about the angle across the crack), and by a whole axis
/// where [`Basis::canonical`]'s choice of axis ties. A cap projected with its group's
/// basis is sheared by at most about the group's spread, far below what a texture shows.
pub(crate) const SAME_PLANE_SINE: f64 = 1e-3;

/// One basis per cap tag over all fragments. Each tag's plane normal is the sum of its
/// triangles' normals (area-weighted, each turned to agree with the sum so far; in
/// fragment and triangle order, so the result is deterministic). Tags whose normals are
/// parallel up to [`SAME_PLANE_SINE`] (either way round) are grouped, transitively, and
/// every tag of a group gets the canonical basis of the group's summed normal. Every
/// triangle of a tag lies in one plane, the two sides of a bond included, so they all
/// share the basis; so do facing caps of two tags in one plane.
pub(crate) fn cap_bases(fragments: &[Fragment], tags: &[Vec<u64>]) -> FastMap<u64, Basis> {
    let mut sums: FastMap<u64, DVec3> = FastMap::default();
    for (f, tags) in fragments.iter().zip(tags) {
        for (tri, &tag) in f.mesh.triangles.iter().zip(tags) {
            if is_surface(tag) || tag == OWN_PLANE {
                continue;
            }
            let [a, b, c] = tri.map(|i| f.mesh.positions[i as usize]);
            add_turned(sums.entry(tag).or_insert(DVec3::ZERO), (b - a).cross(c - a));
        }
    }
    let mut sums: Vec<(u64, DVec3)> = sums.into_iter().collect();
    sums.sort_unstable_by_key(|&(tag, _)| tag);
    let group = same_plane_groups(&sums);
    let mut group_sum = vec![DVec3::ZERO; sums.len()];
    for (&(_, n), &g) in sums.iter().zip(&group) {
        add_turned(&mut group_sum[g], n);
    }
    sums.iter()
        .zip(&group)
        .map(|(&(tag, _), &g)| (tag, Basis::canonical(group_sum[g])))
        .collect()
}

/// Adds the normal `n` to the sum `s`, turned to agree with it (one plane's normals
/// seen from either side add up rather than cancel).
fn add_turned(s: &mut DVec3, n: DVec3) {
    if s.dot(n) < 0.0 {
        *s -= n;
    } else {
        *s += n;
    }
}

/// Per normal of `sums`, the index of its group's first member: normals parallel up to
/// [`SAME_PLANE_SINE`], either way round, joined transitively. Found through a grid of
/// the unit normals (cells twice the bound wide, so a normal's partners lie in its cell
/// or the next one towards it along each axis), looked up with the normal and its
/// opposite.
fn same_plane_groups(sums: &[(u64, DVec3)]) -> Vec<usize> {
    const CELL: f64 = 2.0 * SAME_PLANE_SINE;
    let unit: Vec<Option<DVec3>> = sums.iter().map(|&(_, n)| n.try_normalize()).collect();
    let cell_of = |m: DVec3| (m / CELL).floor().as_i64vec3().to_array();
    let mut groups = crate::util::UnionFind::new(sums.len());
    // Equal normals (a CAD model's axis-aligned caps, by the thousand) join at once, and
    // only the first of them goes into the grid: a cell's list stays short.
    let mut equal: FastMap<[u64; 3], usize> = FastMap::default();
    let mut grid: FastMap<[i64; 3], Vec<usize>> = FastMap::default();
    let mut listed = vec![false; unit.len()];
    for (i, n) in unit.iter().enumerate() {
        let Some(n) = *n else { continue };
        let first_nonzero = n.to_array().into_iter().find(|&x| x != 0.0).unwrap_or(1.0);
        let key = (n * first_nonzero.signum()).to_array().map(f64::to_bits);
        match equal.entry(key) {
            std::collections::hash_map::Entry::Occupied(e) => groups.union(i, *e.get()),
            std::collections::hash_map::Entry::Vacant(e) => {
                e.insert(i);
                listed[i] = true;
                grid.entry(cell_of(n)).or_default().push(i);
            }
        }
    }
    for (i, n) in unit.iter().enumerate() {
        let Some(n) = n.filter(|_| listed[i]) else {
            continue;
        };
        for m in [n, -n] {
            let k = cell_of(m);
            let frac = m / CELL - (m / CELL).floor();
            let step = frac.to_array().map(|f| if f < 0.5 { -1 } else { 1 });
            for corner in 0..8 {
                let mut c = k;
                for (axis, s) in step.iter().enumerate() {
                    if corner >> axis & 1 == 1 {
                        c[axis] += s;
                    }
                }
                for &j in grid.get(&c).map_or(&[][..], Vec::as_slice) {
                    if j < i && unit[j].is_some_and(|o| o.cross(n).length() <= SAME_PLANE_SINE) {
                        groups.union(i, j);
                    }
                }
            }
        }
    }
    // Each group named by its first member (the least tag), so the sums are made in
    // tag order.
    let mut first = vec![usize::MAX; sums.len()];
    (0..sums.len())
        .map(|i| {
            let r = groups.find(i);
            if first[r] == usize::MAX {
                first[r] = i;
            }
            first[r]
        })
        .collect()
}
