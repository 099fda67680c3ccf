//! The command line's error type and exit codes.
//!
//! Exit codes: `0` success, `1` internal failure (a bug or an I/O failure that is not the
//! user's fault), `2` bad input (a bad flag, file, value or mesh, or a request too big for
//! the machine), `130` interrupted by Ctrl-C. clap's own usage errors also exit with `2`.

use std::fmt;

/// Exit code for bad user input.
pub const EXIT_INPUT: u8 = 2;
/// Exit code for an internal failure.
pub const EXIT_INTERNAL: u8 = 1;
/// Exit code when Ctrl-C stopped the command (128 + SIGINT, as shells report it).
pub const EXIT_INTERRUPTED: u8 = 130;

/// What an interrupted command says.
pub const INTERRUPTED_MESSAGE: &str =
    "interrupted (Ctrl-C): stopped before the end; no output file was written";

impl From<shatter_lab::LabError> for CliError {
    fn from(e: shatter_lab::LabError) -> Self {
        match e {
            shatter_lab::LabError::Input(m) => Self::input(m),
            shatter_lab::LabError::Internal(m) => Self::internal(m),
            shatter_lab::LabError::Interrupted => Self::Interrupted,
        }
    }
}

impl From<shatter_geom::progress::Cancelled> for CliError {
    fn from(_: shatter_geom::progress::Cancelled) -> Self {
        Self::Interrupted
    }
}

/// A failed command: what went wrong and whose fault it was.
#[derive(Debug)]
pub enum CliError {
    /// The user's input is wrong (exit code 2).
    Input(anyhow::Error),
    /// Something failed that the user could not prevent (exit code 1).
    Internal(anyhow::Error),
    /// Ctrl-C stopped the command before it finished; no output was written (exit 130).
    Interrupted,
}

impl CliError {
    /// A bad-input error with this message.
    pub fn input(message: impl fmt::Display) -> Self {
        Self::Input(anyhow::anyhow!("{message}"))
    }

    /// An internal error with this message.
    pub fn internal(message: impl fmt::Display) -> Self {
        Self::Internal(anyhow::anyhow!("{message}"))
    }

    /// The process exit code for this error.
    pub fn exit_code(&self) -> u8 {
        match self {
            Self::Input(_) => EXIT_INPUT,
            Self::Internal(_) => EXIT_INTERNAL,
            Self::Interrupted => EXIT_INTERRUPTED,
        }
    }
}

impl fmt::Display for CliError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        // `{:#}` prints the whole context chain on one line: "outer: inner: root".
        match self {
            Self::Input(e) | Self::Internal(e) => write!(f, "{e:#}"),
            Self::Interrupted => f.write_str(INTERRUPTED_MESSAGE),
        }
    }
}

/// Converting a `Result` into a [`CliError`] with context.
pub trait ResultExt<T> {
    /// Bad input, described by `context` followed by the cause.
    fn input_err(self, context: impl fmt::Display) -> Result<T, CliError>;
    /// Internal failure, described by `context` followed by the cause.
    fn internal_err(self, context: impl fmt::Display) -> Result<T, CliError>;
}

impl<T, E> ResultExt<T> for Result<T, E>
where
    E: std::error::Error + Send + Sync + 'static,
{
    fn input_err(self, context: impl fmt::Display) -> Result<T, CliError> {
        self.map_err(|e| CliError::Input(anyhow::Error::new(e).context(context.to_string())))
    }

    fn internal_err(self, context: impl fmt::Display) -> Result<T, CliError> {
        self.map_err(|e| CliError::Internal(anyhow::Error::new(e).context(context.to_string())))
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;

    #[test]
    fn input_errors_exit_2_and_internal_errors_exit_1() {
        assert_eq!(CliError::input("bad").exit_code(), 2);
        assert_eq!(CliError::internal("bug").exit_code(), 1);
        assert_eq!(CliError::Interrupted.exit_code(), 130);
    }

    #[test]
    fn lab_errors_keep_their_kind_and_message() {
        use shatter_lab::LabError;
        let e = CliError::from(LabError::input("--runs must be at least 1"));
        assert_eq!(
            (e.exit_code(), e.to_string().as_str()),
            (2, "--runs must be at least 1")
        );
        assert_eq!(CliError::from(LabError::internal("bug")).exit_code(), 1);
        assert_eq!(CliError::from(LabError::Interrupted).exit_code(), 130);
    }

    #[test]
    fn context_chain_is_printed_on_one_line() {
        let r: Result<(), std::io::Error> = Err(std::io::Error::new(
            std::io::ErrorKind::NotFound,
            "no such file",
        ));
        let e = r.input_err("cannot read 'a.xyz'").unwrap_err();
        assert_eq!(e.to_string(), "cannot read 'a.xyz': no such file");
        assert_eq!(e.exit_code(), 2);
    }
}
