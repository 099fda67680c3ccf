//! The union of closed shells that overlap or cross: the solid `{ w ≥ 1 }` (for closed
//! shells wound outward the generalized winding number is an integer, so this is
//! `w ≥ ½`).
//!
//! Why a crate: computing the union means intersecting every pair of crossing triangles,
//! triangulating each triangle along its intersection curves, and keeping the pieces
//! whose two sides differ in winding number — the mesh-arrangement method of Zhou,
//! Grinspun, Zorin and Jacobson (2016). Done in floating point it fails on exactly the
//! inputs it is for (coplanar faces of CAD parts, edges through edges); done right it
//! needs exact rational constructions. `manifold-rust` (a pure-Rust port of the Manifold
//! kernel, Apache-2.0, no C dependencies) has that engine (its `robust` module: exact
//! predicates and rational constructions, the arrangement, winding numbers per cell).
//! Its cold debug build (with its dependencies: dashu, clipper2-rust, num-traits,
//! rustc-hash) took 53 s of wall time (16 s of CPU) on the project's two-core machine
//! while another build ran. The union only runs when the shells do cross or touch.
//!
//! Two assemblies of the result. The crate's own (`Manifold::rebuild_solid`) gives a
//! lean mesh, but collapses short and collinear edges at its tolerance, which moves
//! vertices off the exact surface: where parts meet face to face (Khronos'
//! 2CylinderEngine) it leaves pairs of triangles crossing deeper than the fracture's
//! tolerance (488 of them). When it does, the arrangement's kept pieces are assembled
//! here instead (`exact_assembly`): each exact vertex rounded to `f64` once (the crate's
//! own correctly rounded value), every piece keeping its triangulation, pinched vertices
//! (solids meeting at a point or along an edge) split into one copy per fan, each moved
//! a hair into its own fan. What rounding leaves touching or crossing is measured by the
//! repair and judged by the validation ([`CROSSING_TOLERANCE`]). The lean assembly stays
//! first because the exact one keeps every vertex the arrangement's triangulation made,
//! which the tetra method's clipping has been seen to handle less well (a duplicated
//! face in one of the spider-like WusonOBJ's tetra fragments).
//!
//! Each output triangle lies on one input triangle (the piece's source); its corners
//! take that triangle's material and its UVs, normals and colours interpolated
//! barycentrically at the corner's position, so surface attributes survive the union
//! unchanged.
//!
//! [`CROSSING_TOLERANCE`]: crate::mesh::CROSSING_TOLERANCE

use std::collections::HashMap;

use glam::DVec3;
use manifold_rust::linalg::Vec3;
use manifold_rust::manifold::Manifold;
use manifold_rust::robust::{cells, intersection_graph, pairing};
use manifold_rust::types::{Error as ManifoldStatus, MeshGL64, OpType, WindingRule};

use super::soup::{Corner, Soup};

/// How far a pinched vertex's copies move into their own fans, as a fraction of the
/// model's bounding-box diagonal: far above the fracture's rounding-length edges (1e-13
/// of a piece), far below anything visible.
const PINCH_STEP: f64 = 1e-11;

/// Why the union failed.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct UnionFailed(pub String);

/// A union and how it was made.
pub(super) struct United {
    pub soup: Soup,
    /// Coordinates snapped together before it (0: the input as it was).
    pub snapped: usize,
}

/// The union of the soup's closed shells (all wound outward, cavities inward), as a new
/// soup with the attributes carried over; `diagonal` is the model's size. Tried in this
/// order, the first whose triangles cross no deeper than the validation's tolerance
/// kept: the crate's lean assembly of the input as it is; of the input with its
/// coordinates snapped ([`SNAP_TOLERANCE`]); the exact assembly of the snapped input.
pub(super) fn union(soup: &Soup, diagonal: f64) -> Result<United, UnionFailed> {
    // A panic inside the crate on some input must not take the caller down: it becomes
    // an error naming the step.
    std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| union_of(soup, diagonal)))
        .unwrap_or_else(|_| {
            Err(UnionFailed(
                "the union of the closed parts failed (an internal error of manifold-rust)".into(),
            ))
        })
}

