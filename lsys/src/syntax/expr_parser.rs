//! The expression parser: precedence climbing with explicit depth accounting.
//!
//! Every tree it returns is at most [`MAX_EXPR_DEPTH`] deep, and parentheses, unary operators
//! and calls nest at most [`MAX_NESTING`] deep, so the recursive descent itself stays shallow
//! and every later walk over the tree is bounded. Binary chains are parsed in loops, so a long
//! flat chain costs linear time up to the point where it is refused.

use crate::error::ParseError;
use crate::model::expr::{
    BinaryOp, Expr, FUNCTIONS, Function, MAX_EXPR_DEPTH, MAX_NESTING, UnaryOp,
};
use crate::syntax::cursor::Cursor;

/// Names an expression may refer to.
pub(crate) trait Scope {
    /// The binding slot of a formal parameter.
    fn var(&self, name: &str) -> Option<u16>;
    /// The value of a constant.
    fn constant(&self, name: &str) -> Option<f64>;
    /// Whether trigonometric functions take and give degrees (cpfg) rather than radians.
    fn degrees(&self) -> bool {
        false
    }
    /// The slot of a block variable.
    fn global(&self, _name: &str) -> Option<u16> {
        None
    }
    /// The array of block variables named `name`: its first slot and dimensions.
    fn array(&self, _name: &str) -> Option<(u16, Vec<u32>)> {
        None
    }
    /// How many function files `func(id, x)` may read.
    fn functions(&self) -> usize {
        0
    }
    /// How many curve files `curveX(id, t)` and the others may read.
    fn curves(&self) -> usize {
        0
    }
}

/// Parses one expression at the cursor. Stops before any character that cannot continue it.
pub(crate) fn parse_expr(cur: &mut Cursor<'_>, scope: &dyn Scope) -> Result<Expr, ParseError> {
    let parsed = ExprParser {
        cur,
        scope,
        nesting: 0,
    }
    .ternary()?;
    Ok(parsed.expr)
}

/// Whether the cursor is at an arrow, `->` or `-->`, which ends an expression.
fn arrow_at(cur: &Cursor<'_>) -> bool {
    matches!(
        (cur.peek(), cur.peek_at(1), cur.peek_at(2)),
        (Some('-'), Some('>'), _) | (Some('-'), Some('-'), Some('>'))
    )
}

/// A subtree and its depth (1 for a leaf), kept together so no walk is needed to measure it.
struct Parsed {
    expr: Expr,
    depth: usize,
}

impl Parsed {
    fn leaf(expr: Expr) -> Parsed {
        Parsed { expr, depth: 1 }
    }
}

struct ExprParser<'c, 'a> {
    cur: &'c mut Cursor<'a>,
    scope: &'c dyn Scope,
    nesting: usize,
}

impl ExprParser<'_, '_> {
    fn nest(&mut self) -> Result<(), ParseError> {
        self.nesting += 1;
        if self.nesting > MAX_NESTING {
            Err(self
                .cur
                .error(format!("expression nested more than {MAX_NESTING} deep")))
        } else {
            Ok(())
        }
    }

    /// A node over `children`, refused at `at` when it would make the tree too deep.
    fn node(
        &self,
        at: usize,
        depth: usize,
        expr: impl FnOnce() -> Expr,
    ) -> Result<Parsed, ParseError> {
        let depth = depth + 1;
        if depth > MAX_EXPR_DEPTH {
            return Err(self.cur.error_at(
                at,
                format!(
                    "expression deeper than {MAX_EXPR_DEPTH} levels (each operator of a chain such as \
                     a+b+c adds one): split it with parentheses or #define constants"
                ),
            ));
        }
        Ok(Parsed {
            expr: expr(),
            depth,
        })
    }

    fn binary(&self, at: usize, op: BinaryOp, l: Parsed, r: Parsed) -> Result<Parsed, ParseError> {
        self.node(at, l.depth.max(r.depth), || {
            Expr::Binary(op, Box::new(l.expr), Box::new(r.expr))
        })
    }

