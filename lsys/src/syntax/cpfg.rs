//! The cpfg dialect's file structure: `.l` files of the virtual laboratory.
//!
//! A cpfg file is C-preprocessed text around one L-system:
//!
//! ```text
//! #define STEPS 10
//! Lsystem: 1
//! derivation length: STEPS
//! ignore: + - /
//! Axiom: A(1)
//! A(n) : n < 5 --> F(n) [+A(n+1)] A(n+1)
//! homomorphism
//! maximum depth: 4
//! F(n) --> F(n/2) F(n/2)
//! endlsystem
//! ```
//!
//! The C preprocessor's macros are expanded first (`preprocessor.rs`). Statements are lines,
//! but a production may run over several: it continues until a blank
//! line, a keyword, a directive, or a line with an arrow of its own once it has its arrow.
//! The productions themselves are read by the shared parser in cpfg mode (`-->`, `*` for
//! the empty successor, trigonometry in degrees, cpfg's modules of several characters).
//! What the engine does not run yet is refused with an `unsupported: ...` error at its place.

use crate::error::ParseError;
use crate::syntax::cursor::Cursor;
use crate::syntax::parser::{GrammarParser, Section, whole_steps};

/// cpfg's keywords, as a line starts with them (compared without case).
const KEYWORDS: &[&str] = &[
    "lsystem:",
    "derivation length:",
    "axiom:",
    "ignore:",
    "consider:",
    "homomorphism",
    "decomposition",
    "maximum depth:",
    "endlsystem",
    "no warnings",
    "warnings",
    "starteach:",
    "endeach:",
    "start:",
    "end:",
    "define:",
    "seed:",
    "ring lsystem",
];

/// The keyword a line starts with, and the column after it (0-based, in characters).
fn keyword(line: &[char]) -> Option<(&'static str, usize)> {
    let indent = line.iter().take_while(|c| c.is_whitespace()).count();
    let rest: String = line[indent..].iter().collect::<String>().to_lowercase();
    KEYWORDS.iter().find_map(|&k| {
        let after = rest.strip_prefix(k)?;
        // A keyword without a colon must be the whole word ("homomorphism", not a module);
        // a colon may follow it ("homomorphism:").
        let whole = k.ends_with(':')
            || after.is_empty()
            || after.starts_with(|c: char| c.is_whitespace() || c == ':');
        whole.then_some((k, indent + k.chars().count()))
    })
}

fn is_blank(line: &[char]) -> bool {
    line.iter().all(|c| c.is_whitespace())
}

use crate::syntax::preprocessor::is_directive;

fn has_arrow(line: &[char]) -> bool {
    line.windows(3).any(|w| w == ['-', '-', '>']) || line.windows(2).any(|w| w == ['-', '>'])
}

/// A statement joined from lines `first..` (1-based line numbers): the text with each line
/// break turned into a space, and where each line starts in it, so that an error's column
/// can be traced back to its own line.
struct Joined {
    chars: Vec<char>,
    first: usize,
    starts: Vec<usize>,
}

impl Joined {
    fn new(lines: &[&[char]], first: usize) -> Joined {
        let mut chars = Vec::new();
        let mut starts = Vec::new();
        for line in lines {
            if !starts.is_empty() {
                chars.push(' ');
            }
            starts.push(chars.len());
            chars.extend_from_slice(line);
        }
        Joined {
            chars,
            first,
            starts,
        }
    }

    /// `error` (found on the joined text, as if it were line `first`) at its own line.
    fn locate(&self, mut error: ParseError) -> ParseError {
        if error.location.line == self.first {
            let offset = error.location.column.saturating_sub(1);
            let k = self.starts.partition_point(|&s| s <= offset).max(1) - 1;
            error.location.line = self.first + k;
            error.location.column = offset - self.starts[k] + 1;
        }
        error
    }
}

fn unsupported(line: usize, column: usize, what: &str) -> ParseError {
    ParseError::new(line, column + 1, format!("unsupported: {what}"))
}