/// How far the union's pinches retreat, as a fraction of their edges' mean length
/// ([`retreat_pinches`]).
const PINCH_RETREAT: f64 = 1e-6;

/// Coordinates closer than this fraction of the model's size are snapped together, axis
/// by axis, when the input's own union crosses itself (`weld::coordinates`).
pub(super) const SNAP_TOLERANCE: f64 = 1e-8;

fn union_of(soup: &Soup, diagonal: f64) -> Result<United, UnionFailed> {
    let tolerance = crate::mesh::CROSSING_TOLERANCE * diagonal;
    let shallow = |s: &Soup| super::crossings(s).1 <= tolerance;
    if let Ok(lean) = lean_union(soup)
        && shallow(&lean)
    {
        return Ok(United {
            soup: lean,
            snapped: 0,
        });
    }
    let mut snapped_soup = soup.clone();
    let snapped = super::weld::coordinates(&mut snapped_soup, SNAP_TOLERANCE * diagonal);
    if snapped > 0 {
        super::weld::exact(&mut snapped_soup);
        super::clean::degenerate(&mut snapped_soup);
        super::clean::duplicates(&mut snapped_soup);
        if let Ok(lean) = lean_union(&snapped_soup)
            && shallow(&lean)
        {
            return Ok(United {
                soup: lean,
                snapped,
            });
        }
    }
    Ok(United {
        soup: exact_assembly(&snapped_soup, diagonal)?,
        snapped,
    })
}

/// The crate's lean assembly, repeated while rounding leaves triangles touching (at most
/// three more rounds).
fn lean_union(soup: &Soup) -> Result<Soup, UnionFailed> {
    let mut lean = crate_assembly(soup)?;
    for _ in 0..3 {
        if !super::needs_union(&lean) {
            break;
        }
        lean = crate_assembly(&lean)?;
    }
    Ok(lean)
}

/// The crate's own assembly of the union (see the module docs), with the attributes of
/// the input triangle each output triangle lies on (its face id).
fn crate_assembly(soup: &Soup) -> Result<Soup, UnionFailed> {
    let mut mesh = MeshGL64 {
        num_prop: 3,
        ..MeshGL64::default()
    };
    mesh.vert_properties = soup.pos.iter().flat_map(|p| p.to_array()).collect();
    mesh.tri_verts = soup.tris.iter().flat_map(|t| t.map(u64::from)).collect();
    mesh.face_id = (0..soup.tris.len() as u64).collect();
    let input = Manifold::from_mesh_gl64_robust(&mesh);
    if input.status() != ManifoldStatus::NoError {
        return Err(UnionFailed(format!(
            "the closed parts could not be imported for their union ({:?})",
            input.status()
        )));
    }
    let solid = input.rebuild_solid(WindingRule::Positive);
    if solid.status() != ManifoldStatus::NoError {
        return Err(UnionFailed(format!(
            "the union of the closed parts failed ({:?})",
            solid.status()
        )));
    }
    let out = solid.get_mesh_gl64(-1);
    let np = (out.num_prop as usize).max(3);
    let mut pos: Vec<DVec3> = out
        .vert_properties
        .chunks_exact(np)
        .map(|v| DVec3::new(v[0], v[1], v[2]))
        .collect();
    let mut tris = Vec::with_capacity(out.tri_verts.len() / 3);
    for tri in out.tri_verts.chunks_exact(3) {
        let tri = [tri[0] as u32, tri[1] as u32, tri[2] as u32];
        if tri.iter().any(|&v| v as usize >= pos.len()) {
            return Err(UnionFailed("the union gave an invalid mesh".into()));
        }
        tris.push(tri);
    }
    retreat_pinches(&mut pos, &tris, PINCH_RETREAT);
    let sources = out.face_id.iter().map(|&f| f as usize);
    Ok(with_attributes(soup, pos, tris, sources))
}

