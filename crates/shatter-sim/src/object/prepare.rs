//! From a spec to simulation-ready geometry: run (or fetch) the fracture, apply the scale,
//! build the convex pieces' collision shapes, find the anchored fragments and the bond
//! adjacency.

use std::sync::Arc;

use glam::Vec3;
use rapier3d::prelude::SharedShape;
use shatter_geom::fracture::{Bond, Fracture, Fragment, Roughness};
use shatter_geom::io::FileSource;
use shatter_geom::model::{Corners, Model};
use shatter_geom::{DMat3, DVec3, TriMesh};

use crate::error::SimError;
use crate::material::{MethodKind, Pattern};
use crate::object::spec::{FractureParams, FractureSource, ObjectSpec};
use crate::runtime::FractureTiming;

/// Simulation-ready geometry of one object, in its own frame with the scale applied.
#[derive(Debug, Clone)]
pub struct Prepared {
    /// The scaled fracture (meshes for the renderer, bonds for the sim).
    pub fracture: Arc<Fracture>,
    /// Per fragment, the collision shapes of its convex pieces (their hulls, and the box
    /// of a piece that is one; built once: a body built again, or a fragment attached to
    /// another body, shares them). A piece whose points span no volume has none.
    pub shapes: Vec<Vec<PieceShape>>,
    /// Per fragment, its mass (volume × density).
    pub masses: Vec<f32>,
    /// Per fragment, the diagonal of its mesh's bounding box (m).
    pub sizes: Vec<f32>,
    /// Per fragment, whether it is bonded to the world (anchored objects only).
    pub anchored: Vec<bool>,
    /// Per fragment, the indices of its bonds.
    pub adjacency: Vec<Vec<u32>>,
    /// Per fragment, whether its bonds cover its whole surface: every triangle is a cut
    /// face, and the bonds' areas add up to theirs. While all its bonds hold, nothing
    /// can touch such a fragment without passing through its neighbours first, so the
    /// clusters model gives it no colliders until then (unless
    /// [`WorldSettings::enclosed_colliders`](crate::WorldSettings::enclosed_colliders));
    /// the block of a `bench scale` landing is four fifths such bricks.
    pub enclosed: Vec<bool>,
}

/// Resolves the fracture of `spec` (unscaled): its fragments, or for an `on_impact`
/// object its intact body as one fragment ([`crate::runtime::whole`]). A mesh file and
/// the files it refers to are read from `files`.
pub fn resolve_fracture(
    spec: &ObjectSpec,
    key: &str,
    files: &dyn FileSource,
) -> Result<Arc<Fracture>, SimError> {
    if spec.runtime.timing == FractureTiming::OnImpact {
        return resolve_whole(spec, key, files);
    }
    match &spec.source {
        FractureSource::Prebuilt(f) => Ok(f.clone()),
        FractureSource::Shape { shape, params } => {
            let method = params.method.unwrap_or(spec.material.method);
            let pattern = params.pattern.unwrap_or(spec.material.pattern);
            let rough = local_roughness(spec);
            let mesh = shape.mesh();
            geom_fracture(Input::Mesh(&mesh), params, method, pattern, &rough, key)
        }
        FractureSource::MeshFile { path, params } => {
            let method = params.method.unwrap_or(spec.material.method);
            let pattern = params.pattern.unwrap_or(spec.material.pattern);
            let model = file_model(path, key, files)?;
            let rough = local_roughness(spec);
            geom_fracture(Input::Model(&model), params, method, pattern, &rough, key)
        }
    }
}

/// A mesh file's model, repaired into a closed solid as `shatter fracture` repairs it
/// (cracks welded, holes filled, open sheets dropped, crossing parts joined): a user's
/// own model, open in places or made of parts, is what the Custom object takes.
fn file_model(path: &str, key: &str, files: &dyn FileSource) -> Result<Model, SimError> {
    let model = shatter_geom::io::load_model_from(path, files)
        .map_err(|e| SimError::mesh(path, e))?
        .model;
    let options = shatter_geom::mesh::repair::RepairOptions::default();
    shatter_geom::mesh::repair::repair(&model, &options)
        .map(|(model, _)| model)
        .map_err(|source| SimError::Repair {
            key: key.to_string(),
            path: path.to_string(),
            source,
        })
}