/// Reads the lines of a cpfg file (comments already removed) into `p`.
pub(crate) fn read(src: &[char], p: &mut GrammarParser) -> Result<(), ParseError> {
    let lines: Vec<&[char]> = src
        .split(|&c| c == '\n')
        .map(|l| l.strip_suffix(&['\r']).unwrap_or(l))
        .collect();
    let mut lsystems = 0;
    // After `endlsystem` only another `Lsystem:` is read.
    let mut ended = false;
    let mut i = 0;
    while i < lines.len() {
        let line = lines[i];
        let n = i + 1;
        let indent = line.iter().take_while(|c| c.is_whitespace()).count();
        if is_blank(line) || line[indent..].starts_with(&['/', '/']) {
            i += 1;
            continue;
        }
        if is_directive(line) {
            preprocessor(line, n, indent)?;
            i += 1;
            continue;
        }
        let found = keyword(line);
        if ended && found.is_none_or(|(word, _)| word != "lsystem:") {
            i += 1;
            continue;
        }
        if let Some((word, after)) = found {
            let mut cur = Cursor::new(line, n);
            cur.set_pos(after);
            // A sub-L-system's axiom and derivation length are its own business: the main
            // system's derivation hands it modules.
            if p.subsystem.is_some() && (word == "axiom:" || word == "derivation length:") {
                i += 1;
                continue;
            }
            match word {
                "lsystem:" => {
                    // The first L-system is the main one; each later one is a sub-L-system
                    // that `?(id, scale) ... $` hands modules to.
                    let at = cur.pos();
                    let id = p.constant_value(&mut cur)?;
                    let id = whole_steps(&cur, at, id)?;
                    lsystems += 1;
                    ended = false;
                    p.section = Section::Main;
                    p.subsystem = if lsystems == 1 { None } else { Some(id) };
                }
                "derivation length:" => {
                    let at = cur.pos();
                    let steps = p.constant_value(&mut cur)?;
                    p.derivation_length = Some(whole_steps(&cur, at, steps)?);
                }
                "axiom:" => {
                    // The axiom runs on over the lines up to the next statement, unless a
                    // production starts among them (its arrow may come lines later).
                    let run = i
                        + 1
                        + lines[i + 1..]
                            .iter()
                            .take_while(|l| !ends_statement(l))
                            .count();
                    // Whether a production starts: the statement the next line starts is
                    // read whole (its block may hold blank lines before its arrow), and it
                    // holds the first arrow of the run if there is one.
                    let production_follows = run > i + 1
                        && lines[i + 1..continuation(&lines, i + 1)]
                            .iter()
                            .any(|l| has_arrow(l));
                    let end = if production_follows { i + 1 } else { run };
                    let joined = Joined::new(&lines[i..end], n);
                    let mut cur = Cursor::new(&joined.chars, n);
                    cur.set_pos(after);
                    p.axiom_line(&mut cur, indent)
                        .map_err(|e| joined.locate(e))?;
                    i = end;
                    continue;
                }
                "ignore:" | "consider:" => p.context_symbols(&mut cur, word == "consider:")?,
                "homomorphism" => p.section = Section::Homomorphism,
                "decomposition" => p.section = Section::Decomposition,
                "maximum depth:" => {
                    let depth = p.depth(&mut cur)?;
                    if !p.set_max_depth(depth) {
                        return Err(cur.error_at(
                            indent,
                            "'maximum depth:' belongs in a homomorphism or decomposition section",
                        ));
                    }
                }
                // Whether cpfg reports modules kept at the maximum depth; they are kept here
                // as in cpfg, without a report.
                "warnings" | "no warnings" => {}
                // The derivation's seed is the caller's choice here (`derive`'s `seed`).
                "seed:" => {}
                "ring lsystem" => p.ring = true,
                "endlsystem" => ended = true,
                "start:" | "end:" | "starteach:" | "endeach:" => {
                    // The block runs over as many lines as its braces take.
                    let end = braces_close(&lines, i);
                    let joined = Joined::new(&lines[i..end], n);
                    let mut cur = Cursor::new(&joined.chars, n);
                    cur.set_pos(after);
                    let block = p.derivation_block(&mut cur).map_err(|e| joined.locate(e))?;
                    let slot = match word {
                        "start:" => &mut p.blocks.start,
                        "starteach:" => &mut p.blocks.start_each,
                        "endeach:" => &mut p.blocks.end_each,
                        _ => &mut p.blocks.end,
                    };
                    slot.extend(block);
                    i = end;
                    continue;
                }
                _ => {
                    // 'define:': arrays of block variables, over as many lines as its braces
                    // take.
                    let end = braces_close(&lines, i);
                    let joined = Joined::new(&lines[i..end], n);
                    let mut cur = Cursor::new(&joined.chars, n);
                    cur.set_pos(after);
                    p.define_block(&mut cur).map_err(|e| joined.locate(e))?;
                    i = end;
                    continue;
                }
            }
            i += 1;
            continue;
        }
        // A production, over as many lines as it takes.
        let end = continuation(&lines, i);
        let joined = Joined::new(&lines[i..end], n);
        let mut cur = Cursor::new(&joined.chars, n);
        let at = cur.location();
        let production = p.production(&mut cur).map_err(|e| joined.locate(e))?;
        p.add_production(production, at);
        i = end;
    }
    Ok(())
}

