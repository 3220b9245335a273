//! A setting outside its range: the one error every crate's options can raise, with the
//! setting's name, its value and what it must be.

/// A setting is NaN, infinite or outside its range: set it within `expected`.
///
/// ```
/// use sylva_base::range::{OutOfRange, check};
///
/// assert!(check("radius", 2.0, 2.0 > 0.0, "a positive number").is_ok());
/// let err = check("radius", f64::NAN, true, "a positive number").unwrap_err();
/// assert_eq!(err.to_string(), "radius = NaN is out of range: expected a positive number");
/// assert_eq!(err, OutOfRange { name: "radius", value: f64::NAN, expected: "a positive number" });
/// ```
#[derive(Debug, Clone, Copy, thiserror::Error)]
#[error("{name} = {value} is out of range: expected {expected}")]
pub struct OutOfRange {
    /// The setting.
    pub name: &'static str,
    /// Its value.
    pub value: f64,
    /// What it must be.
    pub expected: &'static str,
}

/// Compares values bit for bit, so that a NaN that was refused equals itself in tests.
impl PartialEq for OutOfRange {
    fn eq(&self, other: &Self) -> bool {
        self.name == other.name
            && self.value.to_bits() == other.value.to_bits()
            && self.expected == other.expected
    }
}

/// An error unless `value` is finite and `ok`.
pub fn check(
    name: &'static str,
    value: f64,
    ok: bool,
    expected: &'static str,
) -> Result<(), OutOfRange> {
    if value.is_finite() && ok {
        Ok(())
    } else {
        Err(OutOfRange {
            name,
            value,
            expected,
        })
    }
}
