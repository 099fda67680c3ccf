//! What a reader tolerated: the model loaded, but not everything in the file made it in.

use std::fmt;

/// The kind of a [`LoadWarning`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum WarningKind {
    /// Elements that are not triangles (lines, points, curves, faces of fewer than three
    /// corners, non-triangle glTF primitives) were skipped.
    SkippedElements,
    /// A file the model refers to (material library, texture, buffer) could not be read;
    /// the model loaded without it.
    MissingFile,
    /// A file the model refers to could be read but not understood (a broken MTL, an image
    /// that is neither PNG nor JPEG).
    BadFile,
    /// A face names a material that is not defined (it gets a default one).
    UnknownMaterial,
    /// A feature of the file that shatter does not carry (a second UV set, a texture
    /// transform, an unknown statement).
    Unsupported,
    /// The file ends early or its counts disagree with its size; what is there was read.
    Truncated,
    /// Some corners lack an attribute others have (they get a default value).
    MissingAttribute,
}

impl WarningKind {
    /// A short snake_case name, for JSON.
    pub fn name(self) -> &'static str {
        match self {
            WarningKind::SkippedElements => "skipped_elements",
            WarningKind::MissingFile => "missing_file",
            WarningKind::BadFile => "bad_file",
            WarningKind::UnknownMaterial => "unknown_material",
            WarningKind::Unsupported => "unsupported",
            WarningKind::Truncated => "truncated",
            WarningKind::MissingAttribute => "missing_attribute",
        }
    }
}

/// One thing a reader tolerated, with how many times it happened and a message naming
/// the file (and line, where there is one).
///
/// ```
/// use shatter_geom::io::{self, MeshFormat, WarningKind};
/// let obj = b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nl 1 2\nl 2 3\n";
/// let loaded = io::parse_model(obj, MeshFormat::Obj, "mixed.obj").unwrap();
/// let w = &loaded.warnings[0];
/// assert_eq!((w.kind, w.count), (WarningKind::SkippedElements, 2));
/// assert_eq!(w.to_string(), "mixed.obj: skipped 2 line elements (first at line 5)");
/// ```
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct LoadWarning {
    /// What kind of thing.
    pub kind: WarningKind,
    /// How many times (elements skipped, corners without the attribute, ...; 1 for a
    /// single event).
    pub count: usize,
    /// The message, starting with the file's name.
    pub message: String,
}

impl LoadWarning {
    /// A warning of `kind`, `count` times.
    pub fn new(kind: WarningKind, count: usize, message: impl Into<String>) -> LoadWarning {
        LoadWarning {
            kind,
            count,
            message: message.into(),
        }
    }
}

impl fmt::Display for LoadWarning {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.message)
    }
}
