//! The solver's contact pass (reference paper §2.3): which tets may touch,
//! NBS detection among them, and the tet–tet potential forces (Eq. 17) with
//! Coulomb friction at the contact centre and the Eq. 18 ramp.
//!
//! A scene pays only for what it uses: with contact off nothing here runs;
//! with it on, only *contactable* tets are searched — the tets of rigid
//! regions, the tets on the outer surface of each body (when surface contact
//! is asked for), and, for every failed joint or pre-existing fracture face,
//! the node groups G1–G6 of Eq. 15: every tet that has one of the face's
//! three original vertices (a joint's six nodes come from three vertices;
//! "sharing a node" is sharing an original vertex, `Model::origin`). Those
//! vertices become *cracked*.
//!
//! Eq. 16 searches contact within and between these groups, "excluding
//! couples that still have active joint elements between them". Here two
//! contactable tets may touch unless
//!
//! * both are rigid, or they share a node (neighbours in an unjointed
//!   region), or an active joint joins them (face neighbours);
//! * they share an original vertex and no shared vertex separates them:
//!   around each vertex `v` they share, they are linked by a chain of tets
//!   around `v` joined by active joints (or shared nodes) — see
//!   `stars.rs` — unless they share a whole face (three vertices) whose
//!   joint failed (the couple of Eq. 14, always a candidate).
//!
//! So the candidates are the paper's couples minus those still joined
//! through active joints around every vertex they share: intact neighbours
//! (two tets on the same side of a crack, or either side of a crack front,
//! where the crack ends and the material ahead still links them). Their
//! overlap is the compliance of the joints between them — measured at a
//! crack front equal to that of intact neighbours beside it
//! (`tests/solver/contact_activation.rs`) — and a contact force there would
//! push apart material the joints hold together (it did, by 4e-7 N, in the
//! broken bar of `tests/solver/contact.rs`, when any two tets on failed
//! joints could touch). Tets the crack does separate around a shared vertex
//! may touch even with no face on the crack: the tets diagonally across a
//! kink push back on the fragment's corner. Pairs sharing no original
//! vertex are candidates whenever both are contactable.
//!
//! Detection (NBS, O(N) in the contactable tets) keeps the pairs whose
//! bounding spheres are less than the buffer `b` apart and that no face
//! plane of either keeps more than `b` apart, and is repeated only
//! when some contactable node has moved more than `b/2` from its reference
//! position (where it was at the last detection): any two tets that overlap
//! now were then within `b` of each other (`Contact::needs_detection`). A
//! joint failure in between changes the contactable set and the exclusions
//! only for the tets around the failed joint's three vertices
//! (`Contact::joint_failed` marks them *pending*); the next pass adds their
//! pairs with the contactable set, searched with a margin grown by the
//! largest move since the references, and merges them into the sorted
//! candidates (`incremental.rs`), instead of detecting everything again.
//! The candidate pairs are evaluated in parallel, and their forces are
//! summed in ascending pair order; every pair that can touch is a candidate
//! whichever way it was found, and one that does not touch adds nothing, so
//! results depend neither on the thread count, nor on the buffer, nor on
//! when detection ran.
//!
//! Each pair's friction acts at its contact centre, the point of the
//! overlap where its normal force acts: the slip is the relative velocity
//! there and the force goes to each tet's nodes by the centre's barycentric
//! coordinates (`pair::evaluate`), so it has the right moment and slows a
//! spinning body.

mod candidate;
mod certify;
mod cracks;
mod debts;
mod depth;
mod detection;
mod energy;
mod geometry;
mod incremental;
mod onset;
mod pair;
mod saved;
mod settings;
mod stars;
mod start;
mod sums;

use femdem_contact::Nbs;
use femdem_core::{Real, Vec3};
use rayon::prelude::*;
use std::time::Instant;

