//! Bounds on a derivation's memory and time.

/// Bounds that stop a derivation with an error before it exhausts memory or time.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub struct Limits {
    /// Most modules a word may hold. Default 10 million (about 60 MB with offsets).
    pub max_modules: usize,
    /// Most parameters a word may hold in total. Default 40 million (320 MB).
    pub max_params: usize,
    /// Most generations one call may derive. Default 10,000.
    pub max_generations: u32,
    /// Most block statements one derivation may run in all (blocks around conditions and
    /// the derivation together). Default 100 million.
    pub max_statements: u64,
}

impl Limits {
    /// The defaults described on each field.
    pub const DEFAULT: Limits = Limits {
        max_modules: 10_000_000,
        max_params: 40_000_000,
        max_generations: 10_000,
        max_statements: 100_000_000,
    };

    /// Sets [`Limits::max_modules`].
    #[must_use]
    pub fn with_max_modules(mut self, n: usize) -> Self {
        self.max_modules = n;
        self
    }

    /// Sets [`Limits::max_params`].
    #[must_use]
    pub fn with_max_params(mut self, n: usize) -> Self {
        self.max_params = n;
        self
    }

    /// Sets [`Limits::max_statements`].
    #[must_use]
    pub fn with_max_statements(mut self, n: u64) -> Self {
        self.max_statements = n;
        self
    }

    /// Sets [`Limits::max_generations`].
    #[must_use]
    pub fn with_max_generations(mut self, n: u32) -> Self {
        self.max_generations = n;
        self
    }
}

impl Default for Limits {
    fn default() -> Self {
        Self::DEFAULT
    }
}
