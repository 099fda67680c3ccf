//! Validation of the input mesh before fracture ([`TriMesh::validate_solid`] on the
//! welded mesh); an inward mesh — the one unambiguous repair — is flipped.

use super::kernel::Piece;
use super::params::FractureError;
use crate::TriMesh;
use crate::mesh::MeshError;

/// Checks `mesh` and returns its welded working piece, outward, plus warnings.
pub(crate) fn validated_piece(mesh: &TriMesh) -> Result<(Piece, Vec<String>), FractureError> {
    let mut warnings = Vec::new();
    let mut flip = false;
    match mesh.validate_solid() {
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
