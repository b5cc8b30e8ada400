//! The columns `femdem run` writes, by name, and their units: what the
//! writer (`femdem_run::output`) and every reader share.

/// The energy columns of `history.csv`, J, in order (after `time` and
/// `step`).
pub const ENERGY: [&str; 9] = [
    "kinetic",
    "tet_elastic",
    "joint_elastic",
    "damping",
    "fracture",
    "contact",
    "friction",
    "external_work",
    "balance",
];

/// Contact's own columns, with `[contact]`: `contact_normal`, the work the
/// normal contact forces have absorbed up to `t_n` (J; `contact` less what
/// the friction springs hold, with `contact_handed` counted as absorbed:
/// negative when contact has given back more energy than it took and the
/// failed joints held — a conservative force would return to zero after
/// a closed cycle; Eq. 17's leaves a residual, `docs/fidelity.md`),
/// `contact_springs`, the elastic energy the friction springs hold (J),
/// `contact_pairs`, the pairs in contact at the step, `contact_released`,
/// the work done on the bodies by the normal forces of the pairs that
/// started overlapped while they stayed in contact (J; the energy their
/// initial overlap gave back, `[contact] activation`), `contact_handed`,
/// the part of it the failed joints' compression supplied (J; at most the
/// compression energy they held when they failed,
/// `ContactEnergy::handed`: moved from `fracture` to `contact`),
/// `contact_started`, how many such pairs are in contact, and
/// `contact_depth_max`, the deepest overlap of a pair in contact over the
/// element's shortest altitude (`Contact::deepest_overlap`).
pub const CONTACT: [&str; 7] = [
    "contact_normal",
    "contact_springs",
    "contact_pairs",
    "contact_released",
    "contact_handed",
    "contact_started",
    "contact_depth_max",
];

/// The columns of `failures.csv`: the time the joint failed (s), its
/// index, the centroid of its mid-plane (m), its area (m²) and its mode
/// ([`crate::failures::FailureMode`]'s code).
pub const FAILURES: [&str; 7] = ["time", "joint", "x", "y", "z", "area", "mode"];

/// The failure counts of a history, by mode.
pub const BROKEN: [&str; 4] = ["broken_tensile", "broken_shear", "broken_mixed", "broken_collapsed"];

/// The unit of a column `femdem run` writes, when it has one.
pub fn unit(column: &str) -> Option<&'static str> {
    if column == "time" {
        Some("s")
    } else if ENERGY.contains(&column) || column.ends_with("_work") {
        Some("J")
    } else if column == "load" || ["_fx", "_fy", "_fz"].iter().any(|s| column.ends_with(s)) {
        Some("N")
    } else if ["_ux", "_uy", "_uz"].iter().any(|s| column.ends_with(s)) {
        Some("m")
    } else {
        None
    }
}
