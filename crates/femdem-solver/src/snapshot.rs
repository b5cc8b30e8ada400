//! Snapshots of a solver's evolving state, for checkpoints and restart:
//! [`Solver::snapshot`] writes everything a step reads that an earlier step
//! wrote, and [`Solver::restore`] puts it back into a solver built from the
//! same model, loads and settings, which then continues bit for bit as the
//! original would have.
//!
//! A snapshot is the evolving state (`crate::step::Evolving`) serialised
//! with serde in postcard's format: the node state (`x_n`, `v_{n−½}`,
//! `t_n`, `n`; with viscous materials `v_{n−3/2}` too, which the
//! dissipation reads), every joint's history, the ledger (every work and
//! energy term with its held-over half step, and the watch on the balance:
//! `crate::ledger`), the failure record, the last [`StepRecord`], and the
//! contact pass's evolving state (`SavedContact`). It is not the model,
//! the loads or the settings (the caller builds them again from the same
//! input), nor the pipeline: buffers every step overwrites before reading,
//! and the tet stresses kept for output.
//!
//! postcard writes an `f64` by its eight bytes, so every value
//! round-trips exactly; integers as varints; hash maps are written sorted
//! by key, so a snapshot is a function of the state alone. It starts with
//! [`SNAPSHOT_VERSION`]; a snapshot of another version, of a model of
//! another size, or a truncated or malformed one is refused with
//! [`SolverError::Snapshot`], and the solver is left as it was.

use femdem_core::{Real, Vec3};
use serde::{Deserialize, Serialize};

use crate::SolverError;
use crate::contact::SavedContact;
use crate::ledger::Ledger;
use crate::state::{Failure, State};
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
/// 7: the compression energy the failed joints handed over to contact
/// (`ContactEnergy::held`), and the energy the pairs in contact hold
/// (`Contact::potential`, `ContactModel::Gradient`).
/// 8: the certificates of contact's negligible pairs (each candidate's
/// radius, the watched nodes' anchors, the epoch's age and counts).
/// 9: serde (postcard) instead of a hand-written layout; one ledger of
/// every work term (gravity's, each load's, each drive's, a static start's
/// and the kicks', contact's), from which the external work is summed.
/// 10: what the energy-conserving contact's followed pairs leave for its
/// energy-consistent kicks (applied forces, energies, debts;
/// `contact/onset.rs`).
pub const SNAPSHOT_VERSION: u32 = 10;

/// A snapshot as written: the evolving state, borrowed.
#[derive(Serialize)]
struct Written<'a> {
    version: u32,
    dt: Real,
    state: &'a State,
    v_before: &'a [Vec3],
    ledger: &'a Ledger,
    failures: &'a [Failure],
    record: &'a StepRecord,
    contact: Option<SavedContact>,
}

/// A snapshot as read (the fields of [`Written`], in its order).
#[derive(Deserialize)]
struct Read {
    version: u32,
    dt: Real,
    state: State,
    v_before: Vec<Vec3>,
    ledger: Ledger,
    failures: Vec<Failure>,
    record: StepRecord,
    contact: Option<SavedContact>,
}

/// A writer that keeps the first error its inner writer returned.
struct Keeping<W> {
    inner: W,
    error: Option<std::io::Error>,
}

