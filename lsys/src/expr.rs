//! Parameter expressions: syntax tree, parser, printer, and the compiled stack program.

use std::fmt;

use crate::cursor::Cursor;
use crate::error::ParseError;
use crate::random::Random;

/// Deepest nesting of parentheses, unary operators and calls the parser accepts, so that
/// hostile input cannot overflow the stack.
pub(crate) const MAX_NESTING: usize = 64;

/// A unary operator.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum UnaryOp {
    /// `-x`
    Neg,
    /// `!x`: 1 when x is 0, else 0.
    Not,
}

/// A binary operator. Comparisons and logic yield 1 for true and 0 for false.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum BinaryOp {
    /// `+`
    Add,
    /// `-`
    Sub,
    /// `*`
    Mul,
    /// `/`
    Div,
    /// `^`, right-associative power.
    Pow,
    /// `<`
    Lt,
    /// `<=`
    Le,
    /// `>`
    Gt,
    /// `>=`
    Ge,
    /// `==`
    Eq,
    /// `!=`
    Ne,
    /// `&&`
    And,
    /// `||`
    Or,
}

impl BinaryOp {
    fn token(self) -> &'static str {
        match self {
            BinaryOp::Add => "+",
            BinaryOp::Sub => "-",
            BinaryOp::Mul => "*",
            BinaryOp::Div => "/",
            BinaryOp::Pow => "^",
            BinaryOp::Lt => "<",
            BinaryOp::Le => "<=",
            BinaryOp::Gt => ">",
            BinaryOp::Ge => ">=",
            BinaryOp::Eq => "==",
            BinaryOp::Ne => "!=",
            BinaryOp::And => "&&",
            BinaryOp::Or => "||",
        }
    }

    fn apply(self, a: f64, b: f64) -> f64 {
        let truth = |t: bool| if t { 1.0 } else { 0.0 };
        match self {
            BinaryOp::Add => a + b,
            BinaryOp::Sub => a - b,
            BinaryOp::Mul => a * b,
            BinaryOp::Div => a / b,
            BinaryOp::Pow => a.powf(b),
            BinaryOp::Lt => truth(a < b),
            BinaryOp::Le => truth(a <= b),
            BinaryOp::Gt => truth(a > b),
            BinaryOp::Ge => truth(a >= b),
            BinaryOp::Eq => truth(a == b),
            BinaryOp::Ne => truth(a != b),
            BinaryOp::And => truth(a != 0.0 && b != 0.0),
            BinaryOp::Or => truth(a != 0.0 || b != 0.0),
        }
    }
}

/// A built-in function. Trigonometric functions work in radians.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum Function {
    /// `sin(x)`
    Sin,
    /// `cos(x)`
    Cos,
    /// `tan(x)`
    Tan,
    /// `asin(x)`
    Asin,
    /// `acos(x)`
    Acos,
    /// `atan(x)`
    Atan,
    /// `atan2(y, x)`
    Atan2,
    /// `sqrt(x)`
    Sqrt,
    /// `exp(x)`
    Exp,
    /// `log(x)`, the natural logarithm.
    Log,
    /// `abs(x)`
    Abs,
    /// `floor(x)`
    Floor,
    /// `ceil(x)`
    Ceil,
    /// `min(a, b)`
    Min,
    /// `max(a, b)`
    Max,
    /// `uniform(a, b)`: a seeded uniform draw in `[a, b)`.
    Uniform,
    /// `ran(x)`: a seeded uniform draw in `[0, x)` (cpfg).
    Ran,
    /// `nran(mean, sd)`: a seeded normal draw (cpfg).
    Nran,
}

const FUNCTIONS: &[(&str, Function, usize)] = &[
    ("sin", Function::Sin, 1),
    ("cos", Function::Cos, 1),
    ("tan", Function::Tan, 1),
    ("asin", Function::Asin, 1),
    ("acos", Function::Acos, 1),
    ("atan", Function::Atan, 1),
    ("atan2", Function::Atan2, 2),
    ("sqrt", Function::Sqrt, 1),
    ("exp", Function::Exp, 1),
    ("log", Function::Log, 1),
    ("abs", Function::Abs, 1),
    ("floor", Function::Floor, 1),
    ("ceil", Function::Ceil, 1),
    ("min", Function::Min, 2),
    ("max", Function::Max, 2),
    ("uniform", Function::Uniform, 2),
    ("ran", Function::Ran, 1),
    ("nran", Function::Nran, 2),
];

