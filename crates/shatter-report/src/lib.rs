//! Reports for shatter: the data and pictures behind its measurements, and exports of
//! simulation runs for other tools.
//!
//! - [`table`]: CSV tables (one header row, then one row per measurement).
//! - [`plot`]: line plots with one line per series, axis labels, a legend and an
//!   optional min/max band, written as PNG and SVG. Text is drawn with the DejaVu Sans
//!   font shipped in this crate, so no system font library is needed.
//! - [`export`]: animated glTF (GLB): one node per fragment with its mesh, keyframed
//!   translation and rotation, viewable in Blender or any glTF viewer.
//! - [`record`]: a recorder for simulation runs that collects per-step statistics and
//!   fragment poses, then writes them as CSV and animated GLB.
//!
//! ```
//! use shatter_report::plot::{Series, plot_lines};
//! use shatter_report::table::CsvTable;
//!
//! let dir = tempfile::tempdir()?;
//! let mut table = CsvTable::new(["points", "ms"]);
//! table.push_row([0.0, 1.5])?;
//! table.push_row([10.0, 2.0])?;
//! table.write(dir.path().join("creation.csv"))?;
//!
//! let series = vec![Series::new("cube", vec![(0.0, 1.5), (10.0, 2.0)])];
//! plot_lines(
//!     &series,
//!     "Creation time",
//!     "random points",
//!     "ms",
//!     dir.path().join("creation.png"),
//!     dir.path().join("creation.svg"),
//! )?;
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod error;
pub mod export;
pub mod plot;
pub mod record;
pub mod table;

pub use error::ReportError;
