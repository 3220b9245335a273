//! Directives of sylva's notation (`#define`, `#ignore`, `#module`, `#derivation`, `#ring`,
//! blocks, `#decomposition`, `#homomorphism`, `#lsystem`) and the constant values they take.

use super::*;

impl GrammarParser {
    /// The directive at the cursor, its `#` read.
    pub(crate) fn directive(&mut self, cur: &mut Cursor<'_>) -> Result<(), ParseError> {
        let at = cur.pos();
        match cur.ident().as_deref() {
            Some("define") => {
                cur.skip_ws();
                let name_at = cur.pos();
                let Some(name) = cur.ident() else {
                    return Err(cur.error("expected a constant name after #define"));
                };
                let scope = self.names(no_vars());
                let value = parse_expr(cur, &scope)?;
                if !cur.at_end() {
                    return Err(cur.error(format!(
                        "expected end of line after the constant's value, found {}",
                        cur.describe_next()
                    )));
                }
                if !value.is_constant() {
                    return Err(cur.error_at(
                        name_at,
                        "a #define value cannot use '#' or random functions",
                    ));
                }
                let number = value.eval_constant(0.0, 0);
                if !number.is_finite() {
                    return Err(cur.error_at(name_at, format!("constant '{name}' is not finite")));
                }
                self.values.insert(name.clone(), number);
                self.constant_at
                    .push((name.clone(), cur.location_of(name_at)));
                self.constants.push((name, value));
                Ok(())
            }
            Some("array") => {
                self.array_declaration(cur)?;
                if !cur.at_end() {
                    return Err(cur.error(format!(
                        "expected end of line after the array, found {}",
                        cur.describe_next()
                    )));
                }
                Ok(())
            }
            Some("ignore") => {
                cur.eat(':');
                while !cur.at_end() {
                    let id = self.symbol(cur)?;
                    if !self.ignore.contains(&id) {
                        self.ignore.push(id);
                    }
                }
                Ok(())
            }
            Some(name @ ("start" | "starteach" | "endeach" | "end")) => {
                let block = self.derivation_block(cur)?;
                if !cur.at_end() {
                    return Err(cur.error(format!(
                        "expected end of line after the #{name} block, found {}",
                        cur.describe_next()
                    )));
                }
                let slot = match name {
                    "start" => &mut self.blocks.start,
                    "starteach" => &mut self.blocks.start_each,
                    "endeach" => &mut self.blocks.end_each,
                    _ => &mut self.blocks.end,
                };
                slot.extend(block);
                Ok(())
            }
            Some("lsystem") => {
                // `#lsystem N`: the productions after it are sub-L-system N's; `#lsystem`
                // alone returns to the main system.
                cur.skip_ws();
                let at = cur.pos();
                self.subsystem = if cur.at_end() {
                    None
                } else {
                    let id = self.constant_value(cur)?;
                    Some(whole_steps(cur, at, id)?)
                };
                self.section = Section::Main;
                Ok(())
            }
            Some("ring") => {
                // `#ring`: the word is a ring for contexts (cpfg's `ring lsystem`).
                cur.skip_ws();
                if !cur.at_end() {
                    return Err(cur.error(format!(
                        "expected end of line after #ring, found {}",
                        cur.describe_next()
                    )));
                }
                self.ring = true;
                Ok(())
            }
            Some("derivation") => {
                let at = cur.pos();
                let steps = self.constant_value(cur)?;
                self.derivation_length = Some(whole_steps(cur, at, steps)?);
                Ok(())
            }
            Some("module") => {
                cur.eat(':');
                cur.skip_ws();
                if cur.at_end() {
                    return Err(cur.error("expected the names of modules after #module"));
                }
                while !cur.at_end() {
                    let at = cur.pos();
                    let mut name = String::new();
                    while let Some(c) = cur.peek().filter(|c| !c.is_whitespace()) {
                        name.push(c);
                        cur.bump();
                    }
                    if name.is_empty() {
                        cur.bump();
                        cur.skip_ws();
                        continue;
                    }
                    let Some(id) = self.alphabet.intern_name(&name) else {
                        return Err(cur.error_at(
                            at,
                            format!("'{name}' cannot be a module name: 1 to {MAX_NAME_CHARS} characters without spaces, parentheses, commas or brackets"),
                        ));
                    };
                    let chars: Vec<char> = name.chars().collect();
                    // Names of several characters, and single characters the notation
                    // reserves (cpfg's '#' and ',' modules), are read as declared.
                    let declared = chars.len() > 1 || !Alphabet::is_symbol_char(chars[0]);
                    if declared && !self.long_names.iter().any(|(n, _)| *n == chars) {
                        self.long_names.push((chars, Some(id)));
                        self.long_names.sort_by_key(|(n, _)| std::cmp::Reverse(n.len()));
                    }
                    cur.skip_ws();
                }
                Ok(())
            }
            Some(name @ ("decomposition" | "homomorphism")) => {
                self.section = if name == "decomposition" {
                    Section::Decomposition
                } else {
                    Section::Homomorphism
                };
                cur.skip_ws();
                let depth = if cur.at_end() {
                    DEFAULT_MAX_DEPTH
                } else {
                    if cur.ident().as_deref() != Some("depth") {
                        return Err(cur.error(format!(
                            "expected 'depth N' or end of line after #{name}"
                        )));
                    }
                    self.leading_depth(cur)?
                };
                self.set_max_depth(depth);
                cur.skip_ws();
                if !cur.at_end() {
                    let at = cur.pos();
                    if cur.ident().as_deref() != Some("stop") {
                        return Err(cur.error_at(
                            at,
                            format!("expected 'stop' or end of line after #{name} depth N"),
                        ));
                    }
                    self.set_stops_at_depth();
                }
                Ok(())
            }
            _ => Err(cur.error_at(
                at,
                "unknown directive: expected '#define NAME value', '#ignore: symbols', '#module names', '#derivation N', '#ring', '#start { ... }' (or #starteach, #endeach, #end), '#array name[n] = {...}', '#decomposition [depth N]' or '#homomorphism [depth N]'",
            )),
        }
    }