use crate::clock::{PassClock, lap};
use crate::model::Model;
use candidate::Candidates;
use certify::{Certificates, Verdict};
use detection::Update;
pub use energy::ContactEnergy;
pub(crate) use geometry::Geometry;
use pair::{PairForce, PairMap, PairSet, spring_key};
pub(crate) use saved::SavedContact;
use settings::FrictionTable;
pub use settings::{Activation, ContactModel, ContactSettings, NEGLIGIBLE};
use stars::Stars;
use start::NewlyAllowed;

/// `Contact::spring_of` for a candidate with no friction spring.
const NO_SPRING: u32 = u32::MAX;

/// The paper's `n_total` of Eq. 18: steps over which the contact force of
/// a joint that failed in compression rises from zero to its full value
/// (the default of [`ContactSettings::ramp_steps`]).
pub const RAMP_STEPS: u32 = 10;

/// The contact pass's state.
#[derive(Clone, Debug)]
pub struct Contact {
    /// Settings.
    pub settings: ContactSettings,
    friction: FrictionTable,
    contactable: Vec<bool>,
    /// The tets around each original vertex (Eq. 15) and their pieces.
    stars: Stars,
    /// Original vertices on a fracture (a node of a failed joint or of a
    /// pre-existing fracture face).
    cracked: Vec<bool>,
    list: Vec<u32>,
    bonded: PairSet,
    nbs: Nbs,
    centers: Vec<Vec3>,
    radii: Vec<Real>,
    pairs: Vec<femdem_contact::Pair>,
    /// Scratch of the counting sort of `pairs` (see `Contact::detect`).
    first: Vec<u32>,
    fill: Vec<u32>,
    by_first: Vec<u32>,
    /// Candidate pairs (tet indices), ascending: every pair of contactable
    /// tets that may touch and can overlap while no node in `nodes` has
    /// moved more than `b/2` from its reference position in `x_ref`.
    candidates: Vec<(u32, u32)>,
    /// Nodes of the contactable tets (ascending) but those of the `pending`
    /// tets not yet added, and their reference positions: where they were
    /// at the last full detection, or at the addition that made them
    /// contactable since.
    nodes: Vec<u32>,
    x_ref: Vec<Vec3>,
    /// Whether a full detection is needed (a new pass, or pre-existing
    /// fractures).
    stale: bool,
    /// Tets around vertices cracked since the last detection or addition
    /// (ascending): their pairs with the contactable set are not yet all
    /// candidates (see `incremental.rs`).
    pending: Vec<u32>,
    /// Each candidate's force at the last pass (boxed: most candidates
    /// have none, and a `PairForce` is some 350 bytes) and what its
    /// certificate did.
    results: Vec<(Option<Box<PairForce>>, Verdict)>,
    /// The negligible pairs' certificates (`certify.rs`).
    certificates: Certificates,
    /// Pairs whose contacts the last pass asked its geometry for
    /// (`geometry.rs`).
    asked: usize,
    /// The vectors of the last pass's [`geometry::Asked`], reused.
    asked_memory: geometry::Asked,
    /// Host wall-clock time of the passes by part (not a result: see
    /// `clock.rs`).
    pub(crate) clock: PassClock,
    /// Normal contact force per node from the last pass, N.
    pub force: Vec<Vec3>,
    /// Friction force per node from the last pass, N.
    pub friction_force: Vec<Vec3>,
    /// Normal plus friction force per node from the last pass, N (what the
    /// update adds to the internal forces).
    total: Vec<Vec3>,
    /// Velocities `v_{n−½}` of the touched nodes at the last pass.
    v_before: Vec<Vec3>,
    touched: Vec<u32>,
    is_touched: Vec<bool>,
    /// Pairs in contact at the last pass.
    pub active_pairs: usize,
    /// Full detections run so far.
    pub detections: u64,
    /// Incremental detections (the pairs of the tets around failed joints
    /// added to the candidates) run so far.
    pub additions: u64,
    /// Elastic energy of the friction springs after the last pass, J.
    pub spring_energy: Real,
    /// The energy the normal forces of the pairs in contact hold after the
    /// last pass, `Σ W`, J, with [`ContactModel::Gradient`] (see
    /// `PairForce::energy`); 0 with [`ContactModel::Potential`].
    pub potential: Real,
    /// Tangential spring stretch of each pair in contact (friction
    /// history), ascending by pair: built in the sums' pair order and
    /// matched to the candidates by one merge, with no hashing.
    stick: Vec<((u32, u32), Vec3)>,
    stick_next: Vec<((u32, u32), Vec3)>,
    /// Pairs of joints that failed in compression, with their step count
    /// `n_c` of Eq. 18.
    ramp: PairMap<u32>,
    /// Pairs that started overlapped and have not separated since, with
    /// their offset `N_off`, N (see [`Activation`]).
    started: PairMap<Real>,
    started_next: PairMap<Real>,
    /// What cracks have newly allowed to touch since the last pass
    /// (`start.rs`).
    newly: NewlyAllowed,
    /// Normal force per node of the pairs that started overlapped, N.
    started_force: Vec<Vec3>,
    /// The pairs in contact at the last pass (ascending).
    in_contact: Vec<(u32, u32)>,
    /// Each tet's `ℓ = V^{1/3}` (reference volume), m: derived from the
    /// model.
    sizes: Vec<Real>,
    /// With [`ContactModel::Gradient`]: what each pair the last pass
    /// followed leaves for the energy-consistent kicks (`onset.rs`): the
    /// pairs in contact (their applied force, energy and debt, or only the
    /// mark of a pair whose force is not the gradient of its energy), and
    /// those that have separated with a debt still to pay.
    held: PairMap<onset::Held>,
    held_next: PairMap<onset::Held>,
    /// Whether a pass has run (the first has no interval before it).
    primed: bool,
    /// Scratch: for each candidate, whether it was in contact at the last
    /// pass (then clipped before it is bounded: the order of work only,
    /// `femdem_contact::tet_tet_contact_within`).
    was_in_contact: Vec<bool>,
    /// Scratch: for each candidate, the index of its friction spring in
    /// `stick`, or [`NO_SPRING`].
    spring_of: Vec<u32>,
    /// Scratch: each contactable tet's displacement from its anchors,
    /// summarised (`certify::Drift`), when certifying.
    drifts: Vec<certify::Drift>,
    /// Which compilation of the pair kernel runs (the solver sets it with
    /// its tet and joint passes' path; the same bits on every path).
    pub(crate) path: crate::VectorPath,
}

