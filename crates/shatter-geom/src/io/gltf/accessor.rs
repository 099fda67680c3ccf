//! Accessors read by hand, every index, type, stride, offset and count checked against the
//! bytes actually present before anything is read (the `gltf` crate panicked on a
//! POSITION naming a missing accessor, on float indices and on a stride smaller than the
//! element). Nothing is allocated from a count the file states before the count is known
//! to fit in its bytes.

use super::json::Root;

/// Component types, by their glTF code: (name, size in bytes).
fn component(code: u32) -> Option<(&'static str, usize)> {
    Some(match code {
        5120 => ("BYTE", 1),
        5121 => ("UNSIGNED_BYTE", 1),
        5122 => ("SHORT", 2),
        5123 => ("UNSIGNED_SHORT", 2),
        5125 => ("UNSIGNED_INT", 4),
        5126 => ("FLOAT", 4),
        _ => return None,
    })
}

fn components(kind: &str) -> Option<usize> {
    Some(match kind {
        "SCALAR" => 1,
        "VEC2" => 2,
        "VEC3" => 3,
        "VEC4" => 4,
        "MAT2" => 4,
        "MAT3" => 9,
        "MAT4" => 16,
        _ => return None,
    })
}

/// A checked accessor: where its elements are and how to decode them.
pub(crate) struct View<'b> {
    bytes: &'b [u8],
    stride: usize,
    code: u32,
    size: usize,
    normalized: bool,
    pub count: usize,
    pub components: usize,
}

impl View<'_> {
    /// Component `c` of element `i`, as glTF defines its value (normalized integers
    /// mapped to 0..1 or -1..1).
    fn get(&self, i: usize, c: usize) -> f32 {
        let at = i * self.stride + c * self.size;
        let b = &self.bytes[at..at + self.size];
        let n = self.normalized;
        match self.code {
            5120 => {
                let v = f32::from(b[0] as i8);
                if n { (v / 127.0).max(-1.0) } else { v }
            }
            5121 => {
                let v = f32::from(b[0]);
                if n { v / 255.0 } else { v }
            }
            5122 => {
                let v = f32::from(i16::from_le_bytes([b[0], b[1]]));
                if n { (v / 32767.0).max(-1.0) } else { v }
            }
            5123 => {
                let v = f32::from(u16::from_le_bytes([b[0], b[1]]));
                if n { v / 65535.0 } else { v }
            }
            5125 => u32::from_le_bytes([b[0], b[1], b[2], b[3]]) as f32,
            _ => f32::from_le_bytes([b[0], b[1], b[2], b[3]]),
        }
    }

    /// The elements as `N` floats each (the view has exactly `N` components).
    pub fn floats<const N: usize>(&self) -> Vec<[f32; N]> {
        (0..self.count)
            .map(|i| std::array::from_fn(|c| self.get(i, c)))
            .collect()
    }

    /// The elements as `N` floats each, padded with `fill` (a VEC3 colour read as RGBA).
    pub fn floats_padded<const N: usize>(&self, fill: f32) -> Vec<[f32; N]> {
        (0..self.count)
            .map(|i| {
                std::array::from_fn(|c| {
                    if c < self.components {
                        self.get(i, c)
                    } else {
                        fill
                    }
                })
            })
            .collect()
    }

    /// The elements as unsigned integers (a SCALAR of an unsigned integer type).
    pub fn indices(&self) -> Vec<u32> {
        (0..self.count)
            .map(|i| {
                let at = i * self.stride;
                let b = &self.bytes[at..at + self.size];
                match self.size {
                    1 => u32::from(b[0]),
                    2 => u32::from(u16::from_le_bytes([b[0], b[1]])),
                    _ => u32::from_le_bytes([b[0], b[1], b[2], b[3]]),
                }
            })
            .collect()
    }
}

/// What an accessor may be, for the use the reader makes of it.
pub(crate) struct Expect {
    /// Allowed element types (`VEC3`, ...).
    pub kinds: &'static [&'static str],
    /// Allowed component types; `normalized` integer types are accepted where floats are
    /// when `normalized_ok`.
    pub codes: &'static [u32],
    /// Whether integer components must be normalized (texture coordinates, colours).
    pub normalized_ints: bool,
}

