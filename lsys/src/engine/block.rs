//! Statement blocks compiled to flat programs with jumps, and their runner.

use crate::engine::eval::{Op, Span, element_at, eval, offset};
use crate::engine::random::Random;
use crate::model::expr::elements;
use crate::model::statement::Statement;
use crate::model_files::ModelFiles;

/// Most statements one run of a block may execute: a loop that never ends stops here with
/// an error instead of hanging the derivation.
pub const MAX_BLOCK_STATEMENTS: u64 = 1_000_000;

/// One instruction of a block. Jump targets are relative to the block's first instruction.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Instruction {
    /// Evaluate the program and store it in a block variable.
    Store(u16, Span),
    /// Evaluate the second program and store it in the element of the array (first slot,
    /// length) at the offset the first program gives.
    StoreElement(u16, u32, Span, Span),
    /// Evaluate the program and store it in a bound parameter.
    StoreParameter(u16, Span),
    /// Evaluate the program; go to the target when it is zero.
    JumpUnless(Span, u32),
    /// Go to the target.
    Jump(u32),
    /// Evaluate the program for its draws alone.
    Eval(Span),
    /// Evaluate the program and restart the random stream from it.
    Seed(Span),
}

/// Appends `statements` compiled onto `out`, their expressions onto `ops`.
pub(crate) fn compile(statements: &[Statement], ops: &mut Vec<Op>, out: &mut Vec<Instruction>) {
    let base = out.len();
    emit(statements, ops, out, base);
}

fn program(e: &crate::model::expr::Expr, ops: &mut Vec<Op>) -> Span {
    let start = ops.len() as u32;
    e.compile(ops);
    (start, ops.len() as u32)
}

fn emit(statements: &[Statement], ops: &mut Vec<Op>, out: &mut Vec<Instruction>, base: usize) {
    let here = |out: &Vec<Instruction>| (out.len() - base) as u32;
    for s in statements {
        match s {
            Statement::Assign { slot, value, .. } => {
                let p = program(value, ops);
                out.push(Instruction::Store(*slot, p));
            }
            Statement::AssignElement {
                slot,
                dims,
                indices,
                value,
                ..
            } => {
                let start = ops.len() as u32;
                offset(dims, indices, ops);
                let at = (start, ops.len() as u32);
                let p = program(value, ops);
                out.push(Instruction::StoreElement(
                    *slot,
                    elements(dims) as u32,
                    at,
                    p,
                ));
            }
            Statement::SetParameter { slot, value, .. } => {
                let p = program(value, ops);
                out.push(Instruction::StoreParameter(*slot, p));
            }
            Statement::Eval(e) => {
                let p = program(e, ops);
                out.push(Instruction::Eval(p));
            }
            Statement::Seed(e) => {
                let p = program(e, ops);
                out.push(Instruction::Seed(p));
            }
            Statement::If {
                condition,
                then,
                otherwise,
            } => {
                let p = program(condition, ops);
                let test = out.len();
                out.push(Instruction::JumpUnless(p, 0));
                emit(then, ops, out, base);
                if otherwise.is_empty() {
                    out[test] = Instruction::JumpUnless(p, here(out));
                } else {
                    let skip = out.len();
                    out.push(Instruction::Jump(0));
                    out[test] = Instruction::JumpUnless(p, here(out));
                    emit(otherwise, ops, out, base);
                    out[skip] = Instruction::Jump(here(out));
                }
            }
            Statement::While { condition, body } => {
                let top = here(out);
                let p = program(condition, ops);
                let test = out.len();
                out.push(Instruction::JumpUnless(p, 0));
                emit(body, ops, out, base);
                out.push(Instruction::Jump(top));
                out[test] = Instruction::JumpUnless(p, here(out));
            }
            Statement::DoWhile { body, condition } => {
                let top = here(out);
                emit(body, ops, out, base);
                let p = program(condition, ops);
                // Loop while true: skip the jump back when false.
                out.push(Instruction::JumpUnless(p, here(out) + 2));
                out.push(Instruction::Jump(top));
            }
        }
    }
}

/// Runs a compiled block; returns how many statements it ran. Errors (with that number)
/// when it would run more than `cap`.
pub(crate) fn run(
    block: &[Instruction],
    ops: &[Op],
    (vars, globals, files): (&mut [f64], &mut [f64], &ModelFiles),
    generation: f64,
    rng: &mut Random,
    stack: &mut Vec<f64>,
    cap: u64,
) -> Result<u64, u64> {
    let mut pc = 0usize;
    let mut executed = 0u64;
    let value =
        |span: Span, vars: &[f64], globals: &[f64], rng: &mut Random, stack: &mut Vec<f64>| {
            eval(
                &ops[span.0 as usize..span.1 as usize],
                (vars, globals, files),
                generation,
                rng,
                stack,
            )
        };
    while let Some(&instruction) = block.get(pc) {
        executed += 1;
        if executed > cap {
            return Err(executed - 1);
        }
        pc += 1;
        match instruction {
            Instruction::Store(slot, span) => {
                let v = value(span, vars, globals, rng, stack);
                if let Some(g) = globals.get_mut(slot as usize) {
                    *g = v;
                }
            }
            Instruction::StoreElement(slot, len, at, span) => {
                let offset = value(at, vars, globals, rng, stack);
                let v = value(span, vars, globals, rng, stack);
                if let Some(g) = globals.get_mut(slot as usize + element_at(offset, len)) {
                    *g = v;
                }
            }
            Instruction::StoreParameter(slot, span) => {
                let v = value(span, vars, globals, rng, stack);
                if let Some(p) = vars.get_mut(slot as usize) {
                    *p = v;
                }
            }
            Instruction::Eval(span) => {
                value(span, vars, globals, rng, stack);
            }
            Instruction::Seed(span) => {
                let v = value(span, vars, globals, rng, stack);
                // The seed's bits as cpfg's srand takes an integer.
                *rng = Random::new(v as i64 as u64);
            }
            Instruction::JumpUnless(span, target) => {
                let v = value(span, vars, globals, rng, stack);
                if v == 0.0 || v.is_nan() {
                    pc = target as usize;
                }
            }
            Instruction::Jump(target) => pc = target as usize,
        }
    }
    Ok(executed)
}
