//! Stresses on a bond's face and the limits a material sets on them.

use serde::{Deserialize, Serialize};

/// The stresses (Pa) on a bond's face, each ≥ 0: the worst point of the face, from the
/// bond's force (normal part over the area, tangential part over the area) and its moment
/// (bending `6·|M|/A^1.5` at the face's edge added to tension and compression, twisting
/// `3·|T|/A^1.5` added to shear, as for a square face of area `A`).
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct BondStress {
    /// Largest pressing stress.
    pub compression: f64,
    /// Largest pulling stress.
    pub tension: f64,
    /// Largest sliding stress.
    pub shear: f64,
}

/// Which limit a bond passed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Failure {
    /// Crushed.
    Compression,
    /// Pulled apart.
    Tension,
    /// Sheared off.
    Shear,
}

/// A material's strengths in pascals: the stress a bond takes before it breaks.
///
/// ```
/// use shatter_sim::stress::{BondStress, Failure, StressLimits};
/// let limits = StressLimits { compression: 100e6, tension: 6e6, shear: 12e6 };
/// let pulled = BondStress { compression: 0.0, tension: 7e6, shear: 1e6 };
/// assert_eq!(limits.failure(&pulled), Some(Failure::Tension));
/// assert_eq!(limits.failure(&BondStress::default()), None);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct StressLimits {
    /// Compressive strength (Pa).
    pub compression: f64,
    /// Tensile strength (Pa).
    pub tension: f64,
    /// Shear strength (Pa).
    pub shear: f64,
}

impl StressLimits {
    /// The limit passed by the largest margin (stress / limit), or `None` if the stress is
    /// within every limit.
    pub fn failure(&self, s: &BondStress) -> Option<Failure> {
        let ratios = [
            (s.compression / self.compression, Failure::Compression),
            (s.tension / self.tension, Failure::Tension),
            (s.shear / self.shear, Failure::Shear),
        ];
        ratios
            .into_iter()
            .filter(|(r, _)| *r > 1.0)
            .max_by(|x, y| x.0.total_cmp(&y.0))
            .map(|(_, f)| f)
    }

    /// The largest stress / limit ratio (1 = at the limit).
    pub fn utilisation(&self, s: &BondStress) -> f64 {
        (s.compression / self.compression)
            .max(s.tension / self.tension)
            .max(s.shear / self.shear)
    }

    /// Checks that every limit is a positive finite number; `key` prefixes the error.
    pub fn validate(&self, key: &str) -> Result<(), crate::SimError> {
        for (v, name) in [
            (self.compression, "compression"),
            (self.tension, "tension"),
            (self.shear, "shear"),
        ] {
            if !(v.is_finite() && v > 0.0) {
                return Err(crate::SimError::invalid(
                    format!("{key}.{name}"),
                    format!("must be a positive number of pascals, got {v}"),
                ));
            }
        }
        Ok(())
    }
}
