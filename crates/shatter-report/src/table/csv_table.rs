//! An in-memory table written with the `csv` crate (quoting and escaping are its job).

use std::fmt;
use std::path::Path;

use crate::ReportError;

/// One cell of a [`CsvTable`], already formatted.
///
/// Numbers are written in Rust's shortest round-trip form (`0.1`, `12`, `1e-7`), so a
/// reader gets back exactly the value that was measured.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Cell(pub String);

impl fmt::Display for Cell {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

impl From<&str> for Cell {
    fn from(v: &str) -> Self {
        Self(v.to_string())
    }
}

impl From<String> for Cell {
    fn from(v: String) -> Self {
        Self(v)
    }
}

impl From<&String> for Cell {
    fn from(v: &String) -> Self {
        Self(v.clone())
    }
}

macro_rules! cell_from_display {
    ($($t:ty),*) => {$(
        impl From<$t> for Cell {
            fn from(v: $t) -> Self {
                Self(v.to_string())
            }
        }
    )*};
}
cell_from_display!(f64, f32, usize, u64, u32, i64, i32, bool);

/// A table with a fixed header; every row must have one cell per column.
///
/// ```
/// use shatter_report::table::{Cell, CsvTable};
///
/// let mut t = CsvTable::new(["model", "points", "mean_ms"]);
/// t.push_row([Cell::from("cube"), Cell::from(10usize), Cell::from(0.25)])?;
/// assert_eq!(t.to_csv_string()?, "model,points,mean_ms\ncube,10,0.25\n");
/// # Ok::<(), shatter_report::ReportError>(())
/// ```
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct CsvTable {
    header: Vec<String>,
    rows: Vec<Vec<Cell>>,
}

impl CsvTable {
    /// An empty table with these column names.
    pub fn new<I, S>(header: I) -> Self
    where
        I: IntoIterator<Item = S>,
        S: Into<String>,
    {
        Self {
            header: header.into_iter().map(Into::into).collect(),
            rows: Vec::new(),
        }
    }

    /// The column names.
    pub fn header(&self) -> &[String] {
        &self.header
    }

    /// The rows added so far.
    pub fn rows(&self) -> &[Vec<Cell>] {
        &self.rows
    }

    /// Appends a row. Fails, leaving the table unchanged, when the row does not have
    /// exactly one cell per column.
    pub fn push_row<I, C>(&mut self, cells: I) -> Result<(), ReportError>
    where
        I: IntoIterator<Item = C>,
        C: Into<Cell>,
    {
        let row: Vec<Cell> = cells.into_iter().map(Into::into).collect();
        if row.len() != self.header.len() {
            return Err(ReportError::RowLength {
                row: self.rows.len(),
                expected: self.header.len(),
                found: row.len(),
            });
        }
        self.rows.push(row);
        Ok(())
    }

    /// The whole table as CSV text (header first, `\n` line ends).
    pub fn to_csv_string(&self) -> Result<String, ReportError> {
        let mut writer = csv::Writer::from_writer(Vec::new());
        self.write_records(&mut writer, Path::new("<memory>"))?;
        let bytes = writer
            .into_inner()
            .map_err(|e| ReportError::io("<memory>", e.into_error()))?;
        // Every cell came from a Rust string, so the bytes are UTF-8.
        String::from_utf8(bytes).map_err(|e| {
            ReportError::io(
                "<memory>",
                std::io::Error::new(std::io::ErrorKind::InvalidData, e),
            )
        })
    }

    /// Writes the table to `path` (created or truncated).
    pub fn write(&self, path: impl AsRef<Path>) -> Result<(), ReportError> {
        let path = path.as_ref();
        let mut writer = csv::Writer::from_path(path).map_err(|source| ReportError::Csv {
            path: path.to_path_buf(),
            source,
        })?;
        self.write_records(&mut writer, path)?;
        writer.flush().map_err(|e| ReportError::io(path, e))
    }

    fn write_records<W: std::io::Write>(
        &self,
        writer: &mut csv::Writer<W>,
        path: &Path,
    ) -> Result<(), ReportError> {
        let csv_err = |source| ReportError::Csv {
            path: path.to_path_buf(),
            source,
        };
        writer.write_record(&self.header).map_err(csv_err)?;
        for row in &self.rows {
            writer
                .write_record(row.iter().map(|c| c.0.as_str()))
                .map_err(csv_err)?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;

    #[test]
    fn a_short_row_is_refused_and_the_table_is_unchanged() {
        let mut t = CsvTable::new(["a", "b"]);
        let err = t.push_row([1.0]).unwrap_err();
        assert!(matches!(
            err,
            ReportError::RowLength {
                row: 0,
                expected: 2,
                found: 1
            }
        ));
        assert!(t.rows().is_empty());
    }

    #[test]
    fn cells_with_commas_and_quotes_are_quoted() {
        let mut t = CsvTable::new(["name"]);
        t.push_row(["bird, \"low poly\""]).unwrap();
        assert_eq!(
            t.to_csv_string().unwrap(),
            "name\n\"bird, \"\"low poly\"\"\"\n"
        );
    }

    #[test]
    fn floats_round_trip_exactly() {
        let v = 0.1f64 + 0.2;
        assert_eq!(Cell::from(v).0.parse::<f64>().unwrap(), v);
    }
}