/// `tris` over `pos` as a soup whose triangles take the attributes of their source
/// triangles in `soup` (a source out of range: the first material, flat normals).
fn with_attributes(
    soup: &Soup,
    pos: Vec<DVec3>,
    tris: Vec<[u32; 3]>,
    sources: impl Iterator<Item = usize>,
) -> Soup {
    let mut result = Soup {
        pos,
        tris: Vec::with_capacity(tris.len()),
        corners: crate::model::Corners {
            uv: soup.corners.uv.as_ref().map(|_| Vec::new()),
            normal: soup.corners.normal.as_ref().map(|_| Vec::new()),
            color: soup.corners.color.as_ref().map(|_| Vec::new()),
        },
        material: Vec::with_capacity(tris.len()),
    };
    let mut sources = sources;
    for tri in tris {
        match sources.next().filter(|&s| s < soup.tris.len()) {
            Some(s) => {
                let corners = tri.map(|v| interpolate(soup, s, result.pos[v as usize]));
                result.push(tri, corners, soup.material[s]);
            }
            None => {
                let [a, b, c] = tri.map(|v| result.pos[v as usize]);
                let n = (b - a)
                    .cross(c - a)
                    .normalize_or_zero()
                    .as_vec3()
                    .to_array();
                let corner = Corner {
                    normal: n,
                    ..Corner::default()
                };
                let material = soup.material.first().copied().unwrap_or(0);
                result.push(tri, [corner; 3], material);
            }
        }
    }
    result
}

/// The union assembled from the exact arrangement (see the module docs).
fn exact_assembly(soup: &Soup, diagonal: f64) -> Result<Soup, UnionFailed> {
    let p: Vec<[Vec3; 3]> = soup
        .tris
        .iter()
        .map(|t| {
            t.map(|i| {
                let q = soup.pos[i as usize];
                Vec3::new(q.x, q.y, q.z)
            })
        })
        .collect();
    let graph = intersection_graph::build_graph(&p, &[]);
    let complex = cells::build_cells(&graph);
    let wind = cells::windings(&graph, &complex, [&p, &[]]);
    let pieces = cells::extract(&graph, &complex, &wind, OpType::Add, WindingRule::Positive);
    let tris: Vec<[u32; 3]> = pieces.iter().map(|piece| piece.vi).collect();
    // One vertex per (exact vertex, fan copy): the crate's plan splits pinched vertices
    // so that each edge has two triangles.
    let plan = pairing::plan_vertex_splits(
        &tris,
        cells::VertTables {
            verts: &graph.verts,
            verts_f64: &graph.verts_f64,
        },
    );
    let mut index: HashMap<(u32, u32), u32> = HashMap::new();
    let mut pos: Vec<DVec3> = Vec::new();
    let mut out: Vec<[u32; 3]> = Vec::with_capacity(tris.len());
    for (t, tri) in tris.iter().enumerate() {
        out.push(std::array::from_fn(|c| {
            let split = plan.as_ref().map_or(0, |p| p[3 * t + c]);
            let vid = tri[c];
            *index.entry((vid, split)).or_insert_with(|| {
                let q = graph
                    .verts_f64
                    .get(vid as usize)
                    .copied()
                    .unwrap_or_default();
                pos.push(DVec3::new(q.x, q.y, q.z));
                (pos.len() - 1) as u32
            })
        }));
    }
    if pos.iter().any(|p| !p.is_finite()) {
        return Err(UnionFailed("the union gave a non-finite vertex".into()));
    }
    split_fans(&mut pos, &mut out);
    separate_pinches(&mut pos, &out, PINCH_STEP * diagonal);
    if pieces
        .iter()
        .any(|piece| piece.mesh != 0 || piece.tri >= soup.tris.len())
    {
        return Err(UnionFailed("the union gave an invalid mesh".into()));
    }
    Ok(with_attributes(
        soup,
        pos,
        out,
        pieces.iter().map(|piece| piece.tri),
    ))
}