impl Function {
    /// The name used in grammar text.
    pub fn name(self) -> &'static str {
        FUNCTIONS.iter().find(|f| f.1 == self).map_or("?", |f| f.0)
    }

    /// Number of arguments.
    pub fn arity(self) -> usize {
        FUNCTIONS.iter().find(|f| f.1 == self).map_or(0, |f| f.2)
    }

    /// Whether the function draws from the derivation's random stream.
    pub fn is_random(self) -> bool {
        matches!(self, Function::Uniform | Function::Ran | Function::Nran)
    }

    fn apply(self, args: &[f64], rng: &mut Random) -> f64 {
        let a = args[0];
        let b = args.get(1).copied().unwrap_or(0.0);
        match self {
            Function::Sin => a.sin(),
            Function::Cos => a.cos(),
            Function::Tan => a.tan(),
            Function::Asin => a.asin(),
            Function::Acos => a.acos(),
            Function::Atan => a.atan(),
            Function::Atan2 => a.atan2(b),
            Function::Sqrt => a.sqrt(),
            Function::Exp => a.exp(),
            Function::Log => a.ln(),
            Function::Abs => a.abs(),
            Function::Floor => a.floor(),
            Function::Ceil => a.ceil(),
            Function::Min => a.min(b),
            Function::Max => a.max(b),
            Function::Uniform => a + (b - a) * rng.unit(),
            Function::Ran => a * rng.unit(),
            Function::Nran => a + b * rng.normal(),
        }
    }
}

/// A parameter expression as written in the grammar.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum Expr {
    /// A literal number.
    Number(f64),
    /// A `#define`d constant, kept by name for printing.
    Constant {
        /// The constant's name.
        name: String,
        /// Its value.
        value: f64,
    },
    /// A formal parameter of the production, by name and binding slot.
    Var {
        /// The parameter's name.
        name: String,
        /// Its index among the production's bound parameters (left context, predecessor,
        /// right context, in order).
        slot: u16,
    },
    /// `#`: the generation being produced (1 in the first derivation step; 0 in the axiom).
    Generation,
    /// A unary operation.
    Unary(UnaryOp, Box<Expr>),
    /// A binary operation.
    Binary(BinaryOp, Box<Expr>, Box<Expr>),
    /// A function call.
    Call(Function, Vec<Expr>),
}

impl BinaryOp {
    /// Binding strength: higher binds tighter.
    fn precedence(self) -> u8 {
        match self {
            BinaryOp::Or => 1,
            BinaryOp::And => 2,
            BinaryOp::Lt
            | BinaryOp::Le
            | BinaryOp::Gt
            | BinaryOp::Ge
            | BinaryOp::Eq
            | BinaryOp::Ne => 3,
            BinaryOp::Add | BinaryOp::Sub => 4,
            BinaryOp::Mul | BinaryOp::Div => 5,
            BinaryOp::Pow => 7,
        }
    }
}

const UNARY: u8 = 6;
const ATOM: u8 = 8;

impl Expr {
    fn precedence(&self) -> u8 {
        match self {
            Expr::Binary(op, ..) => op.precedence(),
            Expr::Unary(..) => UNARY,
            _ => ATOM,
        }
    }
}

struct Child<'a>(&'a Expr, bool);

impl fmt::Display for Child<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.1 {
            write!(f, "({})", self.0)
        } else {
            write!(f, "{}", self.0)
        }
    }
}

