//! Statement blocks `{ ... }`: C-like assignments, `if`/`else`, `while`, `do ... while`,
//! and expression statements, as cpfg writes them around conditions and derivations.

use std::collections::HashMap;

use crate::error::ParseError;
use crate::model::expr::{Expr, MAX_NESTING};
use crate::model::statement::Statement;
use crate::syntax::cursor::Cursor;
use crate::syntax::expr_parser::{Scope, parse_expr};

/// Names of block variables in `text`: every name assigned with `=` (not `==`, `<=`, `>=`,
/// `!=`), in order of first appearance, so that a block variable can be read in a
/// production that comes before the block assigning it.
pub(crate) fn assigned_names(text: &[char]) -> Vec<String> {
    let mut names: Vec<String> = Vec::new();
    let mut i = 0;
    while i < text.len() {
        let c = text[i];
        let starts = (c.is_ascii_alphabetic() || c == '_')
            && (i == 0 || !(text[i - 1].is_ascii_alphanumeric() || text[i - 1] == '_'));
        if !starts {
            i += 1;
            continue;
        }
        let end = i + text[i..]
            .iter()
            .take_while(|c| c.is_ascii_alphanumeric() || **c == '_')
            .count();
        let mut j = end;
        while text.get(j).is_some_and(|c| *c == ' ' || *c == '\t') {
            j += 1;
        }
        if text.get(j) == Some(&'=') && text.get(j + 1) != Some(&'=') {
            let name: String = text[i..end].iter().collect();
            if !names.contains(&name) {
                names.push(name);
            }
        }
        i = end;
    }
    names
}

/// Parses a block at the cursor, which is at its `{`, through its `}`. `params` are the
/// production's parameters (assignable); `scope` resolves every other name.
pub(crate) fn parse_block(
    cur: &mut Cursor<'_>,
    scope: &dyn Scope,
    params: &HashMap<String, u16>,
) -> Result<Vec<Statement>, ParseError> {
    StatementParser {
        cur,
        scope,
        params,
        nesting: 0,
    }
    .block()
}

struct StatementParser<'c, 'a> {
    cur: &'c mut Cursor<'a>,
    scope: &'c dyn Scope,
    params: &'c HashMap<String, u16>,
    nesting: usize,
}

impl StatementParser<'_, '_> {
    fn block(&mut self) -> Result<Vec<Statement>, ParseError> {
        self.cur.expect('{', "'{' to open a block")?;
        self.nesting += 1;
        if self.nesting > MAX_NESTING {
            return Err(self
                .cur
                .error(format!("blocks nested more than {MAX_NESTING} deep")));
        }
        let mut out = Vec::new();
        loop {
            self.cur.skip_ws();
            match self.cur.peek() {
                Some('}') => {
                    self.cur.bump();
                    break;
                }
                None => return Err(self.cur.error("expected '}' to close the block")),
                _ => self.statement(&mut out)?,
            }
        }
        self.nesting -= 1;
        Ok(out)
    }

