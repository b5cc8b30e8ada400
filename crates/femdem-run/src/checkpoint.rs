//! Checkpoints of `femdem run`: the files `--resume` continues from.
//!
//! A checkpoint holds everything a run needs to continue bit for bit: the
//! solver's evolving state ([`femdem_solver::Solver::snapshot`]), the run
//! loop's schedule ([`Schedule`]: the next step, the next frame and history
//! row times, the post-peak watch) and how far the output had got
//! ([`Marks`]: the byte lengths of `history.csv` and `failures.csv`, the
//! times of the frames of both `.pvd` series), with the [`Identity`] of the
//! case that wrote it (hashes of the case text and of the jointed mesh, and
//! its `--set` overrides).
//!
//! File `checkpoint_{step:012}.femdem-ckpt` in the output directory,
//! little-endian:
//!
//! ```text
//! magic    8 bytes  "FEMDEMCK"
//! version  u32      FORMAT_VERSION
//! length   u64      bytes of the payload
//! checksum u64      FNV-1a 64 of the payload
//! payload           identity, schedule, marks (postcard), then the solver
//!                   snapshot (Solver::write_snapshot) to the end
//! ```
//!
//! The payload is serialised with serde in postcard's format: the
//! identity, schedule and marks, then the serialised evolving state
//! ([`femdem_solver::Solver::write_snapshot`]), streamed to the file
//! through the checksum, whose length and value are written into the
//! header last. Version 2 added the `--set`
//! overrides to the identity; version 3 is the serde payload with the
//! solver's ledger. Older files are refused, naming both versions
//! ([`MIGRATION`] says why they are not migrated).
//!
//! It is written atomically: to `.checkpoint.tmp` in the same directory,
//! flushed to disk (`fsync`), then renamed over its name, and the directory
//! is synced; the history and failure files are synced before, so the
//! lengths it records are on disk. The two latest checkpoints are kept.
//! [`latest`] takes the newest one that is complete (magic, version, length
//! and checksum all right), skipping, with a warning, any that is not.
//!
//! For tests of a crash in the middle of a write, the hidden option
//! `femdem run --pause-checkpoint N` stops the checkpoint of step `N`
//! after its temporary file is written and synced and before the rename:
//! the writer creates [`PAUSED`] in the output directory and waits
//! [`PAUSE_SECONDS`] (a test kills the run there with SIGKILL; if none
//! does, it goes on).

use std::fs::{self, File};
use std::io::{BufWriter, Seek, SeekFrom, Write};
use std::path::{Path, PathBuf};

use anyhow::{Context, Result, bail};
use femdem_mesh::TetMesh;
use serde::{Deserialize, Serialize};

use femdem_case::LoadedCase;

/// The first bytes of every checkpoint file.
pub const MAGIC: &[u8; 8] = b"FEMDEMCK";
/// The layout version written; others are refused, naming both (see
/// [`MIGRATION`]).
pub const FORMAT_VERSION: u32 = 3;
/// Why an older checkpoint is refused rather than migrated.
pub const MIGRATION: &str = "a checkpoint of format 1 or 2 holds a solver snapshot of layout 8 or older, whose \
     energy account this femdem books differently (one ledger, the external work summed from its terms), so a \
     resume from it would not continue bit for bit as an uninterrupted run; run the case again without --resume";
/// Checkpoints kept in the output directory (the newest ones).
pub const KEEP: usize = 2;
const PREFIX: &str = "checkpoint_";
const SUFFIX: &str = ".femdem-ckpt";
/// The file a checkpoint is written to before it is renamed.
pub const TEMPORARY: &str = ".checkpoint.tmp";
/// The file a writer paused by `--pause-checkpoint` creates.
pub const PAUSED: &str = ".checkpoint.paused";
/// How long a paused writer waits before renaming after all, s.
pub const PAUSE_SECONDS: u64 = 60;
/// Bytes before the payload: magic, version, length, checksum.
const HEADER: usize = 8 + 4 + 8 + 8;

/// FNV-1a, 64 bits: a stable hash (the same on every platform and build,
/// unlike `std`'s hasher) to recognise a case and to detect damaged files.
pub fn fnv1a(bytes: &[u8]) -> u64 {
    let mut h = Fnv::new();
    h.write(bytes);
    h.0
}

/// An FNV-1a 64 hash fed piece by piece.
struct Fnv(u64);

