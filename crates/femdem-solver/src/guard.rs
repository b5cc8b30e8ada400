//! The run guard: checks that a run is still computing something
//! meaningful, for a driver to call every so many steps
//! ([`Solver::check`]).
//!
//! Three checks of the state, one pass over nodes and one over tets
//! (cheap next to a step: no force evaluation), in [`Solver::check`]:
//!
//! 1. every position and velocity is finite;
//! 2. no deformable tet is inverted (`J = V/V₀ ≤ 0`; the neo-Hookean law
//!    has a C¹ continuation below `J = 0.01` that pushes an element back,
//!    but a tet turned inside out means the step or the loading is wrong);
//! 3. the time step is still below an element-wise estimate of the critical
//!    step at the current configuration. The critical step `Δt₀` of the
//!    reference configuration ([`crate::stable_time_step`]) is scaled, per
//!    tet, by how much its shortest altitude `ℓ` has shrunk and how much its
//!    P-wave speed has grown under compression:
//!
//!    ```text
//!    Δt_t = Δt₀ · (ℓ / ℓ₀) · c₀ / c(J),   c(J)² / c₀² = (λ + 2μ − λ ln J) / (λ + 2μ)
//!    ```
//!
//!    (the neo-Hookean tangent P-wave modulus of Eq. 1 at volume ratio `J`,
//!    `(λ + 2μ − λ ln J) / J`, over the current density `ρ / J`). The run
//!    is unsafe once `Δt > min_t Δt_t`: a crushed or flattened element has
//!    stiffened past what the step was chosen for.
//!
//! And one of the energy account, in [`Solver::check_energy`]: the balance
//! `B = kinetic + elastic + dissipated − external work` has moved since
//! step 0 by more than a tolerance times the run's energy scale
//! (`|B_n − B_0| > tol · scale_n`, both defined in `crate::ledger`; the
//! account is centred so that an honest run keeps it near round-off,
//! `crate::step`). It reads the last step that evaluated the energies and
//! costs nothing more.

use femdem_core::tet::{FACES, signed_volume, triangle_area};
use femdem_core::{Real, Vec3};
use rayon::prelude::*;
use thiserror::Error;

use crate::ledger::Imbalance;
use crate::model::Model;
use crate::step::Solver;

/// A tolerance for [`Solver::check_contact_energy`] (the default of
/// `femdem run`'s `[contact] energy_tolerance`): 5% of the run's energy
/// scale. Eq. 17's force has no potential, and over a closed,
/// frictionless impact it gives back or keeps up to 2.9% of the impact's
/// energy (the largest of the closed-cycle sweep, `docs/fidelity.md`
/// §10: a face landing at penalty 10 E); the check is for energy put in
/// beyond that — pairs that start overlapped at full force gave back
/// 7–10% of the scale of the README and multi-layer runs (§11).
pub const CONTACT_ENERGY_TOLERANCE: Real = 0.05;

