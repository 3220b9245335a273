//! The seeded random stream used by stochastic productions and random functions.

use rand_core::{Rng, SeedableRng};
use rand_pcg::Pcg64Mcg;

/// A seeded PCG stream with the draws the engine needs. It travels with every evaluation,
/// so it also carries the one other thing an expression can change beyond its value:
/// whether cpfg's `stop(n)` asked the derivation to end after the step under way.
#[derive(Debug, Clone)]
pub(crate) struct Random {
    stream: Pcg64Mcg,
    /// Set by `stop(n)` with `n` other than 1.
    pub(crate) stop: bool,
}

impl Random {
    pub(crate) fn new(seed: u64) -> Self {
        Random {
            stream: Pcg64Mcg::seed_from_u64(seed),
            stop: false,
        }
    }

    /// Uniform in `[0, 1)` with 53 random bits.
    #[inline]
    pub(crate) fn unit(&mut self) -> f64 {
        (self.stream.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
    }

    /// Standard normal by Box–Muller (one draw per call keeps the stream simple to reason about).
    pub(crate) fn normal(&mut self) -> f64 {
        let u1 = 1.0 - self.unit();
        let u2 = self.unit();
        (-2.0 * u1.ln()).sqrt() * (std::f64::consts::TAU * u2).cos()
    }

    /// Gamma(shape, 1) by Marsaglia and Tsang's squeeze method (shapes below 1 boosted by
    /// `U^(1/shape)`). Not positive shapes give NaN.
    pub(crate) fn gamma(&mut self, shape: f64) -> f64 {
        if !(shape > 0.0 && shape.is_finite()) {
            return f64::NAN;
        }
        if shape < 1.0 {
            let u = 1.0 - self.unit();
            return self.gamma(shape + 1.0) * u.powf(1.0 / shape);
        }
        let d = shape - 1.0 / 3.0;
        let c = 1.0 / (9.0 * d).sqrt();
        // Accepts with probability above 0.95 for every shape, so few rounds.
        loop {
            let x = self.normal();
            let v = (1.0 + c * x).powi(3);
            if v <= 0.0 {
                continue;
            }
            let u = 1.0 - self.unit();
            if u.ln() < 0.5 * x * x + d - d * v + d * v.ln() {
                return d * v;
            }
        }
    }

    /// Beta(a, b): a Gamma(a) draw over the sum of it and a Gamma(b) draw (cpfg's `bran`).
    pub(crate) fn beta(&mut self, a: f64, b: f64) -> f64 {
        let x = self.gamma(a);
        let y = self.gamma(b);
        x / (x + y)
    }

    /// The number of successes in `n` trials of probability `p` (cpfg's `biran`); `n` is
    /// capped at a million trials.
    pub(crate) fn binomial(&mut self, n: f64, p: f64) -> f64 {
        if !(n >= 0.0 && (0.0..=1.0).contains(&p)) {
            return f64::NAN;
        }
        let trials = n.min(1e6) as u64;
        (0..trials).filter(|_| self.unit() < p).count() as f64
    }
}
