//! The part of the C preprocessor cpfg models use: `#define` of object-like and
//! function-like macros, expanded by name in later lines as `cpp` would (a macro is not
//! expanded inside its own expansion), `#undef`, and `#ifdef` / `#ifndef` / `#else` /
//! `#endif`. Lines keep their numbers; a line with macros in it has its text replaced.

use std::collections::HashMap;

use crate::error::ParseError;
use crate::syntax::comments::{strip_block_comments, strip_line_comments};
use crate::syntax::parser::MAX_GRAMMAR_BYTES;

/// Most characters macros may add to a file, all lines together: macros that multiply
/// themselves stop here, and however many lines use them the work stays linear in this.
const MAX_EXPANDED_TOTAL: usize = 4 * MAX_GRAMMAR_BYTES;
/// Deepest nesting of macros within macros.
const MAX_EXPANSION_DEPTH: usize = 64;

#[derive(Debug, Clone)]
struct Macro {
    /// `None` for an object-like macro.
    params: Option<Vec<String>>,
    body: Vec<char>,
}

/// The preprocessed lines, each with where it came from: the file (0 the model's own, then
/// the included files in the order they were first read, named in `files`) and its line
/// there.
pub(crate) struct Preprocessed {
    pub(crate) lines: Vec<Vec<char>>,
    pub(crate) origins: Vec<Origin>,
    pub(crate) files: Vec<String>,
}

/// Where a preprocessed line came from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Origin {
    /// Index into [`Preprocessed::files`], 0 for the model's own text.
    pub(crate) file: usize,
    /// 1-based line in that file.
    pub(crate) line: usize,
}

/// The files `#include` names, as the model folder has them.
pub(crate) trait Includes {
    /// The text of the file `name` (as written between the quotes), or why not.
    fn read(&mut self, name: &str) -> Result<String, String>;
}

/// Deepest nesting of included files: a file that includes itself stops here.
pub(crate) const MAX_INCLUDE_DEPTH: usize = 16;

/// The C preprocessor's directives: a line starting with `#` and one of these is a
/// directive; any other `#` starts text (cpfg's `#` width module).
const DIRECTIVES: &[&str] = &[
    "define", "undef", "ifdef", "ifndef", "if", "elif", "else", "endif", "include", "pragma",
    "error", "line",
];

/// Whether `line` is a preprocessor directive.
pub(crate) fn is_directive(line: &[char]) -> bool {
    let indent = line.iter().take_while(|c| c.is_whitespace()).count();
    if line.get(indent) != Some(&'#') {
        return false;
    }
    let rest: String = line[indent + 1..].iter().collect();
    let word: String = rest
        .trim_start()
        .chars()
        .take_while(|c| is_ident(*c))
        .collect();
    DIRECTIVES.contains(&word.as_str())
}

fn is_ident_start(c: char) -> bool {
    c.is_ascii_alphabetic() || c == '_'
}

fn is_ident(c: char) -> bool {
    c.is_ascii_alphanumeric() || c == '_'
}

/// Runs the directives of `src` (comments already removed) and expands its macros. Directive
/// lines become blank; `#define` of a plain constant is also left to the grammar parser,
/// which reads the directive line as before expansion. `#include` is left for the dialect to
/// refuse.
#[cfg(test)]
pub(crate) fn preprocess(src: &[char]) -> Result<Preprocessed, ParseError> {
    preprocess_with(src, None, &[])
}

/// As [`preprocess`], with `#include "NAME"` replaced by the lines of the file `includes`
/// reads (its comments removed, its directives run with the same macros), when given. An
/// error in an included file is reported at its `#include` line, naming the file and place.
/// `predefined` macros (name, body) are defined before the first line, as `cpp -D` does.
pub(crate) fn preprocess_with(
    src: &[char],
    includes: Option<&mut dyn Includes>,
    predefined: &[(String, String)],
) -> Result<Preprocessed, ParseError> {
    let macros = predefined
        .iter()
        .map(|(name, body)| {
            let body = body.chars().collect();
            (name.clone(), Macro { params: None, body })
        })
        .collect();
    let mut run = Run {
        macros,
        budget: MAX_EXPANDED_TOTAL,
        includes,
        out: Preprocessed {
            lines: Vec::new(),
            origins: Vec::new(),
            files: vec![String::new()],
        },
    };
    run.file(src, 0, 0)?;
    Ok(run.out)
}

