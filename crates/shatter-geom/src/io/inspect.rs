//! What a loaded model holds, without fracturing it: shells (closed or open), holes,
//! volume, materials, attribute sets and the reader's warnings.
//!
//! This is what the loader and the mesh checks know, plus what the repair of real-world
//! input ([`crate::mesh::repair`]) would do to the model, in [`Inspection::repair`].

use serde::Serialize;

use super::LoadedModel;
use crate::TriMesh;
use crate::util::UnionFind;

/// One connected part of the welded mesh.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ShellReport {
    /// Its triangles.
    pub triangles: usize,
    /// No boundary and no non-manifold edges.
    pub closed: bool,
    /// Boundary loops (holes) of an open shell.
    pub holes: usize,
    /// Edges used by more than two triangles.
    pub non_manifold_edges: usize,
    /// Edges whose two triangles are wound the same way.
    pub inconsistent_edges: usize,
    /// Signed volume (meaningful for a closed shell; positive when wound outward).
    pub signed_volume: f64,
}

/// A material, as reported.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct MaterialReport {
    /// Its name.
    pub name: String,
    /// Triangles that use it.
    pub triangles: usize,
    /// Linear RGBA base colour.
    pub base_color: [f32; 4],
    /// Its base-colour texture's image name and encoding (`png`, `jpg`), if any.
    pub texture: Option<String>,
}

/// What [`inspect`] found.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Inspection {
    /// Triangles.
    pub triangles: usize,
    /// Distinct vertex positions.
    pub vertices: usize,
    /// Connected parts, largest first.
    pub shells: Vec<ShellReport>,
    /// Boundary loops over all shells.
    pub holes: usize,
    /// Triangles of zero area.
    pub degenerate_triangles: usize,
    /// Signed volume of the whole mesh (meaningful when every shell is closed).
    pub signed_volume: f64,
    /// Whether the mesh is a valid solid as it is (closed, manifold, outward): what
    /// fracture takes without repair.
    pub solid: bool,
    /// Bounding box (min, max).
    pub bounds: Option<([f64; 3], [f64; 3])>,
    /// The materials, in the model's order.
    pub materials: Vec<MaterialReport>,
    /// UV sets (0 or 1: TEXCOORD_0 is what shatter carries).
    pub uv_sets: usize,
    /// Whether the corners carry normals.
    pub normals: bool,
    /// Whether the corners carry colours.
    pub colors: bool,
    /// The reader's warnings.
    pub warnings: Vec<String>,
    /// What repair would do: one line per repair with its counts (empty when the model
    /// needs none), or why it would refuse the model ("2 open sheets and no closed part").
    pub repair: Vec<String>,
    /// Whether repair would refuse the model.
    pub repair_refused: bool,
}

/// Inspects a loaded model.
///
/// ```
/// use shatter_geom::io::{self, MeshFormat};
/// // A tetrahedron and a lone triangle.
/// let obj = b"v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nv 5 5 5\nv 6 5 5\nv 5 6 5\n\
///             f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\nf 5 6 7\n";
/// let loaded = io::parse_model(obj, MeshFormat::Obj, "two.obj").unwrap();
/// let report = io::inspect(&loaded);
/// assert_eq!(report.shells.len(), 2);
/// assert!(report.shells[0].closed);
/// assert_eq!((report.shells[1].closed, report.shells[1].holes), (false, 1));
/// assert!(!report.solid);
/// // Repair would drop the lone triangle.
/// assert_eq!(report.repair, vec!["dropped 1 open sheet (1 triangle) enclosing no volume"]);
/// ```
pub fn inspect(loaded: &LoadedModel) -> Inspection {
    let model = &loaded.model;
    let mesh = model.mesh.welded();
    let whole = mesh.check();
    let n = mesh.positions.len();
    let mut parts = UnionFind::new(n);
    for t in &mesh.triangles {
        parts.union(t[0] as usize, t[1] as usize);
        parts.union(t[1] as usize, t[2] as usize);
    }
    let mut by_root: std::collections::HashMap<usize, Vec<[u32; 3]>> = Default::default();
    for &t in &mesh.triangles {
        by_root
            .entry(parts.find(t[0] as usize))
            .or_default()
            .push(t);
    }
    let mut shells: Vec<ShellReport> = by_root
        .into_values()
        .map(|triangles| {
            let part = TriMesh::new(mesh.positions.clone(), triangles);
            let r = part.check();
            ShellReport {
                triangles: part.triangles.len(),
                closed: r.is_closed(),
                holes: boundary_loops(&part),
                non_manifold_edges: r.non_manifold_edges,
                inconsistent_edges: r.inconsistent_edges,
                signed_volume: r.signed_volume,
            }
        })
        .collect();
    shells.sort_by(|a, b| {
        b.triangles
            .cmp(&a.triangles)
            .then(b.signed_volume.abs().total_cmp(&a.signed_volume.abs()))
    });
    let materials = model
        .materials
        .iter()
        .enumerate()
        .map(|(i, m)| MaterialReport {
            name: m.name.clone(),
            triangles: model.material.iter().filter(|&&k| k as usize == i).count(),
            base_color: m.base_color,
            texture: m
                .base_color_texture
                .as_ref()
                .map(|t| format!("{} ({})", t.image.name, t.image.format.extension())),
        })
        .collect();
    let (repair, repair_refused) =
        match crate::mesh::repair::repair(model, &crate::mesh::repair::RepairOptions::default()) {
            Ok((_, report)) => (report.warnings(), false),
            Err(e) => (vec![format!("refused: {e}")], true),
        };
    Inspection {
        triangles: mesh.triangles.len(),
        vertices: n,
        holes: shells.iter().map(|s| s.holes).sum(),
        shells,
        degenerate_triangles: whole.degenerate_triangles,
        signed_volume: whole.signed_volume,
        solid: whole.is_solid(),
        bounds: mesh.bounds().map(|(lo, hi)| (lo.to_array(), hi.to_array())),
        materials,
        uv_sets: usize::from(model.corners.uv.is_some()),
        normals: model.corners.normal.is_some(),
        colors: model.corners.color.is_some(),
        warnings: loaded.warnings.iter().map(|w| w.to_string()).collect(),
        repair,
        repair_refused,
    }
}

/// Boundary loops of a welded mesh: the connected groups of edges used by one triangle.
fn boundary_loops(mesh: &TriMesh) -> usize {
    let mut uses: std::collections::HashMap<(u32, u32), usize> = Default::default();
    for t in &mesh.triangles {
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            *uses.entry((a.min(b), a.max(b))).or_default() += 1;
        }
    }
    let boundary: Vec<(u32, u32)> = uses
        .into_iter()
        .filter(|&(_, n)| n == 1)
        .map(|(e, _)| e)
        .collect();
    if boundary.is_empty() {
        return 0;
    }
    let mut loops = UnionFind::new(mesh.positions.len());
    for &(a, b) in &boundary {
        loops.union(a as usize, b as usize);
    }
    let mut roots: Vec<usize> = boundary
        .iter()
        .map(|&(a, _)| loops.find(a as usize))
        .collect();
    roots.sort_unstable();
    roots.dedup();
    roots.len()
}
