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
//! kernel, Apache-2.0, no C dependencies) has that engine (`Manifold::rebuild_solid`:
//! exact predicates and rational constructions, arrangement, winding-number
//! classification, one rounding to f64 per output vertex) and keeps, per output
//! triangle, the input face it lies on, from which the attributes are interpolated
//! again. Its cold debug build (with its dependencies: dashu, clipper2-rust, num-traits,
//! rustc-hash) took 53 s of wall time (16 s of CPU) on the project's two-core machine
//! while another build ran. The union only runs when the shells do cross or touch.
//!
//! Each output triangle lies on one input triangle (its face id); its corners take that
//! triangle's material and its UVs, normals and colours interpolated barycentrically at
//! the corner's position, so surface attributes survive the union unchanged.

use glam::DVec3;
use manifold_rust::manifold::Manifold;
use manifold_rust::types::{Error as ManifoldStatus, MeshGL64, WindingRule};

use super::soup::{Corner, Soup};

/// Why the union failed.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct UnionFailed(pub String);

/// The union of the soup's closed shells (all wound outward, cavities inward), as a new
/// soup with the attributes carried over.
pub(super) fn union(soup: &Soup) -> Result<Soup, UnionFailed> {
    // A panic inside the crate on some input must not take the caller down: it becomes
    // an error naming the step.
    std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| union_of(soup))).unwrap_or_else(|_| {
        Err(UnionFailed(
            "the union of the closed parts failed (an internal error of manifold-rust)".into(),
        ))
    })
}

fn union_of(soup: &Soup) -> Result<Soup, UnionFailed> {
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
    let np = out.num_prop as usize;
    let pos: Vec<DVec3> = out
        .vert_properties
        .chunks_exact(np.max(3))
        .map(|v| DVec3::new(v[0], v[1], v[2]))
        .collect();
    let mut result = Soup {
        pos,
        tris: Vec::new(),
        corners: crate::model::Corners {
            uv: soup.corners.uv.as_ref().map(|_| Vec::new()),
            normal: soup.corners.normal.as_ref().map(|_| Vec::new()),
            color: soup.corners.color.as_ref().map(|_| Vec::new()),
        },
        material: Vec::new(),
    };
    let pinched = separate_pinches(&mut result.pos, &out.tri_verts);
    for (t, tri) in out.tri_verts.chunks_exact(3).enumerate() {
        let tri = [tri[0] as u32, tri[1] as u32, tri[2] as u32];
        if tri.iter().any(|&v| v as usize >= result.pos.len()) {
            return Err(UnionFailed("the union gave an invalid mesh".into()));
        }
        let source = out
            .face_id
            .get(t)
            .map(|&f| f as usize)
            .filter(|&f| f < soup.tris.len());
        let (corners, material) = match source {
            Some(s) => (
                tri.map(|v| interpolate(soup, s, result.pos[v as usize])),
                soup.material[s],
            ),
            None => (
                [Corner::default(); 3],
                soup.material.first().copied().unwrap_or(0),
            ),
        };
        let flat = result.flat_normal(tri);
        let corners = if source.is_none() {
            corners.map(|c| Corner { normal: flat, ..c })
        } else {
            corners
        };
        result.push(tri, corners, material);
    }
    let _ = pinched;
    Ok(result)
}

/// Where the union's surface touches itself (two fans of one position, which Manifold
/// keeps as separate vertices: solids that meet at a point or along an edge), moves each
/// copy into its own solid, against its fan's area-weighted normal, by a millionth of
/// its mean edge length, so the two fans no longer share a position (a solid's
/// validation refuses a self-touching surface) and do not cross: both retreat from the
/// contact. (Moving along the surface, towards the fan's neighbours, can push a copy of
/// a flat fan across the coplanar fan it touches.) Returns how many copies moved.
fn separate_pinches(pos: &mut [DVec3], tri_verts: &[u64]) -> usize {
    use std::collections::HashMap;
    let mut by_position: HashMap<[u64; 3], Vec<usize>> = HashMap::new();
    for (v, p) in pos.iter().enumerate() {
        by_position
            .entry(crate::mesh::position_key(*p))
            .or_default()
            .push(v);
    }
    let shared: Vec<Vec<usize>> = by_position.into_values().filter(|g| g.len() > 1).collect();
    if shared.is_empty() {
        return 0;
    }
    let mut normal = vec![DVec3::ZERO; pos.len()];
    let mut length = vec![0.0f64; pos.len()];
    let mut count = vec![0u32; pos.len()];
    for tri in tri_verts.chunks_exact(3) {
        let t = [tri[0] as usize, tri[1] as usize, tri[2] as usize];
        if t.iter().any(|&v| v >= pos.len()) {
            continue;
        }
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
    let mut moved = 0;
    for group in shared {
        for v in group {
            let n = normal[v].normalize_or_zero();
            if count[v] > 0 && n != DVec3::ZERO {
                let step = 1e-6 * length[v] / f64::from(count[v]);
                pos[v] -= n * step;
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
