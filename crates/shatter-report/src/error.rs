//! The one error type of this crate.

use std::path::PathBuf;

/// Why a report could not be written.
#[derive(Debug, thiserror::Error)]
pub enum ReportError {
    /// A file could not be created or written.
    #[error("cannot write '{path}': {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// The cause.
        source: std::io::Error,
    },
    /// The CSV writer failed.
    #[error("cannot write CSV '{path}': {source}")]
    Csv {
        /// The file.
        path: PathBuf,
        /// The cause.
        source: csv::Error,
    },
    /// A table row does not have one cell per column.
    #[error("row {row} has {found} cells but the header has {expected} columns")]
    RowLength {
        /// Index of the row (0 = first row after the header).
        row: usize,
        /// Number of columns in the header.
        expected: usize,
        /// Number of cells in the row.
        found: usize,
    },
    /// A plot was asked for without any point to draw.
    #[error("plot '{title}' has no points to draw")]
    EmptyPlot {
        /// Title of the plot.
        title: String,
    },
    /// A plotted value is NaN or infinite.
    #[error("series '{series}' point {index} is not finite")]
    NonFinitePoint {
        /// Name of the series.
        series: String,
        /// Index of the point in the series.
        index: usize,
    },
    /// The plotting library failed while drawing or saving.
    #[error("cannot draw plot '{path}': {message}")]
    Plot {
        /// The output file.
        path: PathBuf,
        /// The plotting library's message.
        message: String,
    },
    /// An animated scene is inconsistent (a bad index, a count mismatch, a bad value).
    #[error("invalid animated scene: {0}")]
    Scene(String),
    /// The glTF container could not be encoded.
    #[error("cannot encode glTF: {0}")]
    Gltf(String),
}

impl ReportError {
    /// An I/O error on `path`.
    pub(crate) fn io(path: impl Into<PathBuf>, source: std::io::Error) -> Self {
        Self::Io {
            path: path.into(),
            source,
        }
    }
}
