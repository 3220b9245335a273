//! Compiled expressions: postfix programs with constant subtrees folded, and their evaluator.

use crate::engine::random::Random;
use crate::model::expr::{BinaryOp, Expr, Function, UnaryOp, elements};
use crate::model_files::ModelFiles;

/// A range (start, end) into one of the compiled flat tables: ops, items, instructions.
pub(crate) type Span = (u32, u32);

/// One instruction of a compiled expression (postfix).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Op {
    Num(f64),
    Var(u16),
    Global(u16),
    /// Pops a flat offset into the array of block variables at the slot, of the length.
    Element(u16, u32),
    Gen,
    Unary(UnaryOp),
    Binary(BinaryOp),
    /// The operator applied to the top of the stack and a parameter: `x + y` is
    /// `Var(x) WithVar(+, y)`, one push fewer and one pop fewer than `Var Var Binary`.
    WithVar(BinaryOp, u16),
    /// The operator applied to the top of the stack and a number.
    WithNum(BinaryOp, f64),
    Call(Function),
}

impl Expr {
    /// Appends the postfix program for this expression, folding constant subtrees into one
    /// number. Bottom-up in one pass, so the work is linear in the size of the tree.
    pub(crate) fn compile(&self, out: &mut Vec<Op>) {
        compile_folding(self, out);
    }

    fn compile_raw(&self, out: &mut Vec<Op>) {
        match self {
            Expr::Number(v) => out.push(Op::Num(*v)),
            Expr::Constant { value, .. } => out.push(Op::Num(*value)),
            Expr::Var { slot, .. } => out.push(Op::Var(*slot)),
            Expr::Global { slot, .. } => out.push(Op::Global(*slot)),
            Expr::Generation => out.push(Op::Gen),
            // An element is never constant: compiled the one way there is.
            Expr::Element { .. } => {
                compile_folding(self, out);
            }
            Expr::Unary(op, e) => {
                e.compile_raw(out);
                out.push(Op::Unary(*op));
            }
            Expr::Binary(op, a, b) => {
                a.compile_raw(out);
                b.compile_raw(out);
                out.push(Op::Binary(*op));
            }
            Expr::Call(f, args) => {
                for a in args {
                    a.compile_raw(out);
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
            (&[], &[], &ModelFiles::NONE),
            generation,
            &mut Random::new(rng_seed),
            &mut Vec::new(),
        )
    }
}

/// Compiles `e` onto `out` and says whether its value is constant; a constant subtree is
/// replaced by its value right away, so a parent only ever folds already-folded children.
fn compile_folding(e: &Expr, out: &mut Vec<Op>) -> bool {
    let start = out.len();
    let constant = match e {
        Expr::Number(v) | Expr::Constant { value: v, .. } => {
            out.push(Op::Num(*v));
            return true;
        }
        Expr::Var { slot, .. } => {
            out.push(Op::Var(*slot));
            return false;
        }
        Expr::Global { slot, .. } => {
            out.push(Op::Global(*slot));
            return false;
        }
        Expr::Generation => {
            out.push(Op::Gen);
            return false;
        }
        Expr::Element {
            slot,
            dims,
            indices,
            ..
        } => {
            offset(dims, indices, out);
            out.push(Op::Element(*slot, elements(dims) as u32));
            return false;
        }
        Expr::Unary(op, a) => {
            let constant = compile_folding(a, out);
            out.push(Op::Unary(*op));
            constant
        }
        Expr::Binary(op, a, b) => {
            let left = compile_folding(a, out);
            let at = out.len();
            let right = compile_folding(b, out);
            // A right operand that is one parameter or number joins the operator.
            match out[at..] {
                [Op::Var(k)] => out[at] = Op::WithVar(*op, k),
                [Op::Num(v)] => out[at] = Op::WithNum(*op, v),
                _ => out.push(Op::Binary(*op)),
            }
            left && right
        }
        Expr::Call(f, args) => {
            // A model file's values are the model's, not known while compiling.
            let mut constant = f.is_pure();
            for a in args {
                constant &= compile_folding(a, out);
            }
            out.push(Op::Call(*f));
            constant
        }
    };
    if constant {
        let value = eval(
            &out[start..],
            (&[], &[], &ModelFiles::NONE),
            0.0,
            &mut Random::new(0),
            &mut Vec::new(),
        );
        out.truncate(start);
        out.push(Op::Num(value));
    }
    constant
}

/// Compiles the flat offset of an element: row-major, each index clamped to its dimension
/// as cpfg clamps it.
pub(crate) fn offset(dims: &[u32], indices: &[Expr], out: &mut Vec<Op>) {
    for (k, (index, &d)) in indices.iter().zip(dims).enumerate() {
        if k > 0 {
            out.extend([Op::Num(f64::from(d)), Op::Binary(BinaryOp::Mul)]);
        }
        compile_folding(index, out);
        clamp_index(d, out);
        if k > 0 {
            out.push(Op::Binary(BinaryOp::Add));
        }
    }
}

/// Clamps the index on the stack to `0..=dimension - 1`.
fn clamp_index(dimension: u32, out: &mut Vec<Op>) {
    out.extend([
        Op::Num(0.0),
        Op::Call(Function::Max),
        Op::Num(f64::from(dimension.saturating_sub(1))),
        Op::Call(Function::Min),
    ]);
}

/// The element an offset names in an array of `len` elements: the offset truncated (as cpfg
/// truncates it) and kept inside the array.
pub(crate) fn element_at(offset: f64, len: u32) -> usize {
    if offset.is_finite() && offset > 0.0 {
        (offset as usize).min(len.saturating_sub(1) as usize)
    } else {
        0
    }
}

/// Runs a compiled program over the bound parameters and the block variables (`vars`,
/// `globals`). Unbound variables read as 0 (the parser never produces them).
#[inline]
pub(crate) fn eval(
    ops: &[Op],
    (vars, globals, files): (&[f64], &[f64], &ModelFiles),
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
            Op::Global(k) => stack.push(globals.get(k as usize).copied().unwrap_or(0.0)),
            Op::Element(slot, len) => {
                let offset = stack.pop().unwrap_or(0.0);
                let k = slot as usize + element_at(offset, len);
                stack.push(globals.get(k).copied().unwrap_or(0.0));
            }
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
            // The operand joined to the operator changes the top in place.
            Op::WithVar(b, k) => {
                let r = vars.get(k as usize).copied().unwrap_or(0.0);
                if let Some(top) = stack.last_mut() {
                    *top = b.apply(*top, r);
                }
            }
            Op::WithNum(b, r) => {
                if let Some(top) = stack.last_mut() {
                    *top = b.apply(*top, r);
                }
            }
            Op::Call(f) => {
                let n = f.arity();
                let at = stack.len().saturating_sub(n);
                let mut args = [0.0; 3];
                for (slot, v) in args.iter_mut().zip(&stack[at..]) {
                    *slot = *v;
                }
                stack.truncate(at);
                stack.push(if f.reads_files() {
                    files.value(f, args[0], args[1])
                } else {
                    f.apply(&args[..n.max(1)], rng)
                });
            }
        }
    }
    stack.pop().unwrap_or(0.0)
}

