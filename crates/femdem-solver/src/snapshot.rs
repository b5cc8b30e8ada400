//! Snapshots of a solver's evolving state, for checkpoints and restart:
//! [`Solver::snapshot`] writes everything a step reads that an earlier step
//! wrote, and [`Solver::restore`] puts it back into a solver built from the
//! same model, loads and settings, which then continues bit for bit as the
//! original would have.
//!
//! What is saved: the node state (`x_n`, `v_{n−½}`, `t_n`, `n`; with
//! viscous materials `v_{n−3/2}` too, which the dissipation reads) and every
//! joint's history (damage at each integration point, last opening, slip
//! and tractions, softened flags, work, failed flag); the energy account
//! with the half step of work it holds over (in all, per surface load and per drive) and its watch
//! (`crate::account`);
//! the failure record; the last [`StepRecord`] (it carries the failure
//! counts); the contact pass's state (contactable tets, cracked vertices
//! and their pieces, bonded pairs, the candidates with the watched nodes'
//! reference positions, whether a full detection is due, the tets pending
//! an incremental one, the
//! friction springs, the Eq. 18 ramp counters, the nodes touched by the
//! last pass with their forces and velocities, the contact energy
//! account and counters). What is not: the model, the loads and the
//! settings (the caller builds them again from the same input), scratch
//! buffers that every step overwrites before reading (forces, NBS grids,
//! per-chunk sums, surface-load forces, drive targets), and the tet
//! stresses kept for output (recomputed by every step that asks for them).
//!
//! The encoding is a plain little-endian byte stream (the [`Encoder`] and
//! [`Decoder`] here, public so that a caller can frame a snapshot with its
//! own data): integers as `u64`/`u32`, `f64` by its bits, so every value
//! round-trips exactly; hash maps are written sorted by key, so a snapshot
//! is a function of the state alone. It starts with [`SNAPSHOT_VERSION`];
//! a snapshot of another version, of a model of another size, or a
//! truncated one is refused with [`SolverError::Snapshot`].

use femdem_core::Vec3;
use femdem_fracture::{FailureMode, JointHistory, Softened};

use crate::SolverError;
use crate::account::{Account, Imbalance};
use crate::state::{Energies, Failure};
use crate::step::{Solver, StepRecord};

/// The version of the snapshot layout written by [`Solver::snapshot`].
///
/// 2: the energy account centred on `t_n` (the half step of work held
/// over, the watch on the balance, the velocities of the step before).
/// 3: incremental contact detection (the tets pending an addition and the
/// count of additions; each watched node's reference position is where it
/// was at the last full detection or at the addition that made it watched).
/// 4: each surface load's work (in the record) and its half step held over
/// (in the account).
/// 5: each drive's work (in the record) and its half step held over (in the
/// account).
/// 6: contact's pairs that started overlapped, with their offsets, and the
/// work their normal forces did (`ContactSettings::activation`).
/// 7: the compression energy the failed joints handed to contact
/// (`ContactEnergy::held`), and the energy the pairs in contact hold
/// (`Contact::potential`, `ContactModel::Gradient`).
/// 8: the certificates of contact's negligible pairs (each candidate's
/// radius, the watched nodes' anchors, the epoch's age and counts).
pub const SNAPSHOT_VERSION: u32 = 8;

/// Writes values to a little-endian byte stream.
#[derive(Debug, Default)]
pub struct Encoder {
    bytes: Vec<u8>,
}

impl Encoder {
    /// An empty stream.
    pub fn new() -> Encoder {
        Encoder::default()
    }

    /// The bytes written.
    pub fn into_bytes(self) -> Vec<u8> {
        self.bytes
    }

    /// Raw bytes, as they are.
    pub fn raw(&mut self, b: &[u8]) {
        self.bytes.extend_from_slice(b);
    }

    /// A `u8`.
    pub fn u8(&mut self, x: u8) {
        self.bytes.push(x);
    }

    /// A `bool` as one byte, 0 or 1.
    pub fn bool(&mut self, x: bool) {
        self.u8(u8::from(x));
    }

    /// A `u32`.
    pub fn u32(&mut self, x: u32) {
        self.raw(&x.to_le_bytes());
    }

    /// A `u64`.
    pub fn u64(&mut self, x: u64) {
        self.raw(&x.to_le_bytes());
    }

    /// A count (a length or an index), as a `u64`.
    pub fn count(&mut self, x: usize) {
        self.u64(x as u64);
    }