/// The crate assembly's pinches (copies of one position, one per fan) retreat each into
/// its own solid, against its fan's area-weighted normal, by `fraction` of its mean
/// edge length (the union: [`PINCH_RETREAT`]), so the two fans no longer share a
/// position and do not cross: both retreat from the contact. (Moving along the
/// surface, towards the fan's neighbours, can push a copy of a flat fan across the
/// coplanar fan it touches.) Also the tetra method's exact cells'
/// (`fracture::methods::tetra::cells::exact`).
pub(crate) fn retreat_pinches(pos: &mut [DVec3], tris: &[[u32; 3]], fraction: f64) {
    let shared = shared_positions(pos);
    if shared.is_empty() {
        return;
    }
    let mut normal = vec![DVec3::ZERO; pos.len()];
    let mut length = vec![0.0f64; pos.len()];
    let mut count = vec![0u32; pos.len()];
    for t in tris {
        let t = t.map(|v| v as usize);
        let n = (pos[t[1]] - pos[t[0]]).cross(pos[t[2]] - pos[t[0]]);
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            normal[a] += n;
            let d = pos[a].distance(pos[b]);
            length[a] += d;
            count[a] += 1;
            length[b] += d;
            count[b] += 1;
        }
    }
    for v in shared.into_iter().flatten() {
        if let Some(n) = normal[v].try_normalize()
            && count[v] > 0
        {
            pos[v] -= n * (fraction * length[v] / f64::from(count[v]));
        }
    }
}

/// Groups of vertices at one position (more than one each).
fn shared_positions(pos: &[DVec3]) -> Vec<Vec<usize>> {
    let mut by_position: HashMap<[u64; 3], Vec<usize>> = HashMap::new();
    for (v, p) in pos.iter().enumerate() {
        by_position
            .entry(crate::mesh::position_key(*p))
            .or_default()
            .push(v);
    }
    by_position.into_values().filter(|g| g.len() > 1).collect()
}

/// Gives each fan of triangles around a vertex (joined through the edges they share
/// there) a vertex of its own: solids that touch at a single point share no edge there,
/// which the crate's plan (made for edges with more than two triangles) leaves alone.
/// New copies take the same position.
fn split_fans(pos: &mut Vec<DVec3>, tris: &mut [[u32; 3]]) {
    let mut around: Vec<Vec<(u32, u8)>> = vec![Vec::new(); pos.len()];
    for (t, tri) in tris.iter().enumerate() {
        for (k, &v) in tri.iter().enumerate() {
            around[v as usize].push((t as u32, k as u8));
        }
    }
    for (v, corners) in around.iter().enumerate() {
        if corners.len() < 2 {
            continue;
        }
        // Union the corners whose triangles share an edge (v, w).
        let mut sets = crate::util::UnionFind::new(corners.len());
        let mut by_other: HashMap<u32, usize> = HashMap::new();
        for (i, &(t, k)) in corners.iter().enumerate() {
            let tri = tris[t as usize];
            for w in [tri[(k as usize + 1) % 3], tri[(k as usize + 2) % 3]] {
                match by_other.get(&w) {
                    Some(&j) => sets.union(i, j),
                    None => {
                        by_other.insert(w, i);
                    }
                }
            }
        }
        let mut copy_of_root: HashMap<usize, u32> = HashMap::new();
        for (i, &(t, k)) in corners.iter().enumerate() {
            let root = sets.find(i);
            let first = sets.find(0);
            if root == first {
                continue;
            }
            let copy = *copy_of_root.entry(root).or_insert_with(|| {
                pos.push(pos[v]);
                (pos.len() - 1) as u32
            });
            tris[t as usize][k as usize] = copy;
        }
    }
}

/// Where the union's surface touches itself (solids that meet at a point or along an
/// edge: copies of one position, one per fan), moves each copy by `step` into its own
/// fan, towards the mean direction of its triangles' centroids, so the fans no longer
/// share a position (a solid's validation refuses a self-touching surface) and each
/// stays on its own side of the contact. Returns how many copies moved.
fn separate_pinches(pos: &mut [DVec3], tris: &[[u32; 3]], step: f64) -> usize {
    let shared = shared_positions(pos);
    if shared.is_empty() {
        return 0;
    }
    let mut inward = vec![DVec3::ZERO; pos.len()];
    for t in tris {
        let centroid = (pos[t[0] as usize] + pos[t[1] as usize] + pos[t[2] as usize]) / 3.0;
        for &v in t {
            inward[v as usize] += (centroid - pos[v as usize]).normalize_or_zero();
        }
    }
    let mut moved = 0;
    for group in shared {
        for v in group {
            if let Some(d) = inward[v].try_normalize() {
                pos[v] += d * step;
                moved += 1;
            }
        }
    }
    moved
}

