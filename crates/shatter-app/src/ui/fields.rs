//! Parsing of single text fields into typed values, with messages meant for the user.
//!
//! Every function takes the raw text of one field and returns the value or a
//! [`FieldError`], whose `Display` is the short message shown next to that field.

use glam::DVec3;
use thiserror::Error;

/// Why the text of a field is not a value. `text` is the trimmed text the user typed;
/// `value` a number that parsed but is outside the field's range.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum FieldError {
    /// The field is empty; `what` says what it needs ("a number", "a whole number").
    #[error("required: {what}")]
    Required {
        /// What the field needs.
        what: &'static str,
    },
    /// Not a number at all.
    #[error("'{text}' is not a number")]
    NotANumber {
        /// The text typed.
        text: String,
    },
    /// Not a number at all, where a whole number is needed.
    #[error("'{text}' is not a whole number")]
    NotAWholeNumber {
        /// The text typed.
        text: String,
    },
    /// A number, but with a fractional part, where a whole number is needed.
    #[error("'{text}' is not an integer")]
    NotAnInteger {
        /// The text typed.
        text: String,
    },
    /// A negative number where a count is needed.
    #[error("'{text}' is negative")]
    Negative {
        /// The text typed.
        text: String,
    },
    /// A whole number larger than `max`.
    #[error("'{text}' is too large (at most {max})")]
    TooLarge {
        /// The text typed.
        text: String,
        /// The largest value allowed.
        max: u32,
    },
    /// Infinite or NaN.
    #[error("'{text}' is not finite")]
    NotFinite {
        /// The text typed.
        text: String,
    },
    /// Zero or negative where a number `> 0` is needed.
    #[error("must be greater than 0 (got {value})")]
    NotPositive {
        /// The number typed.
        value: f64,
    },
    /// Negative where a number `>= 0` is needed.
    #[error("must not be negative (got {value})")]
    BelowZero {
        /// The number typed.
        value: f64,
    },
    /// Outside `[min, max]`.
    #[error("must be between {min} and {max} (got {value})")]
    OutOfRange {
        /// The number typed.
        value: f64,
        /// Lowest value allowed.
        min: f64,
        /// Highest value allowed.
        max: f64,
    },
    /// One component of a vector or a colour failed; `component` names it ("x", "G").
    /// The component's own error is part of the message, so it is not also a
    /// [`source`](std::error::Error::source) (it is reached through `error`).
    #[error("{component}: {error}")]
    Component {
        /// The axis or channel.
        component: &'static str,
        /// What is wrong with it.
        error: Box<FieldError>,
    },
}

impl FieldError {
    fn component(component: &'static str) -> impl FnOnce(FieldError) -> FieldError {
        move |e| FieldError::Component {
            component,
            error: Box::new(e),
        }
    }
}

/// A non-negative integer ("Random Vertices", "Skip").
///
/// ```
/// use shatter_app::ui::fields::{FieldError, parse_count};
/// assert_eq!(parse_count(" 40 "), Ok(40));
/// assert_eq!(
///     parse_count("4.5"),
///     Err(FieldError::NotAnInteger { text: "4.5".into() })
/// );
/// assert_eq!(parse_count("4.5").unwrap_err().to_string(), "'4.5' is not an integer");
/// ```
pub fn parse_count(text: &str) -> Result<u32, FieldError> {
    let t = text.trim();
    if t.is_empty() {
        return Err(FieldError::Required {
            what: "a whole number",
        });
    }
    if let Ok(v) = t.parse::<u32>() {
        return Ok(v);
    }
    let text = t.to_owned();
    match t.parse::<f64>() {
        Ok(v) if v < 0.0 => Err(FieldError::Negative { text }),
        Ok(v) if v.fract() == 0.0 && v.is_finite() => Err(FieldError::TooLarge {
            text,
            max: u32::MAX,
        }),
        Ok(_) => Err(FieldError::NotAnInteger { text }),
        Err(_) => Err(FieldError::NotAWholeNumber { text }),
    }
}

/// A finite real number.
pub fn parse_real(text: &str) -> Result<f64, FieldError> {
    let t = text.trim();
    if t.is_empty() {
        return Err(FieldError::Required { what: "a number" });
    }
    match t.parse::<f64>() {
        Ok(v) if v.is_finite() => Ok(v),
        Ok(_) => Err(FieldError::NotFinite { text: t.to_owned() }),
        Err(_) => Err(FieldError::NotANumber { text: t.to_owned() }),
    }
}

/// A finite number `> 0`.
pub fn parse_positive(text: &str) -> Result<f64, FieldError> {
    let v = parse_real(text)?;
    if v > 0.0 {
        Ok(v)
    } else {
        Err(FieldError::NotPositive { value: v })
    }
}

/// A finite number `>= 0`.
pub fn parse_non_negative(text: &str) -> Result<f64, FieldError> {
    let v = parse_real(text)?;
    if v >= 0.0 {
        Ok(v)
    } else {
        Err(FieldError::BelowZero { value: v })
    }
}

/// A lifetime in seconds ("Last"): empty means for ever, otherwise a number `> 0`.
pub fn parse_lifetime(text: &str) -> Result<Option<f64>, FieldError> {
    if text.trim().is_empty() {
        Ok(None)
    } else {
        parse_positive(text).map(Some)
    }
}

/// A colour component in `[0, 1]`.
pub fn parse_unit(text: &str) -> Result<f32, FieldError> {
    let v = parse_real(text)?;
    if (0.0..=1.0).contains(&v) {
        Ok(v as f32)
    } else {
        Err(FieldError::OutOfRange {
            value: v,
            min: 0.0,
            max: 1.0,
        })
    }
}

