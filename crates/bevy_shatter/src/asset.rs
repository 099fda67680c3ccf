//! Pre-fractured objects: a GLB written by `shatter fracture MESH --out X.glb` carries
//! the `SHATTER_fracture` glTF extension (docs/shatter-fracture-extension.md): every
//! fragment's mesh, convex pieces and mass properties, the bonds, the anchors and the
//! material. [`FractureAssetLoader`] reads it as a [`FractureAsset`], so a game fractures
//! offline and only loads at runtime; a [`Breakable`](crate::Breakable) whose
//! `prefractured` names such an asset skips the fracture.
//!
//! ```no_run
//! use bevy::prelude::*;
//! use bevy_shatter::{Breakable, FractureAsset};
//!
//! fn setup(mut commands: Commands, assets: Res<AssetServer>) {
//!     // A typed load picks this loader even when Bevy's glTF loader also claims `.glb`.
//!     let wall: Handle<FractureAsset> = assets.load("wall.glb");
//!     commands.spawn((Transform::from_xyz(0.0, 1.0, 0.0), Breakable::prefractured(wall)));
//! }
//! ```

use std::sync::Arc;

use bevy::asset::io::Reader;
use bevy::asset::{AssetLoader, LoadContext};
use bevy::prelude::*;
use shatter_geom::fracture::Fracture;
use shatter_geom::io::{FractureAssetMeta, MeshIoError, parse_fracture};

/// A fracture loaded from a GLB with the `SHATTER_fracture` extension.
#[derive(Asset, TypePath, Debug, Clone)]
pub struct FractureAsset {
    /// The fragments (meshes with their attributes and materials, convex pieces, mass
    /// properties) and the bond graph.
    pub fracture: Arc<Fracture>,
    /// Anchors, material preset and break thresholds, as the file holds them.
    pub meta: FractureAssetMeta,
}

/// Loads [`FractureAsset`]s from `.glb` files (added by [`crate::ShatterPlugin`]).
#[derive(Debug, Default, TypePath)]
pub struct FractureAssetLoader;

/// Why a pre-fractured file could not be loaded.
#[derive(Debug, thiserror::Error)]
pub enum FractureAssetError {
    /// The bytes could not be read.
    #[error("cannot read {path}: {source}")]
    Io {
        /// The asset path.
        path: String,
        /// The reader's error.
        source: std::io::Error,
    },
    /// Not a GLB with a valid `SHATTER_fracture` extension (the message names the part).
    #[error(transparent)]
    Format(#[from] MeshIoError),
}

impl AssetLoader for FractureAssetLoader {
    type Asset = FractureAsset;
    type Settings = ();
    type Error = FractureAssetError;

    async fn load(
        &self,
        reader: &mut dyn Reader,
        _settings: &(),
        load_context: &mut LoadContext<'_>,
    ) -> Result<FractureAsset, FractureAssetError> {
        let path = load_context.path().to_string();
        let mut bytes = Vec::new();
        reader
            .read_to_end(&mut bytes)
            .await
            .map_err(|source| FractureAssetError::Io {
                path: path.clone(),
                source,
            })?;
        let (fracture, meta) = parse_fracture(&bytes, &path)?;
        Ok(FractureAsset {
            fracture: Arc::new(fracture),
            meta,
        })
    }

    fn extensions(&self) -> &[&str] {
        &["glb"]
    }
}
