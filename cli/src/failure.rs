//! Why a subcommand failed, as one line for stderr and an exit status.

use std::fmt;

/// A subcommand's failure: the library's error (its message names the file, the value and
/// what to do) or a check of the command line's own.
#[derive(Debug)]
pub(crate) struct Failure {
    message: String,
    code: u8,
}

impl Failure {
    /// A flag's value the command refuses (exit status 2, as for a command line that does not
    /// parse).
    pub(crate) fn usage(message: impl Into<String>) -> Failure {
        Failure {
            message: message.into(),
            code: 2,
        }
    }

    /// The job failed (exit status 1).
    pub(crate) fn job(message: impl Into<String>) -> Failure {
        Failure {
            message: message.into(),
            code: 1,
        }
    }

    /// The exit status.
    pub(crate) fn code(&self) -> u8 {
        self.code
    }
}

impl fmt::Display for Failure {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        // One line: a library message never spans lines, but a source chain might.
        f.write_str(&self.message.replace('\n', " "))
    }
}

impl<E: std::error::Error> From<E> for Failure {
    fn from(e: E) -> Self {
        Failure::job(e.to_string())
    }
}
