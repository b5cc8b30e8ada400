//! Contact settings: the normal penalty, which surfaces may touch, Coulomb
//! friction per pair of regions, the detection buffer, and which pairs are
//! negligible.

use femdem_core::Real;

/// Contact settings.
#[derive(Clone, Debug, PartialEq)]
pub struct ContactSettings {
    /// Normal penalty `p` of Eq. 17, Pa (a multiple of E).
    pub penalty: Real,
    /// Whether the outer surfaces of bodies are contactable (for collisions
    /// and platens); fracture surfaces always are.
    pub surfaces: bool,
    /// Coulomb friction coefficient μ of every pair of regions not listed in
    /// [`ContactSettings::pair_friction`] (0: frictionless).
    pub friction: Real,
    /// Coulomb friction coefficient of particular pairs of regions (region
    /// indices of the mesh, either order): the paper uses 0.6 on crack faces
    /// (rock against rock) and 0.1 between the disc and the steel platens.
    pub pair_friction: Vec<([u16; 2], Real)>,
    /// Detection buffer `b`, m: NBS keeps every pair whose bounding spheres
    /// are at most `b` apart, and a full detection is repeated only once
    /// some contactable node has moved more than `b/2` from where it was at
    /// the last one (two tets that touch now were then at most `b` apart:
    /// see `Contact::needs_detection`); joint failures in between add their
    /// candidates (see [`ContactSettings::incremental`]). 0 detects at every
    /// step.
    pub buffer: Real,
    /// Steps `n_total` over which the contact force between the tets of a
    /// joint that failed in compression rises from zero (Eq. 18; the paper
    /// uses [`crate::RAMP_STEPS`] = 10; 0: no ramp).
    pub ramp_steps: u32,
    /// Whether a joint failure between two full detections only adds the
    /// candidate pairs of the tets around the failed joint
    /// (`Contact::add_candidates`, the default) instead of detecting all
    /// pairs again. Both give the same forces bit for bit (every pair that
    /// can touch is a candidate either way and forces are summed in
    /// ascending pair order); `false` costs a full detection per failure
    /// and is there for the test that compares the two
    /// (`tests/solver/contact_incremental.rs`) and for profiling.
    pub incremental: bool,
    /// Pairs whose Eq. 17 forces are provably negligible are skipped: a
    /// pair is not evaluated when `femdem_contact::contact_bound` shows
    /// that none of its normal forces can exceed `negligible · p · ℓ²`, `ℓ³`
    /// the smaller tet's reference volume — a contact pressure below
    /// `negligible · p` (6 Pa for the default and p = 60 GPa), and with
    /// friction `(1 + μ)` times that. Tets that
    /// share a vertex across a fracture overlap near it at third order in
    /// the overlap, and are most of the candidates of a fracture network
    /// (`docs/performance.md`). A pair that is evaluated leaves out faces
    /// while the bounds on what their clipped pieces carry sum to at most
    /// that (`femdem_contact::tet_tet_contact_within`), so no normal nodal
    /// force moves by more than `negligible · p · ℓ²` either way: the
    /// slivers where the side faces of tets sharing an edge across a trace
    /// dip into each other. (The faces left out also move the contact
    /// centre where friction acts, and a pair left with no face is not in
    /// contact: its friction spring and, for a pair that started
    /// overlapped, its offset are dropped.) 0 evaluates every candidate and face (Eq. 17
    /// as printed); default [`NEGLIGIBLE`].
    pub negligible: Real,
    /// Whether a pair shown negligible is certified for a radius of node
    /// motion and skipped, without being bounded again, until its nodes
    /// have moved that far (`contact/certify.rs`, the default), instead of
    /// being bounded at every pass. It skips only pairs whose forces are
    /// provably below the same `negligible` threshold, so the results move
    /// within what that threshold allows; `false` is there for the tests
    /// that compare the two and for profiling.
    pub certify: bool,
    /// How a pair that is already overlapping when it is newly allowed to
    /// touch starts (around a failed joint, whose overlap is the compliance
    /// of the joints that held it, or at the first step): see
    /// [`Activation`].
    pub activation: Activation,
    /// The normal force between two tets: see [`ContactModel`].
    pub model: ContactModel,
}

