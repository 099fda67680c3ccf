//! Images the readers carry (as encoded bytes; never decoded here) and the writers copy
//! or embed.

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use super::WarningKind;
use super::context::ReadContext;
use crate::model::{Image, ImageFormat};

/// The encoding of an image from its first bytes (PNG and JPEG signatures).
pub(crate) fn sniff(bytes: &[u8]) -> Option<ImageFormat> {
    if bytes.starts_with(b"\x89PNG\r\n\x1a\n") {
        Some(ImageFormat::Png)
    } else if bytes.starts_with(&[0xFF, 0xD8, 0xFF]) {
        Some(ImageFormat::Jpeg)
    } else {
        None
    }
}

/// What an unknown image probably is, for the warning.
fn describe(bytes: &[u8], path: &Path) -> String {
    let ext = path
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase())
        .unwrap_or_default();
    if bytes.starts_with(b"RIFF") && bytes.get(8..12) == Some(b"WEBP") {
        "WebP".into()
    } else if bytes.starts_with(b"DDS ") {
        "DDS".into()
    } else if bytes.starts_with(b"BM") {
        "BMP".into()
    } else if bytes.starts_with(b"\xABKTX") {
        "KTX".into()
    } else if !ext.is_empty() {
        format!("'.{ext}' (not PNG or JPEG)")
    } else {
        "neither PNG nor JPEG".into()
    }
}

/// An image from its bytes, or `None` (and a warning) if it is neither PNG nor JPEG.
pub(crate) fn from_bytes(
    cx: &mut ReadContext<'_>,
    bytes: Vec<u8>,
    name: String,
    source: Option<PathBuf>,
    what: &str,
) -> Option<Arc<Image>> {
    let Some(format) = sniff(&bytes) else {
        let kind = source
            .as_deref()
            .map(|p| describe(&bytes, p))
            .unwrap_or_else(|| describe(&bytes, Path::new(&name)));
        cx.warn(
            WarningKind::BadFile,
            1,
            format!("{what}: image '{name}' is {kind}; only PNG and JPEG textures are kept, so it is dropped"),
        );
        return None;
    };
    Some(Arc::new(Image {
        name,
        format,
        bytes,
        source,
    }))
}

/// External images read once each, shared by every material that names them.
#[derive(Default)]
pub(crate) struct ImageCache {
    by_path: HashMap<PathBuf, Option<Arc<Image>>>,
}

impl ImageCache {
    /// The image at `path` (resolved already), read through `cx`; `None` and a warning
    /// when it cannot be read or is not PNG or JPEG. `what` says who needs it.
    pub fn load(
        &mut self,
        cx: &mut ReadContext<'_>,
        path: &Path,
        what: &str,
    ) -> Option<Arc<Image>> {
        if let Some(cached) = self.by_path.get(path) {
            return cached.clone();
        }
        let image = match cx.read(path) {
            Ok(bytes) => {
                let name = path
                    .file_name()
                    .map(|n| n.to_string_lossy().into_owned())
                    .unwrap_or_else(|| path.display().to_string());
                from_bytes(cx, bytes, name, Some(path.to_path_buf()), what)
            }
            Err(e) => {
                cx.warn(
                    WarningKind::MissingFile,
                    1,
                    format!(
                        "{what}: cannot read texture {}: {e}; loaded without it",
                        path.display()
                    ),
                );
                None
            }
        };
        self.by_path.insert(path.to_path_buf(), image.clone());
        image
    }
}