    /// Position of the next non-blank character, where an operator is about to be read.
    fn here(&mut self) -> usize {
        self.cur.skip_ws();
        self.cur.pos()
    }

    /// One left-associative precedence level: operands come from `operand`; `operator`
    /// consumes the next operator of this level and names it, or returns `None` to end the
    /// chain. A loop, not recursion, so a chain's length never deepens the call stack.
    fn chain(
        &mut self,
        operand: fn(&mut Self) -> Result<Parsed, ParseError>,
        operator: fn(&mut Self) -> Option<BinaryOp>,
    ) -> Result<Parsed, ParseError> {
        let mut e = operand(self)?;
        loop {
            let at = self.here();
            let Some(op) = operator(self) else {
                return Ok(e);
            };
            let r = operand(self)?;
            e = self.binary(at, op, e, r)?;
        }
    }

    /// `c ? a : b` (C's conditional, right-associative), read as `select(c, a, b)`.
    fn ternary(&mut self) -> Result<Parsed, ParseError> {
        let at = self.here();
        let c = self.or()?;
        self.cur.skip_ws();
        if self.cur.peek() != Some('?') {
            return Ok(c);
        }
        self.cur.bump();
        self.nest()?;
        let a = self.ternary()?;
        self.cur
            .expect(':', "':' in a conditional expression (c ? a : b)")?;
        let b = self.ternary()?;
        self.nesting -= 1;
        let depth = c.depth.max(a.depth).max(b.depth);
        self.node(at, depth, || {
            Expr::Call(Function::Select, vec![c.expr, a.expr, b.expr])
        })
    }

    fn or(&mut self) -> Result<Parsed, ParseError> {
        self.chain(Self::and, |p| p.cur.eat_str("||").then_some(BinaryOp::Or))
    }

    fn and(&mut self) -> Result<Parsed, ParseError> {
        self.chain(Self::cmp, |p| p.cur.eat_str("&&").then_some(BinaryOp::And))
    }

    fn cmp(&mut self) -> Result<Parsed, ParseError> {
        self.chain(Self::add, |p| {
            // Two-character operators first, so that "<=" is not read as "<".
            [
                ("<=", BinaryOp::Le),
                (">=", BinaryOp::Ge),
                ("==", BinaryOp::Eq),
                ("!=", BinaryOp::Ne),
                ("<", BinaryOp::Lt),
                (">", BinaryOp::Gt),
            ]
            .into_iter()
            .find(|(token, _)| p.cur.eat_str(token))
            .map(|(_, op)| op)
        })
    }

    fn add(&mut self) -> Result<Parsed, ParseError> {
        self.chain(Self::mul, |p| {
            // "->" and cpfg's "-->" end a condition; they are not a subtraction.
            if p.cur.peek() == Some('-') && arrow_at(p.cur) {
                return None;
            }
            let op = match p.cur.peek() {
                Some('+') => BinaryOp::Add,
                Some('-') => BinaryOp::Sub,
                _ => return None,
            };
            p.cur.bump();
            Some(op)
        })
    }

    fn mul(&mut self) -> Result<Parsed, ParseError> {
        self.chain(Self::unary, |p| {
            if p.cur.eat('*') {
                Some(BinaryOp::Mul)
            } else if p.cur.eat('/') {
                Some(BinaryOp::Div)
            } else if p.cur.eat('%') {
                Some(BinaryOp::Rem)
            } else {
                None
            }
        })
    }

    fn unary(&mut self) -> Result<Parsed, ParseError> {
        let at = self.here();
        let op = match (self.cur.peek(), self.cur.peek_at(1)) {
            (Some('-'), _) if !arrow_at(self.cur) => Some(UnaryOp::Neg),
            (Some('!'), Some(c)) if c != '=' => Some(UnaryOp::Not),
            _ => None,
        };
        if let Some(op) = op {
            self.cur.bump();
            self.nest()?;
            let e = self.unary()?;
            self.nesting -= 1;
            return self.node(at, e.depth, || Expr::Unary(op, Box::new(e.expr)));
        }
        self.pow()
    }

