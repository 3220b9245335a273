//! Printing: grammars, expressions and words back to the text the parser reads.

use std::fmt;

use crate::engine::lsystem::LSystem;
use crate::model::alphabet::Alphabet;
use crate::model::expr::{BinaryOp, Expr, UnaryOp};
use crate::model::grammar::{ModuleTemplate, Pattern, Production, SuccessorItem};
use crate::model::statement::Statement;
use crate::model::word::Word;

impl BinaryOp {
    /// The operator as written in grammar text.
    fn token(self) -> &'static str {
        match self {
            BinaryOp::Add => "+",
            BinaryOp::Sub => "-",
            BinaryOp::Mul => "*",
            BinaryOp::Div => "/",
            BinaryOp::Rem => "%",
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
            BinaryOp::Mul | BinaryOp::Div | BinaryOp::Rem => 5,
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
            Expr::Constant { name, .. } | Expr::Var { name, .. } | Expr::Global { name, .. } => {
                f.write_str(name)
            }
            Expr::Generation => f.write_str("#"),
            Expr::Element { name, indices, .. } => write_element(f, name, indices),
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

/// An array's element as grammar text: `name[i][j]`.
fn write_element(f: &mut fmt::Formatter<'_>, name: &str, indices: &[Expr]) -> fmt::Result {
    f.write_str(name)?;
    indices.iter().try_for_each(|i| write!(f, "[{i}]"))
}

struct PatternsDisplay<'a>(&'a [Pattern], &'a Alphabet);

impl fmt::Display for PatternsDisplay<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for (i, p) in self.0.iter().enumerate() {
            // Spaces keep "/*" and a leading "//" from reading back as comments.
            if i > 0 {
                f.write_str(" ")?;
            }
            write!(f, "{}", self.1.name(p.symbol))?;
            if !p.params.is_empty() {
                write!(f, "({})", p.params.join(","))?;
            }
        }
        Ok(())
    }
}

struct ItemsDisplay<'a>(&'a [SuccessorItem], &'a Alphabet);

impl fmt::Display for ItemsDisplay<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let mut previous: Option<&ModuleTemplate> = None;
        let spaced = self.1.has_long_names();
        for item in self.0 {
            match item {
                SuccessorItem::Module(m) => {
                    separate(f, previous, m, self.1, spaced)?;
                    write_template(f, m, self.1)?;
                    previous = Some(m);
                    continue;
                }
                SuccessorItem::Choice {
                    probability,
                    then,
                    otherwise,
                } => write!(
                    f,
                    "?({probability})<{}><{}>",
                    ItemsDisplay(then, self.1),
                    ItemsDisplay(otherwise, self.1)
                )?,
            }
            previous = None;
        }
        Ok(())
    }
}

/// Writes a space where two modules would otherwise print as the comment opener `/*`, and
/// between all modules when the alphabet has names of several characters (`spaced`), so
/// that `A B` is not read back as a module `AB`.
fn separate(
    f: &mut fmt::Formatter<'_>,
    previous: Option<&ModuleTemplate>,
    next: &ModuleTemplate,
    alphabet: &Alphabet,
    spaced: bool,
) -> fmt::Result {
    match previous {
        Some(_) if spaced => f.write_str(" "),
        Some(p)
            if p.args.is_empty()
                && alphabet.char(p.symbol) == '/'
                && alphabet.char(next.symbol) == '*' =>
        {
            f.write_str(" ")
        }
        _ => Ok(()),
    }
}

fn write_template(
    f: &mut fmt::Formatter<'_>,
    m: &ModuleTemplate,
    alphabet: &Alphabet,
) -> fmt::Result {
    write!(f, "{}", alphabet.name(m.symbol))?;
    if !m.args.is_empty() {
        f.write_str("(")?;
        for (i, a) in m.args.iter().enumerate() {
            if i > 0 {
                f.write_str(",")?;
            }
            write!(f, "{a}")?;
        }
        f.write_str(")")?;
    }
    Ok(())
}

