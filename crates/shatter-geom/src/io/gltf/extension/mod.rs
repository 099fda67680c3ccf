//! The `SHATTER_fracture` glTF extension: a pre-fractured asset (see
//! `docs/shatter-fracture-extension.md` for the specification and
//! `docs/shatter-fracture.schema.json` for its JSON schema).
//!
//! A GLB written by [`write_fracture_glb`] is an ordinary glTF 2.0 file, one node and
//! mesh per fragment, that any viewer opens (the extension is in `extensionsUsed`, never
//! in `extensionsRequired`). The extension adds what a game needs to simulate it without
//! fracturing again:
//! - on each fragment node: its convex pieces (one `VEC3` float accessor, the pieces'
//!   point counts inline), volume, centroid and inertia tensor (unit density);
//! - at the root: the format version, the fragment nodes in fragment order, the
//!   interior material, the bond graph (area, centroid, normal of each bond), the
//!   anchored fragments, and optionally a material preset name and break thresholds
//!   ([`FractureAssetMeta`]: plain data, the geometry crate knows no physics).
//!
//! [`read_fracture`] and [`parse_fracture`] rebuild the [`Fracture`](crate::fracture::Fracture)
//! from such a file; a file without the extension is
//! [`MeshIoError::NoFractureExtension`](crate::io::MeshIoError::NoFractureExtension) and a
//! malformed one [`MeshIoError::FractureExtension`](crate::io::MeshIoError::FractureExtension).

mod read;
mod write;

use serde::{Deserialize, Serialize};

pub use read::{parse_fracture, read_fracture};
pub use write::{save_fracture_glb, write_fracture_glb};

/// The extension's name, as it appears in `extensionsUsed` and `extensions`.
pub const FRACTURE_EXTENSION: &str = "SHATTER_fracture";

/// The version of the extension this crate writes and the newest it reads. A reader
/// refuses a greater version; fields added without breaking readers keep the version.
pub const FRACTURE_EXTENSION_VERSION: u32 = 1;

/// What a pre-fractured asset carries beyond the geometry: which fragments are held
/// fixed, and the material to simulate it with. The geometry crate stores these as
/// given; the simulator (`shatter-sim`) owns the material presets.
///
/// ```
/// use shatter_geom::io::{BreakThresholds, FractureAssetMeta};
/// let meta = FractureAssetMeta {
///     anchors: vec![0, 3],
///     material: Some("stone".into()),
///     thresholds: Some(BreakThresholds { strength: 20_000.0, compression: 100e6, tension: 6e6, shear: 12e6, wear: 0.2 }),
/// };
/// assert_eq!(meta.anchors.len(), 2);
/// assert_eq!(FractureAssetMeta::default().material, None);
/// ```
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct FractureAssetMeta {
    /// Fragments held fixed (indices into the fracture's fragments); empty when none
    /// is (in the file they are written as node indices, like every fragment reference).
    pub anchors: Vec<u32>,
    /// The material preset's name (`shatter-sim`'s presets: glass, stone, ...), if any.
    pub material: Option<String>,
    /// The bonds' break thresholds, if any.
    pub thresholds: Option<BreakThresholds>,
}

/// Break thresholds of a fractured object's bonds (the simulator's material values).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct BreakThresholds {
    /// Break force of a bond, in newtons.
    pub strength: f64,
    /// Compressive strength of a bond's face, in pascals.
    pub compression: f64,
    /// Tensile strength, in pascals.
    pub tension: f64,
    /// Shear strength, in pascals.
    pub shear: f64,
    /// Health a bond loses to one hit at its full break force (0: no damage).
    pub wear: f64,
}
