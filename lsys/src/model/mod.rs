//! The grammar model: plain data types that the syntax builds and the engine runs.
//! Nothing here parses, prints or derives.

pub(crate) mod alphabet;
pub(crate) mod dialect;
pub(crate) mod expr;
pub(crate) mod grammar;
pub(crate) mod statement;
pub(crate) mod word;