impl fmt::Display for LSystem {
    /// Writes the grammar in the notation [`LSystem::parse`] reads.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let a = &*self.alphabet;
        for (name, e) in &self.constants {
            writeln!(f, "#define {name} {e}")?;
        }
        if let Some(n) = self.derivation_length {
            writeln!(f, "#derivation {n}")?;
        }
        if self.ring {
            writeln!(f, "#ring")?;
        }
        // Names of several characters, and single characters sylva's notation reserves
        // (modules of other dialects), are declared so that they read back.
        let long: Vec<&str> = a
            .names()
            .skip(3)
            .filter(|n| n.chars().nth(1).is_some() || !n.chars().all(Alphabet::is_symbol_char))
            .collect();
        if !long.is_empty() {
            writeln!(f, "#module {}", long.join(" "))?;
        }
        if !self.ignore.is_empty() {
            let s: Vec<&str> = self.ignore.iter().map(|&s| a.name(s)).collect();
            writeln!(f, "#ignore: {}", s.join(" "))?;
        }
        f.write_str("axiom: ")?;
        let mut previous = None;
        let spaced = !long.is_empty();
        for m in &self.axiom {
            separate(f, previous, m, a, spaced)?;
            write_template(f, m, a)?;
            previous = Some(m);
        }
        writeln!(f)?;
        for array in &self.blocks.arrays {
            write!(f, "#array {}", array.name)?;
            array.dims.iter().try_for_each(|d| write!(f, "[{d}]"))?;
            if !array.values.is_empty() {
                f.write_str(" = {")?;
                for (k, v) in array.values.iter().enumerate() {
                    let sep = if k > 0 { ", " } else { "" };
                    write!(f, "{sep}{}", Expr::Number(*v))?;
                }
                f.write_str("}")?;
            }
            writeln!(f)?;
        }
        for (name, block) in [
            ("start", &self.blocks.start),
            ("starteach", &self.blocks.start_each),
            ("endeach", &self.blocks.end_each),
            ("end", &self.blocks.end),
        ] {
            if !block.is_empty() {
                writeln!(f, "#{name} {}", BlockDisplay(block))?;
            }
        }
        write_productions(f, &self.productions, a)?;
        for (name, set) in [
            ("decomposition", &self.decomposition),
            ("homomorphism", &self.homomorphism),
        ] {
            if !set.is_empty() {
                let stop = if set.stops_at_depth { " stop" } else { "" };
                writeln!(f, "#{name} depth {}{stop}", set.max_depth)?;
                write_productions(f, &set.productions, a)?;
            }
        }
        for (id, productions) in &self.subsystems {
            writeln!(f, "#lsystem {id}")?;
            write_productions(f, productions, a)?;
        }
        Ok(())
    }
}

/// A block in grammar notation, on one line: `{ x = 1; if (x > 0) { y = 2; } }`.
struct BlockDisplay<'a>(&'a [Statement]);

impl fmt::Display for BlockDisplay<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("{")?;
        for s in self.0 {
            f.write_str(" ")?;
            match s {
                Statement::Assign { name, value, .. }
                | Statement::SetParameter { name, value, .. } => write!(f, "{name} = {value};")?,
                Statement::AssignElement {
                    name,
                    indices,
                    value,
                    ..
                } => {
                    write_element(f, name, indices)?;
                    write!(f, " = {value};")?
                }
                Statement::Eval(e) => write!(f, "{e};")?,
                Statement::Seed(e) => write!(f, "srand({e});")?,
                Statement::If {
                    condition,
                    then,
                    otherwise,
                } => {
                    write!(f, "if ({condition}) {}", BlockDisplay(then))?;
                    if !otherwise.is_empty() {
                        write!(f, " else {}", BlockDisplay(otherwise))?;
                    }
                }
                Statement::While { condition, body } => {
                    write!(f, "while ({condition}) {}", BlockDisplay(body))?
                }
                Statement::DoWhile { body, condition } => {
                    write!(f, "do {} while ({condition});", BlockDisplay(body))?
                }
            }
        }
        f.write_str(" }")
    }
}

fn write_productions(
    f: &mut fmt::Formatter<'_>,
    productions: &[Production],
    a: &Alphabet,
) -> fmt::Result {
    for p in productions {
        // A line starting with '#' would read as a directive: a label (which the parser
        // skips) goes first when the production's first module is cpfg's '#'.
        let first = p.left.first().unwrap_or(&p.predecessor).symbol;
        if a.name(first).starts_with('#') {
            f.write_str("p0: ")?;
        }
        if !p.left.is_empty() {
            write!(f, "{} < ", PatternsDisplay(&p.left, a))?;
        }
        write!(
            f,
            "{}",
            PatternsDisplay(std::slice::from_ref(&p.predecessor), a)
        )?;
        if !p.predecessor_rest.is_empty() {
            write!(f, " {}", PatternsDisplay(&p.predecessor_rest, a))?;
        }
        if !p.right.is_empty() {
            write!(f, " > {}", PatternsDisplay(&p.right, a))?;
        }
        if !p.pre.is_empty() || p.condition.is_some() || !p.post.is_empty() {
            f.write_str(" :")?;
            if !p.pre.is_empty() {
                write!(f, " {}", BlockDisplay(&p.pre))?;
            }
            match &p.condition {
                Some(c) => write!(f, " {c}")?,
                None => f.write_str(" *")?,
            }
            if !p.post.is_empty() {
                write!(f, " {}", BlockDisplay(&p.post))?;
            }
        }
        write!(f, " -> {}", ItemsDisplay(&p.successor, a))?;
        if let Some(w) = p.weight {
            write!(f, " : {w}")?;
        }
        writeln!(f)?;
    }
    Ok(())
}

impl fmt::Display for Word {
    /// Writes the modules in grammar notation. Numbers print in Rust's shortest round-trip
    /// form, so parsing the text gives back the same bits.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        use fmt::Write;
        let spaced = self.alphabet.has_long_names();
        for (i, m) in self.iter().enumerate() {
            if spaced && i > 0 {
                f.write_char(' ')?;
            }
            f.write_str(m.name)?;
            if !m.params.is_empty() {
                f.write_char('(')?;
                for (k, v) in m.params.iter().enumerate() {
                    if k > 0 {
                        f.write_char(',')?;
                    }
                    write!(f, "{v}")?;
                }
                f.write_char(')')?;
            }
        }
        Ok(())
    }
}
