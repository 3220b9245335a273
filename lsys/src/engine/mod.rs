//! The rewriting engine: a grammar checked and compiled ([`LSystem`](crate::LSystem)),
//! expression programs, the seeded random stream and derivation.

pub(crate) mod block;
pub(crate) mod compile;
pub(crate) mod derive;
pub(crate) mod environment;
pub(crate) mod eval;
pub(crate) mod lsystem;
pub(crate) mod random;
