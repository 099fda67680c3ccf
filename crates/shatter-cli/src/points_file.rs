//! The `POINTS.xyz` format: one point per line.
//!
//! ```text
//! # a comment; blank lines are ignored too
//! 0 0 0
//! 1.5 0 0   # a trailing comment
//! 0 1e-3 0
//! ```
//!
//! Each non-blank line holds exactly three whitespace-separated finite numbers `x y z`.
//! Everything after a `#` is a comment. Errors name the file, the 1-based line and the
//! problem: `points.xyz:7: expected 3 coordinates, found 2`.

use std::path::{Path, PathBuf};

use shatter_geom::DVec3;

/// What is wrong with one line of a points file.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum LineProblem {
    /// The line does not hold exactly three values.
    #[error("expected 3 coordinates, found {found}")]
    WrongCount {
        /// How many values the line holds.
        found: usize,
    },
    /// A value does not parse as a number.
    #[error("'{text}' is not a number")]
    NotANumber {
        /// The offending text.
        text: String,
    },
    /// A value is NaN or infinite.
    #[error("'{text}' is not a finite number")]
    NotFinite {
        /// The offending text.
        text: String,
    },
}

/// Why a points file could not be read.
#[derive(Debug, thiserror::Error)]
pub enum PointsFileError {
    /// The file could not be opened or read.
    #[error("{}: cannot read: {source}", path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// The I/O error.
        source: std::io::Error,
    },
    /// A line is malformed.
    #[error("{}:{line}: {problem}", path.display())]
    Line {
        /// The file.
        path: PathBuf,
        /// 1-based line number.
        line: usize,
        /// What is wrong with it.
        problem: LineProblem,
    },
    /// The file holds no points at all.
    #[error("{}: no points (only blank lines and comments)", path.display())]
    Empty {
        /// The file.
        path: PathBuf,
    },
}

/// Reads and parses a points file.
pub fn read_points_file(path: &Path) -> Result<Vec<DVec3>, PointsFileError> {
    let bytes = std::fs::read(path).map_err(|source| PointsFileError::Io {
        path: path.to_path_buf(),
        source,
    })?;
    let text = String::from_utf8(bytes).map_err(|e| PointsFileError::Io {
        path: path.to_path_buf(),
        source: std::io::Error::new(std::io::ErrorKind::InvalidData, e.utf8_error()),
    })?;
    let points = parse_points(&text).map_err(|(line, problem)| PointsFileError::Line {
        path: path.to_path_buf(),
        line,
        problem,
    })?;
    if points.is_empty() {
        return Err(PointsFileError::Empty {
            path: path.to_path_buf(),
        });
    }
    Ok(points)
}

/// Parses the text of a points file; on failure returns the 1-based line and the problem.
pub fn parse_points(text: &str) -> Result<Vec<DVec3>, (usize, LineProblem)> {
    let mut points = Vec::new();
    for (i, raw) in text.lines().enumerate() {
        let content = raw.split('#').next().unwrap_or("");
        let fields: Vec<&str> = content.split_whitespace().collect();
        if fields.is_empty() {
            continue;
        }
        if fields.len() != 3 {
            return Err((
                i + 1,
                LineProblem::WrongCount {
                    found: fields.len(),
                },
            ));
        }
        let mut xyz = [0.0; 3];
        for (slot, field) in xyz.iter_mut().zip(&fields) {
            *slot = parse_coordinate(field).map_err(|p| (i + 1, p))?;
        }
        points.push(DVec3::from_array(xyz));
    }
    Ok(points)
}

fn parse_coordinate(text: &str) -> Result<f64, LineProblem> {
    let value: f64 = text.parse().map_err(|_| LineProblem::NotANumber {
        text: text.to_string(),
    })?;
    if !value.is_finite() {
        return Err(LineProblem::NotFinite {
            text: text.to_string(),
        });
    }
    Ok(value)
}

