//! Progress on stderr for work that lasts: spinners that appear only after a second, bars for
//! counted work, both hidden with `--quiet` or `--stats`.

use std::time::{Duration, Instant};

use indicatif::{ProgressBar, ProgressStyle};

/// A spinner saying `message` that shows only once a second has passed, or a hidden one.
pub(crate) fn spinner(hidden: bool, message: &str) -> ProgressBar {
    let bar = if hidden {
        ProgressBar::hidden()
    } else {
        ProgressBar::new_spinner()
    };
    bar.set_style(
        ProgressStyle::with_template("{spinner} {msg} {elapsed}")
            .unwrap_or_else(|_| ProgressStyle::default_spinner()),
    );
    bar.set_message(message.to_string());
    // The first tick comes after a second, so quick phases never draw.
    bar.enable_steady_tick(Duration::from_millis(1000));
    bar
}

/// Runs `work` under a [`spinner`] saying `message`.
pub(crate) fn phase<T>(hidden: bool, message: &str, work: impl FnOnce() -> T) -> (T, Duration) {
    let bar = spinner(hidden, message);
    let start = Instant::now();
    let out = work();
    bar.finish_and_clear();
    (out, start.elapsed())
}

/// A bar of `len` steps called `unit`, or a hidden one.
pub(crate) fn bar(hidden: bool, len: u64, unit: &str) -> ProgressBar {
    let bar = if hidden {
        ProgressBar::hidden()
    } else {
        ProgressBar::new(len)
    };
    bar.set_style(
        ProgressStyle::with_template(&format!("{{bar:30}} {{pos}}/{{len}} {unit} {{elapsed}}"))
            .unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
    bar
}

/// Peak resident memory of this process in MiB (Linux `/proc`); 0 where unavailable.
pub(crate) fn peak_rss_mb() -> f64 {
    std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("VmHWM:"))
                .and_then(|l| l.split_whitespace().nth(1)?.parse::<u64>().ok())
        })
        .map_or(0.0, |kb| kb as f64 / 1024.0)
}

/// Milliseconds of `d`.
pub(crate) fn ms(d: Duration) -> f64 {
    d.as_secs_f64() * 1e3
}

/// Prints `value` as one JSON line on stdout.
pub(crate) fn print_stats(value: &impl serde::Serialize) -> Result<(), crate::Failure> {
    println!("{}", serde_json::to_string(value)?);
    Ok(())
}