/// One preprocessing of a model and the files it includes.
struct Run<'a> {
    macros: HashMap<String, Macro>,
    budget: usize,
    includes: Option<&'a mut dyn Includes>,
    out: Preprocessed,
}

impl Run<'_> {
    fn push(&mut self, line: Vec<char>, file: usize, n: usize) {
        self.out.lines.push(line);
        self.out.origins.push(Origin { file, line: n });
    }

    /// Preprocesses the text of file `file`, included `depth` deep, onto the output.
    fn file(&mut self, src: &[char], file: usize, depth: usize) -> Result<(), ParseError> {
        // Whether each open #if's branch is taken, and how many are not: a line is active
        // when none is, known in constant time however deep the nesting.
        let mut conditions: Vec<bool> = Vec::new();
        let mut not_taken = 0usize;
        let lines = spliced(src);
        for (k, raw) in lines.iter().enumerate() {
            let n = k + 1;
            let raw = &raw[..];
            let indent = raw.iter().take_while(|c| c.is_whitespace()).count();
            let active = not_taken == 0;
            let err = |m: String| ParseError::new(n, indent + 1, m);
            if is_directive(raw) {
                let text: String = raw[indent + 1..].iter().collect();
                let text = text.trim_start();
                let word: String = text.chars().take_while(|c| is_ident(*c)).collect();
                let rest = text[word.len()..].trim();
                match word.as_str() {
                    "ifdef" | "ifndef" => {
                        let defined = self.macros.contains_key(rest);
                        let taken = defined == (word == "ifdef");
                        not_taken += usize::from(!taken);
                        conditions.push(taken);
                    }
                    "if" => {
                        let taken = active
                            && condition(rest, &self.macros, &mut self.budget).map_err(err)?;
                        not_taken += usize::from(!taken);
                        conditions.push(taken);
                    }
                    "else" => match conditions.last_mut() {
                        Some(c) => {
                            *c = !*c;
                            if *c {
                                not_taken -= 1;
                            } else {
                                not_taken += 1;
                            }
                        }
                        None => return Err(err("#else without #ifdef".into())),
                    },
                    "endif" => match conditions.pop() {
                        Some(taken) => not_taken -= usize::from(!taken),
                        None => return Err(err("#endif without #ifdef".into())),
                    },
                    "define" if active => {
                        let (name, m) = definition(rest).map_err(err)?;
                        self.macros.insert(name, m);
                        // The line stays for the grammar parser only when it defines a
                        // constant it can read; otherwise it is blank.
                        self.push(raw.to_vec(), file, n);
                        continue;
                    }
                    "undef" if active => {
                        self.macros.remove(rest);
                    }
                    "include" if active && self.includes.is_some() => {
                        self.include(rest, depth).map_err(err)?;
                        // The directive's own line stays, blank, where it was.
                        self.push(Vec::new(), file, n);
                        continue;
                    }
                    "define" | "undef" => {}
                    _ if !active => {}
                    // #include without a folder and the rest: left for the dialect to refuse
                    // at their place.
                    _ => {
                        self.push(raw.to_vec(), file, n);
                        continue;
                    }
                }
                self.push(Vec::new(), file, n);
                continue;
            }
            if !active {
                self.push(Vec::new(), file, n);
                continue;
            }
            let expanded = expand(raw, &self.macros, &mut Vec::new(), 0, &mut self.budget)
                .map_err(|m| ParseError::new(n, 1, m))?;
            self.push(expanded, file, n);
        }
        if !conditions.is_empty() {
            return Err(ParseError::new(
                lines.len().max(1),
                1,
                "#ifdef without #endif",
            ));
        }
        Ok(())
    }

    /// Reads the file an `#include "NAME"` (or `<NAME>`) names and preprocesses it in place.
    fn include(&mut self, rest: &str, depth: usize) -> Result<(), String> {
        let name = rest
            .strip_prefix('"')
            .and_then(|r| r.split_once('"'))
            .or_else(|| rest.strip_prefix('<').and_then(|r| r.split_once('>')))
            .map(|(name, _)| name.trim())
            .filter(|name| !name.is_empty())
            .ok_or_else(|| format!("#include {rest}: expected a file name in quotes"))?;
        if depth >= MAX_INCLUDE_DEPTH {
            return Err(format!(
                "#include \"{name}\": included files nest more than {MAX_INCLUDE_DEPTH} deep"
            ));
        }
        let includes = self.includes.as_mut().ok_or("no model folder")?;
        let text = includes
            .read(name)
            .map_err(|why| format!("#include \"{name}\": {why}"))?;
        let chars: Vec<char> = text
            .strip_prefix('\u{feff}')
            .unwrap_or(&text)
            .chars()
            .collect();
        let file = self.out.files.len();
        self.out.files.push(name.to_owned());
        let src = strip_block_comments(&chars)
            .map_err(|e| format!("in \"{name}\" at {}: {}", e.location, e.message))?;
        let src = strip_line_comments(&src);
        self.file(&src, file, depth + 1)
            .map_err(|e| format!("in \"{name}\" at {}: {}", e.location, e.message))
    }
}