/// Why a run must stop.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum Trouble {
    /// A position or velocity is NaN or infinite.
    #[error("step {step}, t = {time:e} s: node {node} (initially at {x0:?} m) has a non-finite position or velocity")]
    NonFinite {
        /// Step number.
        step: u64,
        /// Time, s.
        time: Real,
        /// The first such node.
        node: usize,
        /// Its reference position, m.
        x0: [Real; 3],
    },
    /// A deformable tet turned inside out.
    #[error("step {step}, t = {time:e} s: tet {tet} at {centroid:?} m is inverted (J = {j:.3e})")]
    Inverted {
        /// Step number.
        step: u64,
        /// Time, s.
        time: Real,
        /// The first such tet.
        tet: usize,
        /// Its current centroid, m.
        centroid: [Real; 3],
        /// Its volume ratio.
        j: Real,
    },
    /// The step exceeds the element-wise estimate of the critical step.
    #[error(
        "step {step}, t = {time:e} s: the time step {dt:e} s exceeds the critical step {estimate:e} s estimated for \
         tet {tet} at {centroid:?} m, which has been compressed to J = {j:.3} with its shortest altitude at {shrink:.3} \
         of its initial value; lower [solver] safety or time_step, or the loading rate"
    )]
    StepTooLarge {
        /// Step number.
        step: u64,
        /// Time, s.
        time: Real,
        /// The time step, s.
        dt: Real,
        /// The estimate, s.
        estimate: Real,
        /// The tet that sets it.
        tet: usize,
        /// Its current centroid, m.
        centroid: [Real; 3],
        /// Its volume ratio.
        j: Real,
        /// Its shortest altitude over the initial one.
        shrink: Real,
    },
    /// The energy account no longer balances.
    #[error(
        "step {step}, t = {time:e} s: the energy balance (kinetic + elastic + dissipated − external work) has moved by \
         {error:.4e} J since step 0, {:.3e} of the run's energy scale {scale:.4e} J, above the tolerance {tolerance:e}: \
         energy was {} that no force accounts for; the integration has lost accuracy (a smaller time step, [solver] \
         safety or time_step, is more accurate) or the state was changed outside the step",
        error.abs() / scale,
        if *error > 0.0 { "gained" } else { "lost" }
    )]
    EnergyBalance {
        /// Step number of the evaluation.
        step: u64,
        /// Its time, s.
        time: Real,
        /// `B_n − B_0`, J.
        error: Real,
        /// The run's energy scale, J.
        scale: Real,
        /// The tolerance, a fraction of the scale.
        tolerance: Real,
    },
    /// The normal contact forces have given back more energy than they
    /// absorbed.
    #[error(
        "step {step}, t = {time:e} s: the normal contact forces have given back {:.4e} J more than they absorbed \
         and the failed joints held, {:.3e} of the run's energy scale {scale:.4e} J, above the tolerance \
         {tolerance:e}: contact has put energy into the run that no load supplied (pairs that started overlapped \
         gave back {released:.4e} J, of which the failed joints' compression held {handed:.4e} J: see [contact] \
         activation)",
        -work,
        -work / scale
    )]
    ContactEnergy {
        /// Step number of the evaluation.
        step: u64,
        /// Its time, s.
        time: Real,
        /// The work the normal contact forces have absorbed, J (negative).
        work: Real,
        /// What the pairs that started overlapped have given back, J.
        released: Real,
        /// The part of it the failed joints' compression held, J
        /// ([`crate::ContactEnergy::handed`]; counted in `work`).
        handed: Real,
        /// The run's energy scale, J.
        scale: Real,
        /// The tolerance, a fraction of the scale.
        tolerance: Real,
    },
}

/// Shortest altitude of a tet: `3V / A_max`.
fn altitude(p: &[Vec3; 4], volume: Real) -> Real {
    let a = FACES.iter().map(|f| triangle_area(&p[f[0]], &p[f[1]], &p[f[2]])).fold(0.0, Real::max);
    3.0 * volume / a
}

/// Per-tet factor `(ℓ/ℓ₀) · c₀/c(J)` by which tet `t`'s share of the
/// critical step has changed, with its `J` and `ℓ/ℓ₀`.
fn step_factor(model: &Model, x: &[Vec3], t: usize, material: usize) -> (Real, Real, Real) {
    let tet = model.tets[t];
    let p = tet.map(|n| x[n as usize]);
    let p0 = tet.map(|n| model.x0[n as usize]);
    let (v, v0) = (signed_volume(&p), model.tet_ref[t].volume);
    let j = v / v0;
    if j <= 0.0 {
        return (0.0, j, 0.0);
    }
    let shrink = altitude(&p, v) / altitude(&p0, v0);
    let m = &model.materials[material].1;
    let (l, mu) = (m.lambda(), m.mu());
    let stiffening = ((l + 2.0 * mu - l * j.ln()) / (l + 2.0 * mu)).max(1.0).sqrt();
    (shrink / stiffening, j, shrink)
}

