//! Errors of the solver crate.

use thiserror::Error;

/// Something the solver cannot work with.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum SolverError {
    /// An inconsistent model, load set or setting.
    #[error("{0}")]
    Setup(String),
    /// A requested time step above the stable limit.
    #[error(
        "time step {requested:e} s exceeds the stable limit {limit:e} s (estimate; use at most {suggested:e} s with safety)"
    )]
    UnstableStep {
        /// The step asked for.
        requested: f64,
        /// The critical step estimated.
        limit: f64,
        /// The safety-reduced step.
        suggested: f64,
    },
}
