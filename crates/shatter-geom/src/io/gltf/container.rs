//! The glTF containers: the GLB header and chunks, the glTF 1.0 check, buffers (the GLB
//! binary chunk, data URIs, external files) and URIs.

use std::path::PathBuf;

use base64::Engine;
use serde_json::Value;

use super::json::Root;
use crate::io::context::ReadContext;

const JSON_CHUNK: u32 = 0x4E4F_534A;
const BIN_CHUNK: u32 = 0x004E_4942;

/// The JSON and binary chunk of a file: a GLB's chunks, or a `.gltf`'s whole text.
pub(crate) struct Container<'b> {
    pub json: &'b [u8],
    pub bin: Option<&'b [u8]>,
}

fn u32_at(bytes: &[u8], at: usize) -> Option<u32> {
    let b = bytes.get(at..at + 4)?;
    Some(u32::from_le_bytes([b[0], b[1], b[2], b[3]]))
}

/// The message for a glTF 1.0 file, which shatter refuses.
pub(crate) fn version_one(says: &str) -> String {
    format!("glTF 1.0 is not supported (this file says {says}); convert it to glTF 2.0")
}

/// Splits a GLB into its chunks (a `.gltf` is one JSON chunk). Anything that does not
/// add up is an error message.
pub(crate) fn split(bytes: &[u8]) -> Result<Container<'_>, String> {
    if !bytes.starts_with(b"glTF") {
        return Ok(Container {
            json: bytes,
            bin: None,
        });
    }
    let version = u32_at(bytes, 4).ok_or("truncated GLB header")?;
    match version {
        1 => return Err(version_one("version 1 in its GLB header")),
        2 => {}
        v => return Err(format!("GLB version {v}: only version 2 is read")),
    }
    let length = u32_at(bytes, 8).ok_or("truncated GLB header")? as usize;
    if length > bytes.len() {
        return Err(format!(
            "truncated GLB: the header says {length} bytes, the file has {}",
            bytes.len()
        ));
    }
    let bytes = &bytes[..length];
    let mut at = 12usize;
    let mut chunks = Vec::new();
    while at < bytes.len() {
        let (Some(len), Some(kind)) = (u32_at(bytes, at), u32_at(bytes, at + 4)) else {
            return Err(format!("truncated GLB chunk header at byte {at}"));
        };
        let start = at + 8;
        let end = start
            .checked_add(len as usize)
            .filter(|&e| e <= bytes.len())
            .ok_or_else(|| {
                format!(
                    "GLB chunk at byte {at} says {len} bytes, but only {} follow",
                    bytes.len().saturating_sub(start)
                )
            })?;
        chunks.push((kind, &bytes[start..end]));
        // Chunks are 4-byte aligned.
        at = end.div_ceil(4) * 4;
    }
    match chunks.first() {
        Some(&(JSON_CHUNK, json)) => Ok(Container {
            json,
            bin: chunks.get(1).filter(|c| c.0 == BIN_CHUNK).map(|c| c.1),
        }),
        _ => Err("GLB without a JSON chunk first".into()),
    }
}

/// Parses the JSON document, refusing glTF 1.0 with a message that says so.
pub(crate) fn document(json: &[u8]) -> Result<Root, String> {
    // A JSON value first: glTF 1.0 documents (objects where 2.0 has arrays) would only
    // give a confusing type error below.
    let value: Value = serde_json::from_slice(json).map_err(|e| format!("invalid JSON: {e}"))?;
    let version = value
        .get("asset")
        .and_then(|a| a.get("version"))
        .and_then(Value::as_str);
    match version {
        Some(v) if v.starts_with("1.") || v == "1" => {
            return Err(version_one(&format!("version {v}")));
        }
        Some(v) if !v.starts_with("2.") => {
            return Err(format!("glTF version {v}: only glTF 2.0 is read"));
        }
        Some(_) => {}
        None => {
            if ["meshes", "accessors", "nodes"]
                .iter()
                .any(|k| value.get(k).is_some_and(Value::is_object))
            {
                return Err(version_one("no version, but uses glTF 1.0's objects"));
            }
        }
    }
    drop(value);
    serde_json::from_slice(json).map_err(|e| format!("invalid glTF 2.0 document: {e}"))
}

/// What a URI refers to: inline bytes (a data URI) or a file (percent-decoded, relative
/// to the main file).
pub(crate) enum Uri {
    Data(Vec<u8>),
    File(PathBuf),
}

/// Resolves `uri`; an error message for a data URI that does not decode.
pub(crate) fn resolve(cx: &ReadContext<'_>, uri: &str) -> Result<Uri, String> {
    if let Some(rest) = uri.strip_prefix("data:") {
        let (meta, data) = rest.split_once(',').ok_or("a data URI without a comma")?;
        if !meta.ends_with(";base64") {
            return Err("a data URI that is not base64".into());
        }
        return base64::engine::general_purpose::STANDARD
            .decode(data.trim())
            .map(Uri::Data)
            .map_err(|e| format!("a data URI that is not valid base64: {e}"));
    }
    let decoded = percent_encoding::percent_decode_str(uri).decode_utf8_lossy();
    Ok(Uri::File(cx.resolve(std::path::Path::new(&*decoded))))
}

/// The bytes of every buffer, or why it is unavailable (an error only if the geometry
/// needs it).
pub(crate) fn buffers(
    cx: &ReadContext<'_>,
    root: &Root,
    bin: Option<&[u8]>,
) -> Vec<Result<Vec<u8>, String>> {
    root.buffers
        .iter()
        .enumerate()
        .map(|(i, b)| match &b.uri {
            None if i == 0 => bin
                .map(<[u8]>::to_vec)
                .ok_or_else(|| "buffer 0 has no uri and the file has no binary chunk".into()),
            None => Err(format!("buffer {i} has no uri")),
            Some(uri) => match resolve(cx, uri)? {
                Uri::Data(bytes) => Ok(bytes),
                Uri::File(path) => cx
                    .read(&path)
                    .map_err(|e| format!("buffer {i}: cannot read {}: {e}", path.display())),
            },
        })
        .collect()
}