impl Fnv {
    fn new() -> Fnv {
        Fnv(0xcbf2_9ce4_8422_2325)
    }

    fn write(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.0 = (self.0 ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3);
        }
    }
}

/// Which case a checkpoint belongs to.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Identity {
    /// The case file, as the run that wrote it named it (for messages).
    pub case_path: String,
    /// FNV-1a of the case file's text.
    pub case_hash: u64,
    /// FNV-1a of the jointed mesh (coordinates by their bits, tets).
    pub mesh_hash: u64,
    /// The `--set` overrides, in their canonical form
    /// ([`femdem_case::Overrides::canonical`]: sorted, values as TOML
    /// writes them).
    pub overrides: Vec<String>,
}

impl Identity {
    /// The identity of `case` (its file, its text and its `--set`
    /// overrides) with jointed mesh `mesh`.
    pub fn of(case: &LoadedCase, mesh: &TetMesh) -> Identity {
        let (path, source) = (&case.path, &case.source);
        let mut h = Fnv::new();
        for c in &mesh.coords {
            c.iter().for_each(|x| h.write(&x.to_bits().to_le_bytes()));
        }
        for t in &mesh.tets {
            t.iter().for_each(|n| h.write(&n.to_le_bytes()));
        }
        let case_path = fs::canonicalize(path).unwrap_or_else(|_| path.to_owned()).display().to_string();
        let overrides = case.overrides.canonical();
        Identity { case_path, case_hash: fnv1a(source.as_bytes()), mesh_hash: h.0, overrides }
    }

    /// Fails, naming both cases, unless checkpoint `file` (of identity
    /// `self`) belongs to the case of identity `now`.
    pub fn check(&self, now: &Identity, file: &Path) -> Result<()> {
        let mut what = match (self.case_hash == now.case_hash, self.mesh_hash == now.mesh_hash) {
            (true, true) => String::new(),
            (false, true) => "its case text differs".to_owned(),
            (true, false) => {
                "its mesh differs (an MSH file it reads changed, or a femdem that numbers meshes otherwise wrote it?)"
                    .to_owned()
            }
            (false, false) => "its case text and mesh differ".to_owned(),
        };
        if self.overrides != now.overrides {
            let list = |o: &[String]| {
                if o.is_empty() {
                    "none".to_owned()
                } else {
                    o.iter().map(|s| format!("--set {s}")).collect::<Vec<_>>().join(" ")
                }
            };
            if !what.is_empty() {
                what.push_str("; ");
            }
            what.push_str(&format!(
                "its --set overrides differ (the checkpoint's: {}; this run's: {})",
                list(&self.overrides),
                list(&now.overrides)
            ));
        }
        if what.is_empty() {
            return Ok(());
        }
        bail!(
            "checkpoint {} was written by case {} (text {:016x}, mesh {:016x}); this run is case {} (text {:016x}, \
             mesh {:016x}), and {what}; resume with the case that wrote it and its --set arguments, or run without \
             --resume to start again",
            file.display(),
            self.case_path,
            self.case_hash,
            self.mesh_hash,
            now.case_path,
            now.case_hash,
            now.mesh_hash
        )
    }
}

/// The run loop's own state at the start of a step.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Schedule {
    /// The step the loop continues with (steps `0..next_step` are done).
    pub next_step: u64,
    /// Simulated time of the next frame, s.
    pub next_frame: f64,
    /// Simulated time of the next history row, s.
    pub next_row: f64,
    /// Whether the run is past the peak and the next step is its last.
    pub ended_past_peak: bool,
    /// The post-peak watch: the largest load so far and the last one, N.
    pub peak: Option<(f64, f64)>,
}

/// How far the output had got.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Marks {
    /// Bytes of `history.csv`.
    pub history_len: u64,
    /// Bytes of `failures.csv`.
    pub failures_len: u64,
    /// Times of the frames of the main series, s.
    pub frames: Vec<f64>,
    /// Times of the frames of the fracture series, s.
    pub fracture_frames: Vec<f64>,
}

/// One checkpoint.
#[derive(Debug, PartialEq)]
pub struct Checkpoint {
    /// The case it belongs to.
    pub identity: Identity,
    /// The run loop's state.
    pub schedule: Schedule,
    /// The output's state.
    pub marks: Marks,
    /// [`femdem_solver::Solver::snapshot`].
    pub solver: Vec<u8>,
}