/// The intact body of an `on_impact` object: its model (with UVs, normals and materials
/// where the file has them) as a single fragment.
fn resolve_whole(
    spec: &ObjectSpec,
    key: &str,
    files: &dyn FileSource,
) -> Result<Arc<Fracture>, SimError> {
    let model = match &spec.source {
        FractureSource::Prebuilt(f) => return Ok(f.clone()),
        FractureSource::Shape { shape, .. } => Model::from_mesh(shape.mesh()),
        FractureSource::MeshFile { path, .. } => file_model(path, key, files)?,
    };
    let whole = crate::runtime::whole(&model).map_err(|source| SimError::Fracture {
        key: key.to_string(),
        source,
    })?;
    Ok(Arc::new(whole))
}

/// The material's roughness (world units) in the object's unscaled frame, where it is
/// fractured: amplitude over the scale's geometric mean, frequency times it (a
/// non-uniform scale stretches the noise with the object).
fn local_roughness(spec: &ObjectSpec) -> Roughness {
    let s = spec.scale.as_dvec3();
    let mean = (s.x * s.y * s.z).cbrt().max(f64::MIN_POSITIVE);
    let r = spec.material.roughness;
    Roughness {
        amplitude: r.amplitude / mean,
        frequency: r.frequency * mean,
        // The object's own seed, so two objects of one material differ.
        seed: r.seed ^ spec.source.params().map_or(0, |p| p.seed),
        ..r
    }
}

