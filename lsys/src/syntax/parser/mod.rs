//! The grammar text parser (ABOP / cpfg notation): dialects, lines, axioms and symbols here;
//! directives and productions in the child modules.

mod arrays;
mod directive;
mod production;

use std::collections::HashMap;

use crate::engine::lsystem::LSystem;
use crate::error::{GrammarError, Location, ParseError};
use crate::model::alphabet::{Alphabet, MAX_NAME_CHARS, POP, PUSH, SymbolId};
use crate::model::dialect::Dialect;
use crate::model::expr::{Expr, MAX_NESTING};
use crate::model::grammar::{ModuleTemplate, Pattern, Production, RuleSet, SuccessorItem};
use crate::model::statement::{Array, Blocks};
use crate::model::word::Word;
use crate::syntax::comments::strip_block_comments;
use crate::syntax::cursor::Cursor;
use crate::syntax::expr_parser::{Scope, parse_expr};
use crate::syntax::statement_parser::parse_block;

/// Longest grammar text accepted, in bytes, so that a parse always finishes quickly.
pub const MAX_GRAMMAR_BYTES: usize = 1 << 22;

/// Most parameters one production may bind (contexts and predecessor together): the width of
/// a binding slot.
const MAX_BINDINGS: usize = u16::MAX as usize;

/// The names an expression can see: `#define` values (evaluated once, when defined) and the
/// production's formal parameters.
struct Names<'a> {
    constants: &'a HashMap<String, f64>,
    vars: &'a HashMap<String, u16>,
    /// Trigonometry in degrees (cpfg).
    degrees: bool,
    /// The grammar's block variables, by slot.
    globals: &'a [String],
    /// How many function files the model has.
    functions: usize,
    /// How many curve files the model has.
    curves: usize,
    /// The grammar's arrays of block variables.
    arrays: &'a [Array],
}

impl Scope for Names<'_> {
    fn var(&self, name: &str) -> Option<u16> {
        self.vars.get(name).copied()
    }
    fn constant(&self, name: &str) -> Option<f64> {
        self.constants.get(name).copied()
    }
    fn degrees(&self) -> bool {
        self.degrees
    }
    fn functions(&self) -> usize {
        self.functions
    }
    fn curves(&self) -> usize {
        self.curves
    }
    fn array(&self, name: &str) -> Option<(u16, Vec<u32>)> {
        self.arrays
            .iter()
            .find(|a| a.name == name)
            .map(|a| (a.slot, a.dims.clone()))
    }
    fn global(&self, name: &str) -> Option<u16> {
        self.globals
            .iter()
            .position(|g| g == name)
            .map(|k| k as u16)
    }
}

impl GrammarParser {
    /// The names an expression of this grammar sees, with `vars` as the production's
    /// parameters.
    fn names<'a>(&'a self, vars: &'a HashMap<String, u16>) -> Names<'a> {
        Names {
            constants: &self.values,
            vars,
            degrees: self.dialect == Dialect::Cpfg,
            globals: &self.globals,
            functions: self.functions,
            curves: self.curves,
            arrays: &self.blocks.arrays,
        }
    }
}

/// No formal parameters: the scope of `#define`, weights and the axiom.
fn no_vars() -> &'static HashMap<String, u16> {
    static EMPTY: std::sync::OnceLock<HashMap<String, u16>> = std::sync::OnceLock::new();
    EMPTY.get_or_init(HashMap::new)
}

/// Whether the cursor is at an arrow (`-->`, `->` or `→`), after whitespace.
fn arrow_next(cur: &mut Cursor<'_>) -> bool {
    cur.skip_ws();
    matches!(
        (cur.peek(), cur.peek_at(1), cur.peek_at(2)),
        (Some('-'), Some('>'), _) | (Some('-'), Some('-'), Some('>')) | (Some('→'), _, _)
    )
}

impl Dialect {
    /// The dialect a text declares: cpfg when a line starts with `Lsystem:` (outside
    /// comments), else sylva's notation.
    pub fn declared_in(text: &str) -> Dialect {
        let src: Vec<char> = text.chars().collect();
        let stripped = strip_block_comments(&src).unwrap_or(src);
        let cpfg = stripped.split(|&c| c == '\n').any(|line| {
            let line: String = line.iter().collect();
            line.trim_start().starts_with("Lsystem:")
        });
        if cpfg { Dialect::Cpfg } else { Dialect::Sylva }
    }
}

