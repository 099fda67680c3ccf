//! Reading a pre-fractured asset: the glTF's fragment meshes and materials plus the
//! `SHATTER_fracture` extension, every index, length and number checked.

use std::collections::HashMap;
use std::path::Path;

use glam::{DMat3, DVec3};
use serde::de::DeserializeOwned;
use serde_json::Value;

use super::{BreakThresholds, FRACTURE_EXTENSION, FRACTURE_EXTENSION_VERSION, FractureAssetMeta};
use crate::TriMesh;
use crate::fracture::{Bond, Fracture, Fragment};
use crate::io::MeshIoError;
use crate::io::context::ReadContext;
use crate::io::files::{FileSource, FileSystem, NoFiles};
use crate::io::gltf::accessor::{self, Expect};
use crate::io::gltf::container;
use crate::io::gltf::json::{self, Root};
use crate::io::gltf::read::{Decoded, Materials, decode_primitive};
use crate::model::{Corners, Material};

const FLOAT: u32 = 5126;

/// Reads a pre-fractured asset written by [`write_fracture_glb`](super::write_fracture_glb)
/// (a `.glb`, or a `.gltf` whose buffers and images are read relative to it): the
/// fragments' meshes with their attributes and materials from the glTF (positions are
/// the file's `f32`; triangles grouped by material, in the file's order), their convex
/// pieces and mass properties, the bonds, and the extension's [`FractureAssetMeta`].
///
/// A file without the extension is [`MeshIoError::NoFractureExtension`]; a malformed
/// extension (a bad index, a wrong length, a non-finite number, a bond to a missing
/// fragment, ...) is [`MeshIoError::FractureExtension`] naming what is wrong; a broken
/// glTF is [`MeshIoError::Gltf`]. Never a panic.
pub fn read_fracture(path: impl AsRef<Path>) -> Result<(Fracture, FractureAssetMeta), MeshIoError> {
    let path = path.as_ref();
    let files = FileSystem;
    let bytes = files.read(path).map_err(|e| MeshIoError::io(path, e))?;
    parse(&bytes, path, &files)
}

/// [`read_fracture`] from bytes in memory (a GLB; `name` is used in messages). Nothing
/// else is read, so a `.gltf` with external buffers fails.
///
/// ```
/// use shatter_geom::io::{self, MeshIoError};
/// use shatter_geom::shapes;
/// let mut plain = Vec::new();
/// io::write_glb(&mut plain, &[io::ExportObject::new("cube", &shapes::cube())]).unwrap();
/// let err = io::parse_fracture(&plain, "cube.glb").unwrap_err();
/// assert!(matches!(err, MeshIoError::NoFractureExtension { .. }));
/// assert!(err.to_string().contains("SHATTER_fracture"));
/// ```
pub fn parse_fracture(
    bytes: &[u8],
    name: impl AsRef<Path>,
) -> Result<(Fracture, FractureAssetMeta), MeshIoError> {
    parse(bytes, name.as_ref(), &NoFiles)
}

fn parse(
    bytes: &[u8],
    path: &Path,
    files: &dyn FileSource,
) -> Result<(Fracture, FractureAssetMeta), MeshIoError> {
    let gltf_error = |message: String| MeshIoError::Gltf {
        path: path.to_path_buf(),
        message,
    };
    let parts = container::split(bytes).map_err(gltf_error)?;
    let root = container::document(parts.json).map_err(gltf_error)?;
    let value: Value =
        serde_json::from_slice(parts.json).map_err(|e| gltf_error(format!("invalid JSON: {e}")))?;
    let Some(ext) = value
        .get("extensions")
        .and_then(|e| e.get(FRACTURE_EXTENSION))
    else {
        return Err(MeshIoError::NoFractureExtension {
            path: path.to_path_buf(),
        });
    };
    let mut cx = ReadContext::new(path, files);
    let buffers = container::buffers(&cx, &root, parts.bin);
    let reader = Reader {
        root: &root,
        value: &value,
        buffers: &buffers,
    };
    let result = reader.read(ext, &mut cx);
    let (mut fracture, meta) = result.map_err(|message| MeshIoError::FractureExtension {
        path: path.to_path_buf(),
        message,
    })?;
    fracture.warnings = cx.warnings.iter().map(|w| w.to_string()).collect();
    Ok((fracture, meta))
}

