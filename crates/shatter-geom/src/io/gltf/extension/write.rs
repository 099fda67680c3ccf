//! Writing a fracture as a GLB with the `SHATTER_fracture` extension.

use std::collections::BTreeSet;
use std::io::Write;
use std::path::Path;

use serde_json::{Value, json};

use super::{FRACTURE_EXTENSION, FRACTURE_EXTENSION_VERSION, FractureAssetMeta};
use crate::fracture::{Fracture, Fragment};
use crate::io::export::ExportMaterials;
use crate::io::{ExportObject, GlbBuilder, MeshIoError, fragment_names};

/// Writes `fracture` as a GLB: one node and mesh per fragment (named `fragment_i`, as
/// the plain GLB export names them), each triangle under its material, TEXCOORD_0,
/// NORMAL and COLOR_0 where the fragments have them, plus the `SHATTER_fracture`
/// extension: per fragment node its convex pieces and mass properties, at the root the
/// bond graph, `meta`'s anchors, material and thresholds, and the format version.
///
/// Errors: an inconsistent fracture (attributes that do not fit the triangles, an anchor
/// or a bond naming a missing fragment, interior flags that disagree with the materials)
/// is [`MeshIoError::BadObject`] (or the export's other object errors); a write failure
/// is [`MeshIoError::Io`].
///
/// ```
/// use shatter_geom::fracture::{fracture, FractureParams, Method};
/// use shatter_geom::io::{self, FractureAssetMeta};
/// use shatter_geom::{shapes, DVec3};
///
/// let params = FractureParams {
///     method: Method::Slice { pieces: 0, planes: Some(vec![(DVec3::ZERO, DVec3::X)]) },
///     seed: 0,
/// };
/// let halves = fracture(&shapes::cube(), &params)?;
/// let meta = FractureAssetMeta { anchors: vec![0], ..Default::default() };
/// let mut glb = Vec::new();
/// io::write_fracture_glb(&mut glb, &halves, &meta)?;
/// // An ordinary glTF for any reader: two fragment nodes.
/// let doc = gltf::Gltf::from_slice(&glb).unwrap();
/// assert_eq!(doc.nodes().count(), 2);
/// assert!(doc.extensions_used().any(|e| e == "SHATTER_fracture"));
/// assert_eq!(doc.extensions_required().count(), 0);
/// // And a pre-fractured asset for shatter.
/// let (back, meta_back) = io::parse_fracture(&glb, "halves.glb")?;
/// assert_eq!(back.bonds.len(), 1);
/// assert_eq!(meta_back, meta);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn write_fracture_glb<W: Write>(
    mut out: W,
    fracture: &Fracture,
    meta: &FractureAssetMeta,
) -> Result<(), MeshIoError> {
    let bytes = fracture_glb(fracture, meta)?;
    out.write_all(&bytes)
        .map_err(|e| MeshIoError::io("<GLB output>", e))
}

/// Writes `fracture` to a GLB file with the `SHATTER_fracture` extension (see
/// [`write_fracture_glb`]).
pub fn save_fracture_glb(
    path: impl AsRef<Path>,
    fracture: &Fracture,
    meta: &FractureAssetMeta,
) -> Result<(), MeshIoError> {
    let path = path.as_ref();
    let bytes = fracture_glb(fracture, meta)?;
    std::fs::write(path, bytes).map_err(|e| MeshIoError::io(path, e))
}

fn bad(object: &str, message: String) -> MeshIoError {
    MeshIoError::BadObject {
        object: object.to_string(),
        message,
    }
}