/// What the payload starts with, before the solver's snapshot: serialised
/// borrowed, read back owned.
#[derive(Serialize)]
struct HeadOut<'a>(&'a Identity, &'a Schedule, &'a Marks);

/// [`HeadOut`] as read.
#[derive(Deserialize)]
struct HeadIn(Identity, Schedule, Marks);

/// A writer that hashes (FNV-1a) and counts what passes through it.
struct Hashing<W> {
    inner: W,
    hash: Fnv,
    len: u64,
}

impl<W: Write> Write for Hashing<W> {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        let n = self.inner.write(buf)?;
        self.hash.write(&buf[..n]);
        self.len += n as u64;
        Ok(n)
    }

    fn flush(&mut self) -> std::io::Result<()> {
        self.inner.flush()
    }
}

/// Writes a checkpoint to `out`, from its start: the header with the
/// length and checksum left blank, the payload — identity, schedule and
/// marks, then the solver's snapshot, streamed by `snapshot` — and then
/// the length and checksum over the blanks. The payload is not held in
/// memory (but for the contact pass's state, which
/// [`femdem_solver::Solver::write_snapshot`] copies).
fn write_to<W: Write + Seek>(
    out: &mut W,
    identity: &Identity,
    schedule: &Schedule,
    marks: &Marks,
    snapshot: &dyn Fn(&mut dyn Write) -> std::io::Result<()>,
) -> std::io::Result<()> {
    out.write_all(MAGIC)?;
    out.write_all(&FORMAT_VERSION.to_le_bytes())?;
    out.write_all(&[0; 16])?;
    let mut payload = Hashing { inner: BufWriter::new(&mut *out), hash: Fnv::new(), len: 0 };
    // The head is small: serialised in memory, so that a failed write is
    // the writer's own error (postcard's writer reports any as a full
    // buffer; the snapshot keeps the writer's error itself).
    payload.write_all(&postcard::to_stdvec(&HeadOut(identity, schedule, marks)).map_err(std::io::Error::other)?)?;
    snapshot(&mut payload)?;
    payload.flush()?;
    let (len, hash) = (payload.len, payload.hash.0);
    drop(payload);
    out.seek(SeekFrom::Start(12))?;
    out.write_all(&len.to_le_bytes())?;
    out.write_all(&hash.to_le_bytes())?;
    out.flush()
}

impl Checkpoint {
    /// Reads a file's bytes; the error says what is wrong with them.
    fn from_bytes(bytes: &[u8]) -> Result<Checkpoint, String> {
        if bytes.len() < HEADER || &bytes[..8] != MAGIC {
            return Err("not a femdem checkpoint (no magic number)".into());
        }
        let version = u32::from_le_bytes(bytes[8..12].try_into().expect("4 bytes"));
        if version != FORMAT_VERSION {
            return Err(format!(
                "format version {version}; this femdem reads version {FORMAT_VERSION} only (no migration: {})",
                MIGRATION
            ));
        }
        let length = u64::from_le_bytes(bytes[12..20].try_into().expect("8 bytes"));
        let checksum = u64::from_le_bytes(bytes[20..28].try_into().expect("8 bytes"));
        let payload = &bytes[HEADER..];
        if payload.len() as u64 != length {
            return Err(format!("incomplete: {} bytes of payload, {length} expected", payload.len()));
        }
        if fnv1a(payload) != checksum {
            return Err("damaged: its checksum does not match".into());
        }
        match postcard::take_from_bytes::<HeadIn>(payload) {
            Ok((HeadIn(identity, schedule, marks), solver)) => {
                Ok(Checkpoint { identity, schedule, marks, solver: solver.to_vec() })
            }
            Err(e) => Err(format!("malformed: {e}")),
        }
    }
}

/// The file name of the checkpoint of step `step`.
fn file_name(step: u64) -> String {
    format!("{PREFIX}{step:012}{SUFFIX}")
}

/// The step of the checkpoint file called `name`, if it is one
/// (`checkpoint_<step>.femdem-ckpt`).
fn step_of(name: &str) -> Option<u64> {
    name.strip_prefix(PREFIX)?.strip_suffix(SUFFIX)?.parse::<u64>().ok()
}

/// Whether `name` is a checkpoint's file name.
pub fn is_checkpoint_name(name: &str) -> bool {
    step_of(name).is_some()
}

