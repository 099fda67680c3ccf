//! The checks every scene value goes through: a word of the vocabulary, a count, a
//! positive number, a time, a colour; each error names the key and its line.

use std::path::{Path, PathBuf};
use std::str::FromStr;

use toml::Spanned;

use shatter_geom::vocab::UnknownWord;

use crate::error::SimError;

/// 1-based line and column of byte `offset` in `text`.
pub fn line_col(text: &str, offset: usize) -> (usize, usize) {
    let offset = offset.min(text.len());
    let before = text.get(..offset).unwrap_or(text);
    let line = before.matches('\n').count() + 1;
    let column = before.rsplit('\n').next().map_or(0, |s| s.chars().count()) + 1;
    (line, column)
}

/// Context for error messages: the source text (for lines) and the scene's folder.
pub(super) struct Ctx<'a> {
    pub(super) text: &'a str,
    pub(super) dir: Option<PathBuf>,
}

impl Ctx<'_> {
    /// `key (line N)`.
    pub(super) fn key<T>(&self, key: &str, spanned: &Spanned<T>) -> String {
        let (line, _) = line_col(self.text, spanned.span().start);
        format!("{key} (line {line})")
    }

    pub(super) fn path(&self, p: &str) -> String {
        match &self.dir {
            Some(d) if Path::new(p).is_relative() => d.join(p).to_string_lossy().into_owned(),
            _ => p.to_string(),
        }
    }
}

/// A vocabulary word (a method, a pattern, a bond model, ...) at `key`.
pub(super) fn word<T: FromStr<Err = UnknownWord>>(
    ctx: &Ctx,
    key: &str,
    v: &Spanned<String>,
) -> Result<T, SimError> {
    v.get_ref()
        .parse()
        .map_err(|e: UnknownWord| SimError::invalid(ctx.key(key, v), e.to_string()))
}

/// An optional vocabulary word at `key`.
pub(super) fn opt_word<T: FromStr<Err = UnknownWord>>(
    ctx: &Ctx,
    key: &str,
    v: &Option<Spanned<String>>,
) -> Result<Option<T>, SimError> {
    v.as_ref().map(|v| word(ctx, key, v)).transpose()
}

pub(super) fn count(
    ctx: &Ctx,
    key: &str,
    v: &Option<Spanned<i64>>,
    min: i64,
    default: u32,
) -> Result<u32, SimError> {
    match v {
        None => Ok(default),
        Some(s) if *s.get_ref() < min || *s.get_ref() > u32::MAX as i64 => Err(SimError::invalid(
            ctx.key(key, s),
            format!("must be an integer >= {min}, got {}", s.get_ref()),
        )),
        Some(s) => Ok(*s.get_ref() as u32),
    }
}

pub(super) fn positive(ctx: &Ctx, key: &str, v: &Spanned<f32>) -> Result<f32, SimError> {
    let x = *v.get_ref();
    if x.is_finite() && x > 0.0 {
        Ok(x)
    } else {
        Err(SimError::invalid(
            ctx.key(key, v),
            format!("must be positive, got {x}"),
        ))
    }
}

pub(super) fn time(ctx: &Ctx, key: &str, v: &Option<Spanned<f64>>) -> Result<f64, SimError> {
    match v {
        None => Ok(0.0),
        Some(t) if t.get_ref().is_finite() && *t.get_ref() >= 0.0 => Ok(*t.get_ref()),
        Some(t) => Err(SimError::invalid(
            ctx.key(key, t),
            format!("must be >= 0, got {}", t.get_ref()),
        )),
    }
}

pub(super) fn color(
    ctx: &Ctx,
    key: &str,
    v: &Option<Spanned<[f32; 3]>>,
    default: [f32; 3],
) -> Result<[f32; 3], SimError> {
    match v {
        None => Ok(default),
        Some(c) if c.get_ref().iter().all(|x| (0.0..=1.0).contains(x)) => Ok(*c.get_ref()),
        Some(c) => Err(SimError::invalid(
            ctx.key(key, c),
            format!("components must be in 0..=1, got {:?}", c.get_ref()),
        )),
    }
}
