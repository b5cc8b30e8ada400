//! Stage 2 of the step: joint failures. One path, [`Solver::unbond`],
//! hands a failed joint's tets to contact, whether the joint failed in the
//! force pass, was broken by decree, or had failed before contact was
//! enabled.

use femdem_core::{Real, Vec3};
use femdem_fracture::joint_kinematics;

use super::Solver;
use crate::state::Failure;

impl Solver {
    /// Appends the joints that failed in the last force evaluation to the
    /// failure record, in joint order, and unbonds their tets.
    pub(super) fn record_failures(&mut self, time: Real) {
        for j in 0..self.pipeline.workspace.failed_now.len() {
            let Some(mode) = self.pipeline.workspace.failed_now[j] else {
                continue;
            };
            let xp = self.scene.model.joints[j].map(|n| self.evolving.state.x[n as usize]);
            let centroid = xp.iter().sum::<Vec3>() / 6.0;
            let k = joint_kinematics(&xp);
            let area = k.as_ref().map_or(0.0, |k| k.frame.area);
            self.evolving.failures.push(Failure { joint: j as u32, time, centroid, area, mode });
            self.unbond(j, closed(k.as_ref()), area);
        }
    }

    /// Breaks joints by decree (a notch or a saw cut seeded in an intact
    /// mesh, or a test of the switch to contact): each joint of `joints`
    /// not yet failed stops carrying force from the next step and is
    /// unbonded as a natural failure is. It is not a material failure:
    /// nothing is added to [`Solver::failures`]. As for a natural failure,
    /// all the work done on the joint (its stored energy included) counts as
    /// `fracture` energy from then on.
    pub fn break_joints(&mut self, joints: &[u32]) {
        self.edit_on_host();
        for &j in joints {
            let history = &mut self.evolving.state.joints[j as usize];
            if !history.failed {
                history.failed = true;
                let xp = self.scene.model.joints[j as usize].map(|n| self.evolving.state.x[n as usize]);
                let k = joint_kinematics(&xp);
                let area = k.as_ref().map_or(0.0, |k| k.frame.area);
                self.unbond(j as usize, closed(k.as_ref()), area);
            }
        }
    }

    /// Hands failed joint `j` to contact, if contact is on
    /// ([`crate::Contact::joint_failed`]): its two tets may touch (Eq. 14) and
    /// the tets around its vertices become contactable (Eq. 15–16). A joint
    /// that failed `compressed` (see [`closed`]) has its contact force ramped
    /// in over the Eq. 18 steps. `area` is its mid-plane area now, for the
    /// compression energy it held (`JointHistory::compression_energy`, at
    /// its last evaluation), which contact may give back as handed over
    /// ([`crate::ContactEnergy::handed`]).
    pub(super) fn unbond(&mut self, j: usize, compressed: bool, area: Real) {
        if let Some(contact) = &mut self.evolving.contact {
            let held = self.evolving.state.joints[j].compression_energy(area);
            contact.joint_failed(&self.scene.model, j, compressed, held, &mut self.evolving.ledger.contact);
        }
    }
}

/// Whether a joint is closed at its current positions (mean opening < 0:
/// failing now, it failed in compression); a collapsed joint is not.
fn closed(k: Option<&femdem_fracture::JointKinematics>) -> bool {
    k.is_some_and(|k| k.opening.iter().sum::<Real>() < 0.0)
}