/// What a precomputed fracture cuts: a built-in shape's bare mesh (drawn in the object's
/// colour), or a file's model, whose UVs, normals and materials the fragments keep.
enum Input<'a> {
    Mesh(&'a TriMesh),
    Model(&'a Model),
}

/// Runs `shatter_geom::fracture` (tetra, voronoi, slice, grid) on a mesh or model, then
/// roughens its cut faces (`rough`; off, or a grid: nothing changes).
fn geom_fracture(
    input: Input<'_>,
    params: &FractureParams,
    method: MethodKind,
    pattern: Pattern,
    rough: &Roughness,
    key: &str,
) -> Result<Arc<Fracture>, SimError> {
    use shatter_geom::fracture as geom;
    let geom_method = match method {
        MethodKind::Tetra => geom::Method::Tetra {
            random_vertices: params.random_vertices as usize,
            skip: params.skip as usize,
            center: params.center,
            placement: params.placement,
        },
        MethodKind::Voronoi => geom::Method::Voronoi {
            seeds: geom::Seeds::Pattern {
                count: params.pieces as usize,
                pattern,
                impact: None,
            },
        },
        MethodKind::Slice => geom::Method::Slice {
            pieces: params.pieces as usize,
            planes: None,
        },
        MethodKind::Grid => geom::Method::Grid {
            cells: params.grid,
            voids: params.grid_voids.clone(),
        },
    };
    let params = geom::FractureParams {
        method: geom_method,
        seed: params.seed,
    };
    let fracture = match input {
        Input::Mesh(mesh) => geom::fracture(mesh, &params),
        Input::Model(model) => geom::fracture_model(model, &params),
    }
    .map_err(|source| SimError::Fracture {
        key: key.to_string(),
        source,
    })?;
    let mut fracture = fracture;
    // A grid's joints stay flat: masonry, whatever its material's roughness.
    if !rough.is_off() && method != MethodKind::Grid {
        geom::roughen(&mut fracture, rough).map_err(|source| SimError::Fracture {
            key: format!("{key}.roughness"),
            source,
        })?;
    }
    Ok(Arc::new(fracture))
}

/// Scales `fracture` and converts it for the simulation.
pub fn prepare(fracture: &Fracture, scale: Vec3, density: f32, anchored: bool) -> Prepared {
    prepare_with(fracture, scale, density, anchored, None)
}

/// One convex piece's collision shapes, in the object's frame.
#[derive(Debug, Clone)]
pub struct PieceShape {
    /// The piece's hull.
    pub hull: SharedShape,
    /// Where the piece is an axis-aligned box (a grid's brick): its centre and half
    /// extents, for a cuboid collider ([`WorldSettings::box_colliders`]).
    ///
    /// [`WorldSettings::box_colliders`]: crate::WorldSettings::box_colliders
    pub cuboid: Option<(Vec3, Vec3)>,
}

/// The collision shapes of `fracture`'s fragments at scale `scale` (see
/// [`Prepared::shapes`]): the hull of each convex piece, built from the hull's triangles
/// where the fragment has them ([`Fragment::convex_hulls`]: a closed surface over the
/// piece's points), else computed from the points; and the box of a piece that is one.
pub fn collision_shapes(fracture: &Fracture, scale: Vec3) -> Vec<Vec<PieceShape>> {
    let s = scale.as_dvec3();
    fracture
        .fragments
        .iter()
        .map(|f| {
            f.convex_pieces
                .iter()
                .enumerate()
                .filter_map(|(k, p)| {
                    let points = || p.iter().map(|v| (*v * s).as_vec3()).collect::<Vec<Vec3>>();
                    let hull = f.convex_hulls.get(k).map(Vec::as_slice);
                    let hull = match hull.filter(|tris| closed_over(tris, p.len())) {
                        Some(tris) => SharedShape::convex_mesh(points(), tris)
                            .or_else(|| SharedShape::convex_hull(&points())),
                        None => SharedShape::convex_hull(&points()),
                    }?;
                    Some(PieceShape {
                        hull,
                        cuboid: super::cuboid::axis_aligned_box(p, s),
                    })
                })
                .collect()
        })
        .collect()
}

/// Whether `tris` is a closed surface over `n` points (at least four triangles, every
/// index below `n`, every directed edge once with its reverse once): what a convex
/// polyhedron built from triangles needs.
fn closed_over(tris: &[[u32; 3]], n: usize) -> bool {
    if tris.len() < 4 || tris.iter().flatten().any(|&i| i as usize >= n) {
        return false;
    }
    let edges = || {
        tris.iter()
            .flat_map(|t| [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])])
    };
    if n <= 256 {
        // A bit per directed edge (a piece has a few dozen corners).
        let mut seen = vec![0u64; (n * n).div_ceil(64)];
        let bit = |a: u32, b: u32| a as usize * n + b as usize;
        for (a, b) in edges() {
            let i = bit(a, b);
            if a == b || seen[i / 64] & (1 << (i % 64)) != 0 {
                return false;
            }
            seen[i / 64] |= 1 << (i % 64);
        }
        return edges().all(|(a, b)| {
            let i = bit(b, a);
            seen[i / 64] & (1 << (i % 64)) != 0
        });
    }
    let mut sorted: Vec<(u32, u32)> = edges().collect();
    sorted.sort_unstable();
    sorted.windows(2).all(|w| w[0] != w[1])
        && sorted
            .iter()
            .all(|&(a, b)| a != b && sorted.binary_search(&(b, a)).is_ok())
}

