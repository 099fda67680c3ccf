//! What a fracture measured, as `shatter fracture --json` reports it.

use serde::Serialize;
use shatter_geom::TriMesh;
use shatter_geom::budget::Estimate;
use shatter_geom::fracture::{Bond, Fracture};

/// An estimate as reported in `--json`.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct EstimateReport {
    /// Peak memory, bytes.
    pub bytes: f64,
    /// Wall-clock seconds.
    pub seconds: f64,
}

impl From<Estimate> for EstimateReport {
    fn from(e: Estimate) -> Self {
        Self {
            bytes: e.bytes,
            seconds: e.seconds,
        }
    }
}

/// The `--json` report of a fracture.
#[derive(Debug, Serialize)]
pub struct FractureReport {
    /// Number of fragments.
    pub fragments: usize,
    /// Number of bonds.
    pub bonds: usize,
    /// Volume of the input mesh (after scaling).
    pub mesh_volume: f64,
    /// Sum of the fragments' volumes.
    pub fragments_volume: f64,
    /// Smallest fragment volume.
    pub min_fragment_volume: f64,
    /// Largest fragment volume.
    pub max_fragment_volume: f64,
    /// Interior (cut) triangles over all fragments.
    pub interior_triangles: usize,
    /// Milliseconds spent in the fracture alone (no loading, no writing).
    pub millis: f64,
    /// Warnings (also printed on stderr).
    pub warnings: Vec<String>,
    /// What the resource check estimated before the fracture.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub estimate: Option<EstimateReport>,
    /// The process's peak resident set at the end (Linux only).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub peak_rss_bytes: Option<u64>,
    /// Every bond, with `--json-bonds` only.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub bond_list: Option<Vec<BondEntry>>,
}

/// One bond of the `--json-bonds` list.
#[derive(Debug, Serialize)]
pub struct BondEntry {
    /// First fragment (index into the fragments as written), `a < b`.
    pub a: u32,
    /// Second fragment.
    pub b: u32,
    /// Area of the shared face.
    pub area: f64,
    /// Centroid of the shared face.
    pub centroid: [f64; 3],
    /// Unit normal of the shared face, pointing from `a` to `b`.
    pub normal: [f64; 3],
}

impl From<&Bond> for BondEntry {
    fn from(b: &Bond) -> Self {
        Self {
            a: b.a,
            b: b.b,
            area: b.area,
            centroid: b.centroid.to_array(),
            normal: b.normal.to_array(),
        }
    }
}

impl FractureReport {
    /// Summarises a fracture of `mesh`.
    pub fn new(mesh: &TriMesh, fracture: &Fracture, millis: f64, warnings: Vec<String>) -> Self {
        let volumes = fracture.fragments.iter().map(|f| f.volume);
        Self {
            fragments: fracture.fragments.len(),
            bonds: fracture.bonds.len(),
            mesh_volume: mesh.signed_volume().abs(),
            fragments_volume: volumes.clone().sum(),
            min_fragment_volume: volumes.clone().fold(f64::INFINITY, f64::min),
            max_fragment_volume: volumes.fold(0.0, f64::max),
            interior_triangles: fracture
                .fragments
                .iter()
                .map(|f| f.interior.iter().filter(|&&i| i).count())
                .sum(),
            millis,
            warnings,
            estimate: None,
            peak_rss_bytes: None,
            bond_list: None,
        }
    }

    /// Adds the list of every bond (`--json-bonds`).
    pub fn with_bond_list(mut self, fracture: &Fracture) -> Self {
        self.bond_list = Some(fracture.bonds.iter().map(BondEntry::from).collect());
        self
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;
    use crate::fracture::{FractureConfig, fracture_timed, load_source};
    use shatter_geom::fracture::Method;
    use shatter_geom::shapes::Shape;

    #[test]
    fn the_report_counts_and_adds_up_the_fracture() {
        let config = FractureConfig::shape(
            Shape::Cube,
            Method::Grid {
                cells: [2, 2, 1],
                voids: Vec::new(),
            },
            0,
        );
        let (model, _) = load_source(&config).unwrap();
        let (f, _, ms) = fracture_timed(&model, &config).unwrap();
        let r = FractureReport::new(&model.mesh, &f, ms, vec!["w".into()]).with_bond_list(&f);
        assert_eq!((r.fragments, r.bonds), (4, 4));
        assert!((r.mesh_volume - 1.0).abs() < 1e-12);
        assert!((r.fragments_volume - 1.0).abs() < 1e-9);
        assert!((r.min_fragment_volume - 0.25).abs() < 1e-9);
        let list = r.bond_list.as_ref().unwrap();
        assert!(
            list.iter()
                .all(|b| b.a < b.b && (b.area - 0.5).abs() < 1e-9)
        );
        let json = serde_json::to_value(&r).unwrap();
        assert!(json.get("estimate").is_none());
        assert_eq!(json["warnings"][0], "w");
    }
}