/// Three fields, each parsed by `parse`; the error names the axis that failed
/// ([`FieldError::Component`]).
pub fn parse_vec3(
    texts: &[String; 3],
    parse: impl Fn(&str) -> Result<f64, FieldError>,
) -> Result<DVec3, FieldError> {
    let mut out = [0.0; 3];
    for (i, (t, axis)) in texts.iter().zip(["x", "y", "z"]).enumerate() {
        out[i] = parse(t).map_err(FieldError::component(axis))?;
    }
    Ok(DVec3::from_array(out))
}

/// Three colour components in `[0, 1]`; the error names the channel that failed
/// ([`FieldError::Component`]).
pub fn parse_color(texts: &[String; 3]) -> Result<[f32; 3], FieldError> {
    let mut out = [0.0; 3];
    for (i, (t, channel)) in texts.iter().zip(["R", "G", "B"]).enumerate() {
        out[i] = parse_unit(t).map_err(FieldError::component(channel))?;
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn s3(a: &str, b: &str, c: &str) -> [String; 3] {
        [a.to_owned(), b.to_owned(), c.to_owned()]
    }

    #[test]
    fn count_rejects_non_integers_and_negatives() {
        assert_eq!(parse_count("12"), Ok(12));
        assert!(
            parse_count("1.5")
                .unwrap_err()
                .to_string()
                .contains("not an integer")
        );
        assert!(
            parse_count("-3")
                .unwrap_err()
                .to_string()
                .contains("negative")
        );
        assert!(
            parse_count("-1.5")
                .unwrap_err()
                .to_string()
                .contains("negative")
        );
        assert!(
            parse_count("5000000000")
                .unwrap_err()
                .to_string()
                .contains("too large")
        );
        assert!(
            parse_count("abc")
                .unwrap_err()
                .to_string()
                .contains("not a whole number")
        );
        assert!(parse_count("").is_err());
    }

    #[test]
    fn reals_must_be_finite() {
        assert_eq!(parse_real("2.5"), Ok(2.5));
        assert!(parse_real("inf").is_err());
        assert!(parse_real("NaN").is_err());
        assert!(parse_positive("0").is_err());
        assert_eq!(parse_non_negative("0"), Ok(0.0));
        assert!(
            parse_non_negative("-1")
                .unwrap_err()
                .to_string()
                .contains("negative")
        );
    }

    #[test]
    fn lifetime_empty_is_forever() {
        assert_eq!(parse_lifetime(""), Ok(None));
        assert_eq!(parse_lifetime("3"), Ok(Some(3.0)));
        assert!(parse_lifetime("0").is_err());
    }

    #[test]
    fn vec3_and_color_name_the_failing_component() {
        assert_eq!(
            parse_vec3(&s3("1", "2", "3"), parse_real),
            Ok(DVec3::new(1.0, 2.0, 3.0))
        );
        assert!(
            parse_vec3(&s3("1", "x", "3"), parse_real)
                .unwrap_err()
                .to_string()
                .starts_with("y:")
        );
        assert!(
            parse_vec3(&s3("1", "1", "0"), parse_positive)
                .unwrap_err()
                .to_string()
                .starts_with("z:")
        );
        assert_eq!(parse_color(&s3("1", "0.5", "0")), Ok([1.0, 0.5, 0.0]));
        assert!(
            parse_color(&s3("1", "2", "0"))
                .unwrap_err()
                .to_string()
                .starts_with("G:")
        );
    }

    #[test]
    fn messages_are_the_ones_the_user_sees() {
        let msg = |r: Result<f64, FieldError>| r.unwrap_err().to_string();
        let count = |t: &str| parse_count(t).unwrap_err().to_string();
        assert_eq!(count(""), "required: a whole number");
        assert_eq!(count("-3"), "'-3' is negative");
        assert_eq!(
            count("5000000000"),
            "'5000000000' is too large (at most 4294967295)"
        );
        assert_eq!(count(" 1.5 "), "'1.5' is not an integer");
        assert_eq!(count("abc"), "'abc' is not a whole number");
        assert_eq!(msg(parse_real("")), "required: a number");
        assert_eq!(msg(parse_real("inf")), "'inf' is not finite");
        assert_eq!(msg(parse_real("x")), "'x' is not a number");
        assert_eq!(msg(parse_positive("0")), "must be greater than 0 (got 0)");
        assert_eq!(
            msg(parse_positive("-1.5")),
            "must be greater than 0 (got -1.5)"
        );
        assert_eq!(
            msg(parse_non_negative("-1")),
            "must not be negative (got -1)"
        );
        assert_eq!(
            parse_unit("2").unwrap_err().to_string(),
            "must be between 0 and 1 (got 2)"
        );
        assert_eq!(
            parse_color(&s3("1", "2", "0")).unwrap_err().to_string(),
            "G: must be between 0 and 1 (got 2)"
        );
        assert_eq!(
            parse_vec3(&s3("1", "1", "0"), parse_positive)
                .unwrap_err()
                .to_string(),
            "z: must be greater than 0 (got 0)"
        );
    }

    #[test]
    fn a_component_error_keeps_the_components_error() {
        let e = parse_vec3(&s3("1", "ten", "3"), parse_real).unwrap_err();
        let FieldError::Component { component, error } = e else {
            panic!("expected a component error, got {e:?}");
        };
        assert_eq!(component, "y");
        assert_eq!(*error, FieldError::NotANumber { text: "ten".into() });
    }
}