    /// An `f64` by its bits (exact).
    pub fn f64(&mut self, x: f64) {
        self.u64(x.to_bits());
    }

    /// A vector of three `f64`.
    pub fn vec3(&mut self, v: &Vec3) {
        for k in 0..3 {
            self.f64(v[k]);
        }
    }

    /// A length-prefixed byte string.
    pub fn bytes(&mut self, b: &[u8]) {
        self.count(b.len());
        self.raw(b);
    }

    /// A length-prefixed list of `f64`.
    pub fn f64s(&mut self, xs: &[f64]) {
        self.count(xs.len());
        xs.iter().for_each(|&x| self.f64(x));
    }

    /// A length-prefixed list of vectors.
    pub fn vec3s(&mut self, vs: &[Vec3]) {
        self.count(vs.len());
        vs.iter().for_each(|v| self.vec3(v));
    }

    /// A length-prefixed list of `u32`.
    pub fn u32s(&mut self, xs: &[u32]) {
        self.count(xs.len());
        xs.iter().for_each(|&x| self.u32(x));
    }

    /// A length-prefixed list of `bool`.
    pub fn bools(&mut self, xs: &[bool]) {
        self.count(xs.len());
        xs.iter().for_each(|&x| self.bool(x));
    }
}

/// Reads what an [`Encoder`] wrote; every read fails with
/// [`SolverError::Snapshot`] past the end or on a value out of range.
#[derive(Debug)]
pub struct Decoder<'a> {
    bytes: &'a [u8],
    at: usize,
}

impl<'a> Decoder<'a> {
    /// A reader at the start of `bytes`.
    pub fn new(bytes: &'a [u8]) -> Decoder<'a> {
        Decoder { bytes, at: 0 }
    }

    /// Bytes not read yet.
    pub fn remaining(&self) -> usize {
        self.bytes.len() - self.at
    }

    /// `n` raw bytes.
    pub fn raw(&mut self, n: usize) -> Result<&'a [u8], SolverError> {
        if n > self.remaining() {
            return Err(snapshot_error(format!(
                "truncated: {n} bytes needed at byte {}, {} left",
                self.at,
                self.remaining()
            )));
        }
        let b = &self.bytes[self.at..self.at + n];
        self.at += n;
        Ok(b)
    }

    fn array<const N: usize>(&mut self) -> Result<[u8; N], SolverError> {
        Ok(self.raw(N)?.try_into().expect("N bytes"))
    }

    /// A `u8`.
    pub fn u8(&mut self) -> Result<u8, SolverError> {
        Ok(self.array::<1>()?[0])
    }

    /// A `bool` (0 or 1).
    pub fn bool(&mut self) -> Result<bool, SolverError> {
        match self.u8()? {
            0 => Ok(false),
            1 => Ok(true),
            b => Err(snapshot_error(format!("a flag of value {b} at byte {}", self.at - 1))),
        }
    }

    /// A `u32`.
    pub fn u32(&mut self) -> Result<u32, SolverError> {
        Ok(u32::from_le_bytes(self.array()?))
    }

    /// A `u64`.
    pub fn u64(&mut self) -> Result<u64, SolverError> {
        Ok(u64::from_le_bytes(self.array()?))
    }

    /// A count (a length or an index); one larger than the bytes left (each
    /// element takes at least one byte) is refused before anything is
    /// allocated for it.
    pub fn count(&mut self) -> Result<usize, SolverError> {
        let n = self.u64()?;
        if n > self.remaining() as u64 {
            return Err(snapshot_error(format!("a length of {n} at byte {} exceeds the data", self.at - 8)));
        }
        Ok(n as usize)
    }

    /// An `f64`.
    pub fn f64(&mut self) -> Result<f64, SolverError> {
        Ok(f64::from_bits(self.u64()?))
    }

    /// A vector of three `f64`.
    pub fn vec3(&mut self) -> Result<Vec3, SolverError> {
        Ok(Vec3::new(self.f64()?, self.f64()?, self.f64()?))
    }