/// [`prepare`], with the collision shapes already built (by [`collision_shapes`] at the
/// same scale; a runtime cut builds them on its thread).
pub(crate) fn prepare_with(
    fracture: &Fracture,
    scale: Vec3,
    density: f32,
    anchored: bool,
    shapes: Option<Vec<Vec<PieceShape>>>,
) -> Prepared {
    let s = scale.as_dvec3();
    let shapes = shapes
        .filter(|v| v.len() == fracture.fragments.len())
        .unwrap_or_else(|| collision_shapes(fracture, scale));
    let fragments: Vec<Fragment> = fracture
        .fragments
        .iter()
        .map(|f| scale_fragment(f, s))
        .collect();
    let bonds: Vec<Bond> = fracture.bonds.iter().map(|b| scale_bond(b, s)).collect();
    let masses = fragments
        .iter()
        .map(|f| (f.volume * density as f64) as f32)
        .collect();
    let mut adjacency = vec![Vec::new(); fragments.len()];
    for (i, b) in bonds.iter().enumerate() {
        if let Some(list) = adjacency.get_mut(b.a as usize) {
            list.push(i as u32);
        }
        if let Some(list) = adjacency.get_mut(b.b as usize) {
            list.push(i as u32);
        }
    }
    let anchored = anchored_fragments(&fragments, anchored);
    let sizes = fragments
        .iter()
        .map(|f| {
            f.mesh
                .bounds()
                .map_or(0.0, |(lo, hi)| (hi - lo).length() as f32)
        })
        .collect();
    let enclosed = enclosed_fragments(&fragments, &bonds, &adjacency);
    Prepared {
        fracture: Arc::new(Fracture {
            fragments,
            bonds,
            materials: fracture.materials.clone(),
            ..Default::default()
        }),
        shapes,
        masses,
        sizes,
        anchored,
        adjacency,
        enclosed,
    }
}

/// Relative tolerance of [`enclosed_fragments`] between a fragment's cut area and its
/// bonds' areas (the two are sums over the same faces, rounded differently).
const ENCLOSED_TOLERANCE: f64 = 1e-6;

/// Per fragment, whether it is enclosed by its bonded neighbours ([`Prepared::enclosed`]).
/// A fragment with a face on the object's surface, or a cut face that no bond covers
/// (a bond left out, a rough face whose bond kept the flat area), is not.
fn enclosed_fragments(fragments: &[Fragment], bonds: &[Bond], adjacency: &[Vec<u32>]) -> Vec<bool> {
    fragments
        .iter()
        .zip(adjacency)
        .map(|(f, adjacent)| {
            let all_cut =
                f.interior.len() == f.mesh.triangles.len() && f.interior.iter().all(|&c| c);
            if adjacent.is_empty() || !all_cut {
                return false;
            }
            let cut: f64 = (0..f.mesh.triangles.len())
                .map(|t| f.mesh.triangle_area(t))
                .sum();
            let bonded: f64 = adjacent
                .iter()
                .filter_map(|&b| bonds.get(b as usize))
                .map(|b| b.area)
                .sum();
            cut > 0.0 && (cut - bonded).abs() <= ENCLOSED_TOLERANCE * cut
        })
        .collect()
}

/// Fragments with a vertex within 1e-6 (relative) of the object's lowest point.
fn anchored_fragments(fragments: &[Fragment], anchored: bool) -> Vec<bool> {
    if !anchored {
        return vec![false; fragments.len()];
    }
    let lowest = |f: &Fragment| {
        f.mesh
            .positions
            .iter()
            .map(|p| p.y)
            .fold(f64::INFINITY, f64::min)
    };
    let (lo, hi) = fragments
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), f| {
            let top = f
                .mesh
                .positions
                .iter()
                .map(|p| p.y)
                .fold(f64::NEG_INFINITY, f64::max);
            (lo.min(lowest(f)), hi.max(top))
        });
    let eps = 1e-6 * (hi - lo).abs().max(1e-9);
    fragments.iter().map(|f| lowest(f) <= lo + eps).collect()
}

/// Corner attributes of a mesh scaled by `s`: UVs and colours as they are, normals by the
/// inverse scale (the inverse transpose of a diagonal scale), renormalised.
fn scale_corners(c: &Corners, s: DVec3) -> Corners {
    let mut out = c.clone();
    if s != DVec3::ONE
        && let Some(normals) = &mut out.normal
    {
        for n in normals.iter_mut().flatten() {
            let m = (DVec3::new(f64::from(n[0]), f64::from(n[1]), f64::from(n[2])) / s)
                .normalize_or_zero();
            *n = m.as_vec3().to_array();
        }
    }
    out
}

