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
        for j in 0..self.workspace.failed_now.len() {
            let Some(mode) = self.workspace.failed_now[j] else {
                continue;
            };
            let xp = self.model.joints[j].map(|n| self.state.x[n as usize]);
            let centroid = xp.iter().sum::<Vec3>() / 6.0;
            let area = joint_kinematics(&xp).map_or(0.0, |k| k.frame.area);
            self.failures.push(Failure { joint: j as u32, time, centroid, area, mode });
            self.unbond(j, true);
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
        for &j in joints {
            let history = &mut self.state.joints[j as usize];
            if !history.failed {
                history.failed = true;
                self.unbond(j as usize, true);
            }
        }
    }

    /// Hands failed joint `j` to contact, if contact is on
    /// ([`crate::Contact::joint_failed`]): its two tets may touch (Eq. 14) and
    /// the tets around its vertices become contactable (Eq. 15–16). With
    /// `ramp`, a joint that
    /// is closed at the current positions (mean opening < 0: it failed in
    /// compression) has its contact force ramped in over the Eq. 18 steps.
    pub(super) fn unbond(&mut self, j: usize, ramp: bool) {
        let Some(contact) = &mut self.contact else {
            return;
        };
        let compressed = ramp && {
            let xp = self.model.joints[j].map(|n| self.state.x[n as usize]);
            joint_kinematics(&xp).map_or(0.0, |k| k.opening.iter().sum::<Real>()) < 0.0
        };
        contact.joint_failed(&self.model, j, compressed);
    }
}
