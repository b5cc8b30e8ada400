//! The energy account's bookkeeping beyond [`Energies`]: the half step of
//! external work held over from one step to the next, and the watch that
//! measures how far the balance has moved since the start
//! ([`Solver::imbalance`], checked by [`Solver::check_energy`]).
//!
//! # The error and its scale
//!
//! At every step that evaluates the energies the watch takes
//!
//! ```text
//! error_n = B_n − B_0,        B = kinetic + elastic + dissipated − external work  (Energies::balance)
//! scale_n = max(|W_n|, |B_0|, max_{k ≤ n} (K_k + U_k + |C_k|), E_floor)
//! ```
//!
//! with `B_0` the balance of step 0 (the energy the run started with:
//! kinetic energy of an initial velocity field, or the stored energy of a
//! static start less the work booked for it), `W` the external work, `K`
//! the kinetic energy, `U` the elastic energy of tets and joints, `C` the
//! contact term, and the floor `E_floor = Σ_tets ½ (λ + 2μ) ε₀² V₀` with
//! `ε₀ = 10⁻⁶`: the energy of a uniform strain of one microstrain over
//! every deformable tet. The floor keeps the ratio meaningful while
//! nothing has happened yet: at rest the elastic energy is round-off
//! (about 10⁻¹² J on the 2,136 tets of the bundled Brazilian disc,
//! changing by 10⁻¹³ J as the mesh starts to move), which would be a
//! sizeable fraction of a scale made of round-off; the floor is 10⁵ times
//! that round-off (2.7·10⁻⁷ J there) and 2·10⁻⁶ of the work that run does
//! (0.145 J).

use femdem_core::Real;

use crate::model::Model;
use crate::state::Energies;
use crate::step::Solver;

/// The strain whose energy over the whole body is the scale's floor.
pub const FLOOR_STRAIN: Real = 1e-6;

/// A tolerance for [`Solver::check_energy`] (the default of `femdem run`'s
/// `[solver] energy_tolerance`): 1% of the run's energy scale. Measured
/// (`docs/reliability.md`): every bundled case, evaluated at every step,
/// stays within 1.2·10⁻⁴ of its scale, the solver's extreme cases within
/// 3.2·10⁻⁴, a bar pulled apart at 2000 m/s within 1.5·10⁻³; energy that no
/// force accounts for beyond 1% of what a run holds or was given is a
/// result no one should use.
pub const ENERGY_TOLERANCE: Real = 0.01;

/// How far the energy account has moved from its start, at the last step
/// that evaluated the energies (see the module documentation of
/// `account.rs` for the formulas).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Imbalance {
    /// Step number `n`.
    pub step: u64,
    /// Time `t_n`, s.
    pub time: Real,
    /// `B_n − B_0`, J: positive when the run holds more energy than the
    /// work done on it accounts for.
    pub error: Real,
    /// The run's energy scale at `t_n`, J.
    pub scale: Real,
}

impl Imbalance {
    /// `|error| / scale` (0 for a run with nothing in it: no deformable
    /// tet, no energy, no error).
    pub fn relative(&self) -> Real {
        if self.scale == 0.0 && self.error == 0.0 { 0.0 } else { self.error.abs() / self.scale }
    }
}

/// The bookkeeping (part of a solver's snapshot).
#[derive(Clone, Debug, Default, PartialEq)]
pub(crate) struct Account {
    /// Work of the external forces and the drives' reactions of the last
    /// step over the half step after its `t_n`, `½ Δt Σ f_n · v_{n+½}`, J:
    /// booked with the next step.
    pub ahead: Real,
    /// The same for each surface load alone (in [`crate::Loads::surfaces`]
    /// order), J: booked into [`crate::StepRecord::surface_work`] with the
    /// next step.
    pub surface_ahead: Vec<Real>,
    /// The same for each drive's reaction (in [`crate::Loads::drives`]
    /// order), J: booked into [`crate::StepRecord::drive_work`].
    pub drive_ahead: Vec<Real>,
    /// `B_0`, once step 0 has been evaluated.
    pub initial: Option<Real>,
    /// The largest `K + U + |C|` evaluated so far, J.
    pub peak_held: Real,
    /// The last evaluation.
    pub last: Option<Imbalance>,
}

impl Account {
    /// Takes the energies of step `n` (all terms current) into the watch.
    pub fn observe(&mut self, step: u64, time: Real, e: &Energies, floor: Real) {
        let balance = e.balance();
        let initial = *self.initial.get_or_insert(balance);
        let held = e.kinetic + e.tet_elastic + e.joint_elastic + e.contact.abs();
        self.peak_held = self.peak_held.max(held);
        let scale = e.external_work.abs().max(initial.abs()).max(self.peak_held).max(floor);
        self.last = Some(Imbalance { step, time, error: balance - initial, scale });
    }
}

/// `E_floor = Σ ½ (λ + 2μ) ε₀² V₀` over the deformable tets of `model`, J.
pub(crate) fn energy_floor(model: &Model) -> Real {
    model
        .tet_material
        .iter()
        .zip(&model.tet_ref)
        .filter_map(|(m, r)| m.index().map(|i| (i, r)))
        .map(|(i, r)| 0.5 * model.materials[i].1.p_wave_modulus() * FLOOR_STRAIN * FLOOR_STRAIN * r.volume)
        .sum()
}

impl Solver {
    /// How far the energy account has moved since step 0, at the last
    /// step that evaluated the energies ([`crate::Want::energy`]; step 0
    /// always does); `None` before the first step.
    pub fn imbalance(&self) -> Option<Imbalance> {
        self.evolving.account.last
    }
}
