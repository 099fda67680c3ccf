//! The pre-fractured asset options of `shatter fracture` (what goes into a `.glb`'s
//! `SHATTER_fracture` extension beyond the geometry), and the extension's summary for
//! `shatter inspect`.

use std::path::Path;

use clap::{Args, ValueEnum};
use serde::Serialize;
use shatter_geom::fracture::Fracture;
use shatter_geom::io::{self, BreakThresholds, FractureAssetMeta, MeshIoError};
use shatter_geom::progress::Progress;
use shatter_sim::material::{MATERIAL_NAMES, Material};

use crate::args::MeshFormat;
use crate::error::CliError;
use shatter_lab::export;

/// Which fragments a pre-fractured asset marks as anchored (held fixed).
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum AnchorRule {
    /// The fragments touching the object's lowest plane (the simulator's rule for an
    /// anchored object).
    Lowest,
}

/// Options of the `SHATTER_fracture` extension written with `--out FILE.glb`.
#[derive(Debug, Clone, Default, Args)]
pub struct AssetArgs {
    /// With --out FILE.glb: the material preset (glass, stone, concrete, wood, ceramic,
    /// ice, brick) written into the SHATTER_fracture extension, with its break
    /// thresholds.
    #[arg(long, value_name = "PRESET")]
    pub material: Option<String>,
    /// With --out FILE.glb: the anchored fragments written into the extension [default:
    /// none].
    #[arg(long, value_enum, value_name = "RULE")]
    pub anchor: Option<AnchorRule>,
}

impl AssetArgs {
    fn any(&self) -> bool {
        self.material.is_some() || self.anchor.is_some()
    }

    /// Refuses the options where they cannot apply (no `.glb` output, a batch) and an
    /// unknown preset, before any work starts.
    pub fn check(&self, out: Option<&Path>, batch: bool) -> Result<(), CliError> {
        if !self.any() {
            return Ok(());
        }
        let glb =
            out.is_some_and(|p| MeshFormat::from_output_path(p).ok() == Some(MeshFormat::Glb));
        if batch || !glb {
            return Err(CliError::input(
                "--material and --anchor go into a pre-fractured asset: they need --out FILE.glb (one MESH or --shape)",
            ));
        }
        if let Some(name) = &self.material
            && Material::preset(name).is_none()
        {
            return Err(CliError::input(format!(
                "--material {name}: unknown preset (expected one of {})",
                MATERIAL_NAMES.join(", ")
            )));
        }
        Ok(())
    }

    /// The extension's metadata for `fracture`.
    pub fn meta(&self, fracture: &Fracture) -> FractureAssetMeta {
        let thresholds = self
            .material
            .as_deref()
            .and_then(Material::preset)
            .map(|m| BreakThresholds {
                strength: widen(m.strength),
                compression: widen(m.compression),
                tension: widen(m.tension),
                shear: widen(m.shear),
                wear: widen(m.wear),
            });
        FractureAssetMeta {
            anchors: match self.anchor {
                Some(AnchorRule::Lowest) => fracture.lowest_fragments(),
                None => Vec::new(),
            },
            material: self.material.clone(),
            thresholds,
        }
    }
}

/// An `f32` preset value as the `f64` it stands for (0.2, not 0.20000000298...).
fn widen(x: f32) -> f64 {
    x.to_string().parse().unwrap_or(f64::from(x))
}

/// Writes the fracture: a `.glb` as a pre-fractured asset with `asset`'s metadata, an
/// `.obj` as before.
pub fn write(
    path: &Path,
    format: MeshFormat,
    fracture: &Fracture,
    asset: &AssetArgs,
    progress: &Progress,
) -> Result<(), CliError> {
    Ok(match format {
        MeshFormat::Glb => {
            export::write_fracture_asset(path, fracture, &asset.meta(fracture), progress)
        }
        MeshFormat::Obj => export::write_fracture(path, format, fracture, progress),
    }?)
}

/// The extension as `shatter inspect` reports it.
#[derive(Debug, Serialize)]
pub struct ExtensionReport {
    /// Fragments.
    pub fragments: usize,
    /// Bonds.
    pub bonds: usize,
    /// Anchored fragments.
    pub anchors: usize,
    /// The material preset, if any.
    pub material: Option<String>,
    /// Why the extension could not be read, if it could not.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub error: Option<String>,
}

/// The `SHATTER_fracture` extension of a glTF file, if it has one (a malformed one is
/// reported with its error, not refused: inspect describes files, it does not judge).
pub fn inspect(path: &Path) -> Option<ExtensionReport> {
    let ext = path.extension()?.to_string_lossy().to_ascii_lowercase();
    if ext != "glb" && ext != "gltf" {
        return None;
    }
    match io::read_fracture(path) {
        Ok((fracture, meta)) => Some(ExtensionReport {
            fragments: fracture.fragments.len(),
            bonds: fracture.bonds.len(),
            anchors: meta.anchors.len(),
            material: meta.material,
            error: None,
        }),
        Err(MeshIoError::NoFractureExtension { .. }) => None,
        Err(e) => Some(ExtensionReport {
            fragments: 0,
            bonds: 0,
            anchors: 0,
            material: None,
            error: Some(e.to_string()),
        }),
    }
}

/// The report as one line of text.
pub fn text(r: &ExtensionReport) -> String {
    match &r.error {
        Some(e) => format!("SHATTER_fracture: unreadable: {e}"),
        None => format!(
            "SHATTER_fracture: {} fragments, {} bonds, {} anchored{}",
            r.fragments,
            r.bonds,
            r.anchors,
            r.material
                .as_ref()
                .map(|m| format!(", material {m}"))
                .unwrap_or_default()
        ),
    }
}