impl GrammarParser {
    /// A parser of `dialect` text whose block variables are `globals`.
    pub(crate) fn new(dialect: Dialect, globals: Vec<String>) -> GrammarParser {
        GrammarParser {
            dialect,
            subsystem: None,
            sub_productions: Vec::new(),
            globals,
            blocks: Blocks::default(),
            derivation_length: None,
            ring: false,
            consider: None,
            long_names: Vec::new(),
            section: Section::Main,
            rule_sets: [RuleSet::default(), RuleSet::default()].map(|mut set| {
                set.max_depth = DEFAULT_MAX_DEPTH;
                // cpfg keeps a module at its section's maximum depth as it is.
                set.stops_at_depth = dialect == Dialect::Cpfg;
                set
            }),
            alphabet: Alphabet::new(),
            constants: Vec::new(),
            values: HashMap::new(),
            constant_at: Vec::new(),
            ignore: Vec::new(),
            functions: 0,
            curves: 0,
            axiom: None,
            productions: Vec::new(),
        }
    }

    /// Adds symbols of several characters that the dialect has of its own.
    pub(crate) fn add_long_names<'a>(&mut self, names: impl IntoIterator<Item = &'a str>) {
        for name in names {
            self.long_names.push((name.chars().collect(), None));
        }
        self.long_names
            .sort_by_key(|(n, _)| std::cmp::Reverse(n.len()));
    }

    /// The L-system of everything read, checked; errors point at the line they were made
    /// on.
    pub(crate) fn finish(self) -> Result<LSystem, ParseError> {
        let mut p = self;
        let dialect = p.dialect;
        if let Some(consider) = p.consider.take() {
            // cpfg's `consider:` names the symbols contexts see: every other one is ignored
            // (brackets always delimit branches).
            p.ignore = (0..p.alphabet.len() as u16)
                .map(SymbolId)
                .filter(|s| !consider.contains(s) && *s != PUSH && *s != POP)
                .collect();
        }
        let Some((axiom, axiom_at)) = p.axiom else {
            return Err(ParseError::new(
                1,
                1,
                "the grammar has no axiom: add a line 'axiom: ...'",
            ));
        };
        // Productions by section, main first, as `from_parts` and `with_rule_sets` number them.
        let mut sections: [Vec<(Production, Location)>; 3] = Default::default();
        for (production, at, section) in p.productions {
            sections[section as usize].push((production, at));
        }
        let [main, decomposition, homomorphism] = sections;
        let production_at: Vec<Location> = main
            .iter()
            .chain(&decomposition)
            .chain(&homomorphism)
            .map(|(_, at)| *at)
            .collect();
        let [mut decomposition_set, mut homomorphism_set] = p.rule_sets;
        decomposition_set.productions = decomposition.into_iter().map(|(p, _)| p).collect();
        homomorphism_set.productions = homomorphism.into_iter().map(|(p, _)| p).collect();
        let productions = main.into_iter().map(|(p, _)| p).collect();
        // The parser checks everything `from_parts` checks, at the place it happens; should a
        // check only `from_parts` makes ever fail, the error still points at the right line.
        let (derivation_length, ring) = (p.derivation_length, p.ring);
        let mut subsystems: Vec<(u32, Vec<Production>)> = Vec::new();
        let mut locations = production_at.clone();
        let mut sub_productions = std::mem::take(&mut p.sub_productions);
        // Grouped by id in order of first appearance; productions keep their order.
        let mut ids: Vec<u32> = Vec::new();
        for (id, _, _) in &sub_productions {
            if !ids.contains(id) {
                ids.push(*id);
            }
        }
        for id in ids {
            let (mine, rest): (Vec<_>, Vec<_>) =
                sub_productions.into_iter().partition(|(k, _, _)| *k == id);
            sub_productions = rest;
            locations.extend(mine.iter().map(|(_, _, at)| *at));
            subsystems.push((id, mine.into_iter().map(|(_, p, _)| p).collect()));
        }
        let (globals, blocks) = (p.globals, p.blocks);
        LSystem::from_parts(p.alphabet, p.constants, p.ignore, axiom, productions)
            .and_then(|system| system.with_rule_sets(decomposition_set, homomorphism_set))
            .and_then(|system| system.with_blocks(globals, blocks))
            .and_then(|system| system.with_subsystems(subsystems))
            .map(|system| {
                system
                    .with_derivation_length(derivation_length)
                    .with_ring(ring)
                    .with_dialect(dialect)
                    .with_locations(locations)
            })
            .map_err(|e| {
                let at = match &e {
                    GrammarError::InvalidAxiom { module, .. } => axiom_at.get(*module).copied(),
                    GrammarError::InvalidProduction { index, .. } => {
                        production_at.get(*index).copied()
                    }
                    GrammarError::InvalidConstant { name, .. } => p
                        .constant_at
                        .iter()
                        .find(|(n, _)| n == name)
                        .map(|&(_, at)| at),
                    _ => None,
                };
                let at = at.unwrap_or(Location { line: 1, column: 1 });
                ParseError::new(at.line, at.column, e.to_string())
            })
    }
}

