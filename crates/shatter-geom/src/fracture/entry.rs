//! The public entry point: validate the mesh, run the method, build the fragments.

use glam::DVec3;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rayon::prelude::*;

use super::attributes::{Source, attach};
use super::bonds::merge::merge_small_with;
use super::error::FractureError;
use super::kernel::convex::{MAX_PIECES, convex_pieces, decomposed_with_hulls, fine_pieces};
use super::kernel::inherit::{Part, inherited_pieces};
use super::kernel::{Piece, Plane, is_surface, mesh_scale};
use super::methods::grid::{Grid, bricks, is_box, sliced};
use super::methods::slice::{random_planes, slice};
use super::methods::tetra::{SLIVER_VOLUME_FRACTION, TetraOptions, tetra};
use super::methods::voronoi::{Cells, Neighbours, delaunay_neighbours, voronoi_cells};
use super::normalize::{Frame, check_cancellation, check_volume_sum};
use super::params::{FractureParams, Method, Pattern, Seeds};
use super::seeds::patterns::{seeds, splinter_weights};
use super::types::{Bond, Fracture, Fragment};
use super::validate::validated_piece;
use crate::TriMesh;
use crate::mesh::mass_properties;
use crate::model::{Corners, Model};

/// Relative distance (of the mesh's size) within which a vertex counts as on a plane.
const PLANE_EPS: f64 = 1e-10;

/// Fractures a closed mesh.
///
/// The mesh is welded (vertices at equal positions merged) and must then be a closed,
/// consistently wound two-manifold; an inward-wound mesh is flipped, with a warning in
/// [`Fracture::warnings`]. The same parameters and seed always give the same result.
///
/// ```
/// use shatter_geom::fracture::{fracture, FractureParams, Method, Seeds};
/// use shatter_geom::{DVec3, TriMesh};
///
/// // A unit cube, 8 shared corners.
/// let p = |x: f64, y: f64, z: f64| DVec3::new(x, y, z);
/// let cube = TriMesh::new(
///     vec![p(0., 0., 0.), p(1., 0., 0.), p(1., 1., 0.), p(0., 1., 0.),
///          p(0., 0., 1.), p(1., 0., 1.), p(1., 1., 1.), p(0., 1., 1.)],
///     vec![[0, 2, 1], [0, 3, 2], [4, 5, 6], [4, 6, 7], [0, 1, 5], [0, 5, 4],
///          [1, 2, 6], [1, 6, 5], [2, 3, 7], [2, 7, 6], [3, 0, 4], [3, 4, 7]],
/// );
/// let params = FractureParams {
///     method: Method::Voronoi { seeds: Seeds::count(8) },
///     seed: 1,
/// };
/// let result = fracture(&cube, &params)?;
/// assert!(result.fragments.len() >= 2);
/// assert!((result.total_volume() - 1.0).abs() < 1e-9);
/// assert!(result.bonds.iter().all(|b| b.a < b.b && b.area > 0.0));
/// # Ok::<(), shatter_geom::fracture::FractureError>(())
/// ```
///
/// Any finite size works or is refused: the mesh is fractured in a local frame scaled to
/// about a unit box (exactly, by powers of two; each axis on its own when one is over a
/// million times thinner than another, with a metric that keeps Voronoi cells the
/// input's) and the results are mapped back. A volume, inertia tensor or bond area beyond
/// `f64` is refused with [`FractureError::OutOfRange`].
pub fn fracture(mesh: &TriMesh, params: &FractureParams) -> Result<Fracture, FractureError> {
    let (mut result, tags) = fracture_tagged(mesh, params, Convex::Decomposed)?;
    let none = Corners::default();
    let source = Source {
        mesh,
        corners: &none,
        material: None,
        materials: &[],
    };
    attach(&mut result, &tags, &source);
    Ok(result)
}

