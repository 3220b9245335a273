//! Arrays of block variables: cpfg's `define: { array len[4][13] = {...}, w[3]; }` and
//! sylva's `#array len[4][13] = {...}`, one declaration a line.

use super::*;

/// Most elements all of a grammar's arrays may have together: each is a block variable.
pub(crate) const MAX_ARRAY_ELEMENTS: usize = 60_000;

impl GrammarParser {
    /// cpfg's `define:` block at the cursor (after the keyword): `{`, `array` statements
    /// (each a comma-separated list of declarations ending in `;`), `}`.
    pub(crate) fn define_block(&mut self, cur: &mut Cursor<'_>) -> Result<(), ParseError> {
        cur.eat(':');
        cur.skip_ws();
        cur.expect('{', "'{' to open the define block")?;
        loop {
            cur.skip_ws();
            if cur.eat('}') {
                break;
            }
            if cur.eat(';') {
                continue;
            }
            let at = cur.pos();
            if cur.ident().as_deref() != Some("array") {
                return Err(cur.error_at(
                    at,
                    "unsupported: a define block statement other than 'array name[n] = {...};'",
                ));
            }
            loop {
                self.array_declaration(cur)?;
                cur.skip_ws();
                if cur.eat(';') {
                    break;
                }
                cur.expect(',', "',' or ';' after an array")?;
            }
        }
        if !cur.at_end() {
            return Err(cur.error(format!(
                "unexpected {} after the define block",
                cur.describe_next()
            )));
        }
        Ok(())
    }

    /// `name[d1][d2] [= {v, ...}]` at the cursor: the array's elements become block
    /// variables after those there are; values are constant, row-major, zeros after them.
    pub(crate) fn array_declaration(&mut self, cur: &mut Cursor<'_>) -> Result<(), ParseError> {
        cur.skip_ws();
        let at = cur.pos();
        let Some(name) = cur.ident() else {
            return Err(cur.error(format!(
                "expected an array's name, found {}",
                cur.describe_next()
            )));
        };
        if self.blocks.arrays.iter().any(|a| a.name == name) {
            return Err(cur.error_at(at, format!("array '{name}' is declared twice")));
        }
        let mut dims = Vec::new();
        loop {
            cur.skip_ws();
            if !cur.eat('[') {
                break;
            }
            let dim_at = cur.pos();
            let scope = self.names(no_vars());
            let size = parse_expr(cur, &scope)?;
            let value = size.eval_constant(0.0, 0);
            if !size.is_constant() || !(1.0..=MAX_ARRAY_ELEMENTS as f64).contains(&value) {
                return Err(cur.error_at(
                    dim_at,
                    format!("an array's size is a constant from 1 to {MAX_ARRAY_ELEMENTS}"),
                ));
            }
            // cpfg truncates a size to a whole number.
            dims.push(value as u32);
            cur.expect(']', "']' after the array's size")?;
        }
        if dims.is_empty() {
            return Err(cur.error_at(at, format!("array '{name}' needs a size: '{name}[n]'")));
        }
        let len = crate::model::expr::elements(&dims);
        let used: usize = self.blocks.arrays.iter().map(Array::len).sum();
        if len > MAX_ARRAY_ELEMENTS - used.min(MAX_ARRAY_ELEMENTS)
            || self.globals.len() + len > u16::MAX as usize
        {
            return Err(cur.error_at(
                at,
                format!("the arrays have more than {MAX_ARRAY_ELEMENTS} elements together"),
            ));
        }
        let mut values = Vec::new();
        cur.skip_ws();
        if cur.eat('=') {
            cur.skip_ws();
            cur.expect('{', "'{' to open the array's values")?;
            loop {
                cur.skip_ws();
                if cur.eat('}') {
                    break;
                }
                let value_at = cur.pos();
                let scope = self.names(no_vars());
                let e = parse_expr(cur, &scope)?;
                let v = e.eval_constant(0.0, 0);
                if !e.is_constant() || !v.is_finite() {
                    return Err(cur.error_at(value_at, "an array's values are constant and finite"));
                }
                // cpfg ignores values past the array's end (with a warning).
                if values.len() < len {
                    values.push(v);
                }
                cur.skip_ws();
                if cur.eat('}') {
                    break;
                }
                cur.expect(',', "',' or '}' between an array's values")?;
            }
        }
        let slot = self.globals.len() as u16;
        self.globals
            .extend((0..len).map(|k| format!("{name}[{k}]")));
        self.blocks.arrays.push(Array {
            name,
            slot,
            dims,
            values,
        });
        Ok(())
    }
}
