//! Strict readers for the scene's numbers and vectors, used by the schema
//! ([`super::file`]) through `#[serde(deserialize_with = ...)]`:
//!
//! - a vector is exactly three numbers: `[0, 1, 0, 99]` is an error naming the length,
//!   not a vector whose fourth number is dropped;
//! - a number the simulation keeps as `f32` must fit it: `1e300` is an error naming
//!   `f32`'s range, not an infinity that a later check calls "not positive", and a
//!   non-zero number too small for it (`1e-50`) is not silently zero.
//!
//! The parser reports these errors with the line, the column and the key, like any
//! other type error.

use std::fmt;
use std::marker::PhantomData;

use serde::de::{self, Deserialize, Deserializer, SeqAccess, Visitor};
use toml::Spanned;

/// The largest magnitude an `f32` holds (about 3.4e38).
pub const F32_LARGEST: f64 = f32::MAX as f64;
/// The smallest non-zero magnitude kept exactly enough (the smallest normal `f32`, about
/// 1.2e-38); below it `f32` loses precision and then rounds to zero.
pub const F32_SMALLEST: f64 = f32::MIN_POSITIVE as f64;

/// Why a number does not fit the simulation's `f32`.
#[derive(Debug, Clone, Copy, PartialEq, thiserror::Error)]
pub enum NarrowError {
    /// Beyond ±3.4e38.
    #[error("{0:e} is too large for the simulation's 32-bit floats (largest magnitude 3.4e38)")]
    TooLarge(f64),
    /// Non-zero but below 1.2e-38.
    #[error(
        "{0:e} is too small for the simulation's 32-bit floats (smallest non-zero magnitude 1.2e-38)"
    )]
    TooSmall(f64),
}

/// `value` as the simulation's `f32`, or why it does not fit. NaN and the infinities
/// pass through unchanged (the key's own check names them), zero stays zero.
///
/// ```
/// use shatter_sim::scene::values::narrow_to_f32;
/// assert_eq!(narrow_to_f32(2.5), Ok(2.5));
/// assert!(narrow_to_f32(1e300).unwrap_err().to_string().contains("largest magnitude 3.4e38"));
/// assert!(narrow_to_f32(-1e-50).is_err());
/// assert_eq!(narrow_to_f32(0.0), Ok(0.0));
/// ```
pub fn narrow_to_f32(value: f64) -> Result<f32, NarrowError> {
    if !value.is_finite() || value == 0.0 {
        return Ok(value as f32);
    }
    if value.abs() > F32_LARGEST {
        return Err(NarrowError::TooLarge(value));
    }
    if value.abs() < F32_SMALLEST {
        return Err(NarrowError::TooSmall(value));
    }
    Ok(value as f32)
}

/// One `f32` read strictly (as a TOML float or integer).
#[derive(Debug, Clone, Copy, PartialEq)]
struct StrictF32(f32);

impl<'de> Deserialize<'de> for StrictF32 {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let v = f64::deserialize(d)?;
        narrow_to_f32(v).map(StrictF32).map_err(de::Error::custom)
    }
}

/// A scalar a vector may hold.
trait Component: Sized + Copy + Default {
    /// Reads one component from a sequence.
    fn next<'de, A: SeqAccess<'de>>(seq: &mut A) -> Result<Option<Self>, A::Error>;
    /// What the components are, for the message ("numbers", "integers").
    const WORD: &'static str;
}

impl Component for f32 {
    fn next<'de, A: SeqAccess<'de>>(seq: &mut A) -> Result<Option<Self>, A::Error> {
        Ok(seq.next_element::<StrictF32>()?.map(|v| v.0))
    }
    const WORD: &'static str = "numbers";
}

impl Component for i64 {
    fn next<'de, A: SeqAccess<'de>>(seq: &mut A) -> Result<Option<Self>, A::Error> {
        seq.next_element::<i64>()
    }
    const WORD: &'static str = "integers";
}

/// Exactly three components.
struct Triple<T>([T; 3]);

impl<'de, T: Component> Deserialize<'de> for Triple<T> {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct V<T>(PhantomData<T>);
        impl<'de, T: Component> Visitor<'de> for V<T> {
            type Value = Triple<T>;
            fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                write!(f, "an array of 3 {} [x, y, z]", T::WORD)
            }
            fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Self::Value, A::Error> {
                let mut out = [T::default(); 3];
                let mut n = 0usize;
                while let Some(v) = T::next(&mut seq)? {
                    if let Some(slot) = out.get_mut(n) {
                        *slot = v;
                    }
                    n += 1;
                }
                if n != 3 {
                    return Err(de::Error::custom(format!(
                        "expected 3 {} [x, y, z], found {n}",
                        T::WORD
                    )));
                }
                Ok(Triple(out))
            }
        }
        d.deserialize_seq(V(PhantomData))
    }
}

