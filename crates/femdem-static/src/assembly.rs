//! Assembly of the global stiffness on the unknowns: every deformable tet
//! ([`crate::stiffness::tet_stiffness`]) and every intact joint
//! ([`crate::stiffness::joint_stiffness`]); rigid tets add nothing (their
//! nodes are held), held components are left out.

use femdem_solver::Model;

use crate::StaticError;
use crate::dofs::{Dofs, HELD};
use crate::sparse::{SymmetricCsc, Triplets};
use crate::stiffness::{face_area, joint_initial_stiffness, joint_stiffness, tet_stiffness};

/// The stiffness of `model` on `dofs`, with the joints for which
/// `intact[j]` holds.
///
/// # Errors
/// [`StaticError::JointStiffness`] for a joint without a finite, positive
/// `p0 / h`.
pub fn assemble(model: &Model, dofs: &Dofs, intact: &[bool]) -> Result<SymmetricCsc, StaticError> {
    let mut t = Triplets::default();
    for (tet, (reference, material)) in model.tets.iter().zip(model.tet_ref.iter().zip(&model.tet_material)) {
        let Some(material) = material.index() else {
            continue;
        };
        let k = tet_stiffness(reference, &model.materials[material].1);
        for a in 0..4 {
            let ia = dofs.index[tet[a] as usize];
            for b in 0..=a {
                let ib = dofs.index[tet[b] as usize];
                for r in 0..3 {
                    for c in 0..3 {
                        // Only one of (a, r, b, c) and (b, c, a, r) for a = b.
                        if (ia[r] == HELD || ib[c] == HELD) || (a == b && c > r) {
                            continue;
                        }
                        t.add(ia[r], ib[c], k[a][b][(r, c)]);
                    }
                }
            }
        }
    }
    for (j, (nodes, joint)) in model.joints.iter().zip(&model.joint_law).enumerate() {
        if !intact[j] {
            continue;
        }
        let stiffness = joint_initial_stiffness(joint);
        if !(stiffness.is_finite() && stiffness > 0.0) {
            return Err(StaticError::JointStiffness { joint: j, stiffness });
        }
        let s = joint_stiffness(joint, face_area(&model.x0, nodes));
        for p in 0..6 {
            let ip = dofs.index[nodes[p] as usize];
            for q in 0..=p {
                let iq = dofs.index[nodes[q] as usize];
                for c in 0..3 {
                    if ip[c] != HELD && iq[c] != HELD {
                        t.add(ip[c], iq[c], s[p][q]);
                    }
                }
            }
        }
    }
    Ok(SymmetricCsc::from_triplets(dofs.count, t))
}