impl Contact {
    /// The contact state of `model` with `settings`; `initial` are tet pairs
    /// in contact from the start (pre-existing fractures).
    pub fn new(model: &Model, settings: ContactSettings, initial: &[(u32, u32)]) -> Contact {
        let n_tets = model.tets.len();
        let mut contactable: Vec<bool> = model.tet_material.iter().map(|m| m.is_rigid()).collect();
        if settings.surfaces {
            for (t, on) in model.surface_tets().into_iter().enumerate() {
                contactable[t] |= on;
            }
        }
        let bonded = model.joint_tets.iter().map(|&[a, b]| spring_key(a, b)).collect();
        let list = (0..n_tets as u32).filter(|&t| contactable[t as usize]).collect();
        let n_regions = model.tet_region.iter().copied().max().map_or(1, |r| r as usize + 1);
        let friction = FrictionTable::new(&settings, n_regions);
        let mut contact = Contact {
            settings,
            friction,
            contactable,
            stars: Stars::new(model),
            cracked: vec![false; model.origin.iter().copied().max().map_or(0, |v| v as usize + 1)],
            list,
            bonded,
            nbs: Nbs::new(),
            centers: Vec::new(),
            radii: Vec::new(),
            pairs: Vec::new(),
            first: Vec::new(),
            fill: Vec::new(),
            by_first: Vec::new(),
            candidates: Vec::new(),
            nodes: Vec::new(),
            x_ref: Vec::new(),
            stale: true,
            pending: Vec::new(),
            results: Vec::new(),
            certificates: Certificates::default(),
            asked: 0,
            asked_memory: geometry::Asked::default(),
            clock: PassClock::default(),
            force: vec![Vec3::zeros(); model.num_nodes()],
            friction_force: vec![Vec3::zeros(); model.num_nodes()],
            total: vec![Vec3::zeros(); model.num_nodes()],
            v_before: Vec::new(),
            touched: Vec::new(),
            is_touched: vec![false; model.num_nodes()],
            active_pairs: 0,
            detections: 0,
            additions: 0,
            spring_energy: 0.0,
            potential: 0.0,
            stick: Vec::new(),
            stick_next: Vec::new(),
            ramp: PairMap::default(),
            started: PairMap::default(),
            started_next: PairMap::default(),
            newly: NewlyAllowed::new(n_tets),
            started_force: vec![Vec3::zeros(); model.num_nodes()],
            in_contact: Vec::new(),
            sizes: model.tet_ref.iter().map(|r| r.volume.cbrt()).collect(),
            held: PairMap::default(),
            held_next: PairMap::default(),
            primed: false,
            was_in_contact: Vec::new(),
            spring_of: Vec::new(),
            drifts: Vec::new(),
            path: crate::VectorPath::Widest,
        };
        // A pre-existing fracture face activates its vertices as a failed
        // joint does: its tets are those of the vertices the pair shares.
        for &(a, b) in initial {
            let ob = model.tets[b as usize].map(|n| model.origin[n as usize]);
            let shared: Vec<u32> =
                model.tets[a as usize].iter().map(|&n| model.origin[n as usize]).filter(|v| ob.contains(v)).collect();
            contact.crack(model, &shared, &[a, b], None);
        }
        contact
    }