/// Parses a word (modules with constant arguments) onto `word`; a module is the longest of
/// `long_names` (longest first) the text continues with, else one character whose id
/// `symbol` gives (`None` when it is not allowed).
pub(crate) fn parse_modules(
    text: &str,
    long_names: &[(Vec<char>, SymbolId)],
    symbol: &mut dyn FnMut(char) -> Option<SymbolId>,
    word: &mut Word,
) -> Result<(), ParseError> {
    let chars: Vec<char> = text.chars().collect();
    let names = Names {
        constants: &HashMap::new(),
        vars: no_vars(),
        degrees: false,
        globals: &[],
        functions: 0,
        curves: 0,
        arrays: &[],
    };
    let mut params = Vec::new();
    for (n, line) in chars.split(|&c| c == '\n').enumerate() {
        let mut cur = Cursor::new(line, n + 1);
        while !cur.at_end() {
            let pos = cur.pos();
            let id = if let Some((id, n)) = long_name_at(&cur, long_names) {
                cur.set_pos(pos + n);
                id
            } else {
                let c = cur.bump().unwrap_or(' ');
                let Some(id) = symbol(c) else {
                    return Err(
                        cur.error_at(pos, format!("'{c}' is not a symbol of this alphabet"))
                    );
                };
                id
            };
            params.clear();
            if cur.eat('(') {
                loop {
                    let at = cur.pos();
                    let value = parse_expr(&mut cur, &names)?.eval_constant(0.0, 0);
                    if !value.is_finite() {
                        return Err(
                            cur.error_at(at, format!("parameter value {value} is not finite"))
                        );
                    }
                    params.push(value);
                    if cur.eat(')') {
                        break;
                    }
                    cur.expect(',', "',' or ')' after a parameter")?;
                }
            }
            word.push(id, &params);
        }
    }
    Ok(())
}

/// Which productions the lines being read add to.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Section {
    Main = 0,
    Decomposition = 1,
    Homomorphism = 2,
}

/// Most steps a derivation length may state.
const MAX_DERIVATION_LENGTH: u32 = 1_000_000;

/// A stated derivation length as a whole number of steps.
pub(crate) fn whole_steps(cur: &Cursor<'_>, at: usize, steps: f64) -> Result<u32, ParseError> {
    if steps.fract() == 0.0 && (0.0..=f64::from(MAX_DERIVATION_LENGTH)).contains(&steps) {
        Ok(steps as u32)
    } else {
        Err(cur.error_at(
            at,
            format!("a derivation length must be a whole number from 0 to {MAX_DERIVATION_LENGTH}, not {steps}"),
        ))
    }
}

/// A rule set's maximum depth when the grammar does not give one (cpfg's default).
const DEFAULT_MAX_DEPTH: u32 = 1;

/// Deepest `maximum depth` accepted: passes beyond this are surely a mistake.
pub const MAX_RULE_DEPTH: u32 = 10_000;