/// The normal force between two overlapping tets.
///
/// * [`ContactModel::Potential`] (the default): Eq. 17 as printed
///   (`femdem_contact::tet_tet_contact`), each clipped piece's force shared
///   among the nodes by its centroid's barycentric coordinates. Its
///   resultant is the derivative of `W = p ∫_{A∩B} (φ_A + φ_B) dV` under a
///   rigid translation, but its nodal shares are not `−∂W/∂x`: over a
///   closed cycle of contact it gives back more or less than it took
///   (`docs/fidelity.md`, section 10).
/// * [`ContactModel::Gradient`]: `f = −∂W/∂x` on all eight nodes exactly
///   (`femdem_contact::tet_tet_gradient`): the same energy and the same
///   resultant on each tet, with nodal forces that conserve energy, and
///   each pair's kick corrected where the leapfrog's trapezoid misses the
///   change of `W` (its onset, where `W`'s curvature jumps: `onset.rs`), so
///   that a closed cycle gives back what it took to round-off
///   (`docs/fidelity.md` §12). About eight clippings where Eq. 17 needs
///   two, and no bound to skip negligible pairs
///   ([`ContactSettings::negligible`] is not read).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum ContactModel {
    /// Eq. 17 as printed.
    #[default]
    Potential,
    /// The exact gradient of Eq. 17's potential energy.
    Gradient,
}

/// How a pair that already overlaps when it is newly allowed to touch
/// starts.
///
/// A pair of contactable tets that may touch comes into contact by
/// approaching, so its overlap and force rise from zero (to within a step's
/// motion). The exceptions are pairs *newly allowed* to touch (`start.rs`
/// finds them: every pair at the first step, and the pairs a crack
/// allows). When a joint fails, every tet around its three vertices
/// becomes contactable (G1–G6 of Eq. 15) and
/// the failed joint's own pair may touch, and their overlap then is what
/// the joints allowed under compression. At full force from their first
/// step such pairs push apart with energy no one stored: the joint's own
/// compression energy was already booked as the joint's (and dissipated
/// with it), and the contact gives it back a second time. The options:
///
/// * [`Activation::Paper`]: as printed, the Eq. 18 ramp for the failed
///   joint's own pair when it failed in compression, every other pair at
///   full force at once;
/// * [`Activation::Ramp`]: the Eq. 18 ramp (`n_c / n_total`) for every
///   pair that overlaps when newly allowed. It only delays the force:
///   the overlap's energy is still given back as the pair separates;
/// * [`Activation::Couple`]: the failed joint's own couple as `Paper`,
///   every other pair as `Offset`;
/// * [`Activation::Settle`] (the default): the failed joint's own couple
///   ramped in over the Eq. 18 steps as an offset that shrinks to zero
///   (its first overlap's force comes in as Eq. 18's, and what it is
///   pressed beyond that acts at once), every other pair as `Offset`;
/// * [`Activation::Offset`]: the pair's first normal resultant `N₀` counts
///   as its zero, `f = f₁₇ · max(0, 1 − N_off / N)`, `N` the Eq. 17
///   resultant now and `N_off ← min(N_off, N)` at every step (first
///   `N₀`). The force rises from zero with any further compression, by
///   `N − N_off` in magnitude, and the offset shrinks only as the pair
///   opens, where the force is zero: for a force proportional to the
///   overlap (two faces pressed flat, where Eq. 17's resultant grows with
///   the depth) it is the 1-D penalty `k max(0, d − d_off)` with
///   `d_off ← min(d_off, d)`, which stores and gives back only what the
///   pair is pressed beyond its start, so activation injects nothing. It
///   replaces the Eq. 18 ramp. Once the pair separates (no overlap) it is
///   forgotten; touching again, it starts from zero overlap as any other.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Activation {
    /// Eq. 18 for the joints that failed in compression only (as printed).
    Paper,
    /// Eq. 18 for every pair that overlaps when newly allowed.
    Ramp,
    /// The first overlap counts as zero for every pair that starts
    /// overlapped (see the enum's documentation).
    Offset,
    /// Eq. 18 for the failed joint's own couple (Eq. 14) when it failed in
    /// compression — it takes over the load the joint carried — and the
    /// offset start for every other pair that starts overlapped, whose
    /// overlap is the compliance of joints that still hold it.
    Couple,
    /// The failed joint's own couple, when it failed in compression, starts
    /// as `Offset` with its offset shrunk to zero over the Eq. 18 steps,
    /// `N_off = N₀ (1 − n_c / n_total)`: its initial overlap's force comes
    /// in as Eq. 18's does, and anything it is pressed beyond that acts at
    /// full force at once (Eq. 18 scales all of it, so a couple pressed
    /// further during the ramp stores less than it gives back); every
    /// other pair that starts overlapped as `Offset`. The default
    /// (`docs/fidelity.md`, section 11, says why).
    #[default]
    Settle,
}