/// A required field of `obj`, deserialized; the error names `what.key`.
fn field<T: DeserializeOwned>(obj: &Value, key: &str, what: &str) -> Result<T, String> {
    let v = obj
        .get(key)
        .ok_or_else(|| format!("{what} has no `{key}`"))?;
    serde_json::from_value(v.clone()).map_err(|e| format!("{what}.{key}: {e}"))
}

/// An optional field of `obj` (absent or null: `None`).
fn optional<T: DeserializeOwned>(obj: &Value, key: &str, what: &str) -> Result<Option<T>, String> {
    match obj.get(key) {
        None | Some(Value::Null) => Ok(None),
        Some(_) => field(obj, key, what).map(Some),
    }
}

fn finite<const N: usize>(v: [f64; N], what: &str) -> Result<[f64; N], String> {
    if v.iter().all(|x| x.is_finite()) {
        Ok(v)
    } else {
        Err(format!("{what} is not finite"))
    }
}

struct Reader<'r> {
    root: &'r Root,
    value: &'r Value,
    buffers: &'r [Result<Vec<u8>, String>],
}

impl Reader<'_> {
    fn read(
        &self,
        ext: &Value,
        cx: &mut ReadContext<'_>,
    ) -> Result<(Fracture, FractureAssetMeta), String> {
        let what = "the root extension";
        if !ext.is_object() {
            return Err(format!("{what} is not a JSON object"));
        }
        let version: u32 = field(ext, "version", what)?;
        if version == 0 || version > FRACTURE_EXTENSION_VERSION {
            return Err(format!(
                "version {version}: this reader reads version {FRACTURE_EXTENSION_VERSION}"
            ));
        }
        let nodes: Vec<usize> = field(ext, "fragments", what)?;
        let mut fragment_of: HashMap<usize, u32> = HashMap::new();
        for (i, &n) in nodes.iter().enumerate() {
            if n >= self.root.nodes.len() {
                return Err(format!(
                    "fragments[{i}] names node {n}, but the file has {} nodes",
                    self.root.nodes.len()
                ));
            }
            if fragment_of.insert(n, i as u32).is_some() {
                return Err(format!("fragments lists node {n} twice"));
            }
        }
        let fragment = |n: usize, what: &str| {
            fragment_of
                .get(&n)
                .copied()
                .ok_or_else(|| format!("{what} names node {n}, which is not a fragment"))
        };
        let interior: usize = field(ext, "interiorMaterial", what)?;
        let count = self.root.materials.len();
        if interior >= count {
            return Err(format!(
                "interiorMaterial is {interior}, but the file has {count} materials"
            ));
        }
        let mut reader = Materials::new(self.root);
        let materials: Vec<Material> = (0..count)
            .map(|m| reader.material(cx, self.buffers, m))
            .collect();
        let fragments = nodes
            .iter()
            .map(|&n| self.fragment(n, interior as u32))
            .collect::<Result<Vec<_>, _>>()?;
        let bonds: Vec<Value> = field(ext, "bonds", what)?;
        let mut out_bonds: Vec<Bond> = Vec::with_capacity(bonds.len());
        for (i, b) in bonds.iter().enumerate() {
            let what = format!("bonds[{i}]");
            let a = fragment(field(b, "a", &what)?, &format!("{what}.a"))?;
            let bb = fragment(field(b, "b", &what)?, &format!("{what}.b"))?;
            if a >= bb {
                return Err(format!(
                    "{what} joins fragments {a} and {bb}: a must come before b in `fragments`"
                ));
            }
            if let Some(last) = out_bonds.last()
                && (last.a, last.b) >= (a, bb)
            {
                return Err(format!(
                    "{what} (fragments {a}, {bb}) is out of order: bonds are sorted by (a, b), each pair once"
                ));
            }
            let [area] = finite([field(b, "area", &what)?], &format!("{what}.area"))?;
            if area < 0.0 {
                return Err(format!("{what}.area is negative ({area})"));
            }
            let centroid = finite(field(b, "centroid", &what)?, &format!("{what}.centroid"))?;
            let normal = DVec3::from(finite(
                field(b, "normal", &what)?,
                &format!("{what}.normal"),
            )?);
            if (normal.length() - 1.0).abs() > 1e-6 {
                return Err(format!(
                    "{what}.normal is not a unit vector (length {})",
                    normal.length()
                ));
            }
            out_bonds.push(Bond {
                a,
                b: bb,
                area,
                centroid: DVec3::from(centroid),
                normal,
            });
        }
        let anchors: Vec<usize> = optional(ext, "anchors", what)?.unwrap_or_default();
        let anchors = anchors
            .iter()
            .enumerate()
            .map(|(i, &n)| fragment(n, &format!("anchors[{i}]")))
            .collect::<Result<Vec<_>, _>>()?;
        let material: Option<String> = optional(ext, "material", what)?;
        let thresholds: Option<BreakThresholds> = optional(ext, "thresholds", what)?;
        if let Some(t) = &thresholds {
            let all = [t.strength, t.compression, t.tension, t.shear, t.wear];
            if all.iter().any(|v| !v.is_finite() || *v < 0.0) {
                return Err("thresholds: every value must be a finite number ≥ 0".into());
            }
        }
        Ok((
            Fracture {
                fragments,
                bonds: out_bonds,
                materials,
                warnings: Vec::new(),
            },
            FractureAssetMeta {
                anchors,
                material,
                thresholds,
            },
        ))
    }

    /// The fragment of node `n`: its mesh from the glTF, the rest from its extension.
    fn fragment(&self, n: usize, interior: u32) -> Result<Fragment, String> {
        let what = format!("node {n}");
        let node = &self.root.nodes[n];
        check_no_transform(node).map_err(|e| format!("{what}: {e}"))?;
        let ext = self.value["nodes"][n]
            .get("extensions")
            .and_then(|e| e.get(FRACTURE_EXTENSION))
            .ok_or_else(|| format!("{what} is a fragment but has no SHATTER_fracture extension"))?;
        let ext_what = format!("{what} extension");
        let [volume] = finite(
            [field(ext, "volume", &ext_what)?],
            &format!("{what} volume"),
        )?;
        if volume <= 0.0 {
            return Err(format!("{what} volume is not positive ({volume})"));
        }
        let centroid = finite(
            field(ext, "centroid", &ext_what)?,
            &format!("{what} centroid"),
        )?;
        let inertia: [f64; 9] = finite(
            field(ext, "inertia", &ext_what)?,
            &format!("{what} inertia"),
        )?;
        let flat_normals: bool = optional(ext, "flatNormals", &ext_what)?.unwrap_or(false);
        let convex_pieces = match optional::<Value>(ext, "convexPieces", &ext_what)? {
            Some(p) => self.convex_pieces(&p, &format!("{what} convexPieces"))?,
            None => Vec::new(),
        };
        let m = node
            .mesh
            .ok_or_else(|| format!("{what} is a fragment but has no mesh"))?;
        let mesh = self.root.meshes.get(m).ok_or_else(|| {
            format!(
                "{what} names mesh {m}, but the file has {} meshes",
                self.root.meshes.len()
            )
        })?;
        let mut decoded = Vec::with_capacity(mesh.primitives.len());
        for (p, prim) in mesh.primitives.iter().enumerate() {
            let pwhat = format!("mesh {m} primitive {p}");
            let mode = prim.mode.unwrap_or(4);
            if !(4..=6).contains(&mode) {
                return Err(format!("{pwhat} is not triangles (mode {mode})"));
            }
            if prim.material.is_none() {
                return Err(format!("{pwhat} has no material"));
            }
            decoded.push(decode_primitive(
                self.root,
                self.buffers,
                prim,
                &pwhat,
                mode,
            )?);
        }
        let (mesh, corners, material) = weld(&decoded, flat_normals);
        if mesh.triangles.is_empty() {
            return Err(format!("{what}: its mesh has no triangles"));
        }
        Ok(Fragment {
            interior: material.iter().map(|&k| k == interior).collect(),
            mesh,
            corners,
            material,
            convex_pieces,
            convex_hulls: Vec::new(),
            volume,
            centroid: DVec3::from(centroid),
            inertia: DMat3::from_cols_array(&inertia),
        })
    }

    fn convex_pieces(&self, p: &Value, what: &str) -> Result<Vec<Vec<DVec3>>, String> {
        let accessor_index: usize = field(p, "points", what)?;
        let counts: Vec<usize> = field(p, "counts", what)?;
        let expect = Expect {
            kinds: &["VEC3"],
            codes: &[FLOAT],
            normalized_ints: false,
        };
        let view = accessor::view(
            self.root,
            self.buffers,
            accessor_index,
            &format!("{what}.points"),
            &expect,
        )?;
        if let Some(k) = counts.iter().position(|&c| c < 4) {
            return Err(format!(
                "{what}.counts[{k}] is {}: a convex piece needs at least 4 points",
                counts[k]
            ));
        }
        let total = counts.iter().try_fold(0usize, |s, &c| s.checked_add(c));
        if total != Some(view.count) {
            return Err(format!(
                "{what}.counts add up to {}, but accessor {accessor_index} has {} points",
                total.map_or("more than usize".to_string(), |t| t.to_string()),
                view.count
            ));
        }
        let points = view.floats::<3>();
        if let Some(i) = points.iter().position(|p| p.iter().any(|x| !x.is_finite())) {
            return Err(format!("{what}: point {i} is not finite"));
        }
        let mut rest = points.as_slice();
        Ok(counts
            .iter()
            .map(|&c| {
                let (piece, tail) = rest.split_at(c);
                rest = tail;
                piece
                    .iter()
                    .map(|p| DVec3::from(p.map(f64::from)))
                    .collect()
            })
            .collect())
    }
}