    /// A length-prefixed byte string.
    pub fn bytes(&mut self) -> Result<&'a [u8], SolverError> {
        let n = self.count()?;
        self.raw(n)
    }

    /// A length-prefixed list of `f64`.
    pub fn f64s(&mut self) -> Result<Vec<f64>, SolverError> {
        let n = self.count()?;
        (0..n).map(|_| self.f64()).collect()
    }

    /// A length-prefixed list of vectors.
    pub fn vec3s(&mut self) -> Result<Vec<Vec3>, SolverError> {
        let n = self.count()?;
        (0..n).map(|_| self.vec3()).collect()
    }

    /// A length-prefixed list of `u32`.
    pub fn u32s(&mut self) -> Result<Vec<u32>, SolverError> {
        let n = self.count()?;
        (0..n).map(|_| self.u32()).collect()
    }

    /// A length-prefixed list of `bool`.
    pub fn bools(&mut self) -> Result<Vec<bool>, SolverError> {
        let n = self.count()?;
        (0..n).map(|_| self.bool()).collect()
    }

    /// Fails unless every byte has been read.
    pub fn finish(&self) -> Result<(), SolverError> {
        match self.remaining() {
            0 => Ok(()),
            n => Err(snapshot_error(format!("{n} bytes left over at the end"))),
        }
    }
}

/// A [`SolverError::Snapshot`].
pub(crate) fn snapshot_error(what: impl Into<String>) -> SolverError {
    SolverError::Snapshot(what.into())
}

/// Fails unless a count read from a snapshot equals the solver's own.
pub(crate) fn expect_count(what: &str, found: usize, expected: usize) -> Result<(), SolverError> {
    if found == expected {
        Ok(())
    } else {
        Err(snapshot_error(format!("{what}: {found} in the snapshot, {expected} in this solver")))
    }
}

fn put_joint(e: &mut Encoder, h: &JointHistory) {
    h.damage.iter().for_each(|&d| e.f64(d));
    e.f64(h.dissipated);
    e.f64(h.released);
    e.f64(h.work);
    h.last.iter().flatten().for_each(|&x| e.f64(x));
    h.last_stress.iter().flatten().for_each(|&x| e.f64(x));
    for s in &h.softened {
        e.bool(s.normal);
        e.bool(s.shear);
    }
    e.bool(h.failed);
}

fn get_joint(d: &mut Decoder<'_>) -> Result<JointHistory, SolverError> {
    let mut h = JointHistory::default();
    for x in &mut h.damage {
        *x = d.f64()?;
    }
    h.dissipated = d.f64()?;
    h.released = d.f64()?;
    h.work = d.f64()?;
    for x in h.last.iter_mut().flatten() {
        *x = d.f64()?;
    }
    for x in h.last_stress.iter_mut().flatten() {
        *x = d.f64()?;
    }
    for s in &mut h.softened {
        *s = Softened { normal: d.bool()?, shear: d.bool()? };
    }
    h.failed = d.bool()?;
    Ok(h)
}

fn put_energies(e: &mut Encoder, x: &Energies) {
    for v in [x.kinetic, x.tet_elastic, x.joint_elastic, x.damping, x.external_work, x.fracture, x.contact, x.friction]
    {
        e.f64(v);
    }
}

fn get_energies(d: &mut Decoder<'_>) -> Result<Energies, SolverError> {
    Ok(Energies {
        kinetic: d.f64()?,
        tet_elastic: d.f64()?,
        joint_elastic: d.f64()?,
        damping: d.f64()?,
        external_work: d.f64()?,
        fracture: d.f64()?,
        contact: d.f64()?,
        friction: d.f64()?,
    })
}

fn put_account(e: &mut Encoder, a: &Account) {
    e.f64(a.ahead);
    e.bool(a.initial.is_some());
    e.f64(a.initial.unwrap_or(0.0));
    e.f64(a.peak_held);
    e.bool(a.last.is_some());
    let last = a.last.unwrap_or(Imbalance { step: 0, time: 0.0, error: 0.0, scale: 0.0 });
    e.u64(last.step);
    [last.time, last.error, last.scale].into_iter().for_each(|x| e.f64(x));
    e.f64s(&a.surface_ahead);
    e.f64s(&a.drive_ahead);
}

fn get_account(d: &mut Decoder<'_>) -> Result<Account, SolverError> {
    let ahead = d.f64()?;
    let initial = (d.bool()?, d.f64()?);
    let peak_held = d.f64()?;
    let has_last = d.bool()?;
    let last = Imbalance { step: d.u64()?, time: d.f64()?, error: d.f64()?, scale: d.f64()? };
    let surface_ahead = d.f64s()?;
    let drive_ahead = d.f64s()?;
    Ok(Account {
        ahead,
        surface_ahead,
        drive_ahead,
        initial: initial.0.then_some(initial.1),
        peak_held,
        last: has_last.then_some(last),
    })
}

