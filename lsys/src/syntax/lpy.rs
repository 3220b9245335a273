//! The declarative subset of L-Py's `.lpy` files.
//!
//! An `.lpy` file is Python with an L-system inside it. The subset read here is what needs no
//! Python interpreter: `module` declarations (names of several characters), constants
//! assigned at the top (`NAME = expression`), `Axiom:`, `derivation length:`, the
//! `production:`, `decomposition:` and `interpretation:` (or `homomorphism:`) sections with
//! `maximum depth:`, `ignore:`/`consider:`, productions written `pred --> successor` (with
//! contexts and conditions), and `endlsystem`; `#` comments. Expressions may use Python's
//! `**`, `and`, `or`, `not`, `True` and `False`. Anything else is Python code, refused with
//! `unsupported: Python code` at its line and column, never skipped silently. The
//! editor's settings after `endlsystem` (materials, the `__lpy_code_version__` block) are not
//! part of the L-system and are not read.

use crate::error::ParseError;
use crate::syntax::cursor::Cursor;
use crate::syntax::parser::{GrammarParser, Section, whole_steps};

/// L-Py's section and statement keywords, as a line starts with them (with their colon).
const KEYWORDS: &[&str] = &[
    "axiom:",
    "derivation length:",
    "production:",
    "interpretation:",
    "homomorphism:",
    "decomposition:",
    "maximum depth:",
    "ignore:",
    "consider:",
    "endlsystem",
    "module ",
    "group ",
    "endgroup",
];

fn unsupported(line: usize, column: usize, what: &str) -> ParseError {
    ParseError::new(line, column + 1, format!("unsupported: {what}"))
}

/// `line` without its `#` comment (Python's, outside strings).
fn without_comment(line: &[char]) -> Vec<char> {
    let mut quote: Option<char> = None;
    let mut out = Vec::with_capacity(line.len());
    for &c in line {
        match (quote, c) {
            (None, '#') => break,
            (None, '"' | '\'') => quote = Some(c),
            (Some(q), _) if c == q => quote = None,
            _ => {}
        }
        out.push(c);
    }
    out
}

/// Python's operators in sylva's spelling, keeping each line's length where it can (the
/// replacements are padded with spaces so that columns stay close).
fn python_operators(line: &[char]) -> Vec<char> {
    let text: String = line.iter().collect();
    let mut out = String::with_capacity(text.len());
    let mut word = String::new();
    let flush = |word: &mut String, out: &mut String| {
        match word.as_str() {
            "and" => out.push_str("&& "),
            "or" => out.push_str("||"),
            "not" => out.push_str("!  "),
            "True" => out.push_str("1   "),
            "False" => out.push_str("0    "),
            _ => out.push_str(word),
        }
        word.clear();
    };
    let mut chars = text.chars().peekable();
    while let Some(c) = chars.next() {
        if c.is_ascii_alphanumeric() || c == '_' {
            word.push(c);
            continue;
        }
        flush(&mut word, &mut out);
        if c == '*' && chars.peek() == Some(&'*') {
            chars.next();
            out.push_str(" ^");
        } else {
            out.push(c);
        }
    }
    flush(&mut word, &mut out);
    out.chars().collect()
}