/// A `#define`'s name and macro, from the text after the word.
fn definition(rest: &str) -> Result<(String, Macro), String> {
    let name: String = rest.chars().take_while(|c| is_ident(*c)).collect();
    if name.is_empty() {
        return Err("expected a macro name after #define".into());
    }
    let after = &rest[name.len()..];
    let (params, body) = if let Some(list) = after.strip_prefix('(') {
        let close = list
            .find(')')
            .ok_or_else(|| format!("macro '{name}': ')' missing"))?;
        let params = list[..close]
            .split(',')
            .map(|p| p.trim().to_string())
            .filter(|p| !p.is_empty())
            .collect();
        (Some(params), list[close + 1..].trim())
    } else {
        (None, after.trim())
    };
    Ok((
        name,
        Macro {
            params,
            body: body.chars().collect(),
        },
    ))
}

/// The source's lines with cpp's line splices joined: a line ending in `\\` continues on
/// the next. The joined line takes the first one's place and blank lines the others', so
/// numbering stays.
fn spliced(src: &[char]) -> Vec<Vec<char>> {
    let mut out: Vec<Vec<char>> = Vec::new();
    let mut pending: Option<Vec<char>> = None;
    let mut blanks = 0;
    for raw in src.split(|&c| c == '\n') {
        let raw = raw.strip_suffix(&['\r']).unwrap_or(raw);
        let mut line = pending.take().unwrap_or_default();
        let trimmed_end = raw.len() - raw.iter().rev().take_while(|c| c.is_whitespace()).count();
        if raw[..trimmed_end].last() == Some(&'\\') {
            // vlab's models end some spliced lines with two backslashes (`\\`), which
            // cpfg reads as one splice: every backslash at the end goes.
            let kept = raw[..trimmed_end]
                .iter()
                .rposition(|&c| c != '\\')
                .map_or(0, |k| k + 1);
            line.extend_from_slice(&raw[..kept]);
            line.push(' ');
            pending = Some(line);
            blanks += 1;
            continue;
        }
        line.extend_from_slice(raw);
        out.push(line);
        out.extend(std::iter::repeat_n(Vec::new(), blanks));
        blanks = 0;
    }
    if let Some(line) = pending {
        out.push(line);
        out.extend(std::iter::repeat_n(Vec::new(), blanks.saturating_sub(1)));
    }
    out
}

