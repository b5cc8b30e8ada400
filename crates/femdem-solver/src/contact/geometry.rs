//! The candidate pairs' Eq. 17 contacts computed elsewhere than in the
//! pass — on a device, `femdem_gpu::Bulk::pair_geometry` — for
//! [`Contact::pass_with`]: what the pass asks for and what it costs.

use femdem_contact::Bounded;
use femdem_core::Real;

use super::{Contact, ContactModel};

/// Where [`Contact::pass_with`] gets the candidate pairs' Eq. 17 contacts:
/// given the pairs, their `negligible` thresholds (m², where the settings
/// have one) and the penalty (Pa), one result per pair, or `None` to
/// compute them on the CPU after all.
pub(crate) type Geometry<'a> = dyn FnMut(&[[u32; 2]], Option<&[Real]>, Real) -> Option<Vec<Bounded>> + 'a;

impl Contact {
    /// Whether [`Contact::pass_with`] asks its geometry for the pairs'
    /// contacts: with the potential model (the gradient one is the CPU's).
    pub(crate) fn geometry_elsewhere(&self) -> bool {
        self.settings.model == ContactModel::Potential
    }

    /// Bytes a pass with [`Contact::pass_with`] moves to and from a device
    /// for its geometry: per candidate pair 8 up (and 8 for its threshold
    /// where `negligible` is set), 240 back.
    pub(crate) fn geometry_bytes(&self) -> usize {
        if !self.geometry_elsewhere() {
            return 0;
        }
        let up = if self.settings.negligible > 0.0 { 16 } else { 8 };
        self.candidates.len() * (up + 240)
    }

    /// The candidates' contacts from `geometry`, one per candidate, where
    /// the model's are computed elsewhere and there are candidates; each
    /// pair's threshold as `pair::evaluate` forms it, `negligible · ℓ²`.
    pub(super) fn ask_geometry(&self, geometry: &mut Geometry<'_>) -> Option<Vec<Bounded>> {
        if !self.geometry_elsewhere() || self.candidates.is_empty() {
            return None;
        }
        let pairs: Vec<[u32; 2]> = self.candidates.iter().map(|&(a, b)| [a, b]).collect();
        let (negligible, sizes) = (self.settings.negligible, &self.sizes);
        let omit = |&(a, b): &(u32, u32)| negligible * sizes[a as usize].min(sizes[b as usize]).powi(2);
        let omits = (negligible > 0.0).then(|| self.candidates.iter().map(omit).collect::<Vec<_>>());
        geometry(&pairs, omits.as_deref(), self.settings.penalty)
    }
}