    /// The nodes the last pass put a force on, ascending.
    pub fn touched(&self) -> &[u32] {
        &self.touched
    }

    /// Normal plus friction force per node from the last pass, N (zero on
    /// nodes the pass did not touch).
    pub fn total_force(&self) -> &[Vec3] {
        &self.total
    }

    /// Books the work of the last pass's forces, once the update has
    /// produced the velocities `v_{n+½}` (`v_new`), centred as the rest of
    /// the account (see `crate::step`): the work `Δt f_n · v_n` of step `n`
    /// is split into `½ Δt f_n · v_{n−½}`, which closes the interval
    /// `[t_{n−1}, t_n]` and is booked now with the half held over from the
    /// last pass, and `½ Δt f_n · v_{n+½}`, which opens `[t_n, t_{n+1}]`
    /// and is held over. Per interval that is the trapezoidal work
    /// `½ (f_{n−1} + f_n) · (x_n − x_{n−1})`, and the terms below belong to
    /// `t_n`. The normal forces absorb `−W_N` (the potential's energy plus
    /// what the Eq. 18 ramp does not give back), the friction forces
    /// `−W_T`, of which the sticking springs still hold `spring_energy`.
    pub fn book_work(&self, energy: &mut ContactEnergy, v_new: &[Vec3], dt: Real) {
        let half = 0.5 * dt;
        let (mut normal, mut friction, mut normal_ahead, mut friction_ahead) = (0.0, 0.0, 0.0, 0.0);
        let (mut released, mut released_ahead) = (0.0, 0.0);
        for (k, &n) in self.touched.iter().enumerate() {
            let (before, after) = (self.v_before[k], v_new[n as usize]);
            let (f_n, f_t) = (self.force[n as usize], self.friction_force[n as usize]);
            normal += half * f_n.dot(&before);
            friction += half * f_t.dot(&before);
            normal_ahead += half * f_n.dot(&after);
            friction_ahead += half * f_t.dot(&after);
            let f_s = self.started_force[n as usize];
            released += half * f_s.dot(&before);
            released_ahead += half * f_s.dot(&after);
        }
        let e = energy;
        e.released += e.released_ahead + released;
        e.released_ahead = released_ahead;
        e.friction_absorbed -= e.friction_ahead + friction;
        e.contact += self.spring_energy - e.spring_booked - (e.normal_ahead + normal);
        e.friction = e.friction_absorbed - self.spring_energy;
        e.spring_booked = self.spring_energy;
        e.normal_ahead = normal_ahead;
        e.friction_ahead = friction_ahead;
    }