/// Fractures a model: [`fracture`] of its mesh, the fragments carrying its attributes.
///
/// Each fragment's surface triangles keep the material of the input triangle they lie
/// on, and their corners the input's UVs, normals and colours interpolated at the
/// corners' positions (exact along cut edges; seams stay seams). Interior (cut)
/// triangles get the `interior` material, appended to the model's list in
/// [`Fracture::materials`], flat normals, white colours and planar UVs: a projection
/// onto the cut's plane, in a basis of the plane alone and one world-space scale for
/// the whole object (one over its largest extent), so both sides of a crack map a point
/// to the same UV. Every fragment has UVs: where the model has none, surface triangles get
/// a box projection in the same frame. Normals and colours the model lacks stay absent.
///
/// ```
/// use shatter_geom::fracture::{fracture_model, FractureParams, Method};
/// use shatter_geom::{model::Model, shapes, DVec3};
///
/// let mut model = Model::from_mesh(shapes::cube());
/// // A UV per corner: u = x + ½, v = y + ½ on every face (the cube spans −½..½).
/// let uv: Vec<[[f32; 2]; 3]> = model.mesh.triangles.iter()
///     .map(|t| t.map(|i| { let p = model.mesh.positions[i as usize];
///                          [(p.x + 0.5) as f32, (p.y + 0.5) as f32] }))
///     .collect();
/// model.corners.uv = Some(uv);
/// let params = FractureParams {
///     method: Method::Slice { pieces: 0, planes: Some(vec![(DVec3::ZERO, DVec3::X)]) },
///     seed: 0,
/// };
/// let result = fracture_model(&model, &params)?;
/// assert_eq!(result.materials.last().unwrap().name, "interior");
/// for f in &result.fragments {
///     let uv = f.corners.uv.as_ref().unwrap();
///     for (t, tri) in f.mesh.triangles.iter().enumerate() {
///         if f.interior[t] { continue; }
///         // A cut corner at x = 0 gets u = ½, as on the input's triangle.
///         for k in 0..3 {
///             let p = f.mesh.positions[tri[k] as usize];
///             assert!((uv[t][k][0] as f64 - (p.x + 0.5)).abs() < 1e-6);
///         }
///     }
/// }
/// # Ok::<(), shatter_geom::fracture::FractureError>(())
/// ```
pub fn fracture_model(model: &Model, params: &FractureParams) -> Result<Fracture, FractureError> {
    fracture_model_with(model, params, Convex::Decomposed)
}

/// [`fracture_model`] without the fragments' convex pieces: every
/// [`Fragment::convex_pieces`] and [`Fragment::convex_hulls`] is empty, the rest (surfaces,
/// attributes, materials, bonds, volumes) is the same. For a result that is only written
/// as meshes (an OBJ carries no convex pieces) and not simulated: decomposing each
/// fragment into convex pieces for collision is about 40 % of a Voronoi fracture's work.
///
/// ```
/// use shatter_geom::fracture::{fracture_model, fracture_model_surfaces, FractureParams};
/// use shatter_geom::{model::Model, shapes};
///
/// let model = Model::from_mesh(shapes::bird());
/// let params = FractureParams::voronoi(20, 3);
/// let surfaces = fracture_model_surfaces(&model, &params)?;
/// let mut full = fracture_model(&model, &params)?;
/// assert!(surfaces.fragments.iter().all(|f| f.convex_pieces.is_empty()));
/// // The same fracture, but for the pieces.
/// for f in &mut full.fragments {
///     assert!(!f.convex_pieces.is_empty());
///     f.convex_pieces.clear();
///     f.convex_hulls.clear();
/// }
/// assert_eq!(surfaces, full);
/// # Ok::<(), shatter_geom::fracture::FractureError>(())
/// ```
pub fn fracture_model_surfaces(
    model: &Model,
    params: &FractureParams,
) -> Result<Fracture, FractureError> {
    fracture_model_with(model, params, Convex::None)
}

