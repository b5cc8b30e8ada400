//! Starting from a displaced state at rest: the hand-over from a static
//! solve (`femdem-static`) to the explicit run.

use femdem_core::Vec3;
use femdem_fracture::{JointHistory, joint_update};

use super::Solver;
use super::prescribed::held_from_start;
use crate::SolverError;
use crate::forces::{Dissipation, Want, Workspace, internal_forces};
use crate::ledger::Trapezoid;
use crate::loads::surface_forces;

impl Solver {
    /// Moves the nodes to `x0 + u` at rest (`v = 0`), before the first
    /// step: the state a static solve found in equilibrium with the loads
    /// of `t = 0`. Returns the elastic energy of that state, J.
    ///
    /// The energy account starts from it, as if a slow ramp had led there:
    /// each joint is evaluated at `x0 + u` from an undamaged history and
    /// keeps that evaluation (its last opening and stresses, any damage)
    /// with the work done on it set to what it stores plus what it has
    /// dissipated; the tets' elastic energy and that work are booked as
    /// external work already done — the work of the loads on a quasi-static
    /// path to that state — so `Energies::balance` starts at zero; each
    /// surface load's work ([`crate::StepRecord::surface_work`]) starts at
    /// its share `½ f_k · u` of it. A joint
    /// that this evaluation fails is left intact and undamaged: the first
    /// step fails it again and records the failure, as every failure is
    /// recorded.
    ///
    /// # Errors
    /// [`SolverError::InitialDisplacement`] after the first step, for a
    /// displacement of the wrong length or not finite, or one that moves a
    /// prescribed (fixed, driven or rigid) component; a component whose
    /// drive starts later is free at the start and may be displaced.
    pub fn start_displaced(&mut self, u: &[Vec3]) -> Result<f64, SolverError> {
        let bad = |why: String| Err(SolverError::InitialDisplacement(why));
        if self.evolving.state.step != 0 {
            return bad(format!("the run is at step {}, not at its start", self.evolving.state.step));
        }
        if u.len() != self.scene.model.num_nodes() {
            return bad(format!("{} displacements for {} nodes", u.len(), self.scene.model.num_nodes()));
        }
        if let Some(i) = u.iter().position(|d| !d.iter().all(|c| c.is_finite())) {
            return bad(format!("node {i}: not finite"));
        }
        let (table, drives) = (&self.pipeline.external.prescribed, &self.scene.loads.drives);
        if let Some((i, c)) = (0..u.len())
            .flat_map(|i| (0..3).map(move |c| (i, c)))
            .find(|&(i, c)| held_from_start(table[i][c], drives) && u[i][c] != 0.0)
        {
            return bad(format!("node {i} component {} is prescribed but displaced", ["x", "y", "z"][c]));
        }
        self.edit_on_host();
        for ((x, x0), d) in self.evolving.state.x.iter_mut().zip(&self.scene.model.x0).zip(u) {
            *x = x0 + d;
        }
        self.evolving.state.v.iter_mut().chain(self.evolving.v_before.iter_mut()).for_each(|v| *v = Vec3::zeros());
        let x = &self.evolving.state.x;
        let mut joint_work = 0.0;
        for ((history, nodes), joint) in
            self.evolving.state.joints.iter_mut().zip(&self.scene.model.joints).zip(&self.scene.model.joint_law)
        {
            let mut h = JointHistory::default();
            let out = joint_update(joint, &mut h, &nodes.map(|n| x[n as usize]), true);
            if !h.failed {
                h.work = out.energy + h.dissipated;
                joint_work += h.work;
                *history = h;
            }
        }
        let mut scratch = Workspace::new(&self.scene.model);
        let mut history = self.evolving.state.joints.clone();
        let want = Want { energy: true, stress: false };
        let sums = internal_forces(
            &self.scene.model,
            x,
            &self.evolving.state.v,
            &mut history,
            &mut scratch,
            want,
            Dissipation::None,
        );
        let stored = sums.tet_energy + sums.joint_energy;
        // Before the first step nothing else is booked: set, not added, so
        // that a second call replaces the first.
        let ledger = &mut self.evolving.ledger;
        ledger.energies.tet_elastic = sums.tet_energy;
        ledger.energies.joint_elastic = sums.joint_energy;
        ledger.energies.fracture = sums.fracture;
        // Each surface load's share of that work: Clapeyron's `½ f_k · u`,
        // the work of loads applied together in proportion on a linear
        // body (its loads at t = 0 on the reference faces). The shares and
        // gravity's add up to the stored energy as far as the state is
        // linear elastic; the rest of the work is the ledger's `start`.
        let mut shares = 0.0;
        for (k, load) in self.scene.loads.surfaces.iter().enumerate() {
            let mut share = 0.0;
            surface_forces(load, &self.scene.model.x0, load.ramp.factor(0.0), |n, f| {
                share += 0.5 * f.dot(&u[n as usize])
            });
            ledger.surfaces[k] = Trapezoid { total: share, ahead: 0.0 };
            self.evolving.record.surface_work[k] = share;
            shares += share;
        }
        ledger.start = sums.tet_energy + joint_work - shares;
        // A kick before the start changed velocities this start has set to
        // zero: its work is gone with them.
        ledger.kicks = 0.0;
        ledger.close();
        Ok(stored)
    }
}
