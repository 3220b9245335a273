//! Statements: the C-like blocks cpfg runs around a production's condition and around the
//! derivation (`Start:`, `StartEach:`, `EndEach:`, `End:`).

use crate::model::expr::Expr;

/// One statement of a block. Variables are the grammar's block variables
/// ([`Expr::Global`]): one value each for the whole derivation, as in cpfg.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum Statement {
    /// `name = value;`
    Assign {
        /// The variable's name.
        name: String,
        /// Its slot among the grammar's block variables.
        slot: u16,
        /// The value given to it.
        value: Expr,
    },
    /// `name[i][j] = value;`: a new value for an element of an array of block variables
    /// (cpfg's `define:` arrays), its indices clamped as reads clamp them.
    AssignElement {
        /// The array's name.
        name: String,
        /// The slot of its first element.
        slot: u16,
        /// Its dimensions, outermost first.
        dims: Vec<u32>,
        /// One index per dimension.
        indices: Vec<Expr>,
        /// The value given to the element.
        value: Expr,
    },
    /// `parameter = value;`: a new value for one of the production's own parameters, seen by
    /// the rest of the block, the condition and the successor.
    SetParameter {
        /// The parameter's name.
        name: String,
        /// Its binding slot.
        slot: u16,
        /// The value given to it.
        value: Expr,
    },
    /// `if (condition) then else otherwise`
    If {
        /// Tested once; non-zero is true.
        condition: Expr,
        /// Run when it is true.
        then: Vec<Statement>,
        /// Run when it is false (empty without `else`).
        otherwise: Vec<Statement>,
    },
    /// `while (condition) body`
    While {
        /// Tested before each round.
        condition: Expr,
        /// Run while it is true.
        body: Vec<Statement>,
    },
    /// `do body while (condition);`
    DoWhile {
        /// Run once, then again while the condition is true.
        body: Vec<Statement>,
        /// Tested after each round.
        condition: Expr,
    },
    /// An expression evaluated for its random draw alone (`ran(1);`).
    Eval(Expr),
    /// `srand(seed);`: restarts the random stream from a seed the model chooses.
    Seed(Expr),
}

/// An array of block variables (cpfg's `define: { array len[4][13] = {...}; }`): its
/// elements are the variables from `slot` on, row-major, set to `values` (zeros after them)
/// before the `start` block.
#[derive(Debug, Clone, PartialEq)]
pub struct Array {
    /// The array's name.
    pub name: String,
    /// The slot of its first element among the grammar's variables.
    pub slot: u16,
    /// Its dimensions, outermost first.
    pub dims: Vec<u32>,
    /// Its first values, row-major; at most as many as it has elements.
    pub values: Vec<f64>,
}

impl Array {
    /// How many elements it has.
    pub fn len(&self) -> usize {
        crate::model::expr::elements(&self.dims)
    }

    /// Whether it has no elements (never, for an array the parser read).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

/// The blocks a grammar runs around its derivation (cpfg's `Start:`, `StartEach:`,
/// `EndEach:` and `End:`), and the arrays set before them (cpfg's `define:`).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Blocks {
    /// Arrays of block variables, set to their values before `start`.
    pub arrays: Vec<Array>,
    /// Before the first step (and before the axiom is decomposed).
    pub start: Vec<Statement>,
    /// Before every step.
    pub start_each: Vec<Statement>,
    /// After every step (and its decomposition).
    pub end_each: Vec<Statement>,
    /// After the last step.
    pub end: Vec<Statement>,
}

impl Blocks {
    /// Whether there are no statements at all.
    pub fn is_empty(&self) -> bool {
        self.arrays.is_empty()
            && self.start.is_empty()
            && self.start_each.is_empty()
            && self.end_each.is_empty()
            && self.end.is_empty()
    }
}

/// Every expression in `statements`, nested ones included.
pub(crate) fn expressions(statements: &[Statement]) -> Vec<&Expr> {
    let mut out = Vec::new();
    let mut pending: Vec<&Statement> = statements.iter().rev().collect();
    while let Some(s) = pending.pop() {
        match s {
            Statement::Assign { value, .. }
            | Statement::SetParameter { value, .. }
            | Statement::Eval(value)
            | Statement::Seed(value) => out.push(value),
            Statement::AssignElement { indices, value, .. } => {
                out.extend(indices);
                out.push(value);
            }
            Statement::If {
                condition,
                then,
                otherwise,
            } => {
                out.push(condition);
                pending.extend(then.iter().chain(otherwise).rev());
            }
            Statement::While { condition, body } | Statement::DoWhile { body, condition } => {
                out.push(condition);
                pending.extend(body.iter().rev());
            }
        }
    }
    out
}