fn fracture_glb(fracture: &Fracture, meta: &FractureAssetMeta) -> Result<Vec<u8>, MeshIoError> {
    let n = fracture.fragments.len();
    let names = fragment_names(n);
    let objects = ExportObject::of_fragments(&fracture.fragments, &names);
    let given = (!fracture.materials.is_empty()).then_some(fracture.materials.as_slice());
    let materials = ExportMaterials::new(given);
    materials.validate(&objects)?;
    let interior = interior_material(&objects, &materials)?;
    check_references(fracture, meta)?;

    let mut b = GlbBuilder::new();
    let ids = b.add_materials(&materials.list);
    let mut nodes = Vec::with_capacity(n);
    for (o, f) in objects.iter().zip(&fracture.fragments) {
        let mesh = b.add_mesh(o, &|t| ids[materials.of(o, t) as usize]);
        let mut node = json!({ "name": o.name });
        if let Some(m) = mesh {
            node["mesh"] = json!(m);
        }
        node["extensions"] = json!({ FRACTURE_EXTENSION: fragment_extension(&mut b, f) });
        nodes.push(b.add_node(node));
    }
    // Nodes are added in fragment order, so fragment i is node nodes[i] (= i).
    let node = |i: u32| nodes[i as usize];
    let bonds: Vec<Value> = fracture
        .bonds
        .iter()
        .map(|bond| {
            json!({
                "a": node(bond.a),
                "b": node(bond.b),
                "area": bond.area,
                "centroid": bond.centroid.to_array(),
                "normal": bond.normal.to_array(),
            })
        })
        .collect();
    let mut root = json!({
        "version": FRACTURE_EXTENSION_VERSION,
        "fragments": nodes,
        "interiorMaterial": ids[interior as usize],
        "bonds": bonds,
        "anchors": meta.anchors.iter().map(|&a| node(a)).collect::<Vec<_>>(),
    });
    if let Some(m) = &meta.material {
        root["material"] = json!(m);
    }
    if let Some(t) = &meta.thresholds {
        root["thresholds"] = json!({
            "strength": t.strength,
            "compression": t.compression,
            "tension": t.tension,
            "shear": t.shear,
            "wear": t.wear,
        });
    }
    b.set("extensionsUsed", json!([FRACTURE_EXTENSION]));
    b.set("extensions", json!({ FRACTURE_EXTENSION: root }));
    b.finish(&nodes)
}

/// The material index (in `materials.list`) every interior triangle has and no surface
/// triangle has: what a reader turns back into the interior flags.
fn interior_material(
    objects: &[ExportObject<'_>],
    materials: &ExportMaterials,
) -> Result<u32, MeshIoError> {
    let mut inside = BTreeSet::new();
    let mut outside = BTreeSet::new();
    for o in objects {
        for t in 0..o.mesh.triangles.len() {
            let m = materials.of(o, t);
            if o.is_interior(t) {
                inside.insert(m);
            } else {
                outside.insert(m);
            }
        }
    }
    match inside.len() {
        0 => Ok(materials.interior),
        1 => {
            let m = inside.into_iter().next().unwrap_or(materials.interior);
            if outside.contains(&m) {
                Err(bad(
                    "fracture",
                    format!(
                        "material {m} is used by interior and surface triangles alike; the SHATTER_fracture extension needs one material for interior faces only"
                    ),
                ))
            } else {
                Ok(m)
            }
        }
        _ => Err(bad(
            "fracture",
            format!(
                "interior triangles use {} materials ({inside:?}); the SHATTER_fracture extension needs exactly one",
                inside.len()
            ),
        )),
    }
}

fn check_references(fracture: &Fracture, meta: &FractureAssetMeta) -> Result<(), MeshIoError> {
    let n = fracture.fragments.len();
    if let Some(a) = meta.anchors.iter().find(|&&a| a as usize >= n) {
        return Err(bad(
            "fracture",
            format!("anchor {a} names a missing fragment (there are {n})"),
        ));
    }
    if let Some((i, b)) = fracture
        .bonds
        .iter()
        .enumerate()
        .find(|(_, b)| b.a as usize >= n || b.b as usize >= n)
    {
        return Err(bad(
            "fracture",
            format!(
                "bond {i} joins fragments {} and {}, but there are {n}",
                b.a, b.b
            ),
        ));
    }
    Ok(())
}

/// The node-level extension object of one fragment; its convex pieces' points go into
/// one accessor.
fn fragment_extension(b: &mut GlbBuilder, f: &Fragment) -> Value {
    let mut ext = json!({
        "volume": f.volume,
        "centroid": f.centroid.to_array(),
        "inertia": f.inertia.to_cols_array(),
    });
    if !f.convex_pieces.is_empty() {
        let points: Vec<[f32; 3]> = f
            .convex_pieces
            .iter()
            .flatten()
            .map(|p| p.as_vec3().to_array())
            .collect();
        let counts: Vec<usize> = f.convex_pieces.iter().map(Vec::len).collect();
        let accessor = b.push_floats(&points, false, true);
        ext["convexPieces"] = json!({ "points": accessor, "counts": counts });
    }
    if f.corners.normal.is_none() {
        // The NORMAL attributes are the writer's flat normals, not the fragment's own.
        ext["flatNormals"] = json!(true);
    }
    ext
}