fn scale_fragment(f: &Fragment, s: DVec3) -> Fragment {
    let det = s.x * s.y * s.z;
    // Second moment C = ½·tr(I)·Id − I scales as det·S·C·S; back to I' = tr(C')·Id − C'.
    let c = DMat3::from_diagonal(DVec3::splat(0.5 * trace(&f.inertia))) - f.inertia;
    let sm = DMat3::from_diagonal(s);
    let c2 = sm * c * sm * det;
    let inertia = DMat3::from_diagonal(DVec3::splat(trace(&c2))) - c2;
    Fragment {
        // (Keeps the fracture's mark, so a runtime cut of the fragment skips the
        // self-intersection search, where the scaling cannot have made it cross itself.)
        mesh: f.mesh.transformed(s, DVec3::ZERO),
        interior: f.interior.clone(),
        corners: scale_corners(&f.corners, s),
        material: f.material.clone(),
        convex_pieces: f
            .convex_pieces
            .iter()
            .map(|p| p.iter().map(|v| *v * s).collect())
            .collect(),
        // A positive scale keeps a hull's triangles a convex, outward surface.
        convex_hulls: f.convex_hulls.clone(),
        volume: f.volume * det,
        centroid: f.centroid * s,
        inertia,
    }
}

fn trace(m: &DMat3) -> f64 {
    m.x_axis.x + m.y_axis.y + m.z_axis.z
}

fn scale_bond(b: &Bond, s: DVec3) -> Bond {
    let n = b.normal / s;
    let len = n.length();
    Bond {
        a: b.a,
        b: b.b,
        area: b.area * (s.x * s.y * s.z) * len,
        centroid: b.centroid * s,
        normal: if len > 0.0 { n / len } else { b.normal },
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testing::box_grid_fracture;

    #[test]
    fn scaling_a_grid_scales_volumes_and_areas() {
        let f = box_grid_fracture([2, 1, 1], DVec3::ONE);
        let p = prepare(&f, Vec3::new(2.0, 3.0, 4.0), 1000.0, true);
        let v: f64 = p.fracture.fragments.iter().map(|f| f.volume).sum();
        assert!((v - 24.0).abs() < 1e-9);
        // The single bond is the x-face: area y·z = 1·0.5 → 3·4·… = 12·0.5 = 6... (unit box
        // split in x: face 1×1 scaled by 3×4).
        assert!((p.fracture.bonds[0].area - 12.0).abs() < 1e-9);
        assert!(p.anchored.iter().all(|a| *a));
        let i = p.fracture.fragments[0].inertia;
        let m = p.fracture.fragments[0].volume;
        // Box 1×3×4 at unit density: Ixx = m(9+16)/12.
        assert!((i.x_axis.x - m * 25.0 / 12.0).abs() < 1e-9);
    }

    #[test]
    fn a_piece_with_its_hull_is_built_from_it_and_a_broken_hull_is_computed_again() {
        use rapier3d::prelude::ShapeType;
        let whole = crate::runtime::whole(&shatter_geom::model::Model::from_mesh(
            shatter_geom::shapes::cube(),
        ))
        .unwrap();
        let cut =
            crate::runtime::cut_fragment(&whole, 0, DVec3::new(0.0, 0.5, 0.0), 10, 3).unwrap();
        let shapes = collision_shapes(&cut, Vec3::ONE);
        for (f, s) in cut.fragments.iter().zip(&shapes) {
            assert_eq!(s.len(), f.convex_pieces.len());
            for (piece, points) in s.iter().zip(&f.convex_pieces) {
                let shape = &piece.hull;
                assert_eq!(shape.shape_type(), ShapeType::ConvexPolyhedron);
                let poly = shape.as_convex_polyhedron().unwrap();
                // From the hull's triangles: every point of the piece is a corner.
                assert_eq!(poly.points().len(), points.len());
            }
        }
        // Hull triangles that do not close up (a file's, say) are not trusted.
        let mut broken = cut.clone();
        for f in &mut broken.fragments {
            for hull in &mut f.convex_hulls {
                hull.pop();
            }
        }
        let again = collision_shapes(&broken, Vec3::ONE);
        assert_eq!(
            again.iter().map(Vec::len).sum::<usize>(),
            shapes.iter().map(Vec::len).sum::<usize>()
        );
    }
}
