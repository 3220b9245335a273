//! Command-line plumbing: flag values, `--help` and the exit status.

/// Parses the value that follows flag `name`, naming the flag in the error.
pub(crate) fn parse_value<T: std::str::FromStr>(
    name: &str,
    value: Option<String>,
) -> Result<T, String>
where
    T::Err: std::fmt::Display,
{
    let text = value.ok_or_else(|| format!("{name} needs a value"))?;
    text.parse().map_err(|e| format!("{name} '{text}': {e}"))
}

/// Prints the usage to stdout and exits with success, as `--help` should.
pub(crate) fn print_help(usage: &str) -> ! {
    println!("{usage}");
    std::process::exit(0)
}

/// The exit status of a run: errors go to stderr with a failure status.
pub(crate) fn finish(result: Result<(), String>) -> std::process::ExitCode {
    if let Err(e) = result {
        eprintln!("error: {e}");
        return std::process::ExitCode::FAILURE;
    }
    std::process::ExitCode::SUCCESS
}
