//! Grammar text: the parser of grammars, expressions and words, and the printer back to text.

pub(crate) mod comments;
pub(crate) mod cpfg;
pub(crate) mod cursor;
pub(crate) mod expr_parser;
pub(crate) mod lpy;
pub(crate) mod model_folder;
pub(crate) mod parser;
pub(crate) mod preprocessor;
pub(crate) mod print;
pub(crate) mod read;
pub(crate) mod statement_parser;
pub(crate) mod word_text;
