//! Materials and the images they use (glTF's metallic-roughness model, which OBJ/MTL
//! maps onto: `Kd` → base colour, `map_Kd` → base-colour texture).

use std::path::PathBuf;
use std::sync::Arc;

use serde::{Deserialize, Serialize};

/// A material: glTF's `pbrMetallicRoughness` subset that shatter keeps.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Material {
    /// Name (from the file, or made up by the reader).
    pub name: String,
    /// Linear RGBA base colour factor.
    pub base_color: [f32; 4],
    /// Base-colour texture, sampled with the corners' UVs (multiplied by `base_color`).
    pub base_color_texture: Option<Texture>,
    /// Metalness, 0..=1.
    pub metallic: f32,
    /// Perceptual roughness, 0..=1.
    pub roughness: f32,
}

impl Default for Material {
    /// A light grey, rough, non-metallic material named `surface`.
    fn default() -> Self {
        Material::named("surface")
    }
}

impl Material {
    /// A light grey, rough, non-metallic material with this name.
    pub fn named(name: impl Into<String>) -> Material {
        Material {
            name: name.into(),
            base_color: [0.8, 0.8, 0.8, 1.0],
            base_color_texture: None,
            metallic: 0.0,
            roughness: 0.9,
        }
    }
}

/// A texture: an image (shared between materials that use the same one).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Texture {
    /// The image.
    pub image: Arc<Image>,
}

/// The encodings of an image that shatter carries through.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum ImageFormat {
    /// PNG (`image/png`).
    Png,
    /// JPEG (`image/jpeg`).
    Jpeg,
}

impl ImageFormat {
    /// The MIME type glTF uses for it.
    pub fn mime(self) -> &'static str {
        match self {
            ImageFormat::Png => "image/png",
            ImageFormat::Jpeg => "image/jpeg",
        }
    }

    /// The usual file extension, without the dot.
    pub fn extension(self) -> &'static str {
        match self {
            ImageFormat::Png => "png",
            ImageFormat::Jpeg => "jpg",
        }
    }
}

/// An encoded image, kept as the file's bytes (never decoded by the geometry crate).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Image {
    /// A name for it: the file name it came from, or the glTF image's name.
    pub name: String,
    /// Its encoding.
    pub format: ImageFormat,
    /// The encoded bytes.
    pub bytes: Vec<u8>,
    /// The file it was read from, when it was an external file.
    pub source: Option<PathBuf>,
}