/// The value of an `#if` condition: its macros expanded, `defined(NAME)` answered, names
/// left over read as 0 (as cpp reads them), and the rest evaluated as a constant expression.
fn condition(
    text: &str,
    macros: &HashMap<String, Macro>,
    budget: &mut usize,
) -> Result<bool, String> {
    // `defined NAME` and `defined(NAME)` answered in one pass over the text.
    let mut answered = String::with_capacity(text.len());
    let mut rest = text;
    while let Some(at) = rest.find("defined") {
        answered.push_str(&rest[..at]);
        let after_word = rest[at + "defined".len()..].trim_start();
        let inner = after_word.strip_prefix('(').unwrap_or(after_word);
        let name: String = inner.chars().take_while(|c| is_ident(*c)).collect();
        let after = &inner[name.len()..];
        rest = if after_word.starts_with('(') {
            after.trim_start().strip_prefix(')').unwrap_or(after)
        } else {
            after
        };
        answered.push(if macros.contains_key(&name) { '1' } else { '0' });
    }
    answered.push_str(rest);
    let chars: Vec<char> = answered.chars().collect();
    let expanded = expand(&chars, macros, &mut Vec::new(), 0, budget)?;
    let zeroed = substitute_names(&expanded);
    let mut cur = crate::syntax::cursor::Cursor::new(&zeroed, 1);
    let value = crate::syntax::expr_parser::parse_expr(&mut cur, &NoNames)
        .map_err(|e| format!("#if: {}", e.message))?;
    if !cur.at_end() {
        return Err(format!("#if: unexpected {}", cur.describe_next()));
    }
    Ok(value.eval_constant(0.0, 0) != 0.0)
}

/// Names in an `#if` that no macro defined are 0.
fn substitute_names(text: &[char]) -> Vec<char> {
    let mut out = Vec::with_capacity(text.len());
    let mut i = 0;
    while i < text.len() {
        if is_ident_start(text[i]) && (i == 0 || !is_ident(text[i - 1])) {
            let end = i + text[i..].iter().take_while(|c| is_ident(**c)).count();
            out.push('0');
            i = end;
        } else {
            out.push(text[i]);
            i += 1;
        }
    }
    out
}

/// The empty scope of `#if` conditions.
struct NoNames;

impl crate::syntax::expr_parser::Scope for NoNames {
    fn var(&self, _: &str) -> Option<u16> {
        None
    }
    fn constant(&self, _: &str) -> Option<f64> {
        None
    }
}

/// `text` with every macro name (not among `hiding`, the macros being expanded) replaced;
/// each expansion's characters are taken from `budget`, an error once it runs out.
fn expand(
    text: &[char],
    macros: &HashMap<String, Macro>,
    hiding: &mut Vec<String>,
    depth: usize,
    budget: &mut usize,
) -> Result<Vec<char>, String> {
    if depth > MAX_EXPANSION_DEPTH {
        return Err(format!("macros nest more than {MAX_EXPANSION_DEPTH} deep"));
    }
    let mut out = Vec::with_capacity(text.len());
    let mut i = 0;
    while i < text.len() {
        let c = text[i];
        let starts_name = is_ident_start(c) && (i == 0 || !is_ident(text[i - 1]));
        if !starts_name {
            out.push(c);
            i += 1;
            continue;
        }
        let end = i + text[i..].iter().take_while(|c| is_ident(**c)).count();
        let name: String = text[i..end].iter().collect();
        let Some(m) = macros.get(&name).filter(|_| !hiding.contains(&name)) else {
            out.extend_from_slice(&text[i..end]);
            i = end;
            continue;
        };
        let (body, next) = match &m.params {
            None => (m.body.clone(), end),
            Some(params) => {
                // A function-like macro's name not followed by '(' is just a name.
                let open = end + text[end..].iter().take_while(|c| c.is_whitespace()).count();
                if text.get(open) != Some(&'(') {
                    out.extend_from_slice(&text[i..end]);
                    i = end;
                    continue;
                }
                let (args, after) = arguments(text, open)
                    .ok_or_else(|| format!("macro '{name}': its arguments' ')' is missing"))?;
                if args.len() != params.len() && !(params.is_empty() && args.len() == 1) {
                    return Err(format!(
                        "macro '{name}' takes {} argument(s), {} given",
                        params.len(),
                        args.len()
                    ));
                }
                // Arguments are expanded first, then put in place of the parameters.
                let mut bound = HashMap::new();
                for (p, a) in params.iter().zip(&args) {
                    bound.insert(p.clone(), expand(a, macros, hiding, depth + 1, budget)?);
                }
                (substitute(&m.body, &bound), after)
            }
        };
        hiding.push(name);
        let expanded = expand(&body, macros, hiding, depth + 1, budget)?;
        hiding.pop();
        *budget = budget.checked_sub(expanded.len()).ok_or_else(|| {
            format!("macros expand to more than {MAX_EXPANDED_TOTAL} characters in all")
        })?;
        out.extend(expanded);
        i = next;
    }
    Ok(out)
}