/// Triangle `s`'s attributes at `p` (projected onto its plane; barycentric weights).
fn interpolate(soup: &Soup, s: usize, p: DVec3) -> Corner {
    let [a, b, c] = soup.tris[s].map(|i| soup.pos[i as usize]);
    let n = (b - a).cross(c - a);
    let nn = n.length_squared();
    if nn <= 0.0 || !nn.is_finite() {
        return soup.corner(s, 0);
    }
    let wa = (c - b).cross(p - b).dot(n) / nn;
    let wb = (a - c).cross(p - c).dot(n) / nn;
    let wc = 1.0 - wa - wb;
    let mut corner = Corner::mix(&[
        (wa, soup.corner(s, 0)),
        (wb, soup.corner(s, 1)),
        (wc, soup.corner(s, 2)),
    ]);
    // Interpolated normals are renormalised.
    let len = corner.normal.iter().map(|x| x * x).sum::<f32>().sqrt();
    if len > 0.0 {
        corner.normal = corner.normal.map(|x| x / len);
    }
    corner
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::TriMesh;
    use crate::model::Model;
    use crate::shapes;

    fn soup_of(meshes: &[TriMesh]) -> Soup {
        let mut soup = Soup::from_model(&Model::from_mesh(TriMesh::merge(meshes)));
        super::super::weld::exact(&mut soup);
        soup
    }

    #[test]
    fn the_exact_assembly_of_two_crossing_cubes_is_their_union() {
        let a = shapes::cube();
        let b = a.transformed(DVec3::ONE, DVec3::splat(0.5));
        let union = exact_assembly(&soup_of(&[a, b]), 3.0).unwrap();
        let mesh = union.mesh();
        assert_eq!(mesh.validate_solid(), Ok(()));
        assert!(
            (mesh.volume() - (2.0 - 0.125)).abs() < 1e-12,
            "{}",
            mesh.volume()
        );
        assert!(mesh.self_intersections(1).is_empty());
        // Every triangle came from an input triangle: one material, as the input's.
        assert!(union.material.iter().all(|&m| m == 0));
    }

    #[test]
    fn cubes_meeting_at_a_corner_get_a_vertex_each_moved_apart() {
        // Two unit cubes sharing only the point (0.5, 0.5, 0.5).
        let a = shapes::cube();
        let b = a.transformed(DVec3::ONE, DVec3::ONE);
        let union = exact_assembly(&soup_of(&[a, b]), 4.0).unwrap();
        let mesh = union.mesh();
        let report = mesh.check();
        assert_eq!(report.non_manifold_vertices, 0, "{report:?}");
        assert_eq!(report.components, 2);
        assert_eq!(mesh.validate_solid(), Ok(()));
        // The two copies of the corner are a hair apart, each inside its own cube's
        // corner region (its coordinates moved towards its own cube).
        let corner = DVec3::splat(0.5);
        let near: Vec<DVec3> = mesh
            .positions
            .iter()
            .copied()
            .filter(|p| p.distance(corner) < 1e-6)
            .collect();
        assert_eq!(near.len(), 2, "{near:?}");
        assert!(near.iter().any(|p| p.cmplt(corner).all()));
        assert!(near.iter().any(|p| p.cmpgt(corner).all()));
        assert!((mesh.volume() - 2.0).abs() < 1e-9);
    }

    #[test]
    fn fans_around_a_vertex_are_split() {
        // Two triangles sharing vertex 0 only, and a third joined to the first by the
        // edge (0, 1): vertex 0 has two fans.
        let mut pos = vec![
            DVec3::ZERO,
            DVec3::X,
            DVec3::Y,
            -DVec3::X,
            -DVec3::Y,
            DVec3::Z,
        ];
        let mut tris = vec![[0, 1, 2], [0, 3, 4], [0, 5, 1]];
        split_fans(&mut pos, &mut tris);
        assert_eq!(pos.len(), 7);
        assert_eq!(pos[6], DVec3::ZERO);
        assert_eq!(tris[0][0], tris[2][0]);
        assert_ne!(tris[0][0], tris[1][0]);
    }
}