impl Solver {
    /// Checks the state (see the module documentation of `guard`) against a
    /// reference critical step `critical` (s, from
    /// [`crate::stable_time_step`]).
    ///
    /// # Errors
    /// The first [`Trouble`] found, naming the node or tet and where it is.
    pub fn check(&self, critical: Real) -> Result<(), Trouble> {
        let (step, time) = (self.evolving.state.step, self.evolving.state.time);
        let s = &self.evolving.state;
        if let Some(node) = (0..s.x.len())
            .into_par_iter()
            .find_first(|&i| !(s.x[i].iter().all(|c| c.is_finite()) && s.v[i].iter().all(|c| c.is_finite())))
        {
            let x0 = self.scene.model.x0[node];
            return Err(Trouble::NonFinite { step, time, node, x0: [x0.x, x0.y, x0.z] });
        }
        let model = &self.scene.model;
        let worst = (0..model.tets.len())
            .into_par_iter()
            .filter_map(|t| model.tet_material[t].index().map(|i| (t, i)))
            .map(|(t, i)| {
                let (factor, j, shrink) = step_factor(model, &s.x, t, i);
                (factor, t, j, shrink)
            })
            .min_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
        let Some((factor, tet, j, shrink)) = worst else {
            return Ok(());
        };
        let centroid = model.tets[tet].iter().map(|&n| s.x[n as usize]).sum::<Vec3>() / 4.0;
        let centroid = [centroid.x, centroid.y, centroid.z];
        if j <= 0.0 {
            return Err(Trouble::Inverted { step, time, tet, centroid, j });
        }
        let estimate = critical * factor;
        if self.dt() > estimate {
            return Err(Trouble::StepTooLarge { step, time, dt: self.dt(), estimate, tet, centroid, j, shrink });
        }
        Ok(())
    }

    /// Checks the energy account: the last evaluation ([`Solver::imbalance`])
    /// must have `|B_n − B_0| ≤ tolerance · scale_n`. Nothing is checked
    /// before the first step. The caller sees that the step it checks
    /// evaluated the energies ([`crate::Want::energy`]): the check reads
    /// the last one that did.
    ///
    /// # Errors
    /// [`Trouble::EnergyBalance`] with the step and time of that
    /// evaluation, the error and the scale.
    pub fn check_energy(&self, tolerance: Real) -> Result<(), Trouble> {
        match self.imbalance() {
            // NaN (non-finite energies) trips too.
            Some(i @ Imbalance { step, time, error, scale }) if i.relative() > tolerance || i.relative().is_nan() => {
                Err(Trouble::EnergyBalance { step, time, error, scale, tolerance })
            }
            _ => Ok(()),
        }
    }

    /// Checks contact's own account: the work the normal contact forces
    /// have absorbed, with what the failed joints' compression held counted
    /// as absorbed ([`Solver::contact_normal_work`]), must not fall below
    /// `−tolerance · scale_n`, the scale of [`Solver::check_energy`] at the
    /// last evaluation. The energy balance cannot see energy that contact
    /// puts in (the contact term is the work of its forces, so the account
    /// closes whatever they do); this sees it once it exceeds the
    /// tolerance. A potential force absorbs what it gives back over a closed
    /// cycle, so an honest run keeps the work at or above zero less the
    /// closed-cycle residual of Eq. 17 (`docs/fidelity.md`). Nothing is
    /// checked without contact or before the first step.
    ///
    /// # Errors
    /// [`Trouble::ContactEnergy`] with the step and time of that
    /// evaluation, the work, what the pairs that started overlapped gave
    /// back and how much of it the joints held, and the scale.
    pub fn check_contact_energy(&self, tolerance: Real) -> Result<(), Trouble> {
        let (Some(energy), Some(work), Some(Imbalance { step, time, scale, .. })) =
            (self.contact_energy(), self.contact_normal_work(), self.imbalance())
        else {
            return Ok(());
        };
        if work < -tolerance * scale || work.is_nan() {
            let (released, handed) = (energy.released, energy.handed());
            return Err(Trouble::ContactEnergy { step, time, work, released, handed, scale, tolerance });
        }
        Ok(())
    }
}