fn get_mode(d: &mut Decoder<'_>) -> Result<FailureMode, SolverError> {
    let code = d.u8()?;
    FailureMode::from_code(code).ok_or_else(|| snapshot_error(format!("unknown failure mode code {code}")))
}

fn put_record(e: &mut Encoder, r: &StepRecord) {
    e.u64(r.step);
    e.f64(r.time);
    e.vec3s(&r.drive_forces);
    e.vec3s(&r.drive_displacements);
    e.f64s(&r.drive_work);
    e.vec3s(&r.surface_forces);
    e.f64s(&r.surface_work);
    e.count(r.new_failures.start);
    e.count(r.new_failures.end);
    let c = &r.failures;
    [c.tensile, c.shear, c.mixed, c.collapsed].into_iter().for_each(|n| e.count(n));
    put_energies(e, &r.energies);
    e.bool(r.energies_current);
    e.count(r.contact_pairs);
}

fn get_record(d: &mut Decoder<'_>, like: &StepRecord) -> Result<StepRecord, SolverError> {
    let step = d.u64()?;
    let time = d.f64()?;
    let drive_forces = d.vec3s()?;
    let drive_displacements = d.vec3s()?;
    let drive_work = d.f64s()?;
    let surface_forces = d.vec3s()?;
    let surface_work = d.f64s()?;
    expect_count("drives", drive_forces.len(), like.drive_forces.len())?;
    expect_count("drive displacements", drive_displacements.len(), like.drive_displacements.len())?;
    expect_count("drives' work", drive_work.len(), like.drive_work.len())?;
    expect_count("surface loads", surface_forces.len(), like.surface_forces.len())?;
    expect_count("surface loads' work", surface_work.len(), like.surface_work.len())?;
    let new_failures = d.count()?..d.count()?;
    let failures =
        crate::FailureCounts { tensile: d.count()?, shear: d.count()?, mixed: d.count()?, collapsed: d.count()? };
    Ok(StepRecord {
        step,
        time,
        drive_forces,
        drive_displacements,
        drive_work,
        surface_forces,
        surface_work,
        new_failures,
        failures,
        energies: get_energies(d)?,
        energies_current: d.bool()?,
        contact_pairs: d.count()?,
    })
}

impl Solver {
    /// The solver's evolving state as bytes (see the module documentation
    /// of `snapshot.rs` for what is in it): give them to [`Solver::restore`]
    /// on a solver built from the same model, loads, time step and contact
    /// settings to continue bit for bit from here.
    pub fn snapshot(&self) -> Vec<u8> {
        let mut e = Encoder::new();
        e.u32(SNAPSHOT_VERSION);
        e.f64(self.dt());
        let s = &self.evolving.state;
        e.vec3s(&s.x);
        e.vec3s(&s.v);
        e.vec3s(&self.evolving.v_before);
        e.f64(s.time);
        e.u64(s.step);
        e.count(s.joints.len());
        s.joints.iter().for_each(|h| put_joint(&mut e, h));
        put_energies(&mut e, self.energies());
        put_account(&mut e, &self.evolving.account);
        e.count(self.failures().len());
        for f in self.failures() {
            e.u32(f.joint);
            e.f64(f.time);
            e.vec3(&f.centroid);
            e.f64(f.area);
            e.u8(f.mode.code());
        }
        put_record(&mut e, self.record());
        match self.contact() {
            Some(c) => {
                e.bool(true);
                c.encode(&mut e);
            }
            None => e.bool(false),
        }
        e.into_bytes()
    }