    /// A block run around the derivation (no parameters), at the cursor: `{ ... }`.
    pub(crate) fn derivation_block(
        &mut self,
        cur: &mut Cursor<'_>,
    ) -> Result<Vec<crate::model::statement::Statement>, ParseError> {
        cur.eat(':');
        cur.skip_ws();
        let scope = self.names(no_vars());
        parse_block(cur, &scope, no_vars())
    }

    /// A constant expression (numbers and `#define`s), then the end of the line.
    pub(crate) fn constant_value(&mut self, cur: &mut Cursor<'_>) -> Result<f64, ParseError> {
        let number = self.leading_constant(cur)?;
        if !cur.at_end() {
            return Err(cur.error(format!(
                "expected end of line after the value, found {}",
                cur.describe_next()
            )));
        }
        Ok(number)
    }

    /// A constant, finite value at the cursor, with anything after it left to read.
    fn leading_constant(&mut self, cur: &mut Cursor<'_>) -> Result<f64, ParseError> {
        cur.skip_ws();
        let at = cur.pos();
        let scope = self.names(no_vars());
        let value = parse_expr(cur, &scope)?;
        let number = value.eval_constant(0.0, 0);
        if !value.is_constant() || !number.is_finite() {
            return Err(cur.error_at(at, "expected a constant, finite value"));
        }
        Ok(number)
    }

    /// A maximum depth: a constant expression with a whole value from 0 to [`MAX_RULE_DEPTH`],
    /// then the end of the line.
    pub(crate) fn depth(&mut self, cur: &mut Cursor<'_>) -> Result<u32, ParseError> {
        let depth = self.leading_depth(cur)?;
        if !cur.at_end() {
            return Err(cur.error(format!(
                "expected end of line after the depth, found {}",
                cur.describe_next()
            )));
        }
        Ok(depth)
    }

    /// A maximum depth as [`GrammarParser::depth`] reads it, with anything after it left to
    /// read.
    fn leading_depth(&mut self, cur: &mut Cursor<'_>) -> Result<u32, ParseError> {
        cur.skip_ws();
        let at = cur.pos();
        let depth = self.leading_constant(cur)?;
        if !(depth.fract() == 0.0 && (0.0..=f64::from(MAX_RULE_DEPTH)).contains(&depth)) {
            return Err(cur.error_at(
                at,
                format!("a maximum depth must be a whole number from 0 to {MAX_RULE_DEPTH}"),
            ));
        }
        Ok(depth as u32)
    }

    /// Makes the section being read keep the modules beyond its depth (`#... depth N stop`).
    pub(crate) fn set_stops_at_depth(&mut self) {
        match self.section {
            Section::Decomposition => self.rule_sets[0].stops_at_depth = true,
            Section::Homomorphism => self.rule_sets[1].stops_at_depth = true,
            Section::Main => {}
        }
    }

    /// Sets the maximum depth of the section being read (a decomposition or homomorphism);
    /// false in the main section, which has none.
    pub(crate) fn set_max_depth(&mut self, depth: u32) -> bool {
        match self.section {
            Section::Decomposition => self.rule_sets[0].max_depth = depth,
            Section::Homomorphism => self.rule_sets[1].max_depth = depth,
            Section::Main => return false,
        }
        true
    }
}