fn respan<T, U>(s: Spanned<T>, f: impl FnOnce(T) -> U) -> Spanned<U> {
    let span = s.span();
    Spanned::new(span, f(s.into_inner()))
}

/// An optional `f32`.
pub fn opt_f32<'de, D: Deserializer<'de>>(d: D) -> Result<Option<f32>, D::Error> {
    Ok(Option::<StrictF32>::deserialize(d)?.map(|v| v.0))
}

/// An optional `f32` with its place in the file.
pub fn opt_spanned_f32<'de, D: Deserializer<'de>>(d: D) -> Result<Option<Spanned<f32>>, D::Error> {
    Ok(Option::<Spanned<StrictF32>>::deserialize(d)?.map(|s| respan(s, |v| v.0)))
}

/// A required `f32` with its place in the file.
pub fn spanned_f32<'de, D: Deserializer<'de>>(d: D) -> Result<Spanned<f32>, D::Error> {
    Ok(respan(Spanned::<StrictF32>::deserialize(d)?, |v| v.0))
}

/// A required vector of three `f32`.
pub fn vec3<'de, D: Deserializer<'de>>(d: D) -> Result<[f32; 3], D::Error> {
    Ok(Triple::<f32>::deserialize(d)?.0)
}

/// An optional vector of three `f32`.
pub fn opt_vec3<'de, D: Deserializer<'de>>(d: D) -> Result<Option<[f32; 3]>, D::Error> {
    Ok(Option::<Triple<f32>>::deserialize(d)?.map(|t| t.0))
}

/// An optional vector of three `f32` with its place in the file.
pub fn opt_spanned_vec3<'de, D: Deserializer<'de>>(
    d: D,
) -> Result<Option<Spanned<[f32; 3]>>, D::Error> {
    Ok(Option::<Spanned<Triple<f32>>>::deserialize(d)?.map(|s| respan(s, |t| t.0)))
}

/// An optional vector of three integers with its place in the file.
pub fn opt_spanned_ivec3<'de, D: Deserializer<'de>>(
    d: D,
) -> Result<Option<Spanned<[i64; 3]>>, D::Error> {
    Ok(Option::<Spanned<Triple<i64>>>::deserialize(d)?.map(|s| respan(s, |t| t.0)))
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde::Deserialize;

    #[derive(Debug, Deserialize)]
    struct Doc {
        #[serde(default, deserialize_with = "opt_vec3")]
        v: Option<[f32; 3]>,
        #[serde(default, deserialize_with = "opt_spanned_f32")]
        x: Option<Spanned<f32>>,
        #[serde(default, deserialize_with = "opt_spanned_ivec3")]
        g: Option<Spanned<[i64; 3]>>,
    }

    fn parse(text: &str) -> Result<Doc, String> {
        toml::from_str::<Doc>(text).map_err(|e| e.message().to_string())
    }

    #[test]
    fn a_vector_is_exactly_three_numbers() {
        assert_eq!(parse("v = [0, 1.5, -2]").unwrap().v, Some([0.0, 1.5, -2.0]));
        assert_eq!(
            parse("v = [0, 1, 0, 99]").unwrap_err(),
            "expected 3 numbers [x, y, z], found 4"
        );
        assert_eq!(
            parse("v = [0, 1]").unwrap_err(),
            "expected 3 numbers [x, y, z], found 2"
        );
        assert_eq!(
            parse("g = [1, 2, 3, 4]").unwrap_err(),
            "expected 3 integers [x, y, z], found 4"
        );
        assert_eq!(
            parse("g = [1, 2, 3]").unwrap().g.unwrap().into_inner(),
            [1, 2, 3]
        );
        assert!(parse("v = 3").is_err());
        assert!(parse("").unwrap().v.is_none());
    }

    #[test]
    fn numbers_beyond_f32_name_the_range() {
        let e = parse("x = 1e300").unwrap_err();
        assert_eq!(
            e,
            "1e300 is too large for the simulation's 32-bit floats (largest magnitude 3.4e38)"
        );
        assert!(
            parse("v = [0, -1e39, 0]")
                .unwrap_err()
                .contains("too large")
        );
        assert!(parse("x = 1e-45").unwrap_err().contains("too small"));
        let x = parse("x = 2").unwrap().x.unwrap();
        assert_eq!(*x.get_ref(), 2.0);
        assert_eq!(x.span(), 4..5);
        // Infinities reach the key's own check, which names them.
        assert_eq!(
            *parse("x = inf").unwrap().x.unwrap().get_ref(),
            f32::INFINITY
        );
    }

    #[test]
    fn narrowing_keeps_everything_f32_can_hold() {
        assert_eq!(narrow_to_f32(3.0e38), Ok(3.0e38));
        assert_eq!(narrow_to_f32(-2.0e-38), Ok(-2.0e-38));
        assert!(matches!(
            narrow_to_f32(-4e38),
            Err(NarrowError::TooLarge(_))
        ));
        assert!(narrow_to_f32(f64::NAN).unwrap().is_nan());
    }
}