    /// Puts back the state of a [`Solver::snapshot`]. The solver must have
    /// been built as the one that took it (same model, loads, time step,
    /// contact on or off with the same settings); nothing is changed unless
    /// the whole snapshot reads.
    ///
    /// # Errors
    /// [`SolverError::Snapshot`] for another layout version, a truncated or
    /// malformed snapshot, or one whose sizes (nodes, joints, tets, drives,
    /// loads), time step or contact do not match this solver.
    pub fn restore(&mut self, bytes: &[u8]) -> Result<(), SolverError> {
        let mut d = Decoder::new(bytes);
        let version = d.u32()?;
        if version != SNAPSHOT_VERSION {
            return Err(snapshot_error(format!("layout version {version}; this build reads {SNAPSHOT_VERSION}")));
        }
        let dt = d.f64()?;
        if dt.to_bits() != self.dt().to_bits() {
            return Err(snapshot_error(format!(
                "time step {dt:e} s in the snapshot, {:e} s in this solver",
                self.dt()
            )));
        }
        let n = self.scene.model.num_nodes();
        let x = d.vec3s()?;
        expect_count("nodes", x.len(), n)?;
        let v = d.vec3s()?;
        expect_count("velocities", v.len(), n)?;
        let v_before = d.vec3s()?;
        expect_count("velocities of the step before", v_before.len(), self.evolving.v_before.len())?;
        let time = d.f64()?;
        let step = d.u64()?;
        let n_joints = d.count()?;
        expect_count("joints", n_joints, self.scene.model.joints.len())?;
        let joints = (0..n_joints).map(|_| get_joint(&mut d)).collect::<Result<Vec<_>, _>>()?;
        let energies = get_energies(&mut d)?;
        let account = get_account(&mut d)?;
        expect_count(
            "surface loads (work held over)",
            account.surface_ahead.len(),
            self.evolving.account.surface_ahead.len(),
        )?;
        expect_count("drives (work held over)", account.drive_ahead.len(), self.evolving.account.drive_ahead.len())?;
        let n_failures = d.count()?;
        let mut failures = Vec::with_capacity(n_failures);
        for _ in 0..n_failures {
            let joint = d.u32()?;
            if joint as usize >= n_joints {
                return Err(snapshot_error(format!("a failure of joint {joint}, but the model has {n_joints}")));
            }
            failures.push(Failure {
                joint,
                time: d.f64()?,
                centroid: d.vec3()?,
                area: d.f64()?,
                mode: get_mode(&mut d)?,
            });
        }
        let record = get_record(&mut d, self.record())?;
        let has_contact = d.bool()?;
        let contact = match (has_contact, self.contact()) {
            (true, Some(c)) => Some(c.decoded(&self.scene.model, &mut d)?),
            (false, None) => None,
            (true, None) => return Err(snapshot_error("the snapshot has contact, this solver has none")),
            (false, Some(_)) => return Err(snapshot_error("the snapshot has no contact, this solver has")),
        };
        d.finish()?;
        self.evolving.state.x = x;
        self.evolving.state.v = v;
        self.evolving.v_before = v_before;
        self.evolving.state.time = time;
        self.evolving.state.step = step;
        self.evolving.state.joints = joints;
        self.put_back(energies, failures, record, contact, account);
        // The pipeline is not in the snapshot: what an earlier step of this
        // solver left there belongs to another state.
        self.pipeline.workspace.internal.fill(Vec3::zeros());
        self.pipeline.forces_current = false;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn values_round_trip_bit_for_bit() {
        let mut e = Encoder::new();
        let xs = [0.1, -0.0, f64::MIN_POSITIVE / 3.0, f64::NAN, f64::INFINITY, 1e300];
        e.f64s(&xs);
        e.vec3(&Vec3::new(1.0 / 3.0, -2.5e-300, 7.0));
        e.u32s(&[0, u32::MAX]);
        e.bools(&[true, false]);
        e.bytes(b"case");
        let bytes = e.into_bytes();
        let mut d = Decoder::new(&bytes);
        let back = d.f64s().unwrap();
        assert_eq!(back.iter().map(|x| x.to_bits()).collect::<Vec<_>>(), xs.map(f64::to_bits).to_vec());
        assert_eq!(d.vec3().unwrap(), Vec3::new(1.0 / 3.0, -2.5e-300, 7.0));
        assert_eq!(d.u32s().unwrap(), vec![0, u32::MAX]);
        assert_eq!(d.bools().unwrap(), vec![true, false]);
        assert_eq!(d.bytes().unwrap(), b"case");
        d.finish().unwrap();
    }

    #[test]
    fn every_truncation_is_an_error_not_a_panic() {
        let mut e = Encoder::new();
        e.f64s(&[1.0, 2.0]);
        e.bytes(b"abc");
        let bytes = e.into_bytes();
        for cut in 0..bytes.len() {
            let mut d = Decoder::new(&bytes[..cut]);
            let r = d.f64s().and_then(|_| d.bytes().map(|_| ()));
            assert!(matches!(r, Err(SolverError::Snapshot(_))), "cut at {cut}: {r:?}");
        }
    }

    #[test]
    fn a_huge_length_is_refused_before_allocating() {
        let mut e = Encoder::new();
        e.u64(u64::MAX);
        let bytes = e.into_bytes();
        let err = Decoder::new(&bytes).f64s().unwrap_err();
        assert!(err.to_string().contains("exceeds the data"), "{err}");
    }
}
