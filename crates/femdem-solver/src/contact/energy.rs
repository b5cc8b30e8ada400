//! The contact terms of the energy account ([`ContactEnergy`]): what the
//! normal forces, friction and the pairs that started overlapped have done,
//! kept in the solver's ledger.

use femdem_core::Real;

/// The contact terms of the energy account, J: kept in the solver's ledger
/// (`crate::ledger`), booked by [`Contact::book_work`].
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct ContactEnergy {
    /// Work absorbed by the normal forces up to `t_n` of the last pass,
    /// plus the elastic energy of the friction springs now.
    pub contact: Real,
    /// Energy dissipated by friction up to `t_n`: the work absorbed by the
    /// friction forces less what the springs still hold.
    pub friction: Real,
    /// The work the friction forces absorbed up to `t_n`.
    pub(super) friction_absorbed: Real,
    /// The springs' energy booked into `contact` so far.
    pub(super) spring_booked: Real,
    /// Work of the last pass's normal forces over the half step after
    /// `t_n`, `½ Δt Σ f_N · v_{n+½}`: booked with the next pass.
    pub(super) normal_ahead: Real,
    /// The same for the friction forces.
    pub(super) friction_ahead: Real,
    /// Work done on the bodies by the normal forces of the pairs that
    /// started overlapped (`ContactSettings::activation`), while they
    /// stayed in contact, up to `t_n`: the energy their initial overlap
    /// gave back (less what they absorbed since), J.
    pub released: Real,
    /// The same over the half step after `t_n`, booked with the next pass.
    pub(super) released_ahead: Real,
    /// The compression energy the failed joints held when they failed
    /// (`JointHistory::compression_energy`), J, for the joints whose couple
    /// starts without an offset (`Contact::joint_failed`): an upper bound
    /// on what their overlaps can honestly give back.
    pub held: Real,
}

impl ContactEnergy {
    /// What the pairs that started overlapped gave back, up to the
    /// compression energy the failed joints held (`clamp(released, 0,
    /// held)`), J: energy the joints handed over to contact, which the
    /// account moves from fracture to contact (`Energies::fracture` less
    /// it, `Energies::contact` plus it). A joint that fails closed leaves
    /// its two tets overlapping by its opening, and its compression was
    /// stored work, not fracture; what contact gives back beyond it is
    /// energy no load supplied, which `Solver::check_contact_energy` sees.
    pub fn handed(&self) -> Real {
        self.released.clamp(0.0, self.held.max(0.0))
    }
}