/// Fragments are in the object's frame: a node transform would move them away from the
/// mass properties and bonds.
fn check_no_transform(node: &json::Node) -> Result<(), String> {
    const IDENTITY: [f64; 16] = [
        1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0,
    ];
    let moved = node.matrix.is_some_and(|m| m != IDENTITY)
        || node.translation.is_some_and(|t| t != [0.0; 3])
        || node.rotation.is_some_and(|r| r != [0.0, 0.0, 0.0, 1.0])
        || node.scale.is_some_and(|s| s != [1.0; 3]);
    if moved {
        Err("a fragment node has a transform; fragments are stored in the object's frame".into())
    } else {
        Ok(())
    }
}

/// One mesh from a fragment's primitives: corners with bit-identical positions become one
/// vertex (the writer split every vertex per corner), triangles in primitive order, each
/// with its primitive's material; UVs, normals and colours per corner where present.
fn weld(decoded: &[Decoded], flat_normals: bool) -> (TriMesh, Corners, Vec<u32>) {
    let mut index: HashMap<[u32; 3], u32> = HashMap::new();
    let mut positions = Vec::new();
    let mut triangles = Vec::new();
    let mut material = Vec::new();
    let has = |f: fn(&Decoded) -> bool| decoded.iter().any(f);
    let (has_uv, has_color) = (has(|d| d.uvs.is_some()), has(|d| d.colors.is_some()));
    let has_normal = !flat_normals && has(|d| d.normals.is_some());
    let (mut uv, mut normal, mut color) = (Vec::new(), Vec::new(), Vec::new());
    for d in decoded {
        for t in &d.triangles {
            let tri = t.map(|i| {
                let p = d.positions[i as usize];
                *index.entry(p.map(f32::to_bits)).or_insert_with(|| {
                    positions.push(DVec3::from(p.map(f64::from)));
                    (positions.len() - 1) as u32
                })
            });
            triangles.push(tri);
            material.push(d.material.unwrap_or(0) as u32);
            let corner = |i: u32| i as usize;
            if has_uv {
                uv.push(t.map(|i| d.uvs.as_ref().map_or([0.0; 2], |v| v[corner(i)])));
            }
            if has_normal {
                normal.push(t.map(|i| d.normals.as_ref().map_or([0.0; 3], |v| v[corner(i)])));
            }
            if has_color {
                color.push(t.map(|i| d.colors.as_ref().map_or([1.0; 4], |v| v[corner(i)])));
            }
        }
    }
    let corners = Corners {
        uv: has_uv.then_some(uv),
        normal: has_normal.then_some(normal),
        color: has_color.then_some(color),
    };
    (TriMesh::new(positions, triangles), corners, material)
}