/// The checkpoint files in `dir` with their steps, newest first.
fn list(dir: &Path) -> Result<Vec<(u64, PathBuf)>> {
    let mut found = Vec::new();
    let entries = fs::read_dir(dir).with_context(|| format!("reading directory {}", dir.display()))?;
    for entry in entries {
        let entry = entry.with_context(|| format!("reading directory {}", dir.display()))?;
        let name = entry.file_name();
        let Some(step) = name.to_str().and_then(step_of) else {
            continue;
        };
        found.push((step, entry.path()));
    }
    found.sort_by_key(|f| std::cmp::Reverse(f.0));
    Ok(found)
}

/// Writes a checkpoint of `identity`, `schedule`, `marks` and the
/// solver's snapshot (streamed by `snapshot`, e.g.
/// [`femdem_solver::Solver::write_snapshot`]) into `dir` atomically (see
/// the module documentation), then removes all but the [`KEEP`] newest
/// checkpoints. Returns the file written. If the checkpoint's step is
/// `pause` (a test hook), waits between the temporary file and the rename.
pub fn write(
    dir: &Path,
    identity: &Identity,
    schedule: &Schedule,
    marks: &Marks,
    snapshot: &dyn Fn(&mut dyn Write) -> std::io::Result<()>,
    pause: Option<u64>,
) -> Result<PathBuf> {
    let path = dir.join(file_name(schedule.next_step));
    let tmp = dir.join(TEMPORARY);
    let written = File::create(&tmp).and_then(|mut f| {
        write_to(&mut f, identity, schedule, marks, snapshot)?;
        f.sync_all()
    });
    written.with_context(|| format!("writing checkpoint {}", tmp.display()))?;
    if pause == Some(schedule.next_step) {
        File::create(dir.join(PAUSED)).with_context(|| format!("creating {}", dir.join(PAUSED).display()))?;
        std::thread::sleep(std::time::Duration::from_secs(PAUSE_SECONDS));
    }
    fs::rename(&tmp, &path).with_context(|| format!("renaming {} to {}", tmp.display(), path.display()))?;
    // The rename itself is durable once the directory is synced (where the
    // platform allows opening a directory; elsewhere this is best effort).
    if let Ok(d) = File::open(dir) {
        let _ = d.sync_all();
    }
    for (_, old) in list(dir)?.into_iter().skip(KEEP) {
        fs::remove_file(&old).with_context(|| format!("removing old checkpoint {}", old.display()))?;
    }
    Ok(path)
}

/// The newest complete checkpoint in `dir` and its file. Incomplete or
/// damaged ones newer than it are skipped, each told to `note` with why.
///
/// # Errors
/// When `dir` holds no complete checkpoint, with the reason for each file
/// that is not.
pub fn latest(dir: &Path, note: &mut dyn FnMut(&str)) -> Result<(PathBuf, Checkpoint)> {
    let found = list(dir)?;
    let mut skipped = Vec::new();
    for (_, path) in found {
        let read = fs::read(&path).map_err(|e| e.to_string()).and_then(|b| Checkpoint::from_bytes(&b));
        match read {
            Ok(c) => return Ok((path, c)),
            Err(why) => {
                note(&format!("skipping checkpoint {}: {why}", path.display()));
                skipped.push(format!("\n  {}: {why}", path.display()));
            }
        }
    }
    bail!(
        "no complete checkpoint in {} (files {PREFIX}*{SUFFIX}){}; run without --resume to start again",
        dir.display(),
        skipped.concat()
    )
}

