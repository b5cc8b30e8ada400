//! The ledger: every work and energy term of the run, with the half step
//! of work each holds over from one step to the next, and the watch that
//! measures how far the balance has moved since the start
//! ([`Solver::imbalance`], checked by [`Solver::check_energy`]).
//!
//! # One sum, by construction
//!
//! Each work term that is booked by intervals is a [`Trapezoid`]: step `n`
//! books `½ Δt f_n · v_{n−½}` with the half step step `n − 1` held over,
//! and holds over `½ Δt f_n · v_{n+½}` (the centring: `crate::step`).
//! The external work is not booked on its own; it is their sum,
//!
//! ```text
//! W = W_start + W_gravity + Σ_k W_load,k + Σ_d W_drive,d + W_kicks
//! ```
//!
//! (`Ledger::close`), so the per-load and per-drive columns of a run add
//! up to its external work exactly, and a new term is one field here.
//! `W_start` is the work booked for a static start
//! ([`Solver::start_displaced`]) beyond the loads' Clapeyron shares, with
//! which each `W_load,k` starts; `W_kicks` the work of
//! [`Solver::kick`]. The contact terms and their held-over halves are
//! [`ContactEnergy`].
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

use serde::{Deserialize, Serialize};

use crate::contact::ContactEnergy;
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
/// `ledger.rs` for the formulas).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
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

/// One work term booked by intervals with the trapezoidal rule
/// (`crate::step`, "The energy account and its time-centring").
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub(crate) struct Trapezoid {
    /// The work from the start to `t_n`, J.
    pub total: Real,
    /// The half step after `t_n`, `½ Δt f_n · v_{n+½}`, J: booked with the
    /// next step.
    pub ahead: Real,
}

impl Trapezoid {
    /// Books step `n`: `back = ½ Δt f_n · v_{n−½}` closes the interval
    /// before `t_n` with the half held over, `ahead = ½ Δt f_n · v_{n+½}`
    /// is held over.
    pub fn book(&mut self, back: Real, ahead: Real) {
        self.total += self.ahead + back;
        self.ahead = ahead;
    }
}

/// The watch on the balance (`Solver::imbalance`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub(crate) struct Watch {
    /// `B_0`, once step 0 has been evaluated.
    pub initial: Option<Real>,
    /// The largest `K + U + |C|` evaluated so far, J.
    pub peak_held: Real,
    /// The last evaluation.
    pub last: Option<Imbalance>,
}

/// Every work and energy term of a run (module documentation): part of the
/// evolving state, and of a checkpoint.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub(crate) struct Ledger {
    /// The terms of `t_n` as reported: the state terms of the last step
    /// that evaluated them, the running ones, and the external work, which
    /// [`Ledger::close`] sums from the terms below.
    pub energies: Energies,
    /// Work booked for a static start beyond the surface loads' Clapeyron
    /// shares (`Solver::start_displaced`), J.
    pub start: Real,
    /// Gravity's work.
    pub gravity: Trapezoid,
    /// Each surface load's work (in `Loads::surfaces` order), from its
    /// Clapeyron share after a static start.
    pub surfaces: Vec<Trapezoid>,
    /// Each drive's reaction work (in `Loads::drives` order).
    pub drives: Vec<Trapezoid>,
    /// The work of `Solver::kick`, J.
    pub kicks: Real,
    /// Contact's terms, with their held-over halves (zero without contact).
    pub contact: ContactEnergy,
    /// The watch on the balance.
    pub watch: Watch,
}

impl Ledger {
    /// A ledger at the start of a run with `surfaces` surface loads and
    /// `drives` drives.
    pub fn new(surfaces: usize, drives: usize) -> Ledger {
        Ledger {
            surfaces: vec![Trapezoid::default(); surfaces],
            drives: vec![Trapezoid::default(); drives],
            ..Ledger::default()
        }
    }

    /// Sets the external work to the sum of its terms, in a fixed order:
    /// `W_start + W_gravity + Σ_k W_load,k + Σ_d W_drive,d + W_kicks`.
    pub fn close(&mut self) {
        let loads: Real = self.surfaces.iter().map(|t| t.total).sum();
        let drives: Real = self.drives.iter().map(|t| t.total).sum();
        self.energies.external_work = self.start + self.gravity.total + loads + drives + self.kicks;
    }

    /// Takes the energies of step `n` (all terms current) into the watch.
    pub fn observe(&mut self, step: u64, time: Real, floor: Real) {
        let (e, w) = (&self.energies, &mut self.watch);
        let balance = e.balance();
        let initial = *w.initial.get_or_insert(balance);
        let held = e.kinetic + e.tet_elastic + e.joint_elastic + e.contact.abs();
        w.peak_held = w.peak_held.max(held);
        let scale = e.external_work.abs().max(initial.abs()).max(w.peak_held).max(floor);
        w.last = Some(Imbalance { step, time, error: balance - initial, scale });
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
        self.evolving.ledger.watch.last
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_trapezoid_books_the_half_it_held_over() {
        let mut t = Trapezoid::default();
        t.book(1.0, 2.0);
        assert_eq!(t, Trapezoid { total: 1.0, ahead: 2.0 });
        t.book(3.0, 5.0);
        assert_eq!(t, Trapezoid { total: 6.0, ahead: 5.0 });
    }

    #[test]
    fn the_external_work_is_the_sum_of_its_terms() {
        let mut l = Ledger::new(2, 1);
        l.start = 0.5;
        l.gravity.total = 1.0;
        l.surfaces[0].total = 2.0;
        l.surfaces[1].total = 4.0;
        l.drives[0].total = 8.0;
        l.kicks = 16.0;
        l.close();
        assert_eq!(l.energies.external_work, 31.5);
    }
}
