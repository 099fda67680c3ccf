//! Validation of the input mesh before fracture ([`TriMesh::validate_solid`] on the
//! welded mesh); an inward mesh — the one unambiguous repair — is flipped.

use super::error::FractureError;
use super::kernel::Piece;
use crate::TriMesh;
use crate::mesh::MeshError;

/// Checks `mesh` and returns its welded working piece, outward, plus warnings. With
/// `fragment` (the input is a fragment the fracture made, unchanged:
/// [`TriMesh::is_fracture_fragment`]) the self-intersection search is skipped.
pub(crate) fn validated_piece(
    mesh: &TriMesh,
    fragment: bool,
) -> Result<(Piece, Vec<String>), FractureError> {
    let mut warnings = Vec::new();
    let mut flip = false;
    match mesh.validate_solid_with(!fragment) {
        Ok(()) => {}
        Err(MeshError::Inward { volume }) => {
            flip = true;
            warnings.push(format!(
                "the mesh was wound inward (signed volume {volume:e}); its {} triangles were \
                 flipped",
                mesh.triangles.len()
            ));
        }
        Err(e) => return Err(FractureError::Mesh(e)),
    }
    let mut piece = Piece::from_mesh_welded(mesh);
    if flip {
        for t in &mut piece.tris {
            t.swap(1, 2);
        }
    }
    if piece.volume() <= 0.0 {
        return Err(FractureError::Mesh(MeshError::ZeroVolume));
    }
    Ok((piece, warnings))
}
