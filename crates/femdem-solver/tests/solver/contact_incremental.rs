//! Incremental detection (`contact/incremental.rs`) gives the answers of a
//! full detection at every joint failure, bit for bit: the sheared block of
//! `common::sheared_block` (joints fail at most steps, friction 0.6 with
//! sticking and slipping springs) stepped 600 steps with incremental
//! detection on and off ends in the same positions, velocities, joint
//! histories, energies and watch on their balance, failure record and step
//! record. Two buffers: 0.2 mm, which the nodes never leave after the first
//! detection (every failure is an addition), and 0.02 mm, which they leave
//! every few dozen steps (full detections by the buffer come between
//! additions, and the watched nodes' references are of different steps).
//! The run with it on must have added candidates at failures and detected
//! in full less often than the other, which never added; both must have had
//! pairs in contact and friction at work, so that the comparison covers the
//! pair sums and the friction springs.

use crate::common::sheared_block;
use femdem_solver::{Solver, Want};

const SIZE: [f64; 3] = [0.02, 0.01, 0.02];
const STEPS: u64 = 600;

fn run(buffer: f64, incremental: bool) -> (Solver, usize) {
    let mut s = sheared_block(SIZE, buffer, incremental);
    let mut in_contact = 0;
    for n in 0..STEPS {
        s.step(Want { energy: n % 7 == 0, stress: false });
        in_contact += usize::from(s.contact().unwrap().active_pairs > 0);
    }
    (s, in_contact)
}

#[test]
fn incremental_detection_gives_the_bits_of_full_detection_at_every_failure() {
    for buffer in [2e-4, 2e-5] {
        let (full, in_contact) = run(buffer, false);
        let (incremental, _) = run(buffer, true);
        let (f, i) = (full.contact().unwrap(), incremental.contact().unwrap());
        eprintln!(
            "buffer {buffer:e} m: {} joints failed; full: {} detections; incremental: {} detections, {} additions; \
             {in_contact} steps in contact",
            full.failures().len(),
            f.detections,
            i.detections,
            i.additions
        );
        assert!(full.failures().len() > 10, "{} failures", full.failures().len());
        assert!(in_contact as u64 > STEPS / 4, "{in_contact} steps in contact");
        assert!(full.energies().friction > 0.0, "friction must act: {:?}", full.energies());
        assert_eq!(f.additions, 0, "the full run must not add");
        assert!(i.additions > 0, "the incremental run must add");
        assert!(i.detections < f.detections, "additions must replace full detections");
        if buffer < 1e-4 {
            assert!(i.detections > 3, "the small buffer must detect in full between additions: {}", i.detections);
        }
        assert!(full.state() == incremental.state(), "positions, velocities or joint histories differ");
        assert_eq!(full.energies(), incremental.energies());
        assert_eq!(full.imbalance(), incremental.imbalance());
        assert_eq!(full.failures(), incremental.failures());
        assert_eq!(full.record(), incremental.record());
    }
}
