//! Reading the line-based data files of a vlab model folder: function, curve and surface
//! files are `key: value` lines and lines of numbers, each error naming its line.

/// The non-empty lines of a model's data file (functions, curves, surfaces), with the line
/// number for errors.
pub(crate) struct Lines<'a> {
    lines: std::iter::Enumerate<std::str::Lines<'a>>,
    line: usize,
}

impl<'a> Lines<'a> {
    pub(crate) fn new(text: &'a str) -> Self {
        Lines {
            lines: text.lines().enumerate(),
            line: 0,
        }
    }

    /// The next non-empty line, trimmed; an error at the end of the file.
    pub(crate) fn next_line(&mut self) -> Result<&'a str, String> {
        for (k, l) in self.lines.by_ref() {
            self.line = k + 1;
            let l = l.trim();
            if !l.is_empty() {
                return Ok(l);
            }
        }
        Err(format!("the file ends after line {}", self.line))
    }

    /// `message` prefixed with the line last read.
    pub(crate) fn at(&self, message: impl std::fmt::Display) -> String {
        format!("line {}: {message}", self.line)
    }

    /// The value of a `key: value` line.
    pub(crate) fn field(&mut self, key: &str) -> Result<&'a str, String> {
        let line = self.next_line()?;
        line.strip_prefix(key)
            .map(str::trim)
            .ok_or_else(|| self.at(format!("expected '{key}', found '{line}'")))
    }

    /// The count of a `key: N` line.
    pub(crate) fn count(&mut self, key: &str) -> Result<usize, String> {
        let value = self.field(key)?;
        value
            .parse()
            .map_err(|_| self.at(format!("{key} '{value}': expected a count")))
    }

    /// The numbers of the next line, all finite (else an error saying it should be `what`).
    pub(crate) fn numbers(&mut self, what: &str) -> Result<Vec<f64>, String> {
        let line = self.next_line()?;
        self.numbers_of(line, what)
    }

    /// The numbers of `line` (the line last read), all finite.
    pub(crate) fn numbers_of(&self, line: &str, what: &str) -> Result<Vec<f64>, String> {
        line.split_whitespace()
            .map(|n| n.parse::<f64>().ok().filter(|v| v.is_finite()))
            .collect::<Option<Vec<f64>>>()
            .ok_or_else(|| self.at(format!("'{line}': expected {what}")))
    }

    /// Appends `point` `times` times (its multiplicity) to `points`; an error at this line
    /// when they come to more than `max`.
    pub(crate) fn repeat<T: Copy>(
        &self,
        points: &mut Vec<T>,
        point: T,
        times: usize,
        max: usize,
    ) -> Result<(), String> {
        points.extend(std::iter::repeat_n(point, times));
        if points.len() > max {
            return Err(self.at(format!("more than {max} points")));
        }
        Ok(())
    }
}
