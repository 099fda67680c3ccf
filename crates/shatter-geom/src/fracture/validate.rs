//! Validation of the input mesh before fracture: finite, indexed correctly, a closed
//! two-manifold consistently wound, with a volume; an inward mesh is flipped.

use std::collections::HashMap;

use super::params::FractureError;
use super::piece::Piece;
use crate::TriMesh;

/// Checks `mesh` and returns its welded working piece, outward, plus warnings.
pub(crate) fn validated_piece(mesh: &TriMesh) -> Result<(Piece, Vec<String>), FractureError> {
    if mesh.triangles.is_empty() {
        return Err(FractureError::EmptyMesh);
    }
    if let Some(vertex) = mesh.positions.iter().position(|p| !p.is_finite()) {
        return Err(FractureError::NonFinite { vertex });
    }
    for (triangle, t) in mesh.triangles.iter().enumerate() {
        if let Some(&index) = t.iter().find(|&&i| i as usize >= mesh.positions.len()) {
            return Err(FractureError::BadIndex {
                triangle,
                index,
                vertices: mesh.positions.len(),
            });
        }
    }
    let mut piece = Piece::from_mesh_welded(mesh);
    let degenerate_triangles = mesh.triangles.len() - piece.tris.len();
    let counts = edge_counts(&piece);
    if counts != (0, 0, 0) || degenerate_triangles > 0 {
        return Err(FractureError::NotSolid {
            boundary_edges: counts.0,
            non_manifold_edges: counts.1,
            inconsistent_edges: counts.2,
            degenerate_triangles,
        });
    }
    let mut warnings = Vec::new();
    let v = piece.volume();
    if v == 0.0 || !v.is_finite() {
        return Err(FractureError::ZeroVolume);
    }
    if v < 0.0 {
        for t in &mut piece.tris {
            t.swap(1, 2);
        }
        warnings.push(format!(
            "the mesh was wound inward (volume {v:e}); its {} triangles were flipped",
            piece.tris.len()
        ));
    }
    Ok((piece, warnings))
}

/// `(boundary, non-manifold, inconsistent)` edge counts of a welded piece.
pub(crate) fn edge_counts(piece: &Piece) -> (usize, usize, usize) {
    // Per undirected edge: (uses a→b with a<b, uses b→a).
    let mut uses: HashMap<(u32, u32), (u32, u32)> = HashMap::new();
    for t in &piece.tris {
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            let e = uses.entry((a.min(b), a.max(b))).or_insert((0, 0));
            if a < b {
                e.0 += 1;
            } else {
                e.1 += 1;
            }
        }
    }
    let (mut boundary, mut non_manifold, mut inconsistent) = (0, 0, 0);
    for &(f, r) in uses.values() {
        match f + r {
            1 => boundary += 1,
            2 if f != 1 => inconsistent += 1,
            2 => {}
            _ => non_manifold += 1,
        }
    }
    (boundary, non_manifold, inconsistent)
}