/// The comma-separated arguments of a call whose '(' is at `open`, and the index after its
/// ')'; commas inside nested parentheses belong to the argument.
fn arguments(text: &[char], open: usize) -> Option<(Vec<Vec<char>>, usize)> {
    let mut depth = 0usize;
    let mut args = vec![Vec::new()];
    for (k, &c) in text.iter().enumerate().skip(open + 1) {
        match c {
            '(' => depth += 1,
            ')' if depth == 0 => return Some((args, k + 1)),
            ')' => depth -= 1,
            ',' if depth == 0 => {
                args.push(Vec::new());
                continue;
            }
            _ => {}
        }
        args.last_mut()?.push(c);
    }
    None
}

/// `body` with each parameter name replaced by its argument (in parentheses' absence, as cpp
/// does: the model's own parentheses decide precedence).
fn substitute(body: &[char], bound: &HashMap<String, Vec<char>>) -> Vec<char> {
    let mut out = Vec::with_capacity(body.len());
    let mut i = 0;
    while i < body.len() {
        if is_ident_start(body[i]) && (i == 0 || !is_ident(body[i - 1])) {
            let end = i + body[i..].iter().take_while(|c| is_ident(**c)).count();
            let name: String = body[i..end].iter().collect();
            match bound.get(&name) {
                Some(arg) => out.extend_from_slice(arg),
                None => out.extend_from_slice(&body[i..end]),
            }
            i = end;
        } else {
            out.push(body[i]);
            i += 1;
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn run(text: &str) -> Vec<String> {
        let chars: Vec<char> = text.chars().collect();
        preprocess(&chars)
            .unwrap()
            .lines
            .iter()
            .map(|l| l.iter().collect())
            .collect()
    }

    #[test]
    fn object_and_function_macros_expand_like_cpp() {
        let lines = run("#define A nran(80,4)\n#define W(x) (x*2+A)\nF(W(3)) A AB\n");
        assert_eq!(lines[2], "F((3*2+nran(80,4))) nran(80,4) AB");
    }

    #[test]
    fn a_macro_is_not_expanded_inside_itself() {
        let lines = run("#define X X+1\nF(X)\n");
        assert_eq!(lines[1], "F(X+1)");
    }

    #[test]
    fn conditionals_keep_or_blank_lines() {
        let lines = run("#define ON\n#ifdef ON\nA\n#else\nB\n#endif\n#ifndef ON\nC\n#endif\n");
        assert_eq!(lines[2], "A");
        assert_eq!(lines[4], "");
        assert_eq!(lines[7], "");
    }

    #[test]
    fn if_conditions_and_line_splices() {
        let lines = run(
            "#define LEAVES 1\n#if LEAVES==1\nA\n#else\nB\n#endif\n#define W(x) \\\n  (x+1)\nW(2)\n",
        );
        assert_eq!(lines[2], "A");
        assert_eq!(lines[4], "");
        assert_eq!(lines.len(), 10, "{lines:?}");
        assert_eq!(lines[8].trim(), "(2+1)");
    }

    #[test]
    fn runaway_macros_are_errors() {
        // Each macro doubles the one before: 2^25 copies of Z, beyond the budget, which
        // stops the work after a bounded amount of it.
        let letters: Vec<char> = ('A'..='Z').collect();
        let mut text: String = letters
            .windows(2)
            .map(|w| format!("#define {} {} {}\n", w[0], w[1], w[1]))
            .collect();
        text.push_str("A\n");
        let text: Vec<char> = text.chars().collect();
        let e = preprocess(&text).err().expect("refused");
        assert!(e.message.contains("in all"), "{}", e.message);
        // Below the budget the same kind of chain expands whole, on one line or many.
        let small: Vec<char> = "#define A B B\n#define B C C\n#define C F F\nA\nA A\n"
            .chars()
            .collect();
        let lines = preprocess(&small).unwrap().lines;
        assert_eq!(lines[3].iter().filter(|&&c| c == 'F').count(), 8);
        assert_eq!(lines[4].iter().filter(|&&c| c == 'F').count(), 16);
    }
}
