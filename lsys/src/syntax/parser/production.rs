//! Productions: predecessor patterns with their contexts, conditions and blocks, and
//! successors.

use super::*;

impl GrammarParser {
    /// The modules of a predecessor or context at the cursor, their parameters named into
    /// `names`.
    fn patterns(
        &mut self,
        cur: &mut Cursor<'_>,
        names: &mut HashMap<String, u16>,
    ) -> Result<Vec<Pattern>, ParseError> {
        let mut out = Vec::new();
        loop {
            cur.skip_ws();
            let pos = cur.pos();
            let Some(c) = cur.peek() else { break };
            let long = long_name_at(cur, &self.long_names).is_some();
            let arrow = c == '-'
                && (cur.peek_at(1) == Some('>')
                    || (cur.peek_at(1) == Some('-') && cur.peek_at(2) == Some('>')));
            if !long && (matches!(c, '<' | '>' | ':' | '→') || arrow) {
                break;
            }
            let symbol = self.symbol(cur)?;
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
                    if names.contains_key(&name) {
                        return Err(cur.error_at(
                            at,
                            format!("parameter '{name}' is named twice in this production"),
                        ));
                    }
                    if names.len() >= MAX_BINDINGS {
                        return Err(cur.error_at(
                            at,
                            format!("more than {MAX_BINDINGS} parameters in one production"),
                        ));
                    }
                    names.insert(name.clone(), names.len() as u16);
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

    /// A cpfg right context with its `=` read: "skip to the end of the current branch".
    /// `=]` is then what `]` alone means in a right context here (the rest of the branch
    /// skipped, its `]` passed), and a `=` that ends the context asks for nothing.
    fn branch_ends(&self, right: Vec<Pattern>) -> Result<Vec<Pattern>, String> {
        let Some(skip) = self.alphabet.id('=') else {
            return Ok(right);
        };
        let mut out: Vec<Pattern> = Vec::with_capacity(right.len());
        let mut pending = false;
        for p in right {
            if pending && p.symbol != POP {
                return Err("unsupported: '=' in a right context not followed by ']' \
                            (the end of the branch it skips to)"
                    .into());
            }
            pending = p.symbol == skip && p.params.is_empty();
            if !pending {
                out.push(p);
            }
        }
        Ok(out)
    }

    /// A whole production at the cursor: contexts, predecessor, blocks, condition, arrow,
    /// successor and weight.
    pub(crate) fn production(&mut self, cur: &mut Cursor<'_>) -> Result<Production, ParseError> {
        // An optional label such as "p1:" (ABOP prints productions that way).
        let start = cur.pos();
        if let Some(label) = cur.ident()
            && !(label.chars().count() >= 2 && cur.eat(':'))
        {
            cur.set_pos(start);
        }
        let mut names = HashMap::new();
        let head_at = {
            cur.skip_ws();
            cur.pos()
        };
        let first = self.patterns(cur, &mut names)?;
        let (left, predecessor) = if cur.eat('<') {
            let at = cur.pos();
            let pred = self.patterns(cur, &mut names)?;
            if first.iter().any(|p| p.symbol == PUSH || p.symbol == POP) {
                return Err(cur.error_at(head_at, "a left context cannot contain '[' or ']'"));
            }
            (first, self.single(cur, pred, at)?)
        } else {
            (Vec::new(), self.single(cur, first, head_at)?)
        };
        let right = if cur.eat('>') {
            let at = cur.pos();
            let right = self.patterns(cur, &mut names)?;
            if self.dialect == Dialect::Cpfg {
                self.branch_ends(right)
                    .map_err(|message| cur.error_at(at, message))?
            } else {
                right
            }
        } else {
            Vec::new()
        };
        let scope = self.names(&names);
        // Blocks: `pred : {pre} condition {post} -> successor`, each part optional.
        let block = |cur: &mut Cursor<'_>| {
            cur.skip_ws();
            if cur.peek() == Some('{') {
                parse_block(cur, &scope, &names)
            } else {
                Ok(Vec::new())
            }
        };
        let mut pre = block(cur)?;
        let mut post = Vec::new();
        let condition = if cur.eat(':') {
            pre.extend(block(cur)?);
            cur.skip_ws();
            let condition = if cur.eat('*') || cur.peek() == Some('{') || arrow_next(cur) {
                None
            } else {
                Some(parse_expr(cur, &scope)?)
            };
            post = block(cur)?;
            condition
        } else {
            None
        };
        if !(cur.eat_str("-->") || cur.eat_str("->") || cur.eat('→')) {
            return Err(cur.error(format!(
                "expected '->' after the predecessor, found {}",
                cur.describe_next()
            )));
        }
        let successor = self.successor(cur, &names, 0, &mut Vec::new())?;
        let weight = if cur.eat(':') {
            cur.skip_ws();
            let at = cur.pos();
            let e = parse_expr(cur, &self.names(no_vars()))?;
            let w = e.eval_constant(0.0, 0);
            if !e.is_constant() || !w.is_finite() || w < 0.0 {
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
        let (predecessor, predecessor_rest) = predecessor;
        Ok(Production {
            left,
            predecessor,
            predecessor_rest,
            right,
            pre,
            condition,
            post,
            successor,
            weight,
        })
    }

    /// Parses successor items up to `:` or `>`, noting where each top-level item starts.
    pub(super) fn successor(
        &mut self,
        cur: &mut Cursor<'_>,
        names: &HashMap<String, u16>,
        depth: usize,
        starts: &mut Vec<usize>,
    ) -> Result<Vec<SuccessorItem>, ParseError> {
        if depth > MAX_NESTING {
            return Err(cur.error(format!("choices nested more than {MAX_NESTING} deep")));
        }
        let mut items = Vec::new();
        if self.dialect == Dialect::Cpfg && depth == 0 {
            // cpfg writes the empty successor as '*'.
            let at = cur.pos();
            if cur.eat('*') {
                cur.skip_ws();
                if cur.at_end() || cur.peek() == Some(':') {
                    return Ok(items);
                }
            }
            cur.set_pos(at);
        }
        loop {
            cur.skip_ws();
            let pos = cur.pos();
            let Some(c) = cur.peek() else { break };
            let long = long_name_at(cur, &self.long_names).is_some();
            if !long && (c == ':' || c == '>') {
                break;
            }
            starts.push(pos);
            if !long && c == '?' {
                cur.bump();
                cur.expect('(', "'(' after '?'")?;
                let scope = self.names(names);
                let probability = parse_expr(cur, &scope)?;
                cur.expect(')', "')' after the choice's probability")?;
                let mut branch = |cur: &mut Cursor<'_>| -> Result<Vec<SuccessorItem>, ParseError> {
                    cur.expect('<', "'<' to open a choice alternative")?;
                    let items = self.successor(cur, names, depth + 1, &mut Vec::new())?;
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
            let symbol = self.symbol(cur)?;
            let scope = self.names(names);
            let mut args = Vec::new();
            if cur.eat('(') {
                loop {
                    cur.skip_ws();
                    if self.dialect == Dialect::Cpfg && cur.peek() == Some('"') {
                        // A label's text (`@L("%.f", c)`): the turtle here draws no text,
                        // so the module keeps its numbers only.
                        skip_string(cur)?;
                    } else {
                        args.push(parse_expr(cur, &scope)?);
                    }
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

/// Moves past a string literal in double quotes (a backslash escapes the next character).
fn skip_string(cur: &mut Cursor<'_>) -> Result<(), ParseError> {
    let at = cur.pos();
    cur.bump();
    loop {
        match cur.bump() {
            Some('"') => return Ok(()),
            Some('\\') => {
                cur.bump();
            }
            Some(_) => {}
            None => return Err(cur.error_at(at, "a string never closed with '\"'")),
        }
    }
}