impl fmt::Display for Expr {
    /// Prints with the fewest parentheses that keep the tree, so that the text parses back to
    /// the same tree and never nests deeper than the text it came from.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Expr::Number(v) if *v < 0.0 || (*v == 0.0 && v.is_sign_negative()) => {
                write!(f, "(-{})", -v)
            }
            Expr::Number(v) => write!(f, "{v}"),
            Expr::Constant { name, .. } | Expr::Var { name, .. } => f.write_str(name),
            Expr::Generation => f.write_str("#"),
            Expr::Unary(op, e) => {
                let sign = if *op == UnaryOp::Neg { "-" } else { "!" };
                write!(f, "{sign}{}", Child(e, e.precedence() < UNARY))
            }
            Expr::Binary(BinaryOp::Pow, a, b) => {
                // The base is an atom; the exponent may be a unary or another power.
                write!(
                    f,
                    "{}^{}",
                    Child(a, a.precedence() < ATOM),
                    Child(b, b.precedence() < UNARY)
                )
            }
            Expr::Binary(op, a, b) => {
                let p = op.precedence();
                // Left-associative: the right operand needs parentheses at equal precedence.
                write!(
                    f,
                    "{}{}{}",
                    Child(a, a.precedence() < p),
                    op.token(),
                    Child(b, b.precedence() <= p)
                )
            }
            Expr::Call(func, args) => {
                write!(f, "{}(", func.name())?;
                for (i, a) in args.iter().enumerate() {
                    if i > 0 {
                        f.write_str(",")?;
                    }
                    write!(f, "{a}")?;
                }
                f.write_str(")")
            }
        }
    }
}

/// Names an expression may refer to.
pub(crate) trait Scope {
    /// The binding slot of a formal parameter.
    fn var(&self, name: &str) -> Option<u16>;
    /// The value of a constant.
    fn constant(&self, name: &str) -> Option<f64>;
}

/// Parses one expression at the cursor. Stops before any character that cannot continue it.
pub(crate) fn parse_expr(cur: &mut Cursor<'_>, scope: &dyn Scope) -> Result<Expr, ParseError> {
    ExprParser {
        cur,
        scope,
        depth: 0,
    }
    .or()
}

struct ExprParser<'c, 'a> {
    cur: &'c mut Cursor<'a>,
    scope: &'c dyn Scope,
    depth: usize,
}

impl ExprParser<'_, '_> {
    fn nest(&mut self) -> Result<(), ParseError> {
        self.depth += 1;
        if self.depth > MAX_NESTING {
            Err(self
                .cur
                .error(format!("expression nested more than {MAX_NESTING} deep")))
        } else {
            Ok(())
        }
    }

    fn or(&mut self) -> Result<Expr, ParseError> {
        let mut e = self.and()?;
        while self.cur.eat_str("||") {
            let r = self.and()?;
            e = Expr::Binary(BinaryOp::Or, Box::new(e), Box::new(r));
        }
        Ok(e)
    }

    fn and(&mut self) -> Result<Expr, ParseError> {
        let mut e = self.cmp()?;
        while self.cur.eat_str("&&") {
            let r = self.cmp()?;
            e = Expr::Binary(BinaryOp::And, Box::new(e), Box::new(r));
        }
        Ok(e)
    }

    fn cmp(&mut self) -> Result<Expr, ParseError> {
        let mut e = self.add()?;
        loop {
            let op = if self.cur.eat_str("<=") {
                BinaryOp::Le
            } else if self.cur.eat_str(">=") {
                BinaryOp::Ge
            } else if self.cur.eat_str("==") {
                BinaryOp::Eq
            } else if self.cur.eat_str("!=") {
                BinaryOp::Ne
            } else if self.cur.eat_str("<") {
                BinaryOp::Lt
            } else if self.is_gt() {
                BinaryOp::Gt
            } else {
                return Ok(e);
            };
            let r = self.add()?;
            e = Expr::Binary(op, Box::new(e), Box::new(r));
        }
    }

    /// `>` is a comparison unless it is the tail of an arrow `->` (never here) — plain check.
    fn is_gt(&mut self) -> bool {
        self.cur.eat_str(">")
    }

