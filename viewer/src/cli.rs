//! Command-line plumbing: flags and their values, `--help`, and the exit status.

use std::str::FromStr;

/// The program's arguments, read flag by flag.
#[derive(Debug)]
pub(crate) struct Flags {
    args: std::iter::Skip<std::env::Args>,
}

impl Flags {
    /// The arguments after the program name.
    pub(crate) fn from_env() -> Self {
        Flags {
            args: std::env::args().skip(1),
        }
    }

    /// The next flag, if any.
    pub(crate) fn next_flag(&mut self) -> Option<String> {
        self.args.next()
    }

    /// The value after `flag`, parsed; the error names the flag and the text.
    pub(crate) fn value<T: FromStr>(&mut self, flag: &str) -> Result<T, String>
    where
        T::Err: std::fmt::Display,
    {
        let Some(text) = self.args.next() else {
            return Err(format!("{flag} needs a value"));
        };
        text.parse().map_err(|e| format!("{flag} '{text}': {e}"))
    }
}

/// Prints the usage to stdout and exits with success, as `--help` should.
pub(crate) fn print_help(usage: &str) -> ! {
    println!("{usage}");
    std::process::exit(0)
}
