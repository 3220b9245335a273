//! USD's text format (usda): values as the format spells them, and prim names.

use std::fmt::Write;

/// Appends `v` in Rust's shortest form that reads back as the same `f32` (usda parses it as
/// a double and rounds to the attribute's type, so the value survives the round trip).
pub(super) fn float(out: &mut String, v: f32) {
    // Writing to a String cannot fail.
    let _ = write!(out, "{v}");
}

/// Appends `v` rounded to four decimals, for half-precision attributes (`quath`): a half
/// keeps about three and a half significant digits, so more only makes the file larger.
pub(super) fn half(out: &mut String, v: f32) {
    let rounded = (v * 10_000.0).round() / 10_000.0;
    // -0 and 0 are the same rotation; one spelling keeps outputs byte-stable.
    float(out, if rounded == 0.0 { 0.0 } else { rounded });
}

/// Appends `(a, b, ...)`.
pub(super) fn tuple(out: &mut String, values: &[f32]) {
    out.push('(');
    for (k, &v) in values.iter().enumerate() {
        if k > 0 {
            out.push_str(", ");
        }
        float(out, v);
    }
    out.push(')');
}

/// Appends `[t, t, ...]`, each element written by `item`, ten to a line.
pub(super) fn array_of<T>(
    out: &mut String,
    items: impl IntoIterator<Item = T>,
    item: impl Fn(&mut String, T),
) {
    out.push('[');
    for (k, t) in items.into_iter().enumerate() {
        if k > 0 {
            out.push_str(if k % 10 == 0 { ",\n" } else { ", " });
        }
        item(out, t);
    }
    out.push(']');
}

/// A prim name made from `text`: USD names are letters, digits and underscores, not
/// starting with a digit; anything else becomes an underscore.
pub(super) fn identifier(text: &str) -> String {
    let mut name: String = text
        .chars()
        .map(|c| if c.is_ascii_alphanumeric() { c } else { '_' })
        .collect();
    if name.is_empty() || name.starts_with(|c: char| c.is_ascii_digit()) {
        name.insert(0, '_');
    }
    name
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn floats_are_written_as_usda_reads_them() {
        let mut out = String::new();
        array_of(&mut out, [1.0f32, -0.5, 0.1, 1e-7], float);
        assert_eq!(out, "[1, -0.5, 0.1, 0.0000001]");
        let mut out = String::new();
        tuple(&mut out, &[0.70710677, -0.0]);
        assert_eq!(out, "(0.70710677, -0)");
    }

    #[test]
    fn halves_keep_four_decimals_and_one_zero() {
        let mut out = String::new();
        for v in [0.70710677f32, -0.00001, 1.0] {
            half(&mut out, v);
            out.push(' ');
        }
        assert_eq!(out, "0.7071 0 1 ");
    }

    #[test]
    fn long_arrays_break_lines() {
        let mut out = String::new();
        array_of(&mut out, 0..12, |o, k| o.push_str(&k.to_string()));
        assert_eq!(out, "[0, 1, 2, 3, 4, 5, 6, 7, 8, 9,\n10, 11]");
    }

    #[test]
    fn identifiers_are_valid_prim_names() {
        assert_eq!(identifier("oak"), "oak");
        assert_eq!(identifier("my tree-2"), "my_tree_2");
        assert_eq!(identifier("2nd"), "_2nd");
        assert_eq!(identifier(""), "_");
        assert_eq!(identifier("ähre"), "_hre");
    }
}
