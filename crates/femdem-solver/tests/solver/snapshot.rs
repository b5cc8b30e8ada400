//! A solver restored from a snapshot continues bit for bit as the one that
//! took it (`Solver::snapshot`, `Solver::restore`): a jointed block sheared
//! and pressed by its top until joints fail, with contact (friction 0.6,
//! a detection buffer, so the candidates, the watched nodes' reference
//! positions and the count of incremental additions are part of the state;
//! failures have added candidates incrementally both before and after the
//! snapshot, asserted) stepped 300 steps, snapshot, then 300 more; a
//! second solver built the same way and restored from the snapshot takes
//! the same 300 steps and ends in the same bits — positions, velocities,
//! joint histories, energies and the watch on their balance, the failure
//! record, the step record and the contact pass's whole state (its own
//! snapshot). The snapshot is taken
//! while joints fail and pairs are in contact (asserted), and the steps
//! ask for energies and stresses on an irregular schedule, as a run's
//! output does.

use crate::common::sheared_block;
use femdem_solver::{Solver, SolverError, Want};

/// The block of these tests: a 0.2 mm buffer, incremental detection.
fn block(size: [f64; 3]) -> Solver {
    sheared_block(size, 2e-4, true)
}

fn want(n: u64) -> Want {
    Want { energy: n.is_multiple_of(7), stress: n % 50 == 3 }
}

#[test]
fn a_restored_solver_continues_bit_for_bit() {
    let size = [0.02, 0.01, 0.02];
    let mut a = block(size);
    for n in 0..300 {
        a.step(want(n));
    }
    let failed = a.failures().len();
    let pairs = a.contact().unwrap().active_pairs;
    assert!(failed > 0 && pairs > 0, "the snapshot must be taken with joints failed ({failed}) and contacts ({pairs})");
    let additions = a.contact().unwrap().additions;
    assert!(additions > 0, "failures must have added candidates incrementally before the snapshot");
    let snap = a.snapshot();

    let mut b = block(size);
    b.restore(&snap).unwrap();
    assert!(b.snapshot() == snap, "restoring then snapshotting gives other bytes");
    for n in 300..600 {
        a.step(want(n));
        b.step(want(n));
    }
    assert!(a.failures().len() > failed, "joints keep failing after the snapshot");
    assert!(b.contact().unwrap().additions > additions, "and add candidates after it");
    assert_eq!(a.state(), b.state(), "positions, velocities, joint histories");
    assert_eq!(a.energies(), b.energies());
    assert_eq!(a.imbalance(), b.imbalance(), "the energy watch");
    assert_eq!(a.failures(), b.failures());
    assert_eq!(a.record(), b.record());
    assert!(a.snapshot() == b.snapshot(), "the whole state, contact included, differs");
}

#[test]
fn a_snapshot_of_another_layout_version_is_refused_by_name() {
    let mut a = block([0.02, 0.01, 0.02]);
    a.step(Want::default());
    let version = femdem_solver::snapshot::SNAPSHOT_VERSION;
    let mut snap = a.snapshot();
    // The version is the first value, a varint: one byte below 128.
    assert_eq!(snap[0] as u32, version);
    snap[0] = (version - 1) as u8;
    let before = a.snapshot();
    let err = a.restore(&snap).unwrap_err().to_string();
    let expected = format!("layout version {}; this build reads {version}", version - 1);
    assert!(err.contains(&expected), "{err}");
    // A hand-written snapshot of layout 8 began with the version as a
    // little-endian u32.
    let mut old = 8u32.to_le_bytes().to_vec();
    old.extend_from_slice(&snap[1..]);
    let err = a.restore(&old).unwrap_err().to_string();
    assert!(err.contains(&format!("layout version 8; this build reads {version}")), "{err}");
    assert!(a.snapshot() == before, "a refused snapshot changed the solver");
}

#[test]
fn a_snapshot_of_another_model_or_a_truncated_one_is_refused() {
    let mut a = block([0.02, 0.01, 0.02]);
    a.step(Want::default());
    let snap = a.snapshot();
    let mut other = block([0.02, 0.01, 0.01]);
    let err = other.restore(&snap).unwrap_err();
    assert!(matches!(err, SolverError::Snapshot(_)), "{err}");
    let before = other.snapshot();
    let mut same = block([0.02, 0.01, 0.02]);
    for cut in [0, 4, snap.len() / 2, snap.len() - 1] {
        let err = same.restore(&snap[..cut]).unwrap_err();
        assert!(err.to_string().starts_with("snapshot: "), "cut at {cut}: {err}");
    }
    assert!(other.snapshot() == before, "a refused snapshot changed the solver");
}

/// A writer that takes `room` bytes and then fails as a full disk does.
struct Full {
    room: usize,
}

impl std::io::Write for Full {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        if self.room == 0 {
            return Err(std::io::Error::new(std::io::ErrorKind::StorageFull, "no space left on device"));
        }
        let n = buf.len().min(self.room);
        self.room -= n;
        Ok(n)
    }

    fn flush(&mut self) -> std::io::Result<()> {
        Ok(())
    }
}

#[test]
fn a_failed_write_reports_the_writers_own_error() {
    let mut a = block([0.02, 0.01, 0.02]);
    a.step(Want::default());
    let size = a.snapshot().len();
    for room in [0, 10, size / 2] {
        let err = a.write_snapshot(Full { room }).unwrap_err();
        assert_eq!(err.kind(), std::io::ErrorKind::StorageFull, "room {room}: {err}");
        assert!(err.to_string().contains("no space left"), "{err}");
    }
    let mut all = Vec::new();
    a.write_snapshot(&mut all).unwrap();
    assert!(all == a.snapshot());
}
