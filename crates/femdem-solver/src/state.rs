//! What the solver carries from step to step, and what it accounts: the
//! node state, the energy account, and the record of joint failures.

use femdem_core::{Real, Vec3};
use femdem_fracture::{FailureMode, JointHistory};

/// Node positions and half-step velocities.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct State {
    /// Positions `x_n`, m.
    pub x: Vec<Vec3>,
    /// Velocities `v_{n−½}`, m/s.
    pub v: Vec<Vec3>,
    /// Time `t_n`, s.
    pub time: Real,
    /// Step count `n`.
    pub step: u64,
    /// Damage history of every joint.
    pub joints: Vec<JointHistory>,
}

/// The energy account, J, every term at `t_n`, the time of the record
/// (the centring and its formulas: `crate::step`, "The energy account and
/// its time-centring").
///
/// The cumulative terms (`damping`, `external_work`, `contact`,
/// `friction`) are booked at every step, by intervals `[t_{n−1}, t_n]`;
/// the state terms (`kinetic`, `tet_elastic`, `joint_elastic`,
/// `fracture`) are evaluated only at steps that ask for them
/// ([`crate::Want::energy`]) and keep their last value otherwise.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Energies {
    /// Kinetic energy, the leapfrog's `½ Σ m v_{n−½} · v_{n+½}` (the
    /// mid-step `½ Σ m |v_n|²` less `⅛ Σ m |v_{n+½} − v_{n−½}|²`).
    pub kinetic: Real,
    /// Elastic energy stored in the tets at `x_n`.
    pub tet_elastic: Real,
    /// Elastic energy stored in the joints at `x_n`.
    pub joint_elastic: Real,
    /// Energy dissipated by viscous damping up to `t_n`:
    /// `Σ_k Δt ∫ η D(v_{k−½}) : D(v̄_k) dv` (`crate::forces::Dissipation`).
    pub damping: Real,
    /// Work of loads, gravity and prescribed motions up to `t_n`: per
    /// interval the trapezoid `½ (f_{k−1} + f_k) · (x_k − x_{k−1})`.
    pub external_work: Real,
    /// Energy dissipated by joint softening and failure up to `t_n`: the
    /// work done on the joints less what the intact ones store.
    pub fracture: Real,
    /// Work absorbed by the normal contact forces up to `t_n` (the
    /// penalty potential's energy plus whatever the Eq. 18 ramp does not
    /// give back), plus the elastic energy of the friction springs now;
    /// per interval the trapezoid, as `external_work`.
    pub contact: Real,
    /// Energy dissipated by Coulomb friction up to `t_n`: the work
    /// absorbed by friction forces less the energy the sticking springs
    /// still hold.
    pub friction: Real,
}

impl Energies {
    /// `kinetic + elastic + dissipated − external work`: constant in an
    /// exact solution (equal to the initial kinetic + elastic energy), and
    /// for a linear elastic body in femdem's discrete one too, to
    /// round-off; how far it has moved is watched by
    /// [`crate::Solver::imbalance`].
    pub fn balance(&self) -> Real {
        self.kinetic
            + self.tet_elastic
            + self.joint_elastic
            + self.damping
            + self.fracture
            + self.contact
            + self.friction
            - self.external_work
    }
}

/// A joint failure.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Failure {
    /// Joint index.
    pub joint: u32,
    /// Time of failure, s (the start of the step that broke it).
    pub time: Real,
    /// Centroid of the joint's mid-plane at failure, m.
    pub centroid: Vec3,
    /// Mid-plane area at failure, m².
    pub area: Real,
    /// How it failed.
    pub mode: FailureMode,
}