    /// The candidate pairs of the last pass (tet indices, ascending): every
    /// pair of contactable tets that may touch and can overlap before the
    /// next detection.
    pub fn candidates(&self) -> &[(u32, u32)] {
        &self.candidates
    }

    /// The candidate pairs the last pass skipped by their certificates
    /// (`certify.rs`): shown negligible for node motions up to a radius
    /// that their nodes have not moved beyond since, and not bounded again
    /// (ascending).
    pub fn certified_skips(&self) -> impl Iterator<Item = (u32, u32)> + '_ {
        self.candidates.iter().zip(&self.results).filter(|(_, r)| r.1.skipped).map(|(p, _)| *p)
    }

    /// The tets that can touch, ascending.
    pub fn contactable(&self) -> &[u32] {
        &self.list
    }

    /// Whether negligible pairs are certified over many steps
    /// (`certify.rs`): when [`ContactSettings::certify`] asks for it, with
    /// the potential's kernel and a `negligible` threshold.
    fn certifying(&self) -> bool {
        self.settings.certify && self.settings.negligible > 0.0 && self.settings.model == ContactModel::Potential
    }

    /// Detects contacts at positions `x` (when needed) and computes the
    /// contact forces on every node into [`Contact::force`] (normal) and
    /// [`Contact::friction_force`] (zero elsewhere; the nodes with a force
    /// are [`Contact::touched`]). `v` (velocities) and `dt` drive the
    /// friction springs (see `pair::evaluate`).
    pub fn pass(&mut self, model: &Model, x: &[Vec3], v: &[Vec3], dt: Real) {
        self.pass_with(model, x, v, dt, None);
    }

    /// [`Contact::pass`] with the candidate pairs' Eq. 17 contacts from
    /// `geometry` (given the pairs, each one's `negligible` threshold in m²
    /// where the settings have one, the penalty and a vector to fill;
    /// `false` back: computed here after all), for
    /// [`ContactModel::Potential`]: the pair kernel on a device
    /// ([`femdem_gpu::Bulk::pair_geometry_into`]: the CPU's operations,
    /// results to round-off, a driver may fuse a product and a sum).
    /// Everything else — detection, certificates,
    /// the boxes' early-out, the Eq. 18 ramp, the start-at-zero offsets,
    /// friction, the sums into nodal forces — is the CPU's as in `pass`.
    pub(crate) fn pass_with(
        &mut self,
        model: &Model,
        x: &[Vec3],
        v: &[Vec3],
        dt: Real,
        geometry: Option<&mut Geometry<'_>>,
    ) {
        let mut clock = Instant::now();
        for &n in &self.touched {
            self.force[n as usize] = Vec3::zeros();
            self.friction_force[n as usize] = Vec3::zeros();
            self.total[n as usize] = Vec3::zeros();
            self.started_force[n as usize] = Vec3::zeros();
            self.is_touched[n as usize] = false;
        }
        self.touched.clear();
        match self.needs_detection(x) {
            Update::None => {}
            Update::Full => self.detect(model, x),
            Update::Add { moved } => self.add_candidates(model, x, moved),
        }
        self.newly.settle();
        let certifying = self.certifying();
        if certifying {
            let cert = &mut self.certificates;
            if cert.stale() {
                cert.renew(&model.tets, &self.list, x);
            } else {
                cert.anchor_new(&model.tets, x);
            }
            self.drifts.resize(model.tets.len(), certify::Drift::default());
            let (contactable, anchor) = (&self.contactable, &cert.anchor);
            self.drifts.par_iter_mut().zip(&model.tets).zip(contactable).for_each(|((d, t), &on)| {
                if on {
                    *d = certify::Drift::of(t, x, anchor);
                }
            });
        }
        // Both lists ascending: one merge.
        self.was_in_contact.clear();
        self.spring_of.clear();
        let mut last = self.in_contact.iter().peekable();
        let mut springs = self.stick.iter().map(|s| &s.0).enumerate().peekable();
        for c in &self.candidates {
            while last.next_if(|&p| p < c).is_some() {}
            self.was_in_contact.push(last.peek().is_some_and(|&p| p == c));
            while springs.next_if(|&(_, p)| p < c).is_some() {}
            let spring = springs.peek().filter(|&&(_, p)| p == c);
            self.spring_of.push(spring.map_or(NO_SPRING, |&(i, _)| i as u32));
        }
        lap(&mut clock, &mut self.clock.detection);
        let precomputed = geometry.and_then(|g| {
            let asked = self.ask_geometry(model, x, g);
            lap(&mut clock, &mut self.clock.geometry);
            asked
        });
        let inputs = Candidates {
            model,
            x,
            v,
            dt,
            sizes: &self.sizes,
            certifying,
            anchor: &self.certificates.anchor,
            drifts: &self.drifts,
            newly: self.newly.any().then_some(&self.newly),
            penalty: self.settings.penalty,
            n_total: Real::from(self.settings.ramp_steps),
            negligible: self.settings.negligible,
            activation: self.settings.activation,
            model_kind: self.settings.model,
            friction: &self.friction,
            stick: &self.stick,
            ramp: &self.ramp,
            started: &self.started,
            precomputed: precomputed.as_ref(),
            held: &self.held,
            primed: self.primed,
        };
        // Last pass's forces freed in parallel (`collect_into_vec` would
        // drop them one by one).
        self.results.par_iter_mut().for_each(|r| r.0 = None);
        let candidates = self
            .candidates
            .par_iter()
            .enumerate()
            .zip(self.certificates.cached.par_iter())
            .zip(self.was_in_contact.par_iter())
            .zip(self.spring_of.par_iter())
            .map(|((((k, &pair), &radius), &clip_first), &spring)| (k, pair, radius, clip_first, spring));
        inputs.evaluate_all(self.path, candidates, &mut self.results);
        let orphans =
            if self.settings.model == ContactModel::Gradient { self.orphans(model, x, v, dt) } else { Vec::new() };
        self.sum_into_nodes(model, &orphans, v, certifying);
        self.keep_asked(precomputed);
        // Eq. 18: n_c counts the steps since the joint failed.
        let n_total = self.settings.ramp_steps;
        self.ramp.retain(|_, n_c| {
            *n_c += 1;
            *n_c <= n_total
        });
        // Springs of pairs no longer in contact are dropped, and so are the
        // pairs that started overlapped once they separate.
        std::mem::swap(&mut self.stick, &mut self.stick_next);
        self.stick_next.clear();
        std::mem::swap(&mut self.started, &mut self.started_next);
        self.started_next.clear();
        std::mem::swap(&mut self.held, &mut self.held_next);
        self.held_next.clear();
        self.primed = true;
        self.newly.clear();
        lap(&mut clock, &mut self.clock.pairs);
    }

    /// The pairs in contact now that started overlapped (see
    /// [`Activation`]).
    pub fn started_pairs(&self) -> usize {
        self.started.len()
    }

    /// The work the normal contact forces have absorbed up to `t_n` of the
    /// last pass, J, with what the failed joints handed over counted as
    /// absorbed ([`ContactEnergy::handed`]): [`ContactEnergy::contact`] less
    /// the friction springs' energy plus the handed energy. Negative when
    /// contact has given back more than it took and the joints held.
    ///
    /// `energy` is the ledger's contact account
    /// ([`crate::Solver::contact_energy`]).
    pub fn normal_work(&self, energy: &ContactEnergy) -> Real {
        energy.contact - self.spring_energy + energy.handed()
    }
}
