//! The document's materials with their base-colour textures (embedded in the GLB, data
//! URIs or external files), read on demand.

use std::sync::Arc;

use crate::io::WarningKind;
use crate::io::context::ReadContext;
use crate::io::gltf::accessor;
use crate::io::gltf::container::{self, Uri};
use crate::io::gltf::json::{self, Root};
use crate::io::image::{self, ImageCache};
use crate::model::{Image, Material, Texture};

/// The glTF default material (spec: white, metallic 1, roughness 1).
pub(super) fn default_material() -> Material {
    Material {
        name: "default".into(),
        base_color: [1.0; 4],
        base_color_texture: None,
        metallic: 1.0,
        roughness: 1.0,
    }
}

/// The materials of a document, read on demand (each image decoded once).
pub(crate) struct Materials<'r> {
    root: &'r Root,
    images: Vec<Option<Option<Arc<Image>>>>,
    cache: ImageCache,
}

impl<'r> Materials<'r> {
    /// Nothing read yet.
    pub(crate) fn new(root: &'r Root) -> Materials<'r> {
        Materials {
            root,
            images: vec![None; root.images.len()],
            cache: ImageCache::default(),
        }
    }

    fn image(
        &mut self,
        cx: &mut ReadContext<'_>,
        buffers: &[Result<Vec<u8>, String>],
        index: usize,
        what: &str,
    ) -> Option<Arc<Image>> {
        if let Some(Some(done)) = self.images.get(index) {
            return done.clone();
        }
        let Some(img) = self.root.images.get(index) else {
            cx.warn(
                WarningKind::BadFile,
                1,
                format!("{what}: image {index} does not exist; dropped"),
            );
            return None;
        };
        let name = img.name.clone().unwrap_or_else(|| format!("image_{index}"));
        let loaded = match (&img.uri, img.buffer_view) {
            (_, Some(view)) => match accessor::view_bytes(self.root, buffers, view) {
                Ok(bytes) => image::from_bytes(cx, bytes.to_vec(), name, None, what),
                Err(e) => {
                    cx.warn(
                        WarningKind::BadFile,
                        1,
                        format!("{what}: image {index}: {e}; dropped"),
                    );
                    None
                }
            },
            (Some(uri), None) => match container::resolve(cx, uri) {
                Ok(Uri::Data(bytes)) => image::from_bytes(cx, bytes, name, None, what),
                Ok(Uri::File(path)) => self.cache.load(cx, &path, what),
                Err(e) => {
                    cx.warn(
                        WarningKind::BadFile,
                        1,
                        format!("{what}: image {index}: {e}; dropped"),
                    );
                    None
                }
            },
            (None, None) => {
                cx.warn(
                    WarningKind::BadFile,
                    1,
                    format!("{what}: image {index} has neither uri nor bufferView; dropped"),
                );
                None
            }
        };
        if let Some(slot) = self.images.get_mut(index) {
            *slot = Some(loaded.clone());
        }
        loaded
    }

    fn texture(
        &mut self,
        cx: &mut ReadContext<'_>,
        buffers: &[Result<Vec<u8>, String>],
        info: &json::TextureInfo,
        what: &str,
    ) -> Option<Texture> {
        if info.tex_coord != 0 {
            cx.warn(
                WarningKind::Unsupported,
                1,
                format!("{what}: its texture uses TEXCOORD_{}; only TEXCOORD_0 is read, so the texture is dropped", info.tex_coord),
            );
            return None;
        }
        if info.extensions.contains_key("KHR_texture_transform") {
            cx.warn(
                WarningKind::Unsupported,
                1,
                format!("{what}: KHR_texture_transform is ignored"),
            );
        }
        let Some(texture) = self.root.textures.get(info.index) else {
            cx.warn(
                WarningKind::BadFile,
                1,
                format!("{what}: texture {} does not exist; dropped", info.index),
            );
            return None;
        };
        let Some(source) = texture.source else {
            cx.warn(
                WarningKind::Unsupported,
                1,
                format!(
                    "{what}: texture {} has no PNG or JPEG source (only an extension's); dropped",
                    info.index
                ),
            );
            return None;
        };
        self.image(cx, buffers, source, what)
            .map(|image| Texture { image })
    }

    /// Material `index` (which must exist), with its texture.
    pub(crate) fn material(
        &mut self,
        cx: &mut ReadContext<'_>,
        buffers: &[Result<Vec<u8>, String>],
        index: usize,
    ) -> Material {
        let m = &self.root.materials[index];
        let name = m
            .name
            .clone()
            .unwrap_or_else(|| format!("material_{index}"));
        let what = format!("material {index} '{name}'");
        let mut out = Material {
            name,
            ..default_material()
        };
        if let Some(pbr) = &m.pbr_metallic_roughness {
            out.base_color = pbr.base_color_factor.unwrap_or([1.0; 4]);
            out.metallic = pbr.metallic_factor.unwrap_or(1.0);
            out.roughness = pbr.roughness_factor.unwrap_or(1.0);
            if let Some(info) = &pbr.base_color_texture {
                out.base_color_texture = self.texture(cx, buffers, info, &what);
            }
        } else if let Some(sg) = m.extensions.get("KHR_materials_pbrSpecularGlossiness") {
            // Its diffuse is the closest thing to a base colour.
            match serde_json::from_value::<json::SpecularGlossiness>(sg.clone()) {
                Ok(sg) => {
                    out.base_color = sg.diffuse_factor.unwrap_or([1.0; 4]);
                    out.metallic = 0.0;
                    out.roughness = 0.5;
                    if let Some(info) = &sg.diffuse_texture {
                        out.base_color_texture = self.texture(cx, buffers, info, &what);
                    }
                }
                Err(e) => cx.warn(
                    WarningKind::BadFile,
                    1,
                    format!("{what}: unreadable KHR_materials_pbrSpecularGlossiness: {e}"),
                ),
            }
        }
        let clamp = |v: f32| {
            if v.is_finite() {
                v.clamp(0.0, 1.0)
            } else {
                1.0
            }
        };
        out.base_color = out.base_color.map(clamp);
        out.metallic = clamp(out.metallic);
        out.roughness = clamp(out.roughness);
        out
    }
}