    /// One statement, appended to `out` (a nested block's statements are appended flat).
    fn statement(&mut self, out: &mut Vec<Statement>) -> Result<(), ParseError> {
        self.cur.skip_ws();
        let start = self.cur.pos();
        match self.cur.peek() {
            Some('{') => {
                out.extend(self.block()?);
                return Ok(());
            }
            Some(';') => {
                self.cur.bump();
                return Ok(());
            }
            _ => {}
        }
        let word = self.cur.ident();
        match word.as_deref() {
            Some("if") => {
                let condition = self.parenthesised()?;
                let then = self.body()?;
                let after = self.cur.pos();
                let otherwise = if self.cur.ident().as_deref() == Some("else") {
                    self.body()?
                } else {
                    self.cur.set_pos(after);
                    Vec::new()
                };
                out.push(Statement::If {
                    condition,
                    then,
                    otherwise,
                });
            }
            Some("while") => {
                let condition = self.parenthesised()?;
                let body = self.body()?;
                out.push(Statement::While { condition, body });
            }
            Some("do") => {
                let body = self.body()?;
                if self.cur.ident().as_deref() != Some("while") {
                    return Err(self.cur.error("expected 'while' after a do-block"));
                }
                let condition = self.parenthesised()?;
                self.cur.expect(';', "';' after do ... while (...)")?;
                out.push(Statement::DoWhile { body, condition });
            }
            Some("srand") => {
                let seed = self.parenthesised()?;
                self.cur.expect(';', "';' after srand(...)")?;
                out.push(Statement::Seed(seed));
            }
            // Output for the modeller's eyes: nothing the derivation needs.
            Some("printf" | "fprintf") => {
                self.skip_call()?;
                self.cur.expect(';', "';' after the call")?;
            }
            Some(name) => {
                let name = name.to_string();
                self.cur.skip_ws();
                if self.cur.peek() == Some('=') && self.cur.peek_at(1) != Some('=') {
                    self.cur.bump();
                    let value = parse_expr(self.cur, self.scope)?;
                    self.cur.expect(';', "';' after the assignment")?;
                    if let Some(&slot) = self.params.get(&name) {
                        out.push(Statement::SetParameter { name, slot, value });
                    } else if let Some(slot) = self.scope.global(&name) {
                        out.push(Statement::Assign { name, slot, value });
                    } else {
                        return Err(self
                            .cur
                            .error_at(start, format!("'{name}' cannot be assigned")));
                    }
                } else {
                    self.cur.set_pos(start);
                    self.expression_statement(out)?;
                }
            }
            None => self.expression_statement(out)?,
        }
        Ok(())
    }

    /// An expression evaluated for its draws, or an array element given a value
    /// (`len[i][j] = v;`: the element is read as an expression reads it, then assigned).
    fn expression_statement(&mut self, out: &mut Vec<Statement>) -> Result<(), ParseError> {
        let start = self.cur.pos();
        let mut e = parse_expr(self.cur, self.scope)?;
        self.cur.skip_ws();
        if self.cur.peek() == Some('=') && self.cur.peek_at(1) != Some('=') {
            let Expr::Element {
                name,
                slot,
                dims,
                indices,
            } = &mut e
            else {
                return Err(self
                    .cur
                    .error_at(start, "only a name or an array's element can be assigned"));
            };
            self.cur.bump();
            let value = parse_expr(self.cur, self.scope)?;
            self.cur.expect(';', "';' after the assignment")?;
            // `Expr` has its own drop, so its fields are taken rather than moved out.
            out.push(Statement::AssignElement {
                name: std::mem::take(name),
                slot: *slot,
                dims: std::mem::take(dims),
                indices: std::mem::take(indices),
                value,
            });
            return Ok(());
        }
        self.cur.expect(';', "';' after the statement")?;
        out.push(Statement::Eval(e));
        Ok(())
    }

    /// A statement or block as the body of `if`, `else`, `while` or `do`.
    fn body(&mut self) -> Result<Vec<Statement>, ParseError> {
        self.nesting += 1;
        if self.nesting > MAX_NESTING {
            return Err(self
                .cur
                .error(format!("statements nested more than {MAX_NESTING} deep")));
        }
        let mut out = Vec::new();
        self.statement(&mut out)?;
        self.nesting -= 1;
        Ok(out)
    }

    fn parenthesised(&mut self) -> Result<Expr, ParseError> {
        self.cur.expect('(', "'(' before the condition")?;
        let e = parse_expr(self.cur, self.scope)?;
        self.cur.expect(')', "')' after the condition")?;
        Ok(e)
    }

    /// Skips a call's parenthesised arguments, strings and nested parentheses included.
    fn skip_call(&mut self) -> Result<(), ParseError> {
        self.cur.expect('(', "'(' after the function's name")?;
        let mut depth = 1;
        let mut quoted = false;
        while depth > 0 {
            match self.cur.bump() {
                None => return Err(self.cur.error("expected ')' to close the call")),
                Some('"') => quoted = !quoted,
                Some('\\') if quoted => {
                    self.cur.bump();
                }
                Some('(') if !quoted => depth += 1,
                Some(')') if !quoted => depth -= 1,
                _ => {}
            }
        }
        Ok(())
    }
}
