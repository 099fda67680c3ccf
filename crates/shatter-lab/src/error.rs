//! The lab's error: whose fault a failure is, so that a command line can choose its exit
//! code (bad input, internal failure, interrupted).

use std::fmt;

use shatter_geom::progress::Cancelled;

/// A failed piece of work: what went wrong and whose fault it was.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum LabError {
    /// The request is wrong: a bad option, file, value or mesh, or too big for the
    /// machine (a command line's exit code 2).
    #[error("{0}")]
    Input(String),
    /// Something failed that the user could not prevent: a bug, or an I/O failure that
    /// is not the user's fault (exit code 1).
    #[error("{0}")]
    Internal(String),
    /// The progress handle was cancelled (Ctrl-C) before the work finished; no output
    /// was written.
    #[error("interrupted before the end; no output file was written")]
    Interrupted,
}

impl LabError {
    /// A bad-input error with this message.
    pub fn input(message: impl fmt::Display) -> Self {
        Self::Input(message.to_string())
    }

    /// An internal error with this message.
    pub fn internal(message: impl fmt::Display) -> Self {
        Self::Internal(message.to_string())
    }
}

impl From<Cancelled> for LabError {
    fn from(_: Cancelled) -> Self {
        Self::Interrupted
    }
}

/// `error` and its sources on one line: "outer: inner: root".
pub fn chain(error: &dyn std::error::Error) -> String {
    let mut text = error.to_string();
    let mut source = error.source();
    while let Some(e) = source {
        text.push_str(": ");
        text.push_str(&e.to_string());
        source = e.source();
    }
    text
}

/// Converting a `Result` into a [`LabError`] with context.
pub trait ResultExt<T> {
    /// Bad input, described by `context` followed by the cause.
    fn input_err(self, context: impl fmt::Display) -> Result<T, LabError>;
    /// Internal failure, described by `context` followed by the cause.
    fn internal_err(self, context: impl fmt::Display) -> Result<T, LabError>;
}

impl<T, E: std::error::Error> ResultExt<T> for Result<T, E> {
    fn input_err(self, context: impl fmt::Display) -> Result<T, LabError> {
        self.map_err(|e| LabError::Input(format!("{context}: {}", chain(&e))))
    }

    fn internal_err(self, context: impl fmt::Display) -> Result<T, LabError> {
        self.map_err(|e| LabError::Internal(format!("{context}: {}", chain(&e))))
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;

    #[derive(Debug, thiserror::Error)]
    #[error("outer")]
    struct Outer(#[source] std::io::Error);

    #[test]
    fn context_and_the_whole_source_chain_are_on_one_line() {
        let r: Result<(), Outer> = Err(Outer(std::io::Error::new(
            std::io::ErrorKind::NotFound,
            "no such file",
        )));
        let e = r.input_err("cannot read 'a.xyz'").unwrap_err();
        assert_eq!(
            e,
            LabError::Input("cannot read 'a.xyz': outer: no such file".into())
        );
        let r: Result<(), std::io::Error> = Err(std::io::Error::other("disk full"));
        assert_eq!(
            r.internal_err("writing").unwrap_err(),
            LabError::Internal("writing: disk full".into())
        );
        assert_eq!(LabError::from(Cancelled), LabError::Interrupted);
    }
}
