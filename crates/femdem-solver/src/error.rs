//! Errors of the solver crate.

use thiserror::Error;

/// Something the solver cannot work with.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum SolverError {
    /// The bulk cannot run on the device asked for (no adapter, no 64-bit
    /// floats, a model too large, contact).
    #[error("device: {0}")]
    Device(String),
    /// A time step that is not finite and positive.
    #[error("time step must be finite and > 0 s, got {0}")]
    TimeStep(f64),
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
    /// A mass-scaling factor below 1 or not finite.
    #[error("mass_scaling must be ≥ 1, got {0}")]
    MassScaling(f64),
    /// The region behaviours do not match the mesh's regions.
    #[error("{regions} regions but {behaviours} region behaviours")]
    RegionCount {
        /// Regions of the mesh.
        regions: usize,
        /// Behaviours given.
        behaviours: usize,
    },
    /// A breakable region without joint parameters.
    #[error("region `{0}` is breakable but has no joint parameters")]
    MissingJointParams(String),
    /// A tet of zero or negative volume in the reference configuration.
    #[error("tet {0} has non-positive volume")]
    InvertedTet(usize),
    /// A joint between two regions neither of which is breakable.
    #[error("joint {0} touches no breakable region")]
    UnbreakableJoint(usize),
    /// A bad strength-heterogeneity parameter.
    #[error("heterogeneity: {0}")]
    Heterogeneity(#[from] femdem_fracture::heterogeneity::DistributionError),
    /// A velocity component claimed by two constraints.
    #[error(
        "node {node} (at ({:e}, {:e}, {:e}) m) has its {component} velocity prescribed twice: by {first} and by {by}; \
         a component can have one constraint only (narrow one of their node selections)",
        at[0], at[1], at[2]
    )]
    PrescribedTwice {
        /// The node.
        node: u32,
        /// Its reference position, m.
        at: [f64; 3],
        /// `x`, `y` or `z`.
        component: &'static str,
        /// The constraint that claimed it first.
        first: String,
        /// The second constraint.
        by: String,
    },
    /// A constraint naming a node the model does not have.
    #[error("{by} names node {node}, but the model has {nodes} nodes")]
    NodeOutOfRange {
        /// The node.
        node: u32,
        /// Nodes of the model.
        nodes: usize,
        /// The constraint.
        by: String,
    },
    /// A node of a rigid region not driven in all three components.
    #[error("node {node} of a rigid region is not driven in all three components: give its platen a velocity")]
    RigidNodeNotDriven {
        /// The node.
        node: u32,
    },
    /// A node without mass with a free component.
    #[error("node {node} has no mass and is not prescribed")]
    MasslessFreeNode {
        /// The node.
        node: u32,
    },
    /// A displaced start ([`crate::Solver::start_displaced`]) that cannot
    /// be taken.
    #[error("initial displacement: {0}")]
    InitialDisplacement(String),
    /// A snapshot that cannot be restored into this solver (see
    /// [`crate::Solver::restore`]).
    #[error("snapshot: {0}")]
    Snapshot(String),
    /// A change to the state between steps that cannot be made
    /// ([`crate::Solver::damp`], [`crate::Solver::kick`]).
    #[error("{0}")]
    Intervention(String),
}