    fn add(&mut self) -> Result<Expr, ParseError> {
        let mut e = self.mul()?;
        loop {
            self.cur.skip_ws();
            // "->" ends a condition; it is not a subtraction.
            let op = match (self.cur.peek(), self.cur.peek_at(1)) {
                (Some('+'), _) => BinaryOp::Add,
                (Some('-'), Some('>')) => return Ok(e),
                (Some('-'), _) => BinaryOp::Sub,
                _ => return Ok(e),
            };
            self.cur.bump();
            let r = self.mul()?;
            e = Expr::Binary(op, Box::new(e), Box::new(r));
        }
    }

    fn mul(&mut self) -> Result<Expr, ParseError> {
        let mut e = self.unary()?;
        loop {
            let op = if self.cur.eat('*') {
                BinaryOp::Mul
            } else if self.cur.eat('/') {
                BinaryOp::Div
            } else {
                return Ok(e);
            };
            let r = self.unary()?;
            e = Expr::Binary(op, Box::new(e), Box::new(r));
        }
    }

    fn unary(&mut self) -> Result<Expr, ParseError> {
        self.cur.skip_ws();
        let op = match (self.cur.peek(), self.cur.peek_at(1)) {
            (Some('-'), Some(c)) if c != '>' => Some(UnaryOp::Neg),
            (Some('!'), Some(c)) if c != '=' => Some(UnaryOp::Not),
            _ => None,
        };
        if let Some(op) = op {
            self.cur.bump();
            self.nest()?;
            let e = self.unary()?;
            self.depth -= 1;
            return Ok(Expr::Unary(op, Box::new(e)));
        }
        self.pow()
    }

    fn pow(&mut self) -> Result<Expr, ParseError> {
        let base = self.atom()?;
        if self.cur.eat('^') {
            self.nest()?;
            let exp = self.unary()?;
            self.depth -= 1;
            return Ok(Expr::Binary(BinaryOp::Pow, Box::new(base), Box::new(exp)));
        }
        Ok(base)
    }

    fn atom(&mut self) -> Result<Expr, ParseError> {
        self.cur.skip_ws();
        let start = self.cur.pos();
        match self.cur.peek() {
            Some('(') => {
                self.cur.bump();
                self.nest()?;
                let e = self.or()?;
                self.depth -= 1;
                self.cur.expect(')', "')' to close the parenthesis")?;
                Ok(e)
            }
            Some('#') => {
                self.cur.bump();
                Ok(Expr::Generation)
            }
            Some(c) if c.is_ascii_digit() || c == '.' => self.number(),
            Some(c) if c.is_ascii_alphabetic() || c == '_' => {
                let name = self.cur.ident().unwrap_or_default();
                if self.cur.eat('(') {
                    return self.call(name, start);
                }
                if let Some(slot) = self.scope.var(&name) {
                    Ok(Expr::Var { name, slot })
                } else if let Some(value) = self.scope.constant(&name) {
                    Ok(Expr::Constant { name, value })
                } else {
                    Err(self.cur.error_at(
                        start,
                        format!("unknown name '{name}': not a parameter of this production nor a #define constant"),
                    ))
                }
            }
            _ => Err(self.cur.error(format!(
                "expected a number, a name, '#' or '(' in an expression, found {}",
                self.cur.describe_next()
            ))),
        }
    }

    fn call(&mut self, name: String, start: usize) -> Result<Expr, ParseError> {
        let Some(&(_, func, arity)) = FUNCTIONS.iter().find(|f| f.0 == name) else {
            return Err(self
                .cur
                .error_at(start, format!("unknown function '{name}'")));
        };
        self.nest()?;
        let mut args = Vec::new();
        if !self.cur.eat(')') {
            loop {
                args.push(self.or()?);
                if self.cur.eat(')') {
                    break;
                }
                self.cur.expect(',', "',' or ')' in the argument list")?;
            }
        }
        self.depth -= 1;
        if args.len() != arity {
            return Err(self.cur.error_at(
                start,
                format!(
                    "function '{name}' takes {arity} argument(s), {} given",
                    args.len()
                ),
            ));
        }
        Ok(Expr::Call(func, args))
    }

    fn number(&mut self) -> Result<Expr, ParseError> {
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
            Ok(v) if v.is_finite() => Ok(Expr::Number(v)),
            _ => Err(self
                .cur
                .error_at(start, format!("'{text}' is not a finite number"))),
        }
    }
}