/// Checks accessor `index` (named `what` in messages: "mesh 0 primitive 1 POSITION")
/// against `expect` and the buffers, and returns its view.
pub(crate) fn view<'b>(
    root: &Root,
    buffers: &'b [Result<Vec<u8>, String>],
    index: usize,
    what: &str,
    expect: &Expect,
) -> Result<View<'b>, String> {
    let a = root.accessors.get(index).ok_or_else(|| {
        format!(
            "{what} names accessor {index}, but the file has {} accessors",
            root.accessors.len()
        )
    })?;
    let at = format!("{what} (accessor {index})");
    let (code_name, size) = component(a.component_type)
        .ok_or_else(|| format!("{at} has unknown componentType {}", a.component_type))?;
    let n = components(&a.kind).ok_or_else(|| format!("{at} has unknown type '{}'", a.kind))?;
    if !expect.kinds.contains(&a.kind.as_str()) || !expect.codes.contains(&a.component_type) {
        return Err(format!(
            "{at} is a {} of {code_name}{}; expected {} of {}",
            a.kind,
            if a.normalized { " (normalized)" } else { "" },
            expect.kinds.join(" or "),
            expect
                .codes
                .iter()
                .filter_map(|&c| component(c).map(|c| c.0))
                .collect::<Vec<_>>()
                .join(", ")
        ));
    }
    if expect.normalized_ints && a.component_type != 5126 && !a.normalized {
        return Err(format!("{at}: integer components must be normalized here"));
    }
    if a.sparse.is_some() {
        return Err(format!(
            "{at} is sparse; sparse accessors are not supported"
        ));
    }
    let view_index = a
        .buffer_view
        .ok_or_else(|| format!("{at} has no bufferView (all zeros); not supported"))?;
    let v = root.buffer_views.get(view_index).ok_or_else(|| {
        format!(
            "{at} names bufferView {view_index}, but the file has {}",
            root.buffer_views.len()
        )
    })?;
    let buffer = match buffers.get(v.buffer) {
        Some(Ok(b)) => b,
        Some(Err(e)) => return Err(format!("{at}: {e}")),
        None => {
            return Err(format!(
                "{at}: bufferView {view_index} names buffer {}, but the file has {}",
                v.buffer,
                buffers.len()
            ));
        }
    };
    let view_end = v
        .byte_offset
        .checked_add(v.byte_length)
        .filter(|&e| e <= buffer.len() as u64)
        .ok_or_else(|| {
            format!(
                "{at}: bufferView {view_index} (bytes {}..+{}) goes past the end of buffer {} ({} bytes)",
                v.byte_offset,
                v.byte_length,
                v.buffer,
                buffer.len()
            )
        })?;
    let view_bytes = &buffer[v.byte_offset as usize..view_end as usize];
    let element = (n * size) as u64;
    let stride = match v.byte_stride {
        None => element,
        Some(s) if s < element => {
            return Err(format!(
                "{at}: bufferView {view_index} has byteStride {s}, smaller than the {element}-byte element"
            ));
        }
        Some(s) if s > 252 || s % size as u64 != 0 => {
            return Err(format!(
                "{at}: bufferView {view_index} has byteStride {s} (must be a multiple of {size} up to 252)"
            ));
        }
        Some(s) => s,
    };
    if a.count == 0 {
        return Err(format!("{at} has count 0"));
    }
    let needed = (a.count - 1)
        .checked_mul(stride)
        .and_then(|x| x.checked_add(element))
        .and_then(|x| x.checked_add(a.byte_offset));
    match needed {
        Some(end) if end <= view_bytes.len() as u64 => {}
        _ => {
            return Err(format!(
                "{at}: {} elements of {element} bytes from byte {} need more than the {} bytes of bufferView {view_index}",
                a.count,
                a.byte_offset,
                view_bytes.len()
            ));
        }
    }
    Ok(View {
        bytes: &view_bytes[a.byte_offset as usize..],
        stride: stride as usize,
        code: a.component_type,
        size,
        normalized: a.normalized,
        count: a.count as usize,
        components: n,
    })
}

/// Bytes of bufferView `index` (for an embedded image).
pub(crate) fn view_bytes<'b>(
    root: &Root,
    buffers: &'b [Result<Vec<u8>, String>],
    index: usize,
) -> Result<&'b [u8], String> {
    let v = root.buffer_views.get(index).ok_or_else(|| {
        format!(
            "bufferView {index} does not exist (the file has {})",
            root.buffer_views.len()
        )
    })?;
    let buffer = match buffers.get(v.buffer) {
        Some(Ok(b)) => b,
        Some(Err(e)) => return Err(e.clone()),
        None => {
            return Err(format!(
                "bufferView {index} names missing buffer {}",
                v.buffer
            ));
        }
    };
    v.byte_offset
        .checked_add(v.byte_length)
        .filter(|&e| e <= buffer.len() as u64)
        .map(|e| &buffer[v.byte_offset as usize..e as usize])
        .ok_or_else(|| {
            format!(
                "bufferView {index} goes past the end of buffer {}",
                v.buffer
            )
        })
}
