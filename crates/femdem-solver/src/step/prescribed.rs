//! Which velocity components are prescribed: fixed (zero), driven by a
//! [`VelocityDrive`](crate::VelocityDrive), or free.

use crate::error::SolverError;
use crate::loads::Loads;
use crate::model::Model;

/// A component no constraint claims.
pub(crate) const FREE: u16 = u16::MAX;
/// A component held at zero velocity.
pub(crate) const FIXED: u16 = u16::MAX - 1;

/// Per node and component: [`FREE`], [`FIXED`], or the index of the drive
/// that prescribes it.
pub(crate) type Prescribed = Vec<[u16; 3]>;

/// The prescribed table of `loads` on `model`.
///
/// # Errors
/// [`SolverError::PrescribedTwice`] when a component is claimed by two
/// constraints, [`SolverError::RigidNodeNotDriven`] when a node of a rigid
/// region is not driven in all three components,
/// [`SolverError::MasslessFreeNode`] when a node without mass has a free
/// component.
pub(crate) fn prescribed(model: &Model, loads: &Loads) -> Result<Prescribed, SolverError> {
    let n = model.num_nodes();
    let mut table = vec![[FREE; 3]; n];
    let mut claim = |node: u32, c: usize, tag: u16, by: &dyn Fn() -> String| -> Result<(), SolverError> {
        let slot =
            table.get_mut(node as usize).ok_or_else(|| SolverError::NodeOutOfRange { node, nodes: n, by: by() })?;
        if slot[c] != FREE && slot[c] != tag {
            return Err(SolverError::PrescribedTwice { node, component: ["x", "y", "z"][c], by: by() });
        }
        slot[c] = tag;
        Ok(())
    };
    for f in &loads.fixed {
        for &node in &f.nodes {
            for c in (0..3).filter(|&c| f.components[c]) {
                claim(node, c, FIXED, &|| "a fixed constraint".to_string())?;
            }
        }
    }
    for (d, drive) in loads.drives.iter().enumerate() {
        for &node in &drive.nodes {
            for c in (0..3).filter(|&c| drive.components[c]) {
                claim(node, c, d as u16, &|| format!("drive `{}`", drive.name))?;
            }
        }
    }
    if let Some(i) = (0..n).find(|&i| model.rigid_node[i] && table[i].contains(&FREE)) {
        return Err(SolverError::RigidNodeNotDriven { node: i as u32 });
    }
    if let Some(i) = (0..n).find(|&i| model.mass[i] <= 0.0 && table[i].contains(&FREE)) {
        return Err(SolverError::MasslessFreeNode { node: i as u32 });
    }
    Ok(table)
}

/// Which nodes of `model` have all three velocity components prescribed by
/// `loads` (fixed or driven; the nodes of rigid regions are): the nodes the
/// stable-step estimate ([`crate::stable_time_step`]) leaves out.
///
/// # Errors
/// As for [`crate::Solver::new`]: an inconsistent set of constraints.
pub fn held_nodes(model: &Model, loads: &Loads) -> Result<Vec<bool>, SolverError> {
    Ok(held(&prescribed(model, loads)?))
}

/// The nodes of `table` with all three components prescribed.
pub(crate) fn held(table: &Prescribed) -> Vec<bool> {
    table.iter().map(|p| p.iter().all(|&c| c != FREE)).collect()
}