/// Reads an `.lpy` file's lines (Python's `#` comments are removed here) into `p`.
pub(crate) fn read(src: &[char], p: &mut GrammarParser) -> Result<(), ParseError> {
    let lines: Vec<Vec<char>> = src
        .split(|&c| c == '\n')
        .map(|l| without_comment(l.strip_suffix(&['\r']).unwrap_or(l)))
        .collect();
    for (k, line) in lines.iter().enumerate() {
        let n = k + 1;
        let indent = line.iter().take_while(|c| c.is_whitespace()).count();
        if indent == line.len() {
            continue;
        }
        let rest: String = line[indent..].iter().collect();
        let lower = rest.to_lowercase();
        let keyword = KEYWORDS
            .iter()
            .find(|k| lower.starts_with(*k) || lower.trim_end() == k.trim_end());
        if indent > 0 && keyword.is_none() {
            return Err(unsupported(
                n,
                indent,
                "Python code (an indented block: a production's Python body or a Python statement)",
            ));
        }
        let line = python_operators(line);
        let mut cur = Cursor::new(&line, n);
        if let Some(&word) = keyword {
            cur.set_pos((indent + word.chars().count()).min(line.len()));
            match word {
                "axiom:" => p.axiom_line(&mut cur, indent)?,
                "derivation length:" => {
                    let at = cur.pos();
                    let steps = p.constant_value(&mut cur)?;
                    p.derivation_length = Some(whole_steps(&cur, at, steps)?);
                }
                "production:" => p.section = Section::Main,
                "interpretation:" | "homomorphism:" => p.section = Section::Homomorphism,
                "decomposition:" => p.section = Section::Decomposition,
                "maximum depth:" => {
                    let depth = p.depth(&mut cur)?;
                    p.set_max_depth(depth);
                }
                "ignore:" | "consider:" => p.context_symbols(&mut cur, word == "consider:")?,
                "module " => {
                    // `module A, B(x), Apex`: the names, without their parameter lists.
                    let text: String = line
                        .get(indent + word.len()..)
                        .unwrap_or(&[])
                        .iter()
                        .collect();
                    let mut names = String::new();
                    let mut depth = 0;
                    for c in text.chars() {
                        match c {
                            '(' => depth += 1,
                            ')' => depth -= 1,
                            ',' if depth == 0 => names.push(' '),
                            _ if depth == 0 => names.push(c),
                            _ => {}
                        }
                    }
                    let declaration: Vec<char> = format!("#module {names}").chars().collect();
                    p.line(&mut Cursor::new(&declaration, n))?;
                }
                "endlsystem" => return Ok(()),
                _ => {
                    return Err(unsupported(
                        n,
                        indent,
                        "L-Py's production groups (group ... endgroup)",
                    ));
                }
            }
            continue;
        }
        // A constant at the top: `NAME = expression` (not `==`).
        if let Some(eq) = assignment(&line) {
            let name: String = line[indent..eq].iter().collect();
            let name = name.trim();
            let value: String = line[eq + 1..].iter().collect();
            let define: Vec<char> = format!("#define {name} {value}").chars().collect();
            return_if_err(p.line(&mut Cursor::new(&define, n)), n, indent)?;
            continue;
        }
        if lower.contains("-->") || lower.contains("->") {
            let at = cur.location();
            let production = p.production(&mut cur)?;
            p.add_production(production, at);
            continue;
        }
        return Err(unsupported(n, indent, "Python code"));
    }
    Ok(())
}

/// Where the `=` of a top-level `NAME = value` is, when the line is one.
fn assignment(line: &[char]) -> Option<usize> {
    let indent = line.iter().take_while(|c| c.is_whitespace()).count();
    let mut k = indent;
    if !line
        .get(k)
        .is_some_and(|c| c.is_ascii_alphabetic() || *c == '_')
    {
        return None;
    }
    while line
        .get(k)
        .is_some_and(|c| c.is_ascii_alphanumeric() || *c == '_')
    {
        k += 1;
    }
    while line.get(k).is_some_and(|c| *c == ' ' || *c == '\t') {
        k += 1;
    }
    (line.get(k) == Some(&'=') && line.get(k + 1) != Some(&'=')).then_some(k)
}

/// A constant whose value is not a constant expression (a lambda, a call of Python's) is
/// Python code.
fn return_if_err(
    result: Result<(), ParseError>,
    n: usize,
    indent: usize,
) -> Result<(), ParseError> {
    result.map_err(|e| {
        unsupported(
            n,
            indent,
            &format!("Python code (a value sylva cannot compute: {})", e.message),
        )
    })
}