/// One instruction of a compiled expression (postfix).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Op {
    Num(f64),
    Var(u16),
    Gen,
    Unary(UnaryOp),
    Binary(BinaryOp),
    Call(Function),
}

impl Expr {
    /// Whether the value depends on bindings, the generation or random draws.
    fn is_constant(&self) -> bool {
        match self {
            Expr::Number(_) | Expr::Constant { .. } => true,
            Expr::Var { .. } | Expr::Generation => false,
            Expr::Unary(_, e) => e.is_constant(),
            Expr::Binary(_, a, b) => a.is_constant() && b.is_constant(),
            Expr::Call(f, args) => !f.is_random() && args.iter().all(Expr::is_constant),
        }
    }

    /// Highest variable slot used plus one.
    pub(crate) fn slots_used(&self) -> usize {
        match self {
            Expr::Var { slot, .. } => *slot as usize + 1,
            Expr::Unary(_, e) => e.slots_used(),
            Expr::Binary(_, a, b) => a.slots_used().max(b.slots_used()),
            Expr::Call(_, args) => args.iter().map(Expr::slots_used).max().unwrap_or(0),
            _ => 0,
        }
    }

    /// Appends the postfix program for this expression, folding constant subtrees.
    pub(crate) fn compile(&self, out: &mut Vec<Op>) {
        if self.is_constant() && !matches!(self, Expr::Number(_)) {
            let mut tmp = Vec::new();
            self.compile_raw(&mut tmp);
            let mut rng = Random::new(0);
            let v = eval(&tmp, &[], 0.0, &mut rng, &mut Vec::new());
            out.push(Op::Num(v));
            return;
        }
        self.compile_raw(out);
    }

    fn compile_raw(&self, out: &mut Vec<Op>) {
        match self {
            Expr::Number(v) => out.push(Op::Num(*v)),
            Expr::Constant { value, .. } => out.push(Op::Num(*value)),
            Expr::Var { slot, .. } => out.push(Op::Var(*slot)),
            Expr::Generation => out.push(Op::Gen),
            Expr::Unary(op, e) => {
                e.compile(out);
                out.push(Op::Unary(*op));
            }
            Expr::Binary(op, a, b) => {
                a.compile(out);
                b.compile(out);
                out.push(Op::Binary(*op));
            }
            Expr::Call(f, args) => {
                for a in args {
                    a.compile(out);
                }
                out.push(Op::Call(*f));
            }
        }
    }

    /// Evaluates the expression with no bindings (for the axiom, constants and weights).
    pub fn eval_constant(&self, generation: f64, rng_seed: u64) -> f64 {
        let mut ops = Vec::new();
        self.compile_raw(&mut ops);
        eval(
            &ops,
            &[],
            generation,
            &mut Random::new(rng_seed),
            &mut Vec::new(),
        )
    }
}

