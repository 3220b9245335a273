//! The grammar text parser (ABOP / cpfg notation).

use crate::alphabet::{Alphabet, SymbolId};
use crate::cursor::Cursor;
use crate::error::ParseError;
use crate::expr::{Expr, MAX_NESTING, Scope, parse_expr};
use crate::grammar::{LSystem, ModuleTemplate, Pattern, Production, SuccessorItem};

/// Longest grammar text accepted, so that a parse always finishes quickly.
pub(crate) const MAX_SOURCE_CHARS: usize = 1 << 22;

struct Constants<'a> {
    defined: &'a [(String, Expr)],
    vars: &'a [String],
}

impl Scope for Constants<'_> {
    fn var(&self, name: &str) -> Option<u16> {
        self.vars.iter().position(|v| v == name).map(|i| i as u16)
    }
    fn constant(&self, name: &str) -> Option<f64> {
        self.defined
            .iter()
            .rev()
            .find(|(n, _)| n == name)
            .map(|(_, e)| e.eval_constant(0.0, 0))
    }
}

/// Replaces `/* ... */` comments by spaces, keeping newlines so positions stay right.
fn strip_block_comments(src: &[char]) -> Result<Vec<char>, ParseError> {
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

pub(crate) fn parse(text: &str) -> Result<LSystem, ParseError> {
    if text.len() > MAX_SOURCE_CHARS {
        return Err(ParseError::new(
            1,
            1,
            format!("grammar text longer than {MAX_SOURCE_CHARS} bytes"),
        ));
    }
    let src: Vec<char> = text.chars().collect();
    let src = strip_block_comments(&src)?;
    let mut p = GrammarParser {
        alphabet: Alphabet::new(),
        constants: Vec::new(),
        ignore: Vec::new(),
        axiom: None,
        productions: Vec::new(),
    };
    for (n, line) in src.split(|&c| c == '\n').enumerate() {
        let line = line.strip_suffix(&['\r']).unwrap_or(line);
        p.line(&mut Cursor::new(line, n + 1))?;
    }
    let Some(axiom) = p.axiom else {
        return Err(ParseError::new(
            1,
            1,
            "the grammar has no axiom: add a line 'axiom: ...'",
        ));
    };
    LSystem::from_parts(p.alphabet, p.constants, p.ignore, axiom, p.productions)
        .map_err(|e| ParseError::new(1, 1, e.to_string()))
}

/// Parses a word (modules with constant arguments); `symbol` gives each character's id, or
/// `None` when it is not allowed.
pub(crate) fn parse_modules(
    text: &str,
    symbol: &mut dyn FnMut(char) -> Option<SymbolId>,
) -> Result<Vec<(SymbolId, Vec<f64>)>, ParseError> {
    let chars: Vec<char> = text.chars().collect();
    let mut out = Vec::new();
    let empty = Constants {
        defined: &[],
        vars: &[],
    };
    for (n, line) in chars.split(|&c| c == '\n').enumerate() {
        let mut cur = Cursor::new(line, n + 1);
        while !cur.at_end() {
            let pos = cur.pos();
            let c = cur.bump().unwrap_or(' ');
            let Some(id) = symbol(c) else {
                return Err(cur.error_at(pos, format!("'{c}' is not a symbol of this alphabet")));
            };
            let mut params = Vec::new();
            if cur.eat('(') {
                loop {
                    let e = parse_expr(&mut cur, &empty)?;
                    params.push(e.eval_constant(0.0, 0));
                    if cur.eat(')') {
                        break;
                    }
                    cur.expect(',', "',' or ')' after a parameter")?;
                }
            }
            out.push((id, params));
        }
    }
    Ok(out)
}

struct GrammarParser {
    alphabet: Alphabet,
    constants: Vec<(String, Expr)>,
    ignore: Vec<SymbolId>,
    axiom: Option<Vec<ModuleTemplate>>,
    productions: Vec<Production>,
}

impl GrammarParser {
    fn line(&mut self, cur: &mut Cursor<'_>) -> Result<(), ParseError> {
        if cur.at_end() || cur.eat_str("//") {
            return Ok(());
        }
        let start = cur.pos();
        if cur.eat('#') {
            return self.directive(cur);
        }
        if cur.eat_str("axiom") || cur.eat_str("ω") {
            if cur.eat(':') {
                return self.axiom_line(cur, start);
            }
            cur.set_pos(start);
        }
        let production = self.production(cur)?;
        self.productions.push(production);
        Ok(())
    }

    fn directive(&mut self, cur: &mut Cursor<'_>) -> Result<(), ParseError> {
        let at = cur.pos();
        match cur.ident().as_deref() {
            Some("define") => {
                let name_at = cur.pos();
                let Some(name) = cur.ident() else {
                    return Err(cur.error("expected a constant name after #define"));
                };
                let scope = Constants {
                    defined: &self.constants,
                    vars: &[],
                };
                let value = parse_expr(cur, &scope)?;
                if !cur.at_end() {
                    return Err(cur.error(format!(
                        "expected end of line after the constant's value, found {}",
                        cur.describe_next()
                    )));
                }
                if !is_constant(&value) {
                    return Err(cur.error_at(
                        name_at,
                        "a #define value cannot use '#' or random functions",
                    ));
                }
                if !value.eval_constant(0.0, 0).is_finite() {
                    return Err(cur.error_at(name_at, format!("constant '{name}' is not finite")));
                }
                self.constants.push((name, value));
                Ok(())
            }
            Some("ignore") => {
                cur.eat(':');
                while !cur.at_end() {
                    let pos = cur.pos();
                    let c = cur.bump().unwrap_or(' ');
                    let id = self.intern(cur, c, pos)?;
                    if !self.ignore.contains(&id) {
                        self.ignore.push(id);
                    }
                }
                Ok(())
            }
            _ => Err(cur.error_at(
                at,
                "unknown directive: expected '#define NAME value' or '#ignore: symbols'",
            )),
        }
    }

    fn intern(&mut self, cur: &Cursor<'_>, c: char, pos: usize) -> Result<SymbolId, ParseError> {
        self.alphabet.intern(c).ok_or_else(|| {
            if Alphabet::is_symbol_char(c) {
                cur.error_at(pos, "too many distinct symbols (at most 65535)")
            } else {
                cur.error_at(pos, format!("'{c}' cannot be a module symbol"))
            }
        })
    }

    fn axiom_line(&mut self, cur: &mut Cursor<'_>, start: usize) -> Result<(), ParseError> {
        if self.axiom.is_some() {
            return Err(cur.error_at(start, "a second axiom: a grammar has exactly one"));
        }
        let items = self.successor(cur, &[], 0)?;
        if !cur.at_end() {
            return Err(cur.error(format!("unexpected {} in the axiom", cur.describe_next())));
        }
        let mut modules = Vec::with_capacity(items.len());
        for item in items {
            match item {
                SuccessorItem::Module(m) => modules.push(m),
                _ => return Err(cur.error_at(start, "the axiom cannot contain a '?' choice")),
            }
        }
        self.axiom = Some(modules);
        Ok(())
    }

    fn patterns(
        &mut self,
        cur: &mut Cursor<'_>,
        names: &mut Vec<String>,
    ) -> Result<Vec<Pattern>, ParseError> {
        let mut out = Vec::new();
        loop {
            cur.skip_ws();
            let pos = cur.pos();
            let Some(c) = cur.peek() else { break };
            if matches!(c, '<' | '>' | ':' | '→') || (c == '-' && cur.peek_at(1) == Some('>')) {
                break;
            }
            cur.bump();
            let symbol = self.intern(cur, c, pos)?;
            let mut params = Vec::new();
            if cur.eat('(') && !cur.eat(')') {
                loop {
                    let at = cur.pos();
                    let Some(name) = cur.ident() else {
                        return Err(cur.error(format!(
                            "expected a parameter name, found {}",
                            cur.describe_next()
                        )));
                    };
                    if names.contains(&name) {
                        return Err(cur.error_at(
                            at,
                            format!("parameter '{name}' is named twice in this production"),
                        ));
                    }
                    names.push(name.clone());
                    params.push(name);
                    if cur.eat(')') {
                        break;
                    }
                    cur.expect(',', "',' or ')' in the parameter list")?;
                }
            }
            if params.len() > u8::MAX as usize {
                return Err(cur.error_at(pos, "more than 255 parameters on one module"));
            }
            out.push(Pattern { symbol, params });
        }
        Ok(out)
    }

    fn production(&mut self, cur: &mut Cursor<'_>) -> Result<Production, ParseError> {
        // An optional label such as "p1:" (ABOP prints productions that way).
        let start = cur.pos();
        if let Some(label) = cur.ident()
            && !(label.chars().count() >= 2 && cur.eat(':'))
        {
            cur.set_pos(start);
        }
        let mut names = Vec::new();
        let head_at = {
            cur.skip_ws();
            cur.pos()
        };
        let first = self.patterns(cur, &mut names)?;
        let (left, predecessor) = if cur.eat('<') {
            let at = cur.pos();
            let pred = self.patterns(cur, &mut names)?;
            if first
                .iter()
                .any(|p| p.symbol == crate::alphabet::PUSH || p.symbol == crate::alphabet::POP)
            {
                return Err(cur.error_at(head_at, "a left context cannot contain '[' or ']'"));
            }
            (first, single(cur, pred, at)?)
        } else {
            (Vec::new(), single(cur, first, head_at)?)
        };
        let right = if cur.eat('>') {
            self.patterns(cur, &mut names)?
        } else {
            Vec::new()
        };
        let scope = Constants {
            defined: &self.constants,
            vars: &names,
        };
        let condition = if cur.eat(':') {
            if cur.eat('*') {
                None
            } else {
                Some(parse_expr(cur, &scope)?)
            }
        } else {
            None
        };
        if !(cur.eat_str("->") || cur.eat('→')) {
            return Err(cur.error(format!(
                "expected '->' after the predecessor, found {}",
                cur.describe_next()
            )));
        }
        let successor = self.successor(cur, &names, 0)?;
        let weight = if cur.eat(':') {
            let at = cur.pos();
            let e = parse_expr(
                cur,
                &Constants {
                    defined: &self.constants,
                    vars: &[],
                },
            )?;
            let w = e.eval_constant(0.0, 0);
            if !is_constant(&e) || !w.is_finite() || w < 0.0 {
                return Err(cur.error_at(
                    at,
                    "a probability must be a constant, finite and not negative",
                ));
            }
            Some(w)
        } else {
            None
        };
        if !cur.at_end() {
            return Err(cur.error(format!(
                "unexpected {} after the production",
                cur.describe_next()
            )));
        }
        Ok(Production {
            left,
            predecessor,
            right,
            condition,
            successor,
            weight,
        })
    }

    fn successor(
        &mut self,
        cur: &mut Cursor<'_>,
        names: &[String],
        depth: usize,
    ) -> Result<Vec<SuccessorItem>, ParseError> {
        if depth > MAX_NESTING {
            return Err(cur.error(format!("choices nested more than {MAX_NESTING} deep")));
        }
        let mut items = Vec::new();
        loop {
            cur.skip_ws();
            let pos = cur.pos();
            let Some(c) = cur.peek() else { break };
            if c == ':' || c == '>' {
                break;
            }
            cur.bump();
            if c == '?' {
                cur.expect('(', "'(' after '?'")?;
                let scope = Constants {
                    defined: &self.constants,
                    vars: names,
                };
                let probability = parse_expr(cur, &scope)?;
                cur.expect(')', "')' after the choice's probability")?;
                let mut branch = |cur: &mut Cursor<'_>| -> Result<Vec<SuccessorItem>, ParseError> {
                    cur.expect('<', "'<' to open a choice alternative")?;
                    let items = self.successor(cur, names, depth + 1)?;
                    cur.expect('>', "'>' to close a choice alternative")?;
                    Ok(items)
                };
                let then = branch(cur)?;
                let otherwise = branch(cur)?;
                items.push(SuccessorItem::Choice {
                    probability,
                    then,
                    otherwise,
                });
                continue;
            }
            let symbol = self.intern(cur, c, pos)?;
            let scope = Constants {
                defined: &self.constants,
                vars: names,
            };
            let mut args = Vec::new();
            if cur.eat('(') {
                loop {
                    args.push(parse_expr(cur, &scope)?);
                    if cur.eat(')') {
                        break;
                    }
                    cur.expect(',', "',' or ')' after a parameter")?;
                }
            }
            if args.len() > u8::MAX as usize {
                return Err(cur.error_at(pos, "more than 255 parameters on one module"));
            }
            items.push(SuccessorItem::Module(ModuleTemplate { symbol, args }));
        }
        Ok(items)
    }
}

fn single(cur: &Cursor<'_>, mut patterns: Vec<Pattern>, at: usize) -> Result<Pattern, ParseError> {
    match patterns.len() {
        1 => Ok(patterns.remove(0)),
        0 => Err(cur.error_at(at, "expected a predecessor symbol")),
        _ => Err(cur.error_at(
            at,
            "expected one predecessor module (use '<' and '>' for contexts)",
        )),
    }
}

fn is_constant(e: &Expr) -> bool {
    match e {
        Expr::Number(_) | Expr::Constant { .. } => true,
        Expr::Unary(_, a) => is_constant(a),
        Expr::Binary(_, a, b) => is_constant(a) && is_constant(b),
        Expr::Call(f, args) => !f.is_random() && args.iter().all(is_constant),
        _ => false,
    }
}