/// The declared names of several characters at the cursor, longest first: the id and length
/// of the first that the text continues with.
pub(crate) fn long_name_at<T: Copy>(
    cur: &Cursor<'_>,
    names: &[(Vec<char>, T)],
) -> Option<(T, usize)> {
    names.iter().find_map(|(name, id)| {
        name.iter()
            .enumerate()
            .all(|(k, &c)| cur.peek_at(k) == Some(c))
            .then_some((*id, name.len()))
    })
}

/// cpfg's modules of several characters (L-Py shares most of them): spheres, circles,
/// generalized cylinders, texture and tropism controls, and the query and communication
/// modules.
pub(crate) const CPFG_LONG_NAMES: &[&str] = &[
    // Width and colour: sylva's notation reserves these characters, cpfg draws with them;
    // '?' opens a sub-L-system.
    "#", ",", "?", "@o", "@O", "@c", "@Gs", "@Gc", "@Ge", "@Gt", "@Gr", "@v", "@!", "@#", "@Ts",
    "@Tp", "@Te", "@Tf", "@Tx", "@R", "@M", "@m", "@H", "@L", "@b", "@Ds", "@De", "@Dd", "@Di",
    "@s", "@D", "@J", "@I", "@P", "@S", "?P", "?H", "?L", "?U", "?E",
];

pub(crate) struct GrammarParser {
    pub(crate) dialect: Dialect,
    /// The sub-L-system whose productions are being read (`None`: the main system).
    pub(crate) subsystem: Option<u32>,
    /// Sub-L-systems' productions, by id, with where each starts.
    pub(crate) sub_productions: Vec<(u32, Production, Location)>,
    /// The block variables: every name the text assigns with '='.
    pub(crate) globals: Vec<String>,
    /// The blocks run around the derivation.
    pub(crate) blocks: Blocks,
    /// The derivation length the grammar states (cpfg's `derivation length:`).
    pub(crate) derivation_length: Option<u32>,
    /// Whether the word is a ring for contexts (cpfg's `ring lsystem`, `#ring`).
    pub(crate) ring: bool,
    /// cpfg's `consider:` symbols, when given.
    pub(crate) consider: Option<Vec<SymbolId>>,
    /// Symbols of several characters (declared with `#module`, or the dialect's own), longest
    /// first, interned when first met: modules are read by the longest such name the text
    /// continues with, else by one character.
    long_names: Vec<(Vec<char>, Option<SymbolId>)>,
    pub(crate) section: Section,
    /// The decomposition's and the homomorphism's depths (their productions are gathered
    /// at the end).
    pub(crate) rule_sets: [RuleSet; 2],
    alphabet: Alphabet,
    constants: Vec<(String, Expr)>,
    /// Each constant's value, computed once when it is defined.
    values: HashMap<String, f64>,
    /// Where each constant was defined, for errors found after parsing.
    constant_at: Vec<(String, Location)>,
    pub(crate) ignore: Vec<SymbolId>,
    /// How many function files `func(id, x)` may read (a model folder's).
    pub(crate) functions: usize,
    /// How many curve files `curveX(id, t)` and the others may read.
    pub(crate) curves: usize,
    /// The axiom and where each of its modules starts.
    axiom: Option<(Vec<ModuleTemplate>, Vec<Location>)>,
    /// The productions, where each starts and its section.
    pub(crate) productions: Vec<(Production, Location, Section)>,
}

impl GrammarParser {
    pub(crate) fn line(&mut self, cur: &mut Cursor<'_>) -> Result<(), ParseError> {
        if cur.at_end() || cur.eat_str("//") {
            return Ok(());
        }
        let start = cur.pos();
        if cur.eat('#') {
            return self.directive(cur);
        }
        if cur.eat_str("axiom") || cur.eat_str("ω") {
            if cur.eat(':') {
                return self.axiom_line(cur, start);
            }
            cur.set_pos(start);
        }
        let at = cur.location();
        let production = self.production(cur)?;
        self.add_production(production, at);
        Ok(())
    }

    /// The symbols of an `ignore:` or `consider:` line, to the end of it.
    pub(crate) fn context_symbols(
        &mut self,
        cur: &mut Cursor<'_>,
        consider: bool,
    ) -> Result<(), ParseError> {
        let mut symbols = Vec::new();
        while !cur.at_end() {
            symbols.push(self.symbol(cur)?);
        }
        if consider {
            self.consider.get_or_insert_with(Vec::new).extend(symbols);
        } else {
            self.ignore.extend(symbols);
        }
        Ok(())
    }