/// The default of [`ContactSettings::negligible`].
pub const NEGLIGIBLE: Real = 1e-10;

impl ContactSettings {
    /// Frictionless contact with penalty `p` (Pa) between all surfaces,
    /// detected at every step, with the couple settling over the paper's
    /// 10 Eq. 18 steps and the offset start of the other pairs that start
    /// overlapped ([`Activation::Settle`]), incremental detection after
    /// joint failures and negligible pairs skipped (and certified over
    /// many steps).
    pub fn new(penalty: Real) -> ContactSettings {
        ContactSettings {
            penalty,
            surfaces: true,
            friction: 0.0,
            pair_friction: Vec::new(),
            buffer: 0.0,
            ramp_steps: crate::RAMP_STEPS,
            incremental: true,
            negligible: NEGLIGIBLE,
            certify: true,
            activation: Activation::default(),
            model: ContactModel::default(),
        }
    }

    /// The friction coefficient between regions `a` and `b`: the last
    /// matching entry of [`ContactSettings::pair_friction`], else
    /// [`ContactSettings::friction`].
    pub fn friction_between(&self, a: u16, b: u16) -> Real {
        self.pair_friction
            .iter()
            .rev()
            .find(|([p, q], _)| (*p, *q) == (a, b) || (*p, *q) == (b, a))
            .map_or(self.friction, |&(_, mu)| mu)
    }
}

/// A dense table of μ per pair of regions, for the pair loop.
#[derive(Clone, Debug)]
pub(crate) struct FrictionTable {
    n: usize,
    mu: Vec<Real>,
}

impl FrictionTable {
    pub(crate) fn new(settings: &ContactSettings, n_regions: usize) -> FrictionTable {
        let mut mu = vec![0.0; n_regions * n_regions];
        for a in 0..n_regions {
            for b in 0..n_regions {
                mu[a * n_regions + b] = settings.friction_between(a as u16, b as u16);
            }
        }
        FrictionTable { n: n_regions, mu }
    }

    pub(crate) fn get(&self, a: u16, b: u16) -> Real {
        self.mu[a as usize * self.n + b as usize]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pair_friction_overrides_the_default_in_either_order() {
        let mut s = ContactSettings::new(1e9);
        s.friction = 0.6;
        s.pair_friction.push(([0, 2], 0.1));
        assert_eq!(s.friction_between(0, 0), 0.6);
        assert_eq!(s.friction_between(2, 0), 0.1);
        assert_eq!(s.friction_between(0, 2), 0.1);
        let t = FrictionTable::new(&s, 3);
        assert_eq!(t.get(2, 0), 0.1);
        assert_eq!(t.get(1, 2), 0.6);
    }
}