/// Fractures fragment `f` of `fracture`: [`fracture_model`] of the fragment (its mesh,
/// corner attributes and materials), whose new fragments take their convex pieces from
/// the fragment's own.
///
/// With a Voronoi method, each new fragment's convex pieces are the fragment's pieces
/// clipped by the new fragment's cell and bounding box ([`Fragment::convex_pieces`], with
/// their hulls in [`Fragment::convex_hulls`]): a cell is convex and so is a piece, so
/// each is a convex polytope, found by clipping alone, and their union covers the new
/// fragment as the fragment's pieces covered it. Pieces under 1e-3 of a new fragment are
/// left out, as the decomposition leaves them out. This is much cheaper than decomposing
/// every new fragment (a runtime cut) and nests: the new fragments can be cut the same
/// way. Pieces are as close to their fragment as the fragment's were to it: give the
/// solid first cut fine pieces ([`intact`]). The other methods, and a fragment without
/// convex pieces, decompose the new fragments as [`fracture_model`] does; pieces without
/// hulls (a fracture read from a file) get theirs computed first. An `f` past the
/// fragments is [`FractureError::BadFragment`].
///
/// ```
/// use shatter_geom::fracture::{fracture_fragment, intact, FractureParams};
/// use shatter_geom::{model::Model, shapes};
///
/// let whole = intact(&Model::from_mesh(shapes::cube()))?;
/// assert_eq!(whole.fragments[0].convex_hulls.len(), 1);
/// let cut = fracture_fragment(&whole, 0, &FractureParams::voronoi(12, 3))?;
/// assert!((cut.total_volume() - 1.0).abs() < 1e-9);
/// for f in &cut.fragments {
///     // One piece per fragment (the cube is one convex piece), with its hull.
///     assert_eq!(f.convex_pieces.len(), 1);
///     assert_eq!(f.convex_hulls.len(), 1);
/// }
/// # Ok::<(), shatter_geom::fracture::FractureError>(())
/// ```
pub fn fracture_fragment(
    fracture: &Fracture,
    f: usize,
    params: &FractureParams,
) -> Result<Fracture, FractureError> {
    let fragment = fracture
        .fragments
        .get(f)
        .ok_or(FractureError::BadFragment {
            fragment: f,
            reason: "no such fragment",
        })?;
    let model = Model {
        mesh: fragment.mesh.clone(),
        corners: fragment.corners.clone(),
        material: fragment.material.clone(),
        materials: fracture.materials.clone(),
    };
    let convex = if fragment.convex_pieces.is_empty() {
        Convex::Decomposed
    } else {
        Convex::Clipped(&fragment.convex_pieces, &fragment.convex_hulls)
    };
    fracture_model_with(&model, params, convex)
}

/// `model` as one fragment, not cut, whose convex pieces are made to be cut again
/// ([`fracture_fragment`]): up to 64 of them, each convex within 1 % of the model's
/// size (where [`fracture_model`] stops at 16), each with its hull
/// ([`Fragment::convex_hulls`]). An object fractured at runtime starts as this.
///
/// ```
/// use shatter_geom::fracture::intact;
/// use shatter_geom::{model::Model, shapes};
///
/// let bird = intact(&Model::from_mesh(shapes::bird()))?;
/// let f = &bird.fragments[0];
/// assert!(f.convex_pieces.len() > 16);
/// assert_eq!(f.convex_hulls.len(), f.convex_pieces.len());
/// assert_eq!(bird.validate(Some(shapes::bird().volume())), Ok(()));
/// # Ok::<(), shatter_geom::fracture::FractureError>(())
/// ```
pub fn intact(model: &Model) -> Result<Fracture, FractureError> {
    fracture_model_with(model, &FractureParams::voronoi(1, 0), Convex::Fine)
}

/// [`fracture_model`], with the convex pieces made as `convex` says.
fn fracture_model_with(
    model: &Model,
    params: &FractureParams,
    convex: Convex<'_>,
) -> Result<Fracture, FractureError> {
    model.check()?;
    let (mut result, tags) = fracture_tagged(&model.mesh, params, convex)?;
    let source = Source {
        mesh: &model.mesh,
        corners: &model.corners,
        material: Some(&model.material),
        materials: &model.materials,
    };
    attach(&mut result, &tags, &source);
    Ok(result)
}

