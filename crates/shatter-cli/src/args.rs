//! Argument value types shared by several commands, and their parsers.
//!
//! Parsers here only check syntax (clap reports their errors with exit code 2); the
//! commands then validate values (positive scale, at least one piece, ...) into a typed
//! configuration, again failing with exit code 2.

use std::path::{Path, PathBuf};

use clap::ValueEnum;
use shatter_geom::DVec3;

use crate::error::CliError;
pub use shatter_lab::export::MeshFormat;

/// Parses `X,Y,Z` (three comma-separated finite numbers) into a vector.
pub fn parse_vec3(text: &str) -> Result<DVec3, String> {
    let parts: Vec<&str> = text.split(',').map(str::trim).collect();
    if parts.len() != 3 {
        return Err(format!(
            "expected 3 comma-separated numbers X,Y,Z, found {}",
            parts.len()
        ));
    }
    let mut xyz = [0.0; 3];
    for (slot, part) in xyz.iter_mut().zip(&parts) {
        let v: f64 = part
            .parse()
            .map_err(|_| format!("'{part}' is not a number"))?;
        if !v.is_finite() {
            return Err(format!("'{part}' is not a finite number"));
        }
        *slot = v;
    }
    Ok(DVec3::from_array(xyz))
}

/// Parses `NX,NY,NZ`: three cell counts, each in 1..=1000 (the scene files' limit).
pub fn parse_cells(text: &str) -> Result<[u32; 3], String> {
    let parts: Vec<&str> = text.split(',').map(str::trim).collect();
    if parts.len() != 3 {
        return Err(format!(
            "expected 3 comma-separated cell counts NX,NY,NZ, found {}",
            parts.len()
        ));
    }
    let mut cells = [0; 3];
    for (slot, part) in cells.iter_mut().zip(&parts) {
        *slot = part
            .parse()
            .ok()
            .filter(|n| (1..=1000).contains(n))
            .ok_or_else(|| format!("'{part}' is not a whole number in 1..=1000"))?;
    }
    Ok(cells)
}

/// Parses one benchmark size: a whole number of at least 1 (used with
/// `value_delimiter = ','`, so `--sizes 1000,10000` gives a list).
pub fn parse_size(text: &str) -> Result<usize, String> {
    let n: usize = text
        .trim()
        .parse()
        .map_err(|_| format!("'{text}' is not a whole number"))?;
    if n == 0 {
        return Err("sizes must be at least 1".to_string());
    }
    Ok(n)
}

/// A validated, strictly positive scale.
pub fn validate_scale(scale: Option<DVec3>) -> Result<DVec3, CliError> {
    let Some(s) = scale else {
        return Ok(DVec3::ONE);
    };
    if s.min_element() <= 0.0 {
        return Err(CliError::input(format!(
            "--scale {},{},{}: every component must be greater than 0",
            s.x, s.y, s.z
        )));
    }
    Ok(s)
}

/// A random point distribution.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum Distribution {
    /// Uniform in the unit cube.
    Uniform,
    /// Uniform in the unit ball.
    Ball,
    /// On the unit sphere (every point cospherical: a degenerate case).
    Sphere,
    /// Standard normal in each coordinate.
    Gaussian,
    /// A regular grid (many cospherical and coplanar points).
    Grid,
}

impl Distribution {
    /// The geometry crate's distribution of the same name.
    pub fn sampling(self) -> shatter_geom::sampling::Distribution {
        use shatter_geom::sampling::Distribution as D;
        match self {
            Self::Uniform => D::Uniform,
            Self::Ball => D::Ball,
            Self::Sphere => D::Sphere,
            Self::Gaussian => D::Gaussian,
            Self::Grid => D::Grid,
        }
    }

    /// The name as typed on the command line.
    pub fn as_str(self) -> &'static str {
        match self {
            Self::Uniform => "uniform",
            Self::Ball => "ball",
            Self::Sphere => "sphere",
            Self::Gaussian => "gaussian",
            Self::Grid => "grid",
        }
    }
}

/// Checks before any work is done that `path` can be written, so that a long computation
/// does not end in a failed write. Leaves no file behind when none existed.
pub fn check_writable(path: &Path) -> Result<PathBuf, CliError> {
    if path.is_dir() {
        return Err(CliError::input(format!(
            "{}: cannot write: is a directory",
            path.display()
        )));
    }
    let parent = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    };
    if !parent.is_dir() {
        return Err(CliError::input(format!(
            "{}: cannot write: directory {} does not exist",
            path.display(),
            parent.display()
        )));
    }
    let existed = path.exists();
    std::fs::OpenOptions::new()
        .append(true)
        .create(true)
        .open(path)
        .map_err(|e| CliError::input(format!("{}: cannot write: {e}", path.display())))?;
    if !existed {
        // Best effort: the real write comes later and reports its own failure.
        let _ = std::fs::remove_file(path);
    }
    Ok(path.to_path_buf())
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;

    #[test]
    fn vec3_parses_three_numbers() {
        assert_eq!(parse_vec3("1,2.5,-3").unwrap(), DVec3::new(1.0, 2.5, -3.0));
        assert_eq!(
            parse_vec3(" 1 , 2 , 3 ").unwrap(),
            DVec3::new(1.0, 2.0, 3.0)
        );
    }

    #[test]
    fn vec3_with_two_components_names_the_count() {
        assert_eq!(
            parse_vec3("1,2").unwrap_err(),
            "expected 3 comma-separated numbers X,Y,Z, found 2"
        );
    }

    #[test]
    fn vec3_refuses_words_and_infinities() {
        assert_eq!(parse_vec3("1,x,2").unwrap_err(), "'x' is not a number");
        assert_eq!(
            parse_vec3("1,inf,2").unwrap_err(),
            "'inf' is not a finite number"
        );
    }

    #[test]
    fn sizes_parse_and_refuse_zero() {
        assert_eq!(parse_size("2000").unwrap(), 2000);
        assert!(parse_size("0").is_err());
        assert!(parse_size("-1").is_err());
        assert!(parse_size("").is_err());
    }

    #[test]
    fn scale_must_be_positive() {
        assert_eq!(validate_scale(None).unwrap(), DVec3::ONE);
        assert!(validate_scale(Some(DVec3::new(1.0, 0.0, 1.0))).is_err());
        assert!(validate_scale(Some(DVec3::new(1.0, 1.0, -2.0))).is_err());
        assert_eq!(
            validate_scale(Some(DVec3::new(1.0, 2.0, 3.0))).unwrap(),
            DVec3::new(1.0, 2.0, 3.0)
        );
    }

    #[test]
    fn writable_check_leaves_no_file_behind() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("out.obj");
        check_writable(&path).unwrap();
        assert!(!path.exists());
        assert!(check_writable(&dir.path().join("missing/out.obj")).is_err());
        assert!(check_writable(dir.path()).is_err());
    }
}
