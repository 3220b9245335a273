//! Helpers shared by the examples.
#![allow(dead_code, reason = "each example uses only some of these helpers")]

/// Peak resident memory of this process in bytes (Linux `/proc`); 0 where unavailable.
pub(crate) fn peak_rss() -> u64 {
    std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("VmHWM:"))
                .and_then(|l| l.split_whitespace().nth(1)?.parse::<u64>().ok())
        })
        .map_or(0, |kb| kb * 1024)
}

/// Parses a flag's value, naming the flag in the error.
pub(crate) fn parse_value<T: std::str::FromStr>(
    name: &str,
    value: Option<String>,
) -> Result<T, String>
where
    T::Err: std::fmt::Display,
{
    let v = value.ok_or_else(|| format!("{name} needs a value"))?;
    v.parse().map_err(|e| format!("{name} '{v}': {e}"))
}

/// Prints the usage to stdout and exits with success, as `--help` should.
pub(crate) fn print_help(usage: &str) -> ! {
    println!("{usage}");
    std::process::exit(0)
}

/// Ends an example: errors go to stderr with a failure status.
pub(crate) fn finish(result: Result<(), String>) -> std::process::ExitCode {
    match result {
        Ok(()) => std::process::ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            std::process::ExitCode::FAILURE
        }
    }
}
