//! Changes to the state between steps that a test, a driver or a user's
//! program may make, each booked in the energy account so that the
//! balance still holds: damping the motion ([`Solver::damp`]) and
//! changing a node's velocity ([`Solver::kick`]).
//!
//! # The booking
//!
//! Between step `n` and step `n + 1` the state holds `v_{n+½}` and
//! `x_{n+1} = x_n + Δt v_{n+½}`. An intervention replaces a free
//! component's `v_{n+½}` by `v'` and moves `x_{n+1}` with it, to `x_n +
//! Δt v'`, so that the node's path over `[t_n, t_{n+1}]` is the one its
//! velocity says (as if an impulse had acted at `t_n`). Step `n` recorded
//! `K_n = ½ m v_{n−½} · v_{n+½}` and held over the work of the loads,
//! reactions and contact `½ Δt G_n · v_{n+½}`; step `n + 1` records
//! `K_{n+1} = ½ m |v'|² + ½ Δt F_{n+1} · v'` and closes the interval with
//! `½ Δt G_{n+1} · v'` (`F = f_int + G` the total force). With the
//! internal forces' trapezoid `−ΔU = ½ Δt (f_int,n + f_int,n+1) · v'`
//! (exact for a linear elastic body, as for every step), the account of
//! `[t_n, t_{n+1}]` is then out by exactly
//!
//! ```text
//! R = ½ m (|v'|² − |v_{n+½}|²) + ½ Δt f_int,n · (v_{n+½} − v'),
//! ```
//!
//! known at the intervention (`f_int,n` is the step's internal force,
//! [`crate::forces::Workspace::internal`]). A damping books `−R` as
//! dissipated (`damping`), a kick books `R` as external work; the balance
//! then holds to the account's own accuracy. Both are booked at once:
//! [`Solver::energies`] read before the next step shows the booking
//! without the kinetic change; the next step's record balances. With
//! viscous materials the internal force holds the viscous one, whose work
//! the account books as dissipation by its own trapezoid: there the
//! booking is approximate to the same order as that trapezoid.
//!
//! Prescribed components (fixed, or driven by an active drive) are left
//! as they are: the next step imposes them again.
//!
//! The loads', reactions' and contact's held-over half steps are numbers
//! step `n` computed with the old `v_{n+½}` (the ledger's `Trapezoid::ahead`
//! of gravity, each load and each drive, contact's held-over work): that is why
//! `G_n` drops out of `R`.
//!
//! Before the first step there is nothing to book against: the state
//! holds `x_0` and `v_{−½}`, and an intervention changes `v_{−½}` alone
//! (with `v_{−3/2}` for viscous materials, as [`Solver::set_velocity`]),
//! booking `½ m (|v'|² − |v|²)` into the terms the balance of step 0 then
//! starts from. After [`Solver::restore`], before a step, the internal
//! forces of step `n` are not known (the pipeline is not checkpointed):
//! an intervention is refused until a step has been taken.

use femdem_core::{Real, Vec3};

use crate::SolverError;
use crate::step::Solver;

impl Solver {
    /// Whether component `c` of node `i` moves freely now (not fixed, not
    /// driven by an active drive).
    fn free(&self, i: usize, c: usize) -> bool {
        self.pipeline.external.imposed(i, c).is_none()
    }

    /// Sets the free components of node `i`'s velocity to those of `v`,
    /// moving `x_{n+1}` with them after the first step; returns `R` of the
    /// module documentation.
    fn replace_velocity(&mut self, i: usize, v: Vec3) -> Real {
        let dt = self.scene.params.dt;
        let started = self.evolving.state.step > 0;
        let (m, f) = (self.scene.model.mass[i], self.pipeline.workspace.internal[i]);
        let mut r = 0.0;
        for c in 0..3 {
            if !self.free(i, c) {
                continue;
            }
            let (old, new) = (self.evolving.state.v[i][c], v[c]);
            r += 0.5 * m * (new * new - old * old);
            self.evolving.state.v[i][c] = new;
            if started {
                r += 0.5 * dt * f[c] * (old - new);
                self.evolving.state.x[i][c] += dt * (new - old);
            } else if let Some(before) = self.evolving.v_before.get_mut(i) {
                before[c] = new;
            }
        }
        r
    }

    /// Refuses an intervention after a restore, before a step (the
    /// module documentation says why).
    fn check_forces(&self, what: &str) -> Result<(), SolverError> {
        if self.evolving.state.step > 0 && !self.pipeline.forces_current {
            return Err(SolverError::Intervention(format!(
                "{what}: the internal forces of step {} are not known after a restore; take a step first",
                self.evolving.state.step
            )));
        }
        Ok(())
    }

    /// Scales the free velocity components `v_{n+½}` of every node by
    /// `keep` (in `[0, 1]`) and books the energy removed as dissipated in
    /// [`crate::Energies::damping`] (exactly, by the module documentation:
    /// `½ Σ m |v|² (1 − keep²)` up to a term of the step's internal
    /// forces). Returns that energy, J.
    ///
    /// Damping every step by a `keep` just below one drives a dynamic run
    /// to its static state (dynamic relaxation).
    ///
    /// # Errors
    /// [`SolverError::Intervention`] for a `keep` outside `[0, 1]` or not
    /// a number, or after a restore before a step; nothing is changed
    /// then.
    pub fn damp(&mut self, keep: Real) -> Result<Real, SolverError> {
        if !(0.0..=1.0).contains(&keep) {
            return Err(SolverError::Intervention(format!("damp: keep must lie in [0, 1], got {keep}")));
        }
        self.check_forces("damp")?;
        self.edit_on_host();
        let mut removed = 0.0;
        for i in 0..self.evolving.state.v.len() {
            let v = self.evolving.state.v[i] * keep;
            removed -= self.replace_velocity(i, v);
        }
        self.evolving.ledger.energies.damping += removed;
        Ok(removed)
    }

    /// Adds `dv` to the free components of node `node`'s velocity
    /// `v_{n+½}` and books the work that takes, `½ m (|v + dv|² − |v|²)`
    /// up to a term of the step's internal forces (module documentation),
    /// as external work: an impulse from outside the model. Returns that
    /// work, J.
    ///
    /// # Errors
    /// [`SolverError::Intervention`] for a node out of range, a `dv` that
    /// is not finite, or after a restore before a step; nothing is changed
    /// then.
    pub fn kick(&mut self, node: usize, dv: Vec3) -> Result<Real, SolverError> {
        let n = self.evolving.state.v.len();
        if node >= n {
            return Err(SolverError::Intervention(format!("kick: node {node} of {n}")));
        }
        if !dv.iter().all(|c| c.is_finite()) {
            return Err(SolverError::Intervention(format!("kick: the velocity change {dv:?} is not finite")));
        }
        self.check_forces("kick")?;
        self.edit_on_host();
        let v = self.evolving.state.v[node] + dv;
        let work = self.replace_velocity(node, v);
        self.evolving.ledger.kicks += work;
        self.evolving.ledger.close();
        Ok(work)
    }
}