/// Where the fragments' convex pieces come from.
#[derive(Debug, Clone, Copy)]
enum Convex<'a> {
    /// None: the fragments' surfaces only ([`fracture_model_surfaces`]).
    None,
    /// Each fragment decomposed on its own ([`convex_pieces`]).
    Decomposed,
    /// Each fragment decomposed finely, with the pieces' hulls ([`fine_pieces`]).
    Fine,
    /// The input's own convex pieces (points, and their hulls when known; in the input's
    /// frame), clipped by each Voronoi cell ([`inherited_pieces`]).
    Clipped(&'a [Vec<DVec3>], &'a [Vec<[u32; 3]>]),
}

/// [`Convex`] in the local frame.
enum LocalConvex {
    None,
    Decomposed,
    Fine,
    Clipped(Vec<Part>),
}

impl LocalConvex {
    /// `convex` with its pieces mapped into `frame` (a piece the frame cannot hold, or
    /// that spans no volume, is left out).
    fn of(convex: Convex<'_>, frame: &Frame) -> LocalConvex {
        match convex {
            Convex::None => LocalConvex::None,
            Convex::Decomposed => LocalConvex::Decomposed,
            Convex::Fine => LocalConvex::Fine,
            Convex::Clipped(points, hulls) => {
                let hulls = (hulls.len() == points.len()).then_some(hulls);
                let parts: Vec<Part> = points
                    .iter()
                    .enumerate()
                    .filter_map(|(k, piece)| {
                        let local: Option<Vec<DVec3>> =
                            piece.iter().map(|&p| frame.point_to_local(p)).collect();
                        Part::new(&local?, hulls.map(|h| h[k].as_slice()))
                    })
                    .collect();
                if parts.is_empty() {
                    LocalConvex::Decomposed
                } else {
                    LocalConvex::Clipped(parts)
                }
            }
        }
    }
}

/// The fracture itself: the fragments (without attributes) and, per fragment, the
/// kernel tag of each triangle (surface tags naming `mesh`'s triangles). The mesh is
/// moved and scaled into a local frame, fractured there and mapped back.
fn fracture_tagged(
    mesh: &TriMesh,
    params: &FractureParams,
    convex: Convex<'_>,
) -> Result<(Fracture, Vec<Vec<u64>>), FractureError> {
    mesh.validate_indices()?;
    let frame = Frame::of(mesh);
    // The parameters in the local frame, and given seeds' Delaunay neighbours, depend on
    // the frame alone: found while the mesh is checked (a mesh error still comes first).
    let (checked, local) = rayon::join(
        || validated_piece(&frame.mesh_to_local(mesh), mesh.is_fracture_fragment()),
        || {
            local_params(&frame, params).map(|local| {
                let neighbours = given_seed_neighbours(&frame, &local);
                (local, neighbours)
            })
        },
    );
    let (piece, warnings) = checked?;
    // Refuse before the work when the whole mesh's own quantities are beyond f64.
    check_cancellation(&piece.pos, &piece.tris)?;
    let (volume, _, inertia) = mass_properties(&piece.pos, &piece.tris);
    frame.volume_to_world(volume, "the mesh's volume")?;
    frame.inertia_to_world(inertia, "the mesh's inertia tensor")?;
    let (params, given_neighbours) = local?;
    // Tetra with skipped surface vertices fills only the points' hull, inside the mesh;
    // a grid with voids leaves them out.
    let partial = match &params.method {
        Method::Tetra { skip, .. } => *skip > 0,
        Method::Grid { voids, .. } => !voids.is_empty(),
        _ => false,
    };
    let convex = LocalConvex::of(convex, &frame);
    let (local, tags) =
        fracture_local(piece, warnings, &params, &convex, &frame, given_neighbours)?;
    // A cut that lost or gained volume is refused, not returned (features far below the
    // cut tolerance, as a body squashed beside a 1e33 spike).
    if !partial || frame.is_per_axis() {
        check_volume_sum(&local, volume)?;
    }
    // Every result is checked as `Fracture::validate` checks it (closed 2-manifold
    // fragments, no faces back to back, well-formed bonds): a wrong one is refused.
    local.validate(None)?;
    let mut result = frame.fracture_to_world(local)?;
    for f in &mut result.fragments {
        f.mesh.mark_solid();
    }
    Ok((result, tags))
}

