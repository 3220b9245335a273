//! Block comments: blanked out before parsing, so that every position keeps its line and
//! column.

use crate::error::ParseError;

/// Replaces `/* ... */` comments by spaces, keeping newlines so positions stay right.
pub(crate) fn strip_block_comments(src: &[char]) -> Result<Vec<char>, ParseError> {
    let mut out = Vec::with_capacity(src.len());
    let (mut line, mut col) = (1, 1);
    let mut i = 0;
    while i < src.len() {
        if src[i] == '/' && src.get(i + 1) == Some(&'*') {
            let (start_line, start_col) = (line, col);
            out.extend([' ', ' ']);
            i += 2;
            col += 2;
            loop {
                if i >= src.len() {
                    return Err(ParseError::new(
                        start_line,
                        start_col,
                        "comment opened here is never closed with '*/'",
                    ));
                }
                if src[i] == '*' && src.get(i + 1) == Some(&'/') {
                    out.extend([' ', ' ']);
                    i += 2;
                    col += 2;
                    break;
                }
                if src[i] == '\n' {
                    out.push('\n');
                    line += 1;
                    col = 1;
                } else {
                    out.push(' ');
                    col += 1;
                }
                i += 1;
            }
            continue;
        }
        if src[i] == '\n' {
            line += 1;
            col = 1;
        } else {
            col += 1;
        }
        out.push(src[i]);
        i += 1;
    }
    Ok(out)
}

/// `text` without its `//` comments (to the end of each line).
pub(crate) fn strip_line_comments(text: &[char]) -> Vec<char> {
    let mut out = Vec::with_capacity(text.len());
    let mut comment = false;
    for (i, &c) in text.iter().enumerate() {
        if c == '\n' {
            comment = false;
        } else if c == '/' && text.get(i + 1) == Some(&'/') {
            comment = true;
        }
        // Characters become spaces so that columns stay where they were.
        out.push(if comment { ' ' } else { c });
    }
    out
}