    fn pow(&mut self) -> Result<Parsed, ParseError> {
        let base = self.atom()?;
        let at = self.here();
        if self.cur.eat('^') {
            self.nest()?;
            let exp = self.unary()?;
            self.nesting -= 1;
            return self.binary(at, BinaryOp::Pow, base, exp);
        }
        Ok(base)
    }

    fn atom(&mut self) -> Result<Parsed, ParseError> {
        let start = self.here();
        match self.cur.peek() {
            Some('(') => {
                self.cur.bump();
                self.nest()?;
                let e = self.ternary()?;
                self.nesting -= 1;
                self.cur.expect(')', "')' to close the parenthesis")?;
                Ok(e)
            }
            Some('#') => {
                self.cur.bump();
                Ok(Parsed::leaf(Expr::Generation))
            }
            Some(c) if c.is_ascii_digit() || c == '.' => self.number(),
            Some(c) if c.is_ascii_alphabetic() || c == '_' => {
                let name = self.cur.ident().unwrap_or_default();
                if self.cur.eat('(') {
                    return self.call(name, start);
                }
                if let Some((slot, dims)) = self.scope.array(&name) {
                    return self.element(name, slot, dims, start);
                }
                if let Some(slot) = self.scope.var(&name) {
                    Ok(Parsed::leaf(Expr::Var { name, slot }))
                } else if let Some(value) = self.scope.constant(&name) {
                    Ok(Parsed::leaf(Expr::Constant { name, value }))
                } else if let Some(slot) = self.scope.global(&name) {
                    Ok(Parsed::leaf(Expr::Global { name, slot }))
                } else {
                    Err(self.cur.error_at(
                        start,
                        format!("unknown name '{name}': not a parameter of this production, a #define constant nor a variable assigned in a block"),
                    ))
                }
            }
            _ => Err(self.cur.error(format!(
                "expected a number, a name, '#' or '(' in an expression, found {}",
                self.cur.describe_next()
            ))),
        }
    }

    /// An element of array `name` (first slot `slot`): its indices, `[i][j]`, one per
    /// dimension.
    fn element(
        &mut self,
        name: String,
        slot: u16,
        dims: Vec<u32>,
        start: usize,
    ) -> Result<Parsed, ParseError> {
        self.nest()?;
        let mut indices = Vec::with_capacity(dims.len());
        let mut depth = 0;
        for _ in 0..dims.len() {
            self.cur.skip_ws();
            if !self.cur.eat('[') {
                return Err(self.cur.error_at(
                    start,
                    format!(
                        "array '{name}' takes {} index(es) in brackets, as '{name}[i]'",
                        dims.len()
                    ),
                ));
            }
            let index = self.ternary()?;
            depth = depth.max(index.depth);
            indices.push(index.expr);
            self.cur.expect(']', "']' after the index")?;
        }
        self.nesting -= 1;
        self.node(start, depth, || Expr::Element {
            name,
            slot,
            dims,
            indices,
        })
    }

    fn call(&mut self, name: String, start: usize) -> Result<Parsed, ParseError> {
        if matches!(name.as_str(), "fopen" | "fclose" | "fflush" | "fscanf") {
            return Err(self.cur.error_at(
                start,
                format!(
                    "unsupported: cpfg's file function '{name}' (a model here neither reads nor \
                     writes files of its own)"
                ),
            ));
        }
        let Some(&(_, func, arity)) = FUNCTIONS.iter().find(|f| f.0 == name) else {
            return Err(self
                .cur
                .error_at(start, format!("unknown function '{name}'")));
        };
        self.nest()?;
        let mut args = Vec::new();
        let mut depth = 0;
        if !self.cur.eat(')') {
            loop {
                if args.len() == arity {
                    return Err(self.cur.error_at(
                        start,
                        format!("function '{name}' takes {arity} argument(s), more given"),
                    ));
                }
                let a = self.ternary()?;
                depth = depth.max(a.depth);
                args.push(a.expr);
                if self.cur.eat(')') {
                    break;
                }
                self.cur.expect(',', "',' or ')' in the argument list")?;
            }
        }
        self.nesting -= 1;
        if args.len() != arity {
            return Err(self.cur.error_at(
                start,
                format!(
                    "function '{name}' takes {arity} argument(s), {} given",
                    args.len()
                ),
            ));
        }
        if func.reads_files() {
            self.check_file(func, &args[0], start)?;
        }
        if self.scope.degrees() {
            return self.in_degrees(func, args, start, depth);
        }
        self.node(start, depth, || Expr::Call(func, args))
    }