impl ModelFiles {
    /// The value of `f`, a function reading the model's files, at `id` (from 1) and `x`; 0
    /// for an id the model does not have, as cpfg gives (the parser refuses constant ones).
    fn value(&self, f: Function, id: f64, x: f64) -> f64 {
        let k = if id >= 1.0 && id.fract() == 0.0 {
            id as usize - 1
        } else {
            usize::MAX
        };
        if f == Function::Func {
            return self.functions.get(k).map_or(0.0, |g| g.value(x));
        }
        let Some(curve) = self.curves.get(k) else {
            return 0.0;
        };
        match f {
            Function::CurveX => curve.at_length(x)[0],
            Function::CurveY => curve.at_length(x)[1],
            Function::CurveZ => curve.at_length(x)[2],
            _ => curve.length(),
        }
    }
}

impl BinaryOp {
    fn apply(self, a: f64, b: f64) -> f64 {
        let truth = |t: bool| if t { 1.0 } else { 0.0 };
        match self {
            BinaryOp::Add => a + b,
            BinaryOp::Sub => a - b,
            BinaryOp::Mul => a * b,
            BinaryOp::Div => a / b,
            BinaryOp::Rem => a % b,
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

impl Function {
    fn apply(self, args: &[f64], rng: &mut Random) -> f64 {
        let a = args.first().copied().unwrap_or(0.0);
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
            Function::Stop => {
                rng.stop |= a != 1.0;
                a
            }
            Function::Select => {
                if a != 0.0 && !a.is_nan() {
                    b
                } else {
                    args.get(2).copied().unwrap_or(0.0)
                }
            }
            Function::Uniform => a + (b - a) * rng.unit(),
            Function::Ran => a * rng.unit(),
            Function::Nran => a + b * rng.normal(),
            Function::Bran => rng.beta(a, b),
            Function::Biran => rng.binomial(a, b),
            // Evaluated by `eval`, which has the model's files.
            Function::Func
            | Function::CurveX
            | Function::CurveY
            | Function::CurveZ
            | Function::CurveLength => 0.0,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::syntax::cursor::Cursor;
    use crate::syntax::expr_parser::{Scope, parse_expr};

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
        eval(
            &ops,
            (&[x], &[], &ModelFiles::NONE),
            3.0,
            &mut Random::new(0),
            &mut Vec::new(),
        )
    }

    /// A right operand that is one parameter or number is joined to its operator, and the
    /// order of operands holds for operators that do not commute.
    #[test]
    fn operands_joined_to_their_operator_keep_their_order() {
        let chars: Vec<char> = "x * 2 + x".chars().collect();
        let e = parse_expr(&mut Cursor::new(&chars, 1), &NoNames).unwrap();
        let mut ops = Vec::new();
        e.compile(&mut ops);
        assert_eq!(
            ops,
            vec![
                Op::Var(0),
                Op::WithNum(BinaryOp::Mul, 2.0),
                Op::WithVar(BinaryOp::Add, 0)
            ]
        );
        assert_eq!(value("x * 2 + x", 3.0), 9.0);
        assert_eq!(value("2 - x", 3.0), -1.0);
        assert_eq!(value("x / 4 - k", 2.0), -9.5);
        assert_eq!(value("(x + 1) ^ x", 2.0), 9.0);
        // Both sides constant: folded to one number still.
        assert_eq!(value("k - 4", 0.0), 6.0);
    }

    /// cpfg's bran(a, b) is a beta draw: its mean is a / (a + b).
    #[test]
    fn beta_and_binomial_draws_have_their_means() {
        let mut rng = Random::new(9);
        let n = 20_000;
        let beta: f64 = (0..n).map(|_| rng.beta(5.0, 16.0)).sum::<f64>() / f64::from(n);
        assert!((beta - 5.0 / 21.0).abs() < 0.005, "{beta}");
        let small: f64 = (0..n).map(|_| rng.beta(0.5, 0.5)).sum::<f64>() / f64::from(n);
        assert!((small - 0.5).abs() < 0.01, "{small}");
        let binomial: f64 = (0..n).map(|_| rng.binomial(10.0, 0.3)).sum::<f64>() / f64::from(n);
        assert!((binomial - 3.0).abs() < 0.05, "{binomial}");
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
