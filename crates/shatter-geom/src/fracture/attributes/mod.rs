//! Attributes of the fragments (UVs, normals, colours, materials), computed at the end
//! from positions alone, so the cutting kernel carries nothing but a tag per triangle.
//!
//! - A surface triangle's tag names the input triangle `T` it lies on
//!   ([`source_triangle`]). Each corner's UV, normal and colour is the barycentric
//!   interpolation of `T`'s corner attributes at the corner's position (projected onto
//!   `T`'s plane; the corner is on `T` up to rounding). This is exact along cut edges and
//!   keeps seams: attributes are per corner and `T` is the corner's own triangle, so one
//!   position on a seam gets each side's value on that side. The triangle keeps `T`'s
//!   material.
//! - A surface triangle of no known source (the tetra method builds its fragments from
//!   tetrahedra, whose outer faces are not cut from the input's triangles) takes the
//!   input triangle nearest its centroid ([`nearest`]) and interpolates the same way.
//! - Where the input has no UVs, surface triangles get a box projection instead: the
//!   planar UVs of the coordinate plane most facing their input triangle ([`Basis::boxed`],
//!   in the same world-space frame), so every fragment has UVs and the pieces of one
//!   input triangle share a chart.
//! - An interior (cap) triangle gets the `interior` material (appended to the input's
//!   list), its flat normal and planar UVs ([`planar`]): the projection onto the cap's
//!   plane in a basis that depends on the plane alone, the same for both sides of a bond,
//!   in world units times one scale for the whole object, so a texture lines up across a
//!   crack. Colours, where the input has them, are white (the material's colour shows).

mod nearest;
mod planar;

#[cfg(test)]
mod tests;

use glam::DVec3;
use rayon::prelude::*;

use super::kernel::{is_surface, source_triangle};
use super::types::Fracture;
use crate::TriMesh;
use crate::io::{INTERIOR_COLOR, INTERIOR_MATERIAL};
use crate::model::{Corners, Material};
use nearest::NearestTriangle;
use planar::{Basis, UvFrame, cap_bases};
pub(crate) use planar::{OWN_PLANE, SAME_PLANE_SINE};

/// What the fragments' attributes come from: the input mesh (as given to the fracture,
/// before welding: the surface tags index its triangles) and its attributes.
pub(crate) struct Source<'a> {
    pub mesh: &'a TriMesh,
    pub corners: &'a Corners,
    /// Per input triangle, its material (`None`: all material 0).
    pub material: Option<&'a [u32]>,
    /// The input's materials (`[]`: one default material).
    pub materials: &'a [Material],
}

/// The material of interior (cut) faces that the fracture appends to the input's list
/// ([`Fracture::materials`]): named `interior`, terracotta, rough.
///
/// ```
/// let m = shatter_geom::fracture::interior_material();
/// assert_eq!(m.name, "interior");
/// assert!(m.base_color_texture.is_none());
/// ```
pub fn interior_material() -> Material {
    let mut m = Material::named(INTERIOR_MATERIAL);
    m.base_color[..3].copy_from_slice(&INTERIOR_COLOR);
    m.roughness = 0.8;
    m
}

/// Sets every fragment's [`corners`](crate::fracture::Fragment::corners) and
/// [`material`](crate::fracture::Fragment::material) and the
/// fracture's [`Fracture::materials`] (the input's, then `interior`). `tags[f]` has the
/// kernel tag of each triangle of fragment `f` (see the module docs).
pub(crate) fn attach(fracture: &mut Fracture, tags: &[Vec<u64>], src: &Source<'_>) {
    let mut materials = if src.materials.is_empty() {
        vec![Material::default()]
    } else {
        src.materials.to_vec()
    };
    let interior = materials.len() as u32;
    materials.push(interior_material());
    let bases = cap_bases(&fracture.fragments, tags);
    // Surface triangles of no known source look up the nearest input triangle, unless
    // there is nothing to look up: no corner attributes and one material.
    let c = src.corners;
    let plain = c.uv.is_none()
        && c.normal.is_none()
        && c.color.is_none()
        && src.material.is_none_or(|m| m.iter().all(|&x| x == m[0]));
    let unknown = !plain
        && tags
            .iter()
            .flatten()
            .any(|&t| is_surface(t) && source_triangle(t).is_none());
    let ctx = Context {
        src,
        surface: src.material.and_then(|m| m.first()).copied().unwrap_or(0),
        interior,
        frame: UvFrame::of(&src.mesh.positions),
        bases,
        nearest: unknown.then(|| NearestTriangle::new(&src.mesh.positions, &src.mesh.triangles)),
    };
    fracture
        .fragments
        .par_iter_mut()
        .zip(tags)
        .with_max_len(1)
        .for_each(|(f, tags)| {
            let (corners, material) = ctx.fragment(&f.mesh, tags);
            f.corners = corners;
            f.material = material;
        });
    fracture.materials = materials;
}

/// Everything the per-fragment pass reads.
struct Context<'a> {
    src: &'a Source<'a>,
    /// The material of a surface triangle whose source is not looked up (the input's
    /// first triangle's: all of them have it then).
    surface: u32,
    interior: u32,
    frame: UvFrame,
    bases: crate::util::FastMap<u64, Basis>,
    nearest: Option<NearestTriangle>,
}