    /// `func(id, x)` needs the model's function files and `curveX(id, t)` and the others
    /// its curve files, and a constant id one of them.
    fn check_file(&self, func: Function, id: &Expr, start: usize) -> Result<(), ParseError> {
        let (count, files) = if func == Function::Func {
            (self.scope.functions(), "function")
        } else {
            (self.scope.curves(), "curve")
        };
        let name = func.name();
        if count == 0 {
            return Err(self.cur.error_at(
                start,
                format!(
                    "unsupported: {name}(id, ...) reads the model's {files} files: load the model's folder (LSystem::from_model_dir, or give sylva the folder or its .l file)"
                ),
            ));
        }
        if id.is_constant() {
            let k = id.eval_constant(0.0, 0);
            if !(k >= 1.0 && k.fract() == 0.0 && k <= count as f64) {
                return Err(self.cur.error_at(
                    start,
                    format!("{name}({k}, ...): the model has {files}s 1 to {count}"),
                ));
            }
        }
        Ok(())
    }

    /// A trigonometric call of a dialect that measures angles in degrees: its argument
    /// turned into radians, or its result into degrees.
    fn in_degrees(
        &self,
        func: Function,
        mut args: Vec<Expr>,
        start: usize,
        depth: usize,
    ) -> Result<Parsed, ParseError> {
        let scale =
            |e: Expr, k: f64| Expr::Binary(BinaryOp::Mul, Box::new(e), Box::new(Expr::Number(k)));
        match func {
            Function::Sin | Function::Cos | Function::Tan => {
                let arg = args.pop().unwrap_or(Expr::Number(0.0));
                let arg = scale(arg, std::f64::consts::PI / 180.0);
                self.node(start, depth + 1, || Expr::Call(func, vec![arg]))
            }
            Function::Asin | Function::Acos | Function::Atan | Function::Atan2 => {
                let call = self.node(start, depth, || Expr::Call(func, args))?;
                self.node(start, call.depth, || {
                    scale(call.expr, 180.0 / std::f64::consts::PI)
                })
            }
            _ => self.node(start, depth, || Expr::Call(func, args)),
        }
    }

    fn number(&mut self) -> Result<Parsed, ParseError> {
        let start = self.cur.pos();
        let mut text = String::new();
        while let Some(c) = self.cur.peek() {
            if c.is_ascii_digit() || c == '.' {
                text.push(c);
                self.cur.bump();
            } else if (c == 'e' || c == 'E')
                && matches!(self.cur.peek_at(1), Some(d) if d.is_ascii_digit() || d == '-' || d == '+')
            {
                text.push(c);
                self.cur.bump();
                if let Some(s @ ('-' | '+')) = self.cur.peek() {
                    text.push(s);
                    self.cur.bump();
                }
            } else {
                break;
            }
        }
        match text.parse::<f64>() {
            Ok(v) if v.is_finite() => Ok(Parsed::leaf(Expr::Number(v))),
            _ => Err(self.cur.error_at(
                start,
                format!("'{}' is not a finite number", shorten(&text)),
            )),
        }
    }
}

/// The first characters of a long token, for messages that must stay one line.
fn shorten(text: &str) -> String {
    const MAX: usize = 40;
    if text.chars().count() <= MAX {
        text.to_string()
    } else {
        text.chars().take(MAX).collect::<String>() + "..."
    }
}
