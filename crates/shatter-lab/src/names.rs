//! Lists of vocabulary words given as options (`cube,bird`), parsed into their values.

use crate::error::LabError;

/// Parses a list of words of a vocabulary (`all` and its `words`, e.g. `Shape::ALL` and
/// `Shape::NAMES`; case-insensitive), refusing unknown and repeated words and an empty
/// list. `option` and `what` name the list in errors ("--models: unknown model 'teapot'
/// (expected one of: cube, ...)").
pub fn parse_list<T: Copy + PartialEq>(
    names: &[String],
    option: &str,
    what: &str,
    all: &[T],
    words: &[&str],
) -> Result<Vec<T>, LabError> {
    let mut values: Vec<T> = Vec::new();
    for name in names.iter().map(|n| n.trim()).filter(|n| !n.is_empty()) {
        let Some(value) = all
            .iter()
            .zip(words)
            .find(|(_, w)| w.eq_ignore_ascii_case(name))
            .map(|(v, _)| *v)
        else {
            return Err(LabError::input(format!(
                "{option}: unknown {what} '{name}' (expected one of: {})",
                words.join(", ")
            )));
        };
        if values.contains(&value) {
            return Err(LabError::input(format!(
                "{option}: {what} '{name}' is repeated"
            )));
        }
        values.push(value);
    }
    if values.is_empty() {
        return Err(LabError::input(format!(
            "{option}: give at least one {what}"
        )));
    }
    Ok(values)
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;
    use shatter_geom::shapes::Shape;

    fn parse(names: &[&str]) -> Result<Vec<Shape>, LabError> {
        let names: Vec<String> = names.iter().map(|s| s.to_string()).collect();
        parse_list(&names, "--models", "model", Shape::ALL, Shape::NAMES)
    }

    #[test]
    fn words_parse_in_order_ignoring_case_and_blanks() {
        assert_eq!(
            parse(&["cube", " BIRD", ""]).unwrap(),
            vec![Shape::Cube, Shape::Bird]
        );
    }

    #[test]
    fn unknown_repeated_and_missing_words_are_input_errors() {
        let e = parse(&["cube", "teapot"]).unwrap_err().to_string();
        assert!(
            e.starts_with("--models: unknown model 'teapot' (expected one of: cube,"),
            "{e}"
        );
        assert!(
            parse(&["cube", "cube"])
                .unwrap_err()
                .to_string()
                .contains("is repeated")
        );
        assert_eq!(
            parse(&[]).unwrap_err(),
            LabError::input("--models: give at least one model")
        );
    }
}