/// The Delaunay neighbours of the seeds the local parameters `local` give (Voronoi with
/// [`Seeds::Points`]), under `frame`'s metric, as [`fracture_local`] would find them;
/// `None` when the seeds are generated or the frame is per axis (where there are no
/// neighbours to find), and `Some(None)` when the seeds have no tetrahedralization.
fn given_seed_neighbours(frame: &Frame, local: &FractureParams) -> Option<Option<Neighbours>> {
    let Method::Voronoi {
        seeds: Seeds::Points(points),
    } = &local.method
    else {
        return None;
    };
    (!frame.is_per_axis()).then(|| delaunay_neighbours(points, frame.metric()))
}

/// The parameters with the user's points and planes in the local frame.
fn local_params(frame: &Frame, params: &FractureParams) -> Result<FractureParams, FractureError> {
    let points = |list: &[DVec3], what: &'static str| {
        check_points(list, what)?;
        list.iter()
            .enumerate()
            .map(|(index, &p)| {
                frame
                    .point_to_local(p)
                    .ok_or(FractureError::TooFar { what, index })
            })
            .collect::<Result<Vec<_>, _>>()
    };
    let method = match &params.method {
        Method::Voronoi { seeds } => Method::Voronoi {
            seeds: match seeds {
                Seeds::Pattern {
                    count,
                    pattern,
                    impact,
                } => Seeds::Pattern {
                    count: *count,
                    pattern: *pattern,
                    impact: match impact {
                        Some(i) => Some(points(std::slice::from_ref(i), "impact point")?[0]),
                        None => None,
                    },
                },
                Seeds::Points(list) => Seeds::Points(points(list, "seed")?),
            },
        },
        Method::Slice { pieces, planes } => Method::Slice {
            pieces: *pieces,
            planes: match planes {
                Some(list) => Some(
                    list.iter()
                        .enumerate()
                        .map(|(index, &(p, n))| {
                            let bad = FractureError::BadInput {
                                what: "plane",
                                index,
                            };
                            if !p.is_finite() || !n.is_finite() {
                                return Err(bad);
                            }
                            let q = frame.point_to_local(p).ok_or(FractureError::TooFar {
                                what: "plane",
                                index,
                            })?;
                            Ok((q, frame.normal_to_local(n).ok_or(bad)?))
                        })
                        .collect::<Result<Vec<_>, _>>()?,
                ),
                None => None,
            },
        },
        m @ (Method::Tetra { .. } | Method::Grid { .. }) => m.clone(),
    };
    Ok(FractureParams {
        method,
        seed: params.seed,
    })
}

