//! Where the host's time around the device goes, by read-back: for each
//! kind of read-back (the resident stage-1 forces, the update, the contact
//! pairs, the rest — a stage 1 that is not resident reads its forces as
//! the rest), the host's wall time to submit it, to wait for the device
//! (its kernels and the copy into host-visible memory), and to read the
//! mapped bytes (copied out, or decoded in place), with the bytes read,
//! and the pairs' upload with the bytes sent. A measurement (`femdem run`'s
//! `read-backs` line, `gpu_contact`), never part of a result:
//! [`crate::Gpu::take_transfers`].

use std::sync::Mutex;
use std::time::Duration;

/// Which read-back a phase belongs to.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ReadBack {
    /// Stage 1 on the device: failures, the listed and the watched nodes.
    Forces,
    /// Stage 5: the update's sums and the contact nodes' new state.
    Update,
    /// The contact pairs' Eq. 17 contacts (`Bulk::pair_geometry`).
    Pairs,
    /// Any other (outputs, failures' details, timings).
    Other,
}

/// A part of a read-back.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Part {
    /// Writing the inputs and recording the kernels (the pairs only).
    Upload,
    /// Finishing the commands and submitting them.
    Submit,
    /// Waiting until the device has run them and copied the results into
    /// host-visible memory.
    Wait,
    /// Reading the mapped bytes: copying them out, or decoding them into
    /// the caller's kept memory (the stage-1 forces, the pairs).
    Read,
}

/// The host's time in one part of one kind of read-back since the last
/// [`crate::Gpu::take_transfers`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Phase {
    /// Which read-back.
    pub read_back: ReadBack,
    /// Which part of it.
    pub part: Part,
    /// How many times.
    pub calls: u64,
    /// Bytes read back (0 for parts that read none).
    pub bytes: u64,
    /// Wall time in all, s.
    pub seconds: f64,
}

impl Phase {
    /// Its name in a summary line, e.g. `pairs wait`.
    pub fn name(&self) -> String {
        let read_back = match self.read_back {
            ReadBack::Forces => "forces",
            ReadBack::Update => "update",
            ReadBack::Pairs => "pairs",
            ReadBack::Other => "other",
        };
        let part = match self.part {
            Part::Upload => "upload",
            Part::Submit => "submit",
            Part::Wait => "wait",
            Part::Read => "read",
        };
        format!("{read_back} {part}")
    }
}

/// The phases, in the order first seen.
#[derive(Debug, Default)]
pub(crate) struct Log(Mutex<Vec<Phase>>);

impl Log {
    /// Adds one call of `part` of `read_back` that took `took` and read
    /// `bytes`.
    pub fn add(&self, read_back: ReadBack, part: Part, bytes: u64, took: Duration) {
        let mut phases = self.0.lock().expect("the transfer log");
        let seconds = took.as_secs_f64();
        match phases.iter_mut().find(|p| p.read_back == read_back && p.part == part) {
            Some(p) => {
                p.calls += 1;
                p.bytes += bytes;
                p.seconds += seconds;
            }
            None => phases.push(Phase { read_back, part, calls: 1, bytes, seconds }),
        }
    }

    /// The phases so far, emptying the log.
    pub fn take(&self) -> Vec<Phase> {
        std::mem::take(&mut *self.0.lock().expect("the transfer log"))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn calls_of_one_part_add_up_and_taking_empties_the_log() {
        let log = Log::default();
        log.add(ReadBack::Pairs, Part::Wait, 240, Duration::from_millis(2));
        log.add(ReadBack::Forces, Part::Wait, 48, Duration::from_millis(1));
        log.add(ReadBack::Pairs, Part::Wait, 480, Duration::from_millis(3));
        let phases = log.take();
        assert_eq!(phases.len(), 2);
        assert_eq!((phases[0].read_back, phases[0].calls, phases[0].bytes), (ReadBack::Pairs, 2, 720));
        assert!((phases[0].seconds - 0.005).abs() < 1e-12);
        assert_eq!((phases[1].read_back, phases[1].calls), (ReadBack::Forces, 1));
        assert_eq!((phases[0].name().as_str(), phases[1].name().as_str()), ("pairs wait", "forces wait"));
        assert!(log.take().is_empty());
    }
}
