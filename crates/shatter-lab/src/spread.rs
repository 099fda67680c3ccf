//! Mean, min and max of repeated measurements: what every sweep and benchmark reports per
//! case.

/// Mean, min and max of some values.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Spread {
    /// Arithmetic mean.
    pub mean: f64,
    /// Smallest value.
    pub min: f64,
    /// Largest value.
    pub max: f64,
}

impl Spread {
    /// The spread of `values`; `None` for no values.
    pub fn of(values: impl IntoIterator<Item = f64>) -> Option<Self> {
        let values: Vec<f64> = values.into_iter().collect();
        if values.is_empty() {
            return None;
        }
        let (min, max) = values
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &v| {
                (lo.min(v), hi.max(v))
            });
        Some(Self {
            mean: values.iter().sum::<f64>() / values.len() as f64,
            min,
            max,
        })
    }

    /// The spread of some counts; all zero for none.
    pub fn of_counts(values: &[usize]) -> Self {
        Self::of(values.iter().map(|&v| v as f64)).unwrap_or(Self {
            mean: 0.0,
            min: 0.0,
            max: 0.0,
        })
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;

    #[test]
    fn spread_is_mean_min_max() {
        let s = Spread::of([2.0, 1.0, 6.0]).unwrap();
        assert_eq!((s.mean, s.min, s.max), (3.0, 1.0, 6.0));
        assert!(Spread::of([]).is_none());
        let c = Spread::of_counts(&[10, 12]);
        assert_eq!((c.mean, c.min, c.max), (11.0, 10.0, 12.0));
        assert_eq!(Spread::of_counts(&[]).mean, 0.0);
    }
}