/// The fracture of the validated `piece`, in the local frame; `metric` keeps Voronoi
/// distances those of the input. `given_neighbours`: the given seeds' Delaunay
/// neighbours when already found ([`given_seed_neighbours`]).
fn fracture_local(
    piece: Piece,
    mut warnings: Vec<String>,
    params: &FractureParams,
    convex: &LocalConvex,
    frame: &Frame,
    given_neighbours: Option<Option<Neighbours>>,
) -> Result<(Fracture, Vec<Vec<u64>>), FractureError> {
    let metric = frame.metric();
    let mut rng = ChaCha8Rng::seed_from_u64(params.seed);
    let scale = mesh_scale(&piece);
    let eps = PLANE_EPS * scale;
    let volume = piece.volume();
    let (fragments, tags, bonds) = match &params.method {
        Method::Tetra {
            random_vertices,
            skip,
            center,
            placement,
        } => {
            let opt = TetraOptions {
                random_vertices: *random_vertices,
                skip: *skip,
                center: *center,
                placement: *placement,
                exact: !frame.is_per_axis(),
            };
            tetra(&piece, volume, &opt, eps, &mut rng, &mut warnings)?
        }
        Method::Voronoi { seeds: given } => {
            let points = match given {
                Seeds::Points(list) => {
                    check_points(list, "seed")?;
                    if list.is_empty() {
                        return Err(FractureError::TooFewPieces(0));
                    }
                    list.clone()
                }
                Seeds::Pattern {
                    count,
                    pattern,
                    impact,
                } => {
                    if *count < 1 {
                        return Err(FractureError::TooFewPieces(*count));
                    }
                    if let Some(i) = impact {
                        check_points(std::slice::from_ref(i), "impact point")?;
                    }
                    seeds(&piece, *count, *pattern, *impact, &mut rng)
                }
            };
            let metric = if given.pattern() == Some(Pattern::Splinter) {
                metric * splinter_weights(frame.half_extents())
            } else {
                metric
            };
            // Per axis, the seeds' Delaunay neighbours under the metric would need
            // coordinates squashed up to 1e-150-fold, beyond what the exact predicates
            // take: every other seed is then a candidate neighbour instead.
            let neighbours = match given_neighbours {
                Some(found) => found,
                None if frame.is_per_axis() => None,
                None => delaunay_neighbours(&points, metric),
            };
            let cells = voronoi_cells(&piece, &points, metric, eps, neighbours);
            finish_cells(cells, volume, eps, convex, &mut warnings)
        }
        Method::Slice { pieces, planes } => {
            let planes = match planes {
                Some(list) => {
                    for (index, (p, n)) in list.iter().enumerate() {
                        if !p.is_finite() || !n.is_finite() || n.length_squared() == 0.0 {
                            return Err(FractureError::BadInput {
                                what: "plane",
                                index,
                            });
                        }
                    }
                    list.clone()
                }
                None => {
                    if *pieces < 1 {
                        return Err(FractureError::TooFewPieces(*pieces));
                    }
                    random_planes(&piece, *pieces, &mut rng)
                }
            };
            let (pieces, bonds) = slice(&piece, &planes, eps);
            finish_cut(pieces, bonds, volume, eps, convex, &mut warnings)
        }
        Method::Grid { cells, voids } => {
            let total = cells
                .iter()
                .try_fold(1u64, |n, &c| n.checked_mul(u64::from(c)));
            if total.is_none_or(|n| n == 0 || n >= u64::from(u32::MAX)) {
                return Err(FractureError::BadGrid { cells: *cells });
            }
            let grid = Grid::over(&piece, *cells, voids);
            if is_box(&piece) {
                bricks(&grid)
            } else {
                let (pieces, bonds) = sliced(&piece, &grid, eps);
                // Parts below the sliver threshold merge into a neighbour, as in the
                // other methods, but a fine grid's whole cells are not slivers: at most
                // a tenth of a cell is.
                let sliver = volume.min(0.1 * grid.cell_volume() / SLIVER_VOLUME_FRACTION);
                finish_cut(pieces, bonds, sliver, eps, convex, &mut warnings)
            }
        }
    };
    let mut fragments: Vec<Fragment> = fragments;
    if matches!(convex, LocalConvex::None) {
        // The methods that make their pieces as they go (a tetrahedron, a brick) make
        // them at no cost; the surfaces-only result has none, whatever the method.
        for f in &mut fragments {
            f.convex_pieces = Vec::new();
            f.convex_hulls = Vec::new();
        }
    }
    if fragments.is_empty() {
        return Err(FractureError::NoFragments);
    }
    let result = Fracture {
        fragments,
        bonds,
        materials: Vec::new(),
        warnings,
    };
    Ok((result, tags))
}

fn check_points(list: &[DVec3], what: &'static str) -> Result<(), FractureError> {
    match list.iter().position(|p| !p.is_finite()) {
        Some(index) => Err(FractureError::BadInput { what, index }),
        None => Ok(()),
    }
}

/// Fragments of a cut method: small pieces merged into neighbours, then built (each
/// decomposed into convex pieces unless `convex` asks for none); with each fragment's
/// triangle tags.
fn finish_cut(
    pieces: Vec<Piece>,
    bonds: Vec<Bond>,
    volume: f64,
    eps: f64,
    convex: &LocalConvex,
    warnings: &mut Vec<String>,
) -> (Vec<Fragment>, Vec<Vec<u64>>, Vec<Bond>) {
    let n = pieces.len();
    let cells = Cells {
        pieces,
        bonds,
        seed: vec![0; n],
        planes: Vec::new(),
    };
    let convex = match convex {
        LocalConvex::None => &LocalConvex::None,
        _ => &LocalConvex::Decomposed,
    };
    finish_cells(cells, volume, eps, convex, warnings)
}

