//! Parsing of single text fields into typed values, with messages meant for the user.
//!
//! Every function takes the raw text of one field and returns the value or a short
//! message to show next to that field.

use glam::DVec3;

/// A non-negative integer ("Random Vertices", "Skip").
///
/// ```
/// use shatter_app::ui::fields::parse_count;
/// assert_eq!(parse_count(" 40 "), Ok(40));
/// assert!(parse_count("4.5").is_err());
/// ```
pub fn parse_count(text: &str) -> Result<u32, String> {
    let t = text.trim();
    if t.is_empty() {
        return Err("required: a whole number".to_owned());
    }
    if let Ok(v) = t.parse::<u32>() {
        return Ok(v);
    }
    match t.parse::<f64>() {
        Ok(v) if v < 0.0 => Err(format!("'{t}' is negative")),
        Ok(v) if v.fract() == 0.0 && v.is_finite() => {
            Err(format!("'{t}' is too large (at most {})", u32::MAX))
        }
        Ok(_) => Err(format!("'{t}' is not an integer")),
        Err(_) => Err(format!("'{t}' is not a whole number")),
    }
}

/// A finite real number.
pub fn parse_real(text: &str) -> Result<f64, String> {
    let t = text.trim();
    if t.is_empty() {
        return Err("required: a number".to_owned());
    }
    match t.parse::<f64>() {
        Ok(v) if v.is_finite() => Ok(v),
        Ok(_) => Err(format!("'{t}' is not finite")),
        Err(_) => Err(format!("'{t}' is not a number")),
    }
}

/// A finite number `> 0`.
pub fn parse_positive(text: &str) -> Result<f64, String> {
    let v = parse_real(text)?;
    if v > 0.0 {
        Ok(v)
    } else {
        Err(format!("must be greater than 0 (got {v})"))
    }
}

/// A finite number `>= 0`.
pub fn parse_non_negative(text: &str) -> Result<f64, String> {
    let v = parse_real(text)?;
    if v >= 0.0 {
        Ok(v)
    } else {
        Err(format!("must not be negative (got {v})"))
    }
}

/// A lifetime in seconds ("Last"): empty means for ever, otherwise a number `> 0`.
pub fn parse_lifetime(text: &str) -> Result<Option<f64>, String> {
    if text.trim().is_empty() {
        Ok(None)
    } else {
        parse_positive(text).map(Some)
    }
}

/// A colour component in `[0, 1]`.
pub fn parse_unit(text: &str) -> Result<f32, String> {
    let v = parse_real(text)?;
    if (0.0..=1.0).contains(&v) {
        Ok(v as f32)
    } else {
        Err(format!("must be between 0 and 1 (got {v})"))
    }
}

/// Three fields, each parsed by `parse`; the message names the axis that failed.
pub fn parse_vec3(
    texts: &[String; 3],
    parse: impl Fn(&str) -> Result<f64, String>,
) -> Result<DVec3, String> {
    let mut out = [0.0; 3];
    for (i, (t, axis)) in texts.iter().zip(["x", "y", "z"]).enumerate() {
        out[i] = parse(t).map_err(|e| format!("{axis}: {e}"))?;
    }
    Ok(DVec3::from_array(out))
}

/// Three colour components in `[0, 1]`; the message names the channel that failed.
pub fn parse_color(texts: &[String; 3]) -> Result<[f32; 3], String> {
    let mut out = [0.0; 3];
    for (i, (t, channel)) in texts.iter().zip(["R", "G", "B"]).enumerate() {
        out[i] = parse_unit(t).map_err(|e| format!("{channel}: {e}"))?;
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
        assert!(parse_count("1.5").unwrap_err().contains("not an integer"));
        assert!(parse_count("-3").unwrap_err().contains("negative"));
        assert!(parse_count("-1.5").unwrap_err().contains("negative"));
        assert!(parse_count("5000000000").unwrap_err().contains("too large"));
        assert!(
            parse_count("abc")
                .unwrap_err()
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
        assert!(parse_non_negative("-1").unwrap_err().contains("negative"));
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
                .starts_with("y:")
        );
        assert!(
            parse_vec3(&s3("1", "1", "0"), parse_positive)
                .unwrap_err()
                .starts_with("z:")
        );
        assert_eq!(parse_color(&s3("1", "0.5", "0")), Ok([1.0, 0.5, 0.0]));
        assert!(
            parse_color(&s3("1", "2", "0"))
                .unwrap_err()
                .starts_with("G:")
        );
    }
}