impl<W: std::io::Write> std::io::Write for Keeping<W> {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        self.inner.write(buf).inspect_err(|e| {
            self.error.get_or_insert_with(|| std::io::Error::new(e.kind(), e.to_string()));
        })
    }

    fn flush(&mut self) -> std::io::Result<()> {
        self.inner.flush().inspect_err(|e| {
            self.error.get_or_insert_with(|| std::io::Error::new(e.kind(), e.to_string()));
        })
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

impl Solver {
    /// The solver's evolving state as bytes (see the module documentation
    /// of `snapshot.rs` for what is in it): give them to [`Solver::restore`]
    /// on a solver built from the same model, loads, time step and contact
    /// settings to continue bit for bit from here.
    pub fn snapshot(&self) -> Vec<u8> {
        let mut out = Vec::new();
        self.write_snapshot(&mut out)
            .expect("writing to memory (with the state on a device, call Solver::sync_device first)");
        out
    }

    /// [`Solver::snapshot`] streamed to `w`, without the whole snapshot in
    /// memory (the contact pass's state excepted).
    ///
    /// # Errors
    /// What writing to `w` fails with; with the bulk on a device
    /// ([`Solver::use_device`]), a state whose joint histories have not been
    /// brought back by [`Solver::sync_device`] since the last step.
    pub fn write_snapshot(&self, w: impl std::io::Write) -> std::io::Result<()> {
        if self.pipeline.device.as_ref().is_some_and(|d| !d.synced) {
            // The joint histories are on the device: writing the host's
            // would lose them without a word.
            return Err(std::io::Error::other(
                "the joint histories are on the device: call Solver::sync_device before writing a snapshot",
            ));
        }
        let e = &self.evolving;
        let written = Written {
            version: SNAPSHOT_VERSION,
            dt: self.dt(),
            state: &e.state,
            v_before: &e.v_before,
            ledger: &e.ledger,
            failures: &e.failures,
            record: &e.record,
            contact: e.contact.as_ref().map(|c| c.saved()),
        };
        let mut out = Keeping { inner: w, error: None };
        let result = postcard::to_io(&written, &mut out).map(|_| ());
        match result {
            Ok(_) => Ok(()),
            // postcard reports every failed write as a full buffer: give
            // back the writer's own error (a full disk, say).
            Err(_) if out.error.is_some() => Err(out.error.take().expect("checked")),
            Err(postcard::Error::SerdeSerCustom) => Err(std::io::Error::other("a value serde cannot write")),
            Err(other) => Err(std::io::Error::other(other)),
        }
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
        let (version, _) =
            postcard::take_from_bytes::<u32>(bytes).map_err(|e| snapshot_error(format!("no layout version: {e}")))?;
        if version != SNAPSHOT_VERSION {
            return Err(snapshot_error(format!("layout version {version}; this build reads {SNAPSHOT_VERSION}")));
        }
        let (read, rest) = postcard::take_from_bytes::<Read>(bytes)
            .map_err(|e| snapshot_error(format!("malformed or truncated: {e}")))?;
        if !rest.is_empty() {
            return Err(snapshot_error(format!("{} bytes left over at the end", rest.len())));
        }
        debug_assert_eq!(read.version, version);
        if read.dt.to_bits() != self.dt().to_bits() {
            return Err(snapshot_error(format!(
                "time step {:e} s in the snapshot, {:e} s in this solver",
                read.dt,
                self.dt()
            )));
        }
        let n = self.scene.model.num_nodes();
        let (state, mine) = (&read.state, &self.evolving);
        expect_count("nodes", state.x.len(), n)?;
        expect_count("velocities", state.v.len(), n)?;
        expect_count("velocities of the step before", read.v_before.len(), mine.v_before.len())?;
        let n_joints = self.scene.model.joints.len();
        expect_count("joints", state.joints.len(), n_joints)?;
        expect_count("surface loads' work", read.ledger.surfaces.len(), mine.ledger.surfaces.len())?;
        expect_count("drives' work", read.ledger.drives.len(), mine.ledger.drives.len())?;
        let (r, like) = (&read.record, &mine.record);
        expect_count("drives", r.drive_forces.len(), like.drive_forces.len())?;
        expect_count("drive displacements", r.drive_displacements.len(), like.drive_displacements.len())?;
        expect_count("drives' work (record)", r.drive_work.len(), like.drive_work.len())?;
        expect_count("surface loads", r.surface_forces.len(), like.surface_forces.len())?;
        expect_count("surface loads' work (record)", r.surface_work.len(), like.surface_work.len())?;
        if let Some(f) = read.failures.iter().find(|f| f.joint as usize >= n_joints) {
            return Err(snapshot_error(format!("a failure of joint {}, but the model has {n_joints}", f.joint)));
        }
        let new = &read.record.new_failures;
        if new.start > new.end || new.end > read.failures.len() {
            return Err(snapshot_error(format!(
                "the last step's new failures {new:?}, but {} failures",
                read.failures.len()
            )));
        }
        if read.contact.is_none() && read.ledger.contact != crate::ContactEnergy::default() {
            return Err(snapshot_error("contact energy terms in a snapshot without contact"));
        }
        let contact = match (read.contact, self.contact()) {
            (Some(saved), Some(c)) => Some(c.restored(&self.scene.model, saved)?),
            (None, None) => None,
            (Some(_), None) => return Err(snapshot_error("the snapshot has contact, this solver has none")),
            (None, Some(_)) => return Err(snapshot_error("the snapshot has no contact, this solver has")),
        };
        let e = &mut self.evolving;
        e.state = read.state;
        e.v_before = read.v_before;
        e.ledger = read.ledger;
        e.failures = read.failures;
        e.record = read.record;
        e.contact = contact;
        // The pipeline is not in the snapshot: what an earlier step of this
        // solver left there belongs to another state.
        self.pipeline.workspace.internal.fill(Vec3::zeros());
        self.pipeline.forces_current = false;
        if let Some(device) = &mut self.pipeline.device {
            // The host's state is the truth now: sent up before the next step.
            device.synced = true;
            device.edited = true;
        }
        Ok(())
    }
}