/// Barycentric coordinates of `p` (projected onto the triangle's plane) in `[a, b, c]`;
/// with `clamp`, clamped to the triangle (for points on it up to rounding, so a sliver
/// triangle cannot blow rounding up). A degenerate triangle gives its centroid's.
fn barycentric([a, b, c]: [DVec3; 3], p: DVec3, clamp: bool) -> [f64; 3] {
    let n = (b - a).cross(c - a);
    let nn = n.length_squared();
    if !(nn > 0.0 && nn.is_finite()) {
        return [1.0 / 3.0; 3];
    }
    let wa = (c - b).cross(p - b).dot(n) / nn;
    let wb = (a - c).cross(p - c).dot(n) / nn;
    let wc = (b - a).cross(p - a).dot(n) / nn;
    let w = [wa, wb, wc];
    if !w.iter().all(|x| x.is_finite()) {
        return [1.0 / 3.0; 3];
    }
    if !clamp {
        return w;
    }
    let w = w.map(|x| x.clamp(0.0, 1.0));
    let sum: f64 = w.iter().sum();
    if sum > 0.0 {
        w.map(|x| x / sum)
    } else {
        [1.0 / 3.0; 3]
    }
}

/// `Σ wₖ·vₖ` of three corner values, in `f64`.
fn mix<const N: usize>(v: &[[f32; N]; 3], w: [f64; 3]) -> [f64; N] {
    std::array::from_fn(|i| (0..3).map(|k| f64::from(v[k][i]) * w[k]).sum())
}

/// The unit normal of a triangle by its winding (zero when degenerate).
fn flat_normal([a, b, c]: [DVec3; 3]) -> DVec3 {
    (b - a).cross(c - a).normalize_or_zero()
}

fn to_f32<const N: usize>(v: [f64; N]) -> [f32; N] {
    v.map(|x| x as f32)
}

impl Context<'_> {
    /// The corners and materials of one fragment (`tags`: its triangles' tags).
    fn fragment(&self, mesh: &TriMesh, tags: &[u64]) -> (Corners, Vec<u32>) {
        let n = mesh.triangles.len();
        let have = self.src.corners;
        // Every fragment has UVs: the input's where it has them, else a box projection.
        let mut uv = Vec::with_capacity(n);
        let mut normal = have.normal.as_ref().map(|_| Vec::with_capacity(n));
        let mut color = have.color.as_ref().map(|_| Vec::with_capacity(n));
        let mut material = Vec::with_capacity(n);
        for (tri, &tag) in mesh.triangles.iter().zip(tags) {
            let p = tri.map(|i| mesh.positions[i as usize]);
            let source = if is_surface(tag) {
                match source_triangle(tag) {
                    Some(s) if (s as usize) < self.src.mesh.triangles.len() => {
                        Some((s as usize, true))
                    }
                    _ => self
                        .nearest
                        .as_ref()
                        .and_then(|nt| nt.nearest((p[0] + p[1] + p[2]) / 3.0))
                        .map(|s| (s, false)),
                }
            } else {
                None
            };
            match source {
                Some((s, clamp)) => {
                    let st =
                        self.src.mesh.triangles[s].map(|i| self.src.mesh.positions[i as usize]);
                    // The corners' weights in the source triangle, for the corner
                    // attributes (an input with none needs none). A face of no known
                    // source may lie off the surface (tetrahedra of a concave mesh): it
                    // is moved so that its centroid is at the nearest point of the
                    // source triangle, whose value it then takes on average.
                    let w = if have.uv.is_some() || have.normal.is_some() || have.color.is_some() {
                        let shift = if clamp {
                            DVec3::ZERO
                        } else {
                            let c = (p[0] + p[1] + p[2]) / 3.0;
                            nearest::closest_point(st, c) - c
                        };
                        p.map(|q| barycentric(st, q + shift, clamp))
                    } else {
                        [[0.0; 3]; 3]
                    };
                    material.push(self.src.material.map_or(0, |m| m[s]));
                    match &have.uv {
                        Some(v) => uv.push(w.map(|w| to_f32(mix(&v[s], w)))),
                        None => {
                            let basis = Basis::boxed(flat_normal(st));
                            uv.push(p.map(|q| self.frame.uv(&basis, q)));
                        }
                    }
                    if let (Some(out), Some(v)) = (&mut normal, &have.normal) {
                        let flat = flat_normal(p);
                        out.push(w.map(|w| {
                            let m = DVec3::from_array(mix(&v[s], w));
                            to_f32(m.try_normalize().unwrap_or(flat).to_array())
                        }));
                    }
                    if let (Some(out), Some(v)) = (&mut color, &have.color) {
                        out.push(w.map(|w| to_f32(mix(&v[s], w).map(|x| x.clamp(0.0, 1.0)))));
                    }
                }
                None => {
                    // A cap (or a surface triangle of an input without triangles).
                    material.push(if is_surface(tag) {
                        self.surface
                    } else {
                        self.interior
                    });
                    let basis = if is_surface(tag) {
                        Basis::boxed(flat_normal(p))
                    } else if tag == OWN_PLANE {
                        Basis::of_triangle(p)
                    } else {
                        self.bases
                            .get(&tag)
                            .copied()
                            .unwrap_or_else(|| Basis::of_triangle(p))
                    };
                    uv.push(p.map(|q| self.frame.uv(&basis, q)));
                    if let Some(out) = &mut normal {
                        // The plane's normal, turned to the triangle's side.
                        let n = if basis.n.dot(flat_normal(p)) < 0.0 {
                            -basis.n
                        } else {
                            basis.n
                        };
                        out.push([to_f32(n.to_array()); 3]);
                    }
                    if let Some(out) = &mut color {
                        out.push([[1.0; 4]; 3]);
                    }
                }
            }
        }
        (
            Corners {
                uv: Some(uv),
                normal,
                color,
            },
            material,
        )
    }
}
