//! A triangle primitive's vertex data and triangles, decoded from its accessors (every
//! one checked) once, to be instanced at every node that uses it.

use crate::io::gltf::accessor::{self, Expect};
use crate::io::gltf::json::{self, Root};

const FLOAT: u32 = 5126;
const INTEGERS_AND_FLOAT: &[u32] = &[5120, 5121, 5122, 5123, 5125, FLOAT];

/// A primitive's vertex data, decoded once and instanced at every node that uses it.
pub(crate) struct Decoded {
    pub positions: Vec<[f32; 3]>,
    pub normals: Option<Vec<[f32; 3]>>,
    pub uvs: Option<Vec<[f32; 2]>>,
    pub colors: Option<Vec<[f32; 4]>>,
    /// Triangles as vertex indices, wound as in the file.
    pub triangles: Vec<[u32; 3]>,
    pub material: Option<usize>,
}

/// Decodes a triangle primitive (`mode` 4, 5 or 6) into its vertex data and triangles,
/// every accessor and index checked; the error message names `what`.
pub(crate) fn decode_primitive(
    root: &Root,
    buffers: &[Result<Vec<u8>, String>],
    prim: &json::Primitive,
    what: &str,
    mode: u32,
) -> Result<Decoded, String> {
    let attribute = |name: &str| prim.attributes.get(name).copied();
    let position = attribute("POSITION").ok_or_else(|| format!("{what} has no POSITION"))?;
    let vec3 = Expect {
        kinds: &["VEC3"],
        codes: INTEGERS_AND_FLOAT,
        normalized_ints: false,
    };
    let positions = accessor::view(root, buffers, position, &format!("{what} POSITION"), &vec3)?;
    let count = positions.count;
    let same_count = |v: &accessor::View<'_>, name: &str| {
        if v.count == count {
            Ok(())
        } else {
            Err(format!(
                "{what} {name} has {} elements, POSITION has {count}",
                v.count
            ))
        }
    };
    let normals = match attribute("NORMAL") {
        Some(i) => {
            let v = accessor::view(root, buffers, i, &format!("{what} NORMAL"), &vec3)?;
            same_count(&v, "NORMAL")?;
            Some(v.floats::<3>())
        }
        None => None,
    };
    let uvs = match attribute("TEXCOORD_0") {
        Some(i) => {
            let expect = Expect {
                kinds: &["VEC2"],
                codes: &[5121, 5123, FLOAT],
                normalized_ints: true,
            };
            let v = accessor::view(root, buffers, i, &format!("{what} TEXCOORD_0"), &expect)?;
            same_count(&v, "TEXCOORD_0")?;
            Some(v.floats::<2>())
        }
        None => None,
    };
    let colors = match attribute("COLOR_0") {
        Some(i) => {
            let expect = Expect {
                kinds: &["VEC3", "VEC4"],
                codes: &[5121, 5123, FLOAT],
                normalized_ints: true,
            };
            let v = accessor::view(root, buffers, i, &format!("{what} COLOR_0"), &expect)?;
            same_count(&v, "COLOR_0")?;
            Some(v.floats_padded::<4>(1.0))
        }
        None => None,
    };
    let indices: Vec<u32> = match prim.indices {
        Some(i) => {
            let expect = Expect {
                kinds: &["SCALAR"],
                codes: &[5121, 5123, 5125],
                normalized_ints: false,
            };
            let v = accessor::view(root, buffers, i, &format!("{what} indices"), &expect)?;
            let ix = v.indices();
            if let Some(&bad) = ix.iter().find(|&&k| k as usize >= count) {
                return Err(format!(
                    "{what} indices reference vertex {bad}, but POSITION has {count}"
                ));
            }
            ix
        }
        None => (0..count as u32).collect(),
    };
    let triangles: Vec<[u32; 3]> = match mode {
        5 => indices
            .windows(3)
            .enumerate()
            .map(|(k, w)| {
                if k % 2 == 0 {
                    [w[0], w[1], w[2]]
                } else {
                    [w[1], w[0], w[2]]
                }
            })
            // Repeated corners stitch strips together; they are no triangles.
            .filter(|t| t[0] != t[1] && t[1] != t[2] && t[0] != t[2])
            .collect(),
        6 => indices
            .get(1..)
            .unwrap_or(&[])
            .windows(2)
            .map(|w| [indices[0], w[0], w[1]])
            .collect(),
        _ => indices
            .chunks_exact(3)
            .map(|t| [t[0], t[1], t[2]])
            .collect(),
    };
    if let Some(m) = prim.material
        && m >= root.materials.len()
    {
        return Err(format!(
            "{what} names material {m}, but the file has {} materials",
            root.materials.len()
        ));
    }
    Ok(Decoded {
        positions: positions.floats::<3>(),
        normals,
        uvs,
        colors,
        triangles,
        material: prim.material,
    })
}
