//! The Delaunay benchmark: the tetrahedralization of random point sets, timed, with its
//! peak memory and the result's size per point.

use std::time::Instant;

use serde::{Deserialize, Serialize};
use shatter_geom::delaunay;
use shatter_geom::sampling::{self, Distribution};

use crate::error::{LabError, ResultExt};
use crate::memory;

/// One measured size.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Row {
    /// Points given.
    pub points: usize,
    /// Points after removing duplicates.
    pub unique_points: usize,
    /// Tetrahedra made.
    pub tetrahedra: usize,
    /// Milliseconds of the tetrahedralization.
    pub millis: f64,
    /// Points per second.
    pub points_per_second: f64,
    /// Peak RSS during the tetrahedralization minus the RSS just before it (the points
    /// were already allocated), per point. `None` where `/proc` is unavailable.
    pub peak_bytes_per_point: Option<f64>,
    /// Heap bytes the result holds once shrunk to fit (its packed tetrahedra,
    /// `representative`, `duplicates`), per point; measured after the peak.
    pub result_bytes_per_point: f64,
}

/// The `--json` report.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Report {
    /// The distribution's name.
    pub distribution: String,
    /// The points' seed.
    pub seed: u64,
    /// One row per size.
    pub rows: Vec<Row>,
    /// Process-wide peak RSS (VmHWM) at the end, in bytes.
    pub process_peak_rss_bytes: Option<u64>,
    /// Whether each row's peak was measured alone (`/proc/self/clear_refs` reset worked)
    /// or is process-wide.
    pub per_row_peak: bool,
}

/// Times and measures the tetrahedralization of `n` random points of `distribution`
/// in this process; also says whether the peak was reset for it.
pub fn measure(distribution: Distribution, n: usize, seed: u64) -> Result<(Row, bool), LabError> {
    let points = sampling::sample(distribution, n, seed);
    let reset = memory::reset_peak();
    let before = memory::current_rss_bytes();
    let start = Instant::now();
    let mut tets = delaunay::tetrahedralize(&points)
        .input_err(format!("{n} random {} points", distribution.name()))?;
    let millis = start.elapsed().as_secs_f64() * 1e3;
    let peak = memory::peak_rss_bytes();
    let peak_bytes_per_point = match (before, peak) {
        (Some(b), Some(p)) => Some(p.saturating_sub(b) as f64 / n as f64),
        _ => None,
    };
    tets.shrink_to_fit();
    let row = Row {
        points: n,
        unique_points: tets.unique_points,
        tetrahedra: tets.len(),
        millis,
        points_per_second: n as f64 / (millis / 1e3).max(1e-9),
        peak_bytes_per_point,
        result_bytes_per_point: tets.heap_bytes() as f64 / n as f64,
    };
    Ok((row, reset))
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;

    #[test]
    fn a_measured_size_counts_its_points_and_tetrahedra() {
        let (row, _) = measure(Distribution::Uniform, 500, 1).unwrap();
        assert_eq!((row.points, row.unique_points), (500, 500));
        // A uniform set has about 6.5 tetrahedra per point.
        assert!(
            row.tetrahedra > 2000 && row.tetrahedra < 5000,
            "{}",
            row.tetrahedra
        );
        assert!(row.result_bytes_per_point > 0.0);
    }

    #[test]
    fn too_few_points_are_bad_input_naming_them() {
        let e = measure(Distribution::Uniform, 3, 0).unwrap_err();
        assert!(matches!(e, LabError::Input(_)), "{e:?}");
        assert!(
            e.to_string().starts_with("3 random uniform points: "),
            "{e}"
        );
    }
}
