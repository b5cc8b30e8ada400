//! The unknowns: one per free displacement component. A component is held
//! at zero displacement when it is fixed, driven by a velocity from the
//! first step on (its displacement at `t = 0` is zero; a drive with a later
//! `start_time` leaves its components free), or belongs to a node of a
//! rigid (platen) region.

use femdem_solver::{Loads, Model};

/// Marker of a held component in [`Dofs::index`].
pub const HELD: u32 = u32::MAX;

/// The numbering of the free components, node by node in node order.
#[derive(Clone, Debug, PartialEq)]
pub struct Dofs {
    /// For each node and component, its unknown or [`HELD`].
    pub index: Vec<[u32; 3]>,
    /// Number of unknowns.
    pub count: usize,
}

impl Dofs {
    /// The free components of `model` under `loads`' constraints (checked
    /// for consistency by the caller, e.g. with
    /// [`femdem_solver::held_nodes`]).
    pub fn new(model: &Model, loads: &Loads) -> Dofs {
        let n = model.num_nodes();
        let mut held = vec![[false; 3]; n];
        for (i, h) in held.iter_mut().enumerate() {
            if model.rigid_node[i] {
                *h = [true; 3];
            }
        }
        let constraints = loads
            .fixed
            .iter()
            .map(|f| (&f.nodes, f.components))
            .chain(loads.drives.iter().filter(|d| d.from_start()).map(|d| (&d.nodes, d.components)));
        for (nodes, components) in constraints {
            for &node in nodes {
                for c in (0..3).filter(|&c| components[c]) {
                    held[node as usize][c] = true;
                }
            }
        }
        let mut count = 0u32;
        let index = held
            .iter()
            .map(|h| {
                h.map(|is_held| {
                    if is_held {
                        HELD
                    } else {
                        count += 1;
                        count - 1
                    }
                })
            })
            .collect();
        Dofs { index, count: count as usize }
    }
}
