//! The load vector of the static solve: the surface loads at `t = 0` on the
//! reference geometry and gravity on the physical mass, on the unknowns.

use femdem_core::{Real, Vec3};
use femdem_solver::loads::surface_forces;
use femdem_solver::{Loads, Model};

use crate::StaticError;
use crate::dofs::{Dofs, HELD};

/// The nodal external forces at `t = 0` (N): each surface load at its
/// factor `ramp.factor(0)` on the reference faces
/// ([`femdem_solver::loads::surface_forces`]), and gravity `g m / s` on the
/// physical mass (`s` the mass-scaling factor), as the explicit step
/// applies them. A static start holds the loads at their full value from
/// `t = 0` ([`crate::hold_surface_loads`]), so this is their held value.
///
/// # Errors
/// [`StaticError::NonFiniteLoad`].
pub fn nodal_loads(model: &Model, loads: &Loads) -> Result<Vec<Vec3>, StaticError> {
    let mut f = vec![Vec3::zeros(); model.num_nodes()];
    for load in &loads.surfaces {
        surface_forces(load, &model.x0, load.ramp.factor(0.0), |n, force| f[n as usize] += force);
    }
    for (fi, m) in f.iter_mut().zip(&model.mass) {
        *fi += loads.gravity * (m / model.mass_scaling);
    }
    match f.iter().position(|v| !v.iter().all(|c| c.is_finite())) {
        Some(node) => Err(StaticError::NonFiniteLoad { node }),
        None => Ok(f),
    }
}

/// The components of the nodal vectors `v` on the unknowns.
pub fn gather(dofs: &Dofs, v: &[Vec3]) -> Vec<Real> {
    let mut out = vec![0.0; dofs.count];
    for (idx, vi) in dofs.index.iter().zip(v) {
        for c in 0..3 {
            if idx[c] != HELD {
                out[idx[c] as usize] = vi[c];
            }
        }
    }
    out
}

/// The nodal vectors of the unknowns `u` (zero on held components).
pub fn scatter(dofs: &Dofs, u: &[Real]) -> Vec<Vec3> {
    dofs.index.iter().map(|idx| Vec3::from_fn(|c, _| if idx[c] == HELD { 0.0 } else { u[idx[c] as usize] })).collect()
}
