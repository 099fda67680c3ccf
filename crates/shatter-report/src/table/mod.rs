//! CSV tables: a header row, then one row per measurement.

mod csv_table;

pub use csv_table::{Cell, CsvTable};
