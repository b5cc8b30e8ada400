//! The joints' arrays on the device: the law of each joint, its history,
//! and the packing of both into the flat layouts `wgsl/joints.wgsl` reads:
//! number by number (number `k` of joint `j` of `n` at `k n + j`), so that
//! neighbouring invocations touch neighbouring words.

use femdem_core::Real;
use femdem_fracture::{Coupling, FailureMode, GfCalibration, Joint, JointHistory, Softened};

/// Numbers per joint in the law array.
pub(crate) const LAW: usize = 10;
/// Numbers per joint in the history array.
pub(crate) const HISTORY: usize = 24;
/// The flag bit of a failed joint.
const FAILED: u32 = 1 << 6;

/// What the device needs of the cohesive joints: the CPU solver's arrays.
#[derive(Clone, Copy, Debug)]
pub struct JointMesh<'a> {
    /// The six nodes of each joint (`N1 … N6`, `femdem_fracture`'s order).
    pub joints: &'a [[u32; 6]],
    /// Each joint's law (Eq. 3–13 parameters).
    pub law: &'a [Joint],
    /// Each joint's history at the start.
    pub history: &'a [JointHistory],
    /// Node-to-slot table of the joints in compressed rows (slots
    /// `6 joint + local`), as for the tets.
    pub gather_offsets: &'a [u32],
    /// See `gather_offsets`.
    pub gather_slots: &'a [u32],
}

impl JointMesh<'_> {
    /// No joints, for a mesh of `num_nodes` nodes whose gather table is
    /// `offsets` (all zeros, `num_nodes + 1` of them).
    pub fn none(offsets: &[u32]) -> JointMesh<'_> {
        JointMesh { joints: &[], law: &[], history: &[], gather_offsets: offsets, gather_slots: &[] }
    }
}

/// Rows of `width` numbers, one per item, laid out number by number
/// (`[row0[0], row1[0], …, row0[1], row1[1], …]`).
pub(crate) fn by_number(rows: &[Real], width: usize) -> Vec<Real> {
    let n = rows.len() / width;
    (0..width).flat_map(|k| (0..n).map(move |j| rows[j * width + k])).collect()
}

/// [`by_number`] undone: `n` items' rows of `width` numbers.
pub(crate) fn rows(numbers: &[Real], n: usize, width: usize) -> Vec<Real> {
    (0..n).flat_map(|j| (0..width).map(move |k| numbers[k * n + j])).collect()
}

/// The `law` array of `wgsl/joints.wgsl` (its numbers 0..10 per joint).
pub(crate) fn pack_law(law: &[Joint]) -> Vec<Real> {
    let rows: Vec<Real> = law
        .iter()
        .flat_map(|j| {
            let p = &j.params;
            let calibration = match p.calibration {
                GfCalibration::Paper => 0.0,
                GfCalibration::Exact => 1.0,
            };
            let coupling = match p.coupling {
                Coupling::Printed => 0.0,
                Coupling::Multiplicative => 1.0,
                Coupling::Capped => 2.0,
            };
            [
                p.penalty,
                p.tensile_strength,
                p.cohesion,
                p.gf_shear,
                j.h,
                j.delta_np,
                j.delta_nc,
                j.tan_phi,
                calibration,
                coupling,
            ]
        })
        .collect();
    by_number(&rows, LAW)
}

/// `hist` and `flags` of `wgsl/joints.wgsl`.
pub(crate) fn pack_history(history: &[JointHistory]) -> (Vec<Real>, Vec<u32>) {
    let mut numbers = Vec::with_capacity(HISTORY * history.len());
    let mut flags = Vec::with_capacity(history.len());
    for h in history {
        numbers.extend(h.damage);
        numbers.extend([h.dissipated, h.released, h.work]);
        numbers.extend(h.last.iter().flatten());
        numbers.extend(h.last_stress.iter().flatten());
        let mut f = if h.failed { FAILED } else { 0 };
        for (i, s) in h.softened.iter().enumerate() {
            f |= (u32::from(s.normal) | u32::from(s.shear) << 1) << (2 * i);
        }
        flags.push(f);
    }
    (by_number(&numbers, HISTORY), flags)
}

/// The histories back from their rows of [`HISTORY`] numbers (`hist`
/// through [`rows`]) and `flags`.
pub(crate) fn unpack_history(numbers: &[Real], flags: &[u32]) -> Vec<JointHistory> {
    numbers
        .chunks_exact(HISTORY)
        .zip(flags)
        .map(|(n, &f)| JointHistory {
            damage: [n[0], n[1], n[2]],
            dissipated: n[3],
            released: n[4],
            work: n[5],
            last: std::array::from_fn(|i| std::array::from_fn(|k| n[6 + 4 * i + k])),
            last_stress: std::array::from_fn(|i| [n[18 + 2 * i], n[19 + 2 * i]]),
            softened: std::array::from_fn(|i| Softened {
                normal: f >> (2 * i) & 1 == 1,
                shear: f >> (2 * i + 1) & 1 == 1,
            }),
            failed: f & FAILED != 0,
        })
        .collect()
}

/// The failure the kernel reports (`failed[j]`).
pub(crate) fn mode(code: u32) -> Option<FailureMode> {
    match code {
        0 => None,
        1 => Some(FailureMode::Tensile),
        2 => Some(FailureMode::Shear),
        3 => Some(FailureMode::Mixed),
        _ => Some(FailureMode::Collapsed),
    }
}
