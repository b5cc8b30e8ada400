//! Which velocity components are prescribed: fixed (zero), driven by a
//! [`VelocityDrive`](crate::VelocityDrive), or free.

use crate::error::SolverError;
use crate::loads::{Loads, VelocityDrive};
use crate::model::Model;

/// What prescribes one velocity component of a node.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Claim {
    /// No constraint: the component moves freely.
    Free,
    /// Held at zero velocity.
    Fixed,
    /// Driven by [`Loads::drives`]`[d]`.
    Drive(u16),
}

/// Per node and component: what prescribes it.
pub(crate) type Prescribed = Vec<[Claim; 3]>;

/// The prescribed table of `loads` on `model`.
///
/// # Errors
/// [`SolverError::PrescribedTwice`] when a component is claimed by two
/// constraints, [`SolverError::RigidNodeNotDriven`] when a node of a rigid
/// region is not driven in all three components,
/// [`SolverError::MasslessFreeNode`] when a node without mass has a free
/// component. A component whose only constraint is a drive with a later
/// `start_time` is free at the start, and counts as such for the last two.
pub(crate) fn prescribed(model: &Model, loads: &Loads) -> Result<Prescribed, SolverError> {
    let n = model.num_nodes();
    let mut table = vec![[Claim::Free; 3]; n];
    let name = |tag: Claim| match tag {
        Claim::Drive(d) => format!("drive `{}`", loads.drives[d as usize].name),
        _ => "a fixed constraint".to_string(),
    };
    let mut claim = |node: u32, c: usize, tag: Claim, by: &dyn Fn() -> String| -> Result<(), SolverError> {
        let slot =
            table.get_mut(node as usize).ok_or_else(|| SolverError::NodeOutOfRange { node, nodes: n, by: by() })?;
        if slot[c] != Claim::Free && slot[c] != tag {
            let p = model.x0[node as usize];
            return Err(SolverError::PrescribedTwice {
                node,
                at: [p[0], p[1], p[2]],
                component: ["x", "y", "z"][c],
                first: name(slot[c]),
                by: by(),
            });
        }
        slot[c] = tag;
        Ok(())
    };
    for f in &loads.fixed {
        for &node in &f.nodes {
            for c in (0..3).filter(|&c| f.components[c]) {
                claim(node, c, Claim::Fixed, &|| "a fixed constraint".to_string())?;
            }
        }
    }
    for (d, drive) in loads.drives.iter().enumerate() {
        for &node in &drive.nodes {
            for c in (0..3).filter(|&c| drive.components[c]) {
                claim(node, c, Claim::Drive(d as u16), &|| format!("drive `{}`", drive.name))?;
            }
        }
    }
    let loose = |i: usize| table[i].iter().any(|&tag| !held_from_start(tag, &loads.drives));
    if let Some(i) = (0..n).find(|&i| model.rigid_node[i] && loose(i)) {
        return Err(SolverError::RigidNodeNotDriven { node: i as u32 });
    }
    if let Some(i) = (0..n).find(|&i| model.mass[i] <= 0.0 && loose(i)) {
        return Err(SolverError::MasslessFreeNode { node: i as u32 });
    }
    Ok(table)
}

/// Which nodes of `model` have all three velocity components prescribed by
/// `loads` from the first step on (fixed or driven; the nodes of rigid
/// regions are): the nodes the stable-step estimate
/// ([`crate::stable_time_step`]) leaves out. A component held by a drive
/// with a later `start_time` counts as free (holding it later only raises
/// the critical step).
///
/// # Errors
/// As for [`crate::Solver::new`]: an inconsistent set of constraints.
pub fn held_nodes(model: &Model, loads: &Loads) -> Result<Vec<bool>, SolverError> {
    Ok(held(&prescribed(model, loads)?, &loads.drives))
}

/// The nodes of `table` with all three components prescribed from the
/// first step on (`drives`: the drives the table's indices name).
pub(crate) fn held(table: &Prescribed, drives: &[VelocityDrive]) -> Vec<bool> {
    table.iter().map(|p| p.iter().all(|&tag| held_from_start(tag, drives))).collect()
}

/// Whether a component claimed by `tag` is prescribed from the first step
/// on.
pub(crate) fn held_from_start(tag: Claim, drives: &[VelocityDrive]) -> bool {
    match tag {
        Claim::Free => false,
        Claim::Fixed => true,
        Claim::Drive(d) => drives[d as usize].from_start(),
    }
}
