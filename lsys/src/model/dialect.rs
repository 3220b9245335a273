//! Which notation a grammar is written in.

/// The notations grammar text may be written in.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum Dialect {
    /// sylva's notation (ABOP's, one production per line): [`LSystem::parse`](crate::LSystem::parse)'s default.
    Sylva,
    /// cpfg's `.l` files (the virtual laboratory): `Lsystem:` ... `endlsystem`, `-->`,
    /// `derivation length:`, `consider:`, trigonometry in degrees, `*` for the empty word.
    Cpfg,
    /// The declarative subset of L-Py's `.lpy` files (OpenAlea): `module` declarations,
    /// constants, `Axiom:`, `production:`/`interpretation:`/`decomposition:` sections with
    /// `-->` productions; Python code is refused.
    LPy,
}

impl Dialect {
    /// The dialect a file's extension names: `.l` is cpfg, `.lpy` L-Py; anything else
    /// sylva's notation.
    pub fn of_path(path: &std::path::Path) -> Dialect {
        match path.extension().and_then(|e| e.to_str()) {
            Some("l") => Dialect::Cpfg,
            Some("lpy") => Dialect::LPy,
            _ => Dialect::Sylva,
        }
    }
}
