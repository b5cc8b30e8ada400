//! Errors of the static start.

use thiserror::Error;

/// Why a static solve gave no answer. A static start never returns a
/// displacement it has not checked: every failure is one of these.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum StaticError {
    /// What the solver refuses: inconsistent loads and constraints (as
    /// [`femdem_solver::Solver::new`] would report them), or a hand-over
    /// ([`femdem_solver::Solver::start_displaced`]) it cannot take.
    #[error("{0}")]
    Solver(#[from] femdem_solver::SolverError),
    /// Tets that start in contact across pre-existing fracture faces (no
    /// joint ties them): their coupling is not linearised here, so the
    /// bodies they separate would be solved as if apart.
    #[error(
        "{pairs} tet pairs start in contact across pre-existing fracture faces; the static start does not \
         linearise contact: use the dynamic start"
    )]
    InitialContact {
        /// Number of such pairs.
        pairs: usize,
    },
    /// A joint whose parameters give no finite, positive initial stiffness
    /// `p0 / h`.
    #[error("joint {joint}: initial stiffness p0/h = {stiffness} Pa/m is not finite and > 0")]
    JointStiffness {
        /// The joint.
        joint: usize,
        /// `p0 / h`.
        stiffness: f64,
    },
    /// A load that is not finite on the reference geometry.
    #[error("the external force on node {node} is not finite")]
    NonFiniteLoad {
        /// The node.
        node: usize,
    },
    /// The sparse Cholesky factorisation failed: the stiffness (with the
    /// shift on floating bodies) is not numerically positive definite, or
    /// memory ran out.
    #[error("sparse Cholesky factorisation of the {dofs}-unknown stiffness failed: {reason}")]
    Factorisation {
        /// Unknowns.
        dofs: usize,
        /// faer's reason.
        reason: String,
    },
    /// The refined solution still leaves a residual above the tolerance.
    #[error(
        "the static solve did not converge: relative residual ‖K u − f‖/‖f‖ = {residual:e} after {iterations} \
         refinements (tolerance {tolerance:e})"
    )]
    NotConverged {
        /// The last relative residual.
        residual: f64,
        /// The tolerance asked for.
        tolerance: f64,
        /// Refinement steps taken.
        iterations: usize,
    },
    /// The correction to the explicit model's own equilibrium did not
    /// converge: the loaded state is not reached elastically (joints past
    /// their peak soften faster than the initial tangent can follow).
    #[error(
        "the explicit model's equilibrium was not reached: relative out-of-balance force {residual:e} after \
         {iterations} corrections (tolerance {tolerance:e}), {past_peak} joints past their peak"
    )]
    ModelNotConverged {
        /// The last relative out-of-balance force.
        residual: f64,
        /// The tolerance asked for.
        tolerance: f64,
        /// Corrections taken.
        iterations: usize,
        /// Joints with a point past its peak at the last evaluation.
        past_peak: usize,
    },
    /// Options out of range.
    #[error("static solve options: {0}")]
    Options(String),
}