/// The line after the one where the braces opened at line `i` close (or the end).
fn braces_close(lines: &[&[char]], i: usize) -> usize {
    let mut depth = 0i64;
    let mut opened = false;
    for (k, line) in lines.iter().enumerate().skip(i) {
        depth += brace_balance(line);
        opened |= line.contains(&'{');
        if opened && depth <= 0 {
            return k + 1;
        }
    }
    lines.len()
}

/// The braces a line opens, less those it closes.
fn brace_balance(line: &[char]) -> i64 {
    line.iter()
        .map(|&c| match c {
            '{' => 1,
            '}' => -1,
            _ => 0,
        })
        .sum()
}

fn ends_statement(line: &[char]) -> bool {
    is_blank(line) || is_directive(line) || keyword(line).is_some()
}

/// Where the statement starting at line `i` ends (exclusive): at a blank line outside a
/// statement block, a keyword, a directive, or, once the statement has its arrow, at a line
/// that begins the next production: one with an arrow, or one with a condition (`:`) whose
/// arrow comes on a later line.
fn continuation(lines: &[&[char]], i: usize) -> usize {
    let mut arrow = has_arrow(lines[i]);
    // Inside a statement block a blank line (a comment's, once comments are gone) is part
    // of the block.
    let mut open = brace_balance(lines[i]);
    let mut j = i + 1;
    while j < lines.len() {
        let line = lines[j];
        if open > 0 && is_blank(line) {
            j += 1;
            continue;
        }
        if ends_statement(line) {
            break;
        }
        open += brace_balance(line);
        if arrow && has_arrow(line) {
            break;
        }
        if arrow && line.contains(&':') {
            let arrow_follows = lines[j + 1..]
                .iter()
                .take_while(|l| !ends_statement(l))
                .any(|l| has_arrow(l));
            if arrow_follows {
                break;
            }
        }
        arrow |= has_arrow(line);
        j += 1;
    }
    j
}

/// A preprocessor line left after preprocessing: `#define` was run already (its macros are
/// expanded in the lines); `#include` and the rest of the C preprocessor are refused.
fn preprocessor(line: &[char], n: usize, indent: usize) -> Result<(), ParseError> {
    let rest: String = line[indent + 1..].iter().collect();
    let word: String = rest
        .trim_start()
        .chars()
        .take_while(|c| c.is_ascii_alphanumeric())
        .collect();
    match word.as_str() {
        "define" | "undef" => Ok(()),
        "include" => Err(unsupported(
            n,
            indent,
            "#include (the model needs another file)",
        )),
        _ => Err(unsupported(
            n,
            indent,
            &format!("the C preprocessor's #{word}"),
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn keywords_are_found_with_and_without_colons() {
        let line: Vec<char> = "homomorphism: no warnings".chars().collect();
        assert_eq!(keyword(&line), Some(("homomorphism", 12)));
        let line: Vec<char> = "  Lsystem: 1".chars().collect();
        assert_eq!(keyword(&line), Some(("lsystem:", 10)));
        let line: Vec<char> = "homomorphismX --> F".chars().collect();
        assert_eq!(keyword(&line), None);
    }
}
