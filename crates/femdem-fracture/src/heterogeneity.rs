//! Random joint strengths (the heterogeneity the paper names as missing for
//! loadings with homogeneous stress fields, §4).
//!
//! Each joint's `f_t` (and, independently, `c`) is its mean value times a
//! factor drawn from a distribution of mean 1:
//!
//! * Weibull with modulus `m`: scale `1 / Γ(1 + 1/m)`, so the mean is 1 and
//!   the coefficient of variation `√(Γ(1+2/m)/Γ(1+1/m)² − 1)`;
//! * normal with mean 1 and standard deviation `cov`, redrawn below 0.01
//!   (truncation: keep `cov ≤ 0.3` for the mean to stay 1 to 1e-3).
//!
//! Draws come from a ChaCha8 stream seeded by the user's seed, so the same
//! seed gives the same strengths on any machine and thread count.

use femdem_core::Real;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution as _, Normal, Weibull};

/// The distribution of the strength factors.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Distribution {
    /// Weibull of modulus `m` (shape), mean 1.
    Weibull {
        /// Weibull modulus, > 0 (larger is more uniform; rocks: 3–10).
        modulus: Real,
    },
    /// Normal of mean 1.
    Normal {
        /// Coefficient of variation (standard deviation), ≥ 0.
        cov: Real,
    },
}

impl Distribution {
    /// The theoretical mean and standard deviation of the factors
    /// (untruncated for the normal).
    pub fn mean_and_std(&self) -> (Real, Real) {
        match *self {
            Distribution::Weibull { modulus } => {
                let g1 = libm::tgamma(1.0 + 1.0 / modulus);
                let g2 = libm::tgamma(1.0 + 2.0 / modulus);
                (1.0, (g2 / (g1 * g1) - 1.0).sqrt())
            }
            Distribution::Normal { cov } => (1.0, cov),
        }
    }
}

/// `n` strength factors of mean 1 drawn from `dist` with `seed`.
///
/// # Errors
/// A message when the distribution's parameter is out of range.
pub fn strength_factors(n: usize, dist: Distribution, seed: u64) -> Result<Vec<Real>, String> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    match dist {
        Distribution::Weibull { modulus } => {
            if !(modulus.is_finite() && modulus > 0.0) {
                return Err(format!("Weibull modulus must be > 0, got {modulus}"));
            }
            let scale = 1.0 / libm::tgamma(1.0 + 1.0 / modulus);
            let w = Weibull::new(scale, modulus).map_err(|e| e.to_string())?;
            Ok((0..n).map(|_| w.sample(&mut rng)).collect())
        }
        Distribution::Normal { cov } => {
            if !(cov.is_finite() && cov >= 0.0) {
                return Err(format!("coefficient of variation must be ≥ 0, got {cov}"));
            }
            let d = Normal::new(1.0, cov).map_err(|e| e.to_string())?;
            Ok((0..n)
                .map(|_| {
                    loop {
                        let v: Real = d.sample(&mut rng);
                        if v > 0.01 {
                            break v;
                        }
                    }
                })
                .collect())
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn stats(v: &[Real]) -> (Real, Real) {
        let n = v.len() as Real;
        let mean = v.iter().sum::<Real>() / n;
        let var = v.iter().map(|x| (x - mean).powi(2)).sum::<Real>() / (n - 1.0);
        (mean, var.sqrt())
    }

    #[test]
    fn same_seed_same_strengths() {
        let d = Distribution::Weibull { modulus: 6.0 };
        assert_eq!(strength_factors(1000, d, 7).unwrap(), strength_factors(1000, d, 7).unwrap());
        assert_ne!(strength_factors(1000, d, 7).unwrap(), strength_factors(1000, d, 8).unwrap());
    }

    /// With n = 200,000 samples the standard error of the mean is σ/√n
    /// (≤ 0.0006 here) and of the standard deviation about σ/√(2n); the
    /// bounds are five standard errors.
    #[test]
    fn sample_mean_and_spread_match_the_distribution() {
        let n = 200_000;
        for d in [
            Distribution::Weibull { modulus: 4.0 },
            Distribution::Weibull { modulus: 10.0 },
            Distribution::Normal { cov: 0.2 },
        ] {
            let v = strength_factors(n, d, 42).unwrap();
            let (mean, std) = stats(&v);
            let (m0, s0) = d.mean_and_std();
            let se_mean = s0 / (n as Real).sqrt();
            let se_std = s0 / (2.0 * n as Real).sqrt() * 2.0; // kurtosis margin
            assert!((mean - m0).abs() < 5.0 * se_mean, "{d:?}: mean {mean}");
            assert!((std - s0).abs() < 5.0 * se_std, "{d:?}: std {std} vs {s0}");
        }
    }

    #[test]
    fn bad_parameters_are_refused() {
        assert!(strength_factors(1, Distribution::Weibull { modulus: 0.0 }, 0).is_err());
        assert!(strength_factors(1, Distribution::Normal { cov: -1.0 }, 0).is_err());
    }
}