/// Writes points in the same format (for round-trip tests).
#[cfg(test)]
pub fn format_points(points: &[DVec3]) -> String {
    use std::fmt;
    struct Lines<'a>(&'a [DVec3]);
    impl fmt::Display for Lines<'_> {
        fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
            for p in self.0 {
                writeln!(f, "{} {} {}", p.x, p.y, p.z)?;
            }
            Ok(())
        }
    }
    Lines(points).to_string()
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;

    #[test]
    fn comments_blank_lines_and_tabs_are_accepted() {
        let text = "# header\n\n0 0 0\n1\t2   3 # trailing\n  -1e-3 4.5 +6\n";
        let points = parse_points(text).unwrap();
        assert_eq!(
            points,
            vec![
                DVec3::ZERO,
                DVec3::new(1.0, 2.0, 3.0),
                DVec3::new(-1e-3, 4.5, 6.0)
            ]
        );
    }

    #[test]
    fn a_short_line_names_its_line_number_and_count() {
        let err = parse_points("0 0 0\n# c\n1 2\n").unwrap_err();
        assert_eq!(err, (3, LineProblem::WrongCount { found: 2 }));
        assert_eq!(err.1.to_string(), "expected 3 coordinates, found 2");
    }

    #[test]
    fn a_long_line_is_refused() {
        let err = parse_points("1 2 3 4\n").unwrap_err();
        assert_eq!(err, (1, LineProblem::WrongCount { found: 4 }));
    }

    #[test]
    fn a_word_is_not_a_number() {
        let err = parse_points("1 abc 3\n").unwrap_err();
        assert_eq!(err.1.to_string(), "'abc' is not a number");
    }

    #[test]
    fn nan_and_infinity_are_refused() {
        for bad in ["nan", "inf", "-inf", "NaN", "1e400"] {
            let err = parse_points(&format!("0 0 {bad}\n")).unwrap_err();
            assert_eq!(
                err,
                (
                    1,
                    LineProblem::NotFinite {
                        text: bad.to_string()
                    }
                ),
                "{bad}"
            );
        }
    }

    #[test]
    fn file_errors_name_the_file_and_line() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("points.xyz");
        std::fs::write(&path, "0 0 0\n1 1\n").unwrap();
        let err = read_points_file(&path).unwrap_err();
        assert_eq!(
            err.to_string(),
            format!("{}:2: expected 3 coordinates, found 2", path.display())
        );
    }

    #[test]
    fn an_empty_file_is_an_error() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("empty.xyz");
        std::fs::write(&path, "# nothing\n\n").unwrap();
        assert!(matches!(
            read_points_file(&path),
            Err(PointsFileError::Empty { .. })
        ));
    }

    /// Checks what the reader said about `text`: an error on a line of the text, or
    /// points that are all finite, one per non-blank, non-comment line.
    fn check_parse(text: &str) {
        match parse_points(text) {
            Ok(points) => {
                assert!(points.iter().all(|p| p.is_finite()));
                let lines = text
                    .lines()
                    .filter(|l| !l.split('#').next().unwrap_or("").trim().is_empty())
                    .count();
                assert_eq!(points.len(), lines);
            }
            Err((line, problem)) => {
                assert!(line >= 1 && line <= text.lines().count(), "line {line}");
                assert!(!problem.to_string().is_empty());
            }
        }
    }

    const VALID: &str =
        "# a tetrahedron and its centre\n0 0 0\n1 0 0\n0 1 0   # c\n0 0 1\n\n0.25 0.25 0.25\n";
    const TOKENS: [&str; 16] = [
        "1e400", "-1e-400", "nan", "inf", "0x10", "1,5", "#", "\n", "\t", " ", "\r\n", "1e", "+",
        "-0", "١", "\u{feff}",
    ];

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig {
            cases: 1024, failure_persistence: None, ..Default::default()
        })]

        #[test]
        fn random_bytes_never_panic(bytes in proptest::collection::vec(proptest::prelude::any::<u8>(), 0..400)) {
            check_parse(&String::from_utf8_lossy(&bytes));
            // Not UTF-8 at all: the file reader refuses it with a message.
            let dir = tempfile::tempdir().unwrap();
            let path = dir.path().join("p.xyz");
            std::fs::write(&path, &bytes).unwrap();
            if let Err(e) = read_points_file(&path) {
                assert!(e.to_string().starts_with(&path.display().to_string()));
            }
        }

        #[test]
        fn mutated_valid_files_never_panic(
            edits in proptest::collection::vec(
                (proptest::prelude::any::<usize>(), 0..TOKENS.len(), proptest::prelude::any::<bool>()),
                1..5,
            ),
        ) {
            let mut text: Vec<char> = VALID.chars().collect();
            for (at, token, replace) in edits {
                let at = at % (text.len() + 1);
                if replace && at < text.len() {
                    text.remove(at);
                }
                for (k, c) in TOKENS[token].chars().enumerate() {
                    text.insert(at + k, c);
                }
            }
            check_parse(&text.into_iter().collect::<String>());
        }
    }

    #[test]
    fn format_then_parse_round_trips() {
        let points = vec![DVec3::new(0.1, -2.5, 1e-9), DVec3::new(1e6, 3.0, -0.0)];
        assert_eq!(parse_points(&format_points(&points)).unwrap(), points);
    }
}