/// Runs a compiled program. Unbound variables read as 0 (the parser never produces them).
#[inline]
pub(crate) fn eval(
    ops: &[Op],
    vars: &[f64],
    generation: f64,
    rng: &mut Random,
    stack: &mut Vec<f64>,
) -> f64 {
    // Most arguments are a lone number or parameter: skip the stack machine for them.
    match ops {
        [Op::Num(v)] => return *v,
        [Op::Var(k)] => return vars.get(*k as usize).copied().unwrap_or(0.0),
        _ => {}
    }
    stack.clear();
    for op in ops {
        match *op {
            Op::Num(v) => stack.push(v),
            Op::Var(k) => stack.push(vars.get(k as usize).copied().unwrap_or(0.0)),
            Op::Gen => stack.push(generation),
            Op::Unary(u) => {
                let a = stack.pop().unwrap_or(0.0);
                stack.push(match u {
                    UnaryOp::Neg => -a,
                    UnaryOp::Not => f64::from(u8::from(a == 0.0)),
                });
            }
            Op::Binary(b) => {
                let r = stack.pop().unwrap_or(0.0);
                let l = stack.pop().unwrap_or(0.0);
                stack.push(b.apply(l, r));
            }
            Op::Call(f) => {
                let n = f.arity();
                let at = stack.len().saturating_sub(n);
                let mut args = [0.0; 2];
                for (slot, v) in args.iter_mut().zip(&stack[at..]) {
                    *slot = *v;
                }
                stack.truncate(at);
                stack.push(f.apply(&args[..n.max(1)], rng));
            }
        }
    }
    stack.pop().unwrap_or(0.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    struct NoNames;
    impl Scope for NoNames {
        fn var(&self, name: &str) -> Option<u16> {
            (name == "x").then_some(0)
        }
        fn constant(&self, name: &str) -> Option<f64> {
            (name == "k").then_some(10.0)
        }
    }

    fn value(text: &str, x: f64) -> f64 {
        let chars: Vec<char> = text.chars().collect();
        let e = parse_expr(&mut Cursor::new(&chars, 1), &NoNames).unwrap();
        let mut ops = Vec::new();
        e.compile(&mut ops);
        eval(&ops, &[x], 3.0, &mut Random::new(0), &mut Vec::new())
    }

    #[test]
    fn precedence_follows_mathematics() {
        assert_eq!(value("1+2*3", 0.0), 7.0);
        assert_eq!(value("-2^2", 0.0), -4.0);
        assert_eq!(value("2^3^2", 0.0), 512.0);
        assert_eq!(value("1 < 2 && 3 > 2 || 0", 0.0), 1.0);
        assert_eq!(value("(1+2)*x", 4.0), 12.0);
        assert_eq!(value("k/4 - #", 0.0), -0.5);
        assert_eq!(value("!0 + !5", 0.0), 1.0);
    }

    #[test]
    fn constant_subtrees_fold_to_one_number() {
        let chars: Vec<char> = "k*2+sin(0)".chars().collect();
        let e = parse_expr(&mut Cursor::new(&chars, 1), &NoNames).unwrap();
        let mut ops = Vec::new();
        e.compile(&mut ops);
        assert_eq!(ops, vec![Op::Num(20.0)]);
    }

    #[test]
    fn printing_parses_back_to_the_same_tree() {
        for text in [
            "1+2*3",
            "-(x^2)",
            "min(x,k)/(1-x)",
            "!(x>=1)&&#<3",
            "x-(1-x)",
            "-x^-x^2",
            "(-x)^2",
            "x- -x",
            "1<2<3",
            "!!x",
            "2^(x+1)",
        ] {
            let chars: Vec<char> = text.chars().collect();
            let e = parse_expr(&mut Cursor::new(&chars, 1), &NoNames).unwrap();
            let printed: Vec<char> = e.to_string().chars().collect();
            let again = parse_expr(&mut Cursor::new(&printed, 1), &NoNames).unwrap();
            assert_eq!(again, e, "{text}");
        }
    }

    /// Found by the fuzzer: fully parenthesised printing of a long sum nested past the limit.
    #[test]
    fn long_chains_print_without_nesting() {
        let text = (0..200)
            .map(|i| format!("x*{i}"))
            .collect::<Vec<_>>()
            .join("+");
        let chars: Vec<char> = text.chars().collect();
        let e = parse_expr(&mut Cursor::new(&chars, 1), &NoNames).unwrap();
        let printed: Vec<char> = e.to_string().chars().collect();
        assert!(!printed.contains(&'('));
        assert_eq!(
            parse_expr(&mut Cursor::new(&printed, 1), &NoNames).unwrap(),
            e
        );
    }

    #[test]
    fn deep_nesting_is_an_error_not_a_stack_overflow() {
        let text = "(".repeat(10_000) + "1" + &")".repeat(10_000);
        let chars: Vec<char> = text.chars().collect();
        assert!(parse_expr(&mut Cursor::new(&chars, 1), &NoNames).is_err());
        let text = "-".repeat(10_000) + "1";
        let chars: Vec<char> = text.chars().collect();
        assert!(parse_expr(&mut Cursor::new(&chars, 1), &NoNames).is_err());
    }
}
