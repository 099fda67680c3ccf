//! The CSV writer's files parse back, with a `csv` reader, into the header and rows
//! that were written.
#![allow(clippy::unwrap_used)]

use shatter_report::ReportError;
use shatter_report::table::{Cell, CsvTable};

#[test]
fn a_written_table_parses_back_with_its_header_and_rows() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("creation.csv");
    let mut table = CsvTable::new(["model", "placement", "random_points", "mean_ms"]);
    let rows = [
        ("cube", "thesis", 0usize, 0.125f64),
        ("bird, low poly", "interior", 10, 2.5e-3),
        ("capsule", "thesis", 500, 13.0),
    ];
    for (m, p, n, ms) in rows {
        table
            .push_row([Cell::from(m), Cell::from(p), Cell::from(n), Cell::from(ms)])
            .unwrap();
    }
    table.write(&path).unwrap();

    let mut reader = csv::Reader::from_path(&path).unwrap();
    let header: Vec<String> = reader.headers().unwrap().iter().map(String::from).collect();
    assert_eq!(header, ["model", "placement", "random_points", "mean_ms"]);
    let records: Vec<csv::StringRecord> = reader.records().map(Result::unwrap).collect();
    assert_eq!(records.len(), rows.len());
    for (record, (m, p, n, ms)) in records.iter().zip(rows) {
        assert_eq!(&record[0], m);
        assert_eq!(&record[1], p);
        assert_eq!(record[2].parse::<usize>().unwrap(), n);
        assert_eq!(record[3].parse::<f64>().unwrap(), ms);
    }
}

#[test]
fn writing_into_a_missing_directory_names_the_file() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("no/such/dir/t.csv");
    let table = CsvTable::new(["a"]);
    let err = table.write(&path).unwrap_err();
    assert!(matches!(err, ReportError::Csv { .. }));
    assert!(err.to_string().contains("no/such/dir/t.csv"));
}