    /// Files a production under the section (and sub-L-system) being read.
    pub(crate) fn add_production(&mut self, production: Production, at: Location) {
        match self.subsystem {
            Some(id) if self.section == Section::Main => {
                self.sub_productions.push((id, production, at));
            }
            _ => self.productions.push((production, at, self.section)),
        }
    }

    /// The module symbol at the cursor, read past: the longest declared name it continues
    /// with, else one character.
    pub(crate) fn symbol(&mut self, cur: &mut Cursor<'_>) -> Result<SymbolId, ParseError> {
        let pos = cur.pos();
        let found = self.long_names.iter().position(|(name, _)| {
            name.iter()
                .enumerate()
                .all(|(k, &c)| cur.peek_at(k) == Some(c))
        });
        if let Some(k) = found {
            let (name, id) = &mut self.long_names[k];
            let n = name.len();
            let id = match id {
                Some(id) => *id,
                None => {
                    let text: String = name.iter().collect();
                    let new = self.alphabet.intern_name(&text).ok_or_else(|| {
                        cur.error_at(pos, "too many distinct symbols (at most 65535)")
                    })?;
                    *id = Some(new);
                    new
                }
            };
            cur.set_pos(pos + n);
            return Ok(id);
        }
        let c = cur.bump().unwrap_or(' ');
        self.intern(cur, c, pos)
    }

    fn intern(&mut self, cur: &Cursor<'_>, c: char, pos: usize) -> Result<SymbolId, ParseError> {
        self.alphabet.intern(c).ok_or_else(|| {
            if Alphabet::is_symbol_char(c) {
                cur.error_at(pos, "too many distinct symbols (at most 65535)")
            } else {
                cur.error_at(pos, format!("'{c}' cannot be a module symbol"))
            }
        })
    }

    pub(crate) fn axiom_line(
        &mut self,
        cur: &mut Cursor<'_>,
        start: usize,
    ) -> Result<(), ParseError> {
        if self.axiom.is_some() {
            return Err(cur.error_at(start, "a second axiom: a grammar has exactly one"));
        }
        let mut starts = Vec::new();
        let items = self.successor(cur, no_vars(), 0, &mut starts)?;
        if !cur.at_end() {
            return Err(cur.error(format!("unexpected {} in the axiom", cur.describe_next())));
        }
        let mut modules = Vec::with_capacity(items.len());
        let mut locations = Vec::with_capacity(items.len());
        for (item, at) in items.into_iter().zip(starts) {
            let SuccessorItem::Module(m) = item else {
                return Err(cur.error_at(at, "the axiom cannot contain a '?' choice"));
            };
            // The axiom is evaluated once, now: a value that is not finite is an error here.
            if let Some(v) = m
                .args
                .iter()
                .map(|a| a.eval_constant(0.0, 0))
                .find(|v| !v.is_finite())
            {
                return Err(cur.error_at(
                    at,
                    format!("the axiom module's parameter value {v} is not finite"),
                ));
            }
            modules.push(m);
            locations.push(cur.location_of(at));
        }
        self.axiom = Some((modules, locations));
        Ok(())
    }
}

impl GrammarParser {
    /// A predecessor's first module and the rest of a string predecessor (cpfg's
    /// `A B --> ...`, read in every dialect). Brackets in a string predecessor are matched
    /// as they stand, as cpfg matches them (`[f P(r)] : r > 9 --> *` removes a whole
    /// branch); a bracket alone is no predecessor.
    fn single(
        &self,
        cur: &Cursor<'_>,
        mut patterns: Vec<Pattern>,
        at: usize,
    ) -> Result<(Pattern, Vec<Pattern>), ParseError> {
        if patterns.is_empty() {
            return Err(cur.error_at(at, "expected a predecessor symbol"));
        }
        if patterns.len() == 1 && (patterns[0].symbol == PUSH || patterns[0].symbol == POP) {
            return Err(cur.error_at(
                at,
                "a predecessor cannot be '[' or ']' alone (use '<' and '>' for contexts)",
            ));
        }
        let first = patterns.remove(0);
        Ok((first, patterns))
    }
}