/// Removes the checkpoints in `dir` newer than step `step` (after a resume
/// from `step`, those are damaged or belong to a future this run will
/// write again) or, with `None`, all of them (a fresh run), and a leftover
/// temporary file (and [`PAUSED`]).
pub fn remove_after(dir: &Path, step: Option<u64>) -> Result<()> {
    for (s, path) in list(dir)? {
        if step.is_none_or(|step| s > step) {
            fs::remove_file(&path).with_context(|| format!("removing checkpoint {}", path.display()))?;
        }
    }
    for leftover in [TEMPORARY, PAUSED] {
        let file = dir.join(leftover);
        if file.exists() {
            fs::remove_file(&file).with_context(|| format!("removing {}", file.display()))?;
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sample() -> Checkpoint {
        Checkpoint {
            identity: Identity {
                case_path: "a.toml".into(),
                case_hash: 1,
                mesh_hash: 2,
                overrides: vec!["solver.end_time=0.001".into()],
            },
            schedule: Schedule {
                next_step: 7,
                next_frame: 0.1 + 0.2,
                next_row: 1e-7,
                ended_past_peak: false,
                peak: Some((3.0, -0.0)),
            },
            marks: Marks { history_len: 100, failures_len: 40, frames: vec![0.0, 0.5], fracture_frames: vec![0.0] },
            solver: vec![1, 2, 3],
        }
    }

    /// The file `write` would write for `c`.
    fn to_bytes(c: &Checkpoint) -> Vec<u8> {
        let mut out = std::io::Cursor::new(Vec::new());
        write_to(&mut out, &c.identity, &c.schedule, &c.marks, &|w| w.write_all(&c.solver)).unwrap();
        out.into_inner()
    }

    #[test]
    fn a_checkpoint_round_trips_and_any_damage_is_detected() {
        let c = sample();
        let bytes = to_bytes(&c);
        assert_eq!(Checkpoint::from_bytes(&bytes).unwrap(), c);
        for cut in 0..bytes.len() {
            assert!(Checkpoint::from_bytes(&bytes[..cut]).is_err(), "cut at {cut}");
        }
        for at in 0..bytes.len() {
            let mut bad = bytes.clone();
            bad[at] ^= 0x10;
            assert!(Checkpoint::from_bytes(&bad).is_err(), "flipped byte {at}");
        }
    }

    /// A checkpoint of an older format (1 and 2: the hand-written layout
    /// with a solver snapshot of layout 8 or older) or a newer one is
    /// refused, naming both versions, as is a file of this format whose
    /// payload does not read.
    #[test]
    fn a_checkpoint_of_another_format_is_refused_naming_both_versions() {
        let bytes = to_bytes(&sample());
        for version in [1u32, 2, FORMAT_VERSION + 1] {
            let mut other = bytes.clone();
            other[8..12].copy_from_slice(&version.to_le_bytes());
            let err = Checkpoint::from_bytes(&other).unwrap_err();
            assert!(
                err.contains(&format!("format version {version}; this femdem reads version {FORMAT_VERSION}")),
                "{err}"
            );
        }
        let payload = [0xff_u8; 4];
        let mut garbled = MAGIC.to_vec();
        garbled.extend_from_slice(&FORMAT_VERSION.to_le_bytes());
        garbled.extend_from_slice(&(payload.len() as u64).to_le_bytes());
        garbled.extend_from_slice(&fnv1a(&payload).to_le_bytes());
        garbled.extend_from_slice(&payload);
        assert!(Checkpoint::from_bytes(&garbled).unwrap_err().starts_with("malformed"));
    }

    /// A file that takes `room` bytes and then fails as a full disk does.
    struct Full {
        file: std::io::Cursor<Vec<u8>>,
        room: usize,
    }

    impl Write for Full {
        fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
            if self.room == 0 {
                return Err(std::io::Error::new(std::io::ErrorKind::StorageFull, "no space left on device"));
            }
            let n = self.file.write(&buf[..buf.len().min(self.room)])?;
            self.room -= n;
            Ok(n)
        }

        fn flush(&mut self) -> std::io::Result<()> {
            Ok(())
        }
    }

    impl Seek for Full {
        fn seek(&mut self, to: SeekFrom) -> std::io::Result<u64> {
            self.file.seek(to)
        }
    }

    #[test]
    fn a_full_disk_is_reported_as_such() {
        let c = sample();
        for room in [HEADER, HEADER + 5] {
            let mut out = Full { file: std::io::Cursor::new(Vec::new()), room };
            let err = write_to(&mut out, &c.identity, &c.schedule, &c.marks, &|w| w.write_all(&c.solver)).unwrap_err();
            assert_eq!(err.kind(), std::io::ErrorKind::StorageFull, "room {room}: {err}");
        }
    }

    #[test]
    fn fnv1a_matches_its_reference_values() {
        // From the FNV reference test suite.
        assert_eq!(fnv1a(b""), 0xcbf2_9ce4_8422_2325);
        assert_eq!(fnv1a(b"a"), 0xaf63_dc4c_8601_ec8c);
        assert_eq!(fnv1a(b"foobar"), 0x8594_4171_f739_67e8);
    }
}
