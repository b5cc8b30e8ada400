//! The correction to the explicit model's own equilibrium.
//!
//! The linear solution `u` balances the loads through the initial
//! tangent. The explicit model at `x0 + u` is not linear: the neo-Hookean
//! tets (Eq. 1) and the pressures on the current faces differ at the order
//! of the strain, and a joint's hardening branch (Eq. 11,
//! `σ = (2r − r²) f`) is softer than its initial tangent by `r/2`, which
//! is not small in a body loaded near its strength (the polyaxial cube's
//! joints reach `r ≈ 0.3`). Started there, the explicit run would ring.
//!
//! So the static start corrects `u` by modified Newton iterations on the
//! explicit model's out-of-balance force, with the factorised initial
//! tangent:
//!
//! ```text
//! r(u) = f_ext(x0 + u) + f_int(x0 + u),     u ← u + A⁻¹ r_b(u)
//! ```
//!
//! (accelerated by Anderson mixing, `crate::anderson`), where `f_int` is
//! exactly what the first explicit step evaluates
//! (`femdem_solver::forces::internal_forces` with undamaged joint
//! histories and zero velocity), `f_ext` the surface loads of `t = 0` on
//! the current geometry and gravity, and `r_b` is `r` relieved of its
//! rigid-body part on free bodies. A plain iteration contracts the error
//! by about `1 − k_t / k_0` of the softest joints (the tangent over the
//! initial stiffness): a few iterations for a body well below its peak,
//! hundreds where joints have passed it; the mixing keeps that to tens. A joint
//! point pushed past its peak softens (the evaluation is path-free: the
//! history is undamaged each time, as at the first step); its count is
//! reported. The first explicit step then finds the residual it was left
//! with: the run starts at rest in its own equilibrium.

use femdem_core::{Real, Vec3};
use femdem_fracture::JointHistory;
use femdem_solver::forces::{Dissipation, Want, Workspace, internal_forces};
use femdem_solver::loads::surface_forces;
use femdem_solver::{Loads, Model};

use crate::StaticError;
use crate::anderson::Anderson;
use crate::dofs::Dofs;
use crate::loads::{gather, scatter};
use crate::system::{System, norm};

/// Joints the last evaluation found past their peak.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct JointCount {
    /// Joints with a point past its peak (damage above zero).
    pub past_peak: usize,
    /// Joints that failed (two points at `D = 1`).
    pub failed: usize,
}

/// The out-of-balance force of the explicit model, with its buffers.
pub struct ModelResidual<'a> {
    model: &'a Model,
    loads: &'a Loads,
    dofs: &'a Dofs,
    workspace: Workspace,
    x: Vec<Vec3>,
    v: Vec<Vec3>,
    history: Vec<JointHistory>,
}

impl<'a> ModelResidual<'a> {
    /// Buffers for `model`.
    pub fn new(model: &'a Model, loads: &'a Loads, dofs: &'a Dofs) -> ModelResidual<'a> {
        let n = model.num_nodes();
        ModelResidual {
            model,
            loads,
            dofs,
            workspace: Workspace::new(model),
            x: model.x0.clone(),
            v: vec![Vec3::zeros(); n],
            history: vec![JointHistory::default(); model.joints.len()],
        }
    }

    /// `r = f_ext + f_int` at `x0 + u` on the unknowns (module doc), and the
    /// joints found past their peak.
    pub fn evaluate(&mut self, u: &[Real]) -> (Vec<Real>, JointCount) {
        let m = self.model;
        for ((x, x0), d) in self.x.iter_mut().zip(&m.x0).zip(scatter(self.dofs, u)) {
            *x = x0 + d;
        }
        self.history.iter_mut().for_each(|h| *h = JointHistory::default());
        internal_forces(
            m,
            &self.x,
            &self.v,
            &mut self.history,
            &mut self.workspace,
            Want::default(),
            Dissipation::None,
        );
        let mut f = self.workspace.internal.clone();
        for load in &self.loads.surfaces {
            surface_forces(load, &self.x, load.ramp.factor(0.0), |n, force| f[n as usize] += force);
        }
        for (fi, mi) in f.iter_mut().zip(&m.mass) {
            *fi += self.loads.gravity * (mi / m.mass_scaling);
        }
        let count = JointCount {
            past_peak: self.history.iter().filter(|h| h.damage.iter().any(|&d| d > 0.0)).count(),
            failed: self.history.iter().filter(|h| h.failed).count(),
        };
        (gather(self.dofs, &f), count)
    }
}

/// What the correction reached.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Correction {
    /// The relative out-of-balance force at the returned displacement.
    pub residual: Option<Real>,
    /// Corrections taken.
    pub iterations: usize,
    /// The relative out-of-balance force before each correction and at
    /// the end.
    pub history: Vec<Real>,
    /// The round-off floor relative to the load (set by the caller).
    pub floor: Real,
    /// Joints past their peak or failed at the returned displacement.
    pub joints: JointCount,
}

/// Corrects `u` to the explicit model's equilibrium (module doc) until
/// its relieved out-of-balance force is at most `accept · f_norm`; a mixed
/// step that doubles the best residual restarts the mixing from the best
/// iterate, and the best iterate is what is returned.
///
/// # Errors
/// [`StaticError::ModelNotConverged`] after `max_iterations` corrections.
pub fn correct(
    system: &System,
    eval: &mut ModelResidual<'_>,
    u: &mut Vec<Real>,
    f_norm: Real,
    accept: Real,
    max_iterations: usize,
) -> Result<Correction, StaticError> {
    let mut report = Correction::default();
    let mut mixing = Anderson::default();
    let mut best: Option<(Real, Vec<Real>, JointCount)> = None;
    loop {
        let (mut r, count) = eval.evaluate(u);
        system.relieve(&mut r);
        let rel = norm(&r) / f_norm;
        report.history.push(rel);
        if !rel.is_finite() {
            break;
        }
        let best_rel = best.as_ref().map_or(Real::INFINITY, |b| b.0);
        if rel < best_rel {
            best = Some((rel, u.clone(), count));
        } else if rel > 2.0 * best_rel {
            mixing.restart();
            u.clone_from(&best.as_ref().expect("a best iterate").1);
            continue;
        }
        if rel <= accept || report.iterations == max_iterations {
            break;
        }
        system.solve(&mut r);
        *u = mixing.next(u, &r);
        system.remove_rigid(u);
        report.iterations += 1;
    }
    let (rel, best_u, count) = match best {
        Some(b) if b.0 <= accept => b,
        other => {
            let (residual, past_peak) = other.map_or((Real::NAN, 0), |b| (b.0, b.2.past_peak));
            return Err(StaticError::ModelNotConverged {
                residual,
                tolerance: accept,
                iterations: report.iterations,
                past_peak,
            });
        }
    };
    *u = best_u;
    report.residual = Some(rel);
    report.joints = count;
    Ok(report)
}