/// [`finish_cut`] of a Voronoi cut, the fragments' convex pieces made as `convex` says
/// (clipped pieces by the cells each fragment was made of).
fn finish_cells(
    cells: Cells,
    volume: f64,
    eps: f64,
    convex: &LocalConvex,
    warnings: &mut Vec<String>,
) -> (Vec<Fragment>, Vec<Vec<u64>>, Vec<Bond>) {
    let Cells {
        pieces,
        bonds,
        seed,
        planes,
    } = cells;
    let (pieces, bonds, merged, new_id) =
        merge_small_with(pieces, bonds, SLIVER_VOLUME_FRACTION * volume, &[], eps);
    // Per fragment, the cells it was made of.
    let mut made_of: Vec<Vec<u32>> = vec![Vec::new(); pieces.len()];
    for (i, &f) in new_id.iter().enumerate() {
        if let (Some(list), Some(&s)) = (made_of.get_mut(f as usize), seed.get(i))
            && !list.contains(&s)
        {
            list.push(s);
        }
    }
    if merged.lonely > 0 {
        warnings.push(format!(
            "{} fragments below the sliver threshold had no other fragment to merge into",
            merged.lonely
        ));
    }
    if merged.unjoined > 0 {
        warnings.push(format!(
            "{} fragments below the sliver threshold were kept apart: joining them to a \
             neighbour would not give a closed surface",
            merged.unjoined
        ));
    }
    // Independent per fragment, so in parallel (order kept).
    let (fragments, tags) = pieces
        .into_par_iter()
        .zip(made_of)
        .with_max_len(1)
        .map(|(mut p, made_of)| {
            p.weld();
            let cells: Vec<&[Plane]> = made_of
                .iter()
                .filter_map(|&s| planes.get(s as usize).map(Vec::as_slice))
                .collect();
            (built_fragment(&p, convex, &cells, eps), p.tags)
        })
        .unzip();
    (fragments, tags, bonds)
}

/// The fragment of the closed piece `p`, its convex pieces made as `convex` says (when
/// clipped, by `cells`, the planes of the cells it was made of).
fn built_fragment(p: &Piece, convex: &LocalConvex, cells: &[&[Plane]], eps: f64) -> Fragment {
    match convex {
        LocalConvex::None => fragment_without_pieces(p),
        LocalConvex::Decomposed => fragment(p),
        LocalConvex::Fine => {
            let mut f = fragment_without_pieces(p);
            (f.convex_pieces, f.convex_hulls) = fine_pieces(p);
            f
        }
        LocalConvex::Clipped(parts) => {
            let mut f = fragment_without_pieces(p);
            (f.convex_pieces, f.convex_hulls) = inherited_pieces(p, f.volume, parts, cells, eps)
                .unwrap_or_else(|| decomposed_with_hulls(p, MAX_PIECES));
            f
        }
    }
}

/// A fragment from a closed cut piece.
pub(crate) fn fragment(p: &Piece) -> Fragment {
    let mut f = fragment_without_pieces(p);
    f.convex_pieces = convex_pieces(p);
    f
}

/// [`fragment`] without its convex pieces.
fn fragment_without_pieces(p: &Piece) -> Fragment {
    let (volume, centroid, inertia) = mass_properties(&p.pos, &p.tris);
    Fragment {
        mesh: TriMesh::new(p.pos.clone(), p.tris.clone()),
        interior: p.tags.iter().map(|&t| !is_surface(t)).collect(),
        // Set at the end, from the tags (see `attributes`).
        corners: Corners::default(),
        material: Vec::new(),
        convex_pieces: Vec::new(),
        convex_hulls: Vec::new(),
        volume,
        centroid,
        inertia,
    }
}
