//! femdem's run driver as a library: a case integrated to its end time,
//! with its output directory checked ([`outdir`]), VTU frames, PVD series,
//! a CSV history and failure list ([`output`]), checkpoints to resume from
//! bit for bit ([`checkpoint`]), the run guard and the stop rules
//! ([`run`]). Each history header records what produced it
//! ([`provenance`]).
//!
//! It writes nothing to the terminal and installs no signal handler: what
//! happens is told to an [`Observer`], and a run stops early, writing a
//! checkpoint, when the caller's stop flag is set. The `femdem` command
//! line is a thin layer over it; another program can run a case so:
//!
//! ```no_run
//! use std::sync::atomic::AtomicBool;
//! let options = femdem_run::RunOptions { out: Some("out/my-disc".into()), overwrite: true, ..Default::default() };
//! let summary = femdem_run::run(
//!     std::path::Path::new("cases/brazilian-split.toml"),
//!     options,
//!     &AtomicBool::new(false),
//!     &mut femdem_run::Quiet,
//! )?;
//! println!("{} steps; history in {}", summary.steps, summary.history.display());
//! # Ok::<(), anyhow::Error>(())
//! ```

pub mod checkpoint;
mod driver;
pub mod outdir;
pub mod output;
mod peak;
pub mod provenance;

use std::path::PathBuf;

pub use driver::run;

/// What a run is asked for, beyond the case file.
#[derive(Clone, Debug, Default)]
pub struct RunOptions {
    /// The output directory (default: `[output] dir`, else
    /// `out/<case stem>`).
    pub out: Option<PathBuf>,
    /// Worker threads (overrides `[solver] threads`).
    pub threads: Option<usize>,
    /// `key.path=value` overrides of the case ([`femdem_case::overrides`]).
    pub set: Vec<String>,
    /// Continue from the latest complete checkpoint in a directory
    /// (`Some(None)`: in the output directory).
    pub resume: Option<Option<PathBuf>>,
    /// For tests: stop as the stop flag would once this many steps are
    /// done, writing a checkpoint.
    pub stop_after_steps: Option<u64>,
    /// For tests: the checkpoint of this step pauses before its rename
    /// ([`checkpoint::write`]).
    pub pause_checkpoint: Option<u64>,
    /// Where the step runs, `cpu` or `gpu` (overrides `[solver] device`;
    /// `docs/case-format.md`, "On a GPU").
    pub device: Option<String>,
    /// Remove the results of an earlier run from the output directory
    /// (femdem's own files only) instead of refusing it.
    pub overwrite: bool,
    /// The memory the run may use: a mesh that, once built, would need
    /// more with its joints is refused before they are inserted
    /// (`femdem_case::prepare::prepare_within`; `None`: not checked).
    pub memory: Option<femdem_case::memory::Available>,
}

/// The state of the model a progress report shows, besides steps and
/// time.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Status {
    /// Joints failed so far.
    pub failed_joints: usize,
    /// The load `F` of Eq. 21 at the last step, N, with
    /// `[output.load_strain]`.
    pub load: Option<f64>,
}

/// What a run tells its caller while it goes. Every method has a default
/// that ignores it.
pub trait Observer {
    /// A line of information or a warning (a warning starts with
    /// `warning`), without a program-name prefix.
    fn note(&mut self, line: &str) {
        let _ = line;
    }
    /// The step loop starts at step `first` of `total`, with `elements`
    /// deformable tets evaluated per step.
    fn started(&mut self, first: u64, total: u64, elements: u64) {
        let _ = (first, total, elements);
    }
    /// `steps` steps (counted from step 0) are done at simulated time
    /// `time`, s; `status` computes the model's state when called.
    fn stepped(&mut self, steps: u64, time: f64, status: &dyn Fn() -> Status) {
        let _ = (steps, time, status);
    }
    /// The step loop is over (at its end, past the peak, stopped by the
    /// guard or by the stop flag).
    fn ended(&mut self) {}
}

/// An [`Observer`] that ignores everything.
pub struct Quiet;

impl Observer for Quiet {}

/// How a run ended early past the peak load (`[output.load_strain]
/// stop_below_peak`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PastPeak {
    /// The load at the last step, N.
    pub last: f64,
    /// The fraction of the peak it fell below.
    pub fraction: f64,
    /// The peak load, N.
    pub peak: f64,
}

/// What a finished (or interrupted) run did and where its results are.
#[derive(Clone, Debug)]
pub struct Summary {
    /// Whether the stop flag (or `stop_after_steps`) ended it before its
    /// end; its state is in [`Summary::checkpoint`].
    pub interrupted: bool,
    /// Steps taken since step 0.
    pub steps: u64,
    /// The simulated time reached, s.
    pub time: f64,
    /// Set when the run ended past its peak load.
    pub past_peak: Option<PastPeak>,
    /// Wall time of this call's step loop, s.
    pub wall: f64,
    /// Tet-steps per second of this call's step loop (deformable tets).
    pub throughput: f64,
    /// The vector unit the CPU's tet and joint passes and contact pair
    /// kernel were compiled for
    /// (`femdem_solver::widest_name`).
    pub vector_unit: &'static str,
    /// Joints failed.
    pub failed_joints: usize,
    /// The output directory.
    pub dir: PathBuf,
    /// The `.pvd` series of the frames.
    pub frames: PathBuf,
    /// The `.pvd` series of the fracture surfaces.
    pub fractures: PathBuf,
    /// `history.csv`.
    pub history: PathBuf,
    /// `failures.csv`.
    pub failures: PathBuf,
    /// The last checkpoint written, if any.
    pub checkpoint: Option<PathBuf>,
    /// The `--set` overrides, canonical, as a resumed run must repeat
    /// them.
    pub overrides: Vec<String>,
    /// The adapter the step ran on and which stages (`None`: the CPU).
    pub device: Option<String>,
    /// Bytes a step moved between host and device at least (0 on the CPU).
    pub device_bytes: u64,
    /// Host wall-clock time of the steps by stage (`None` without a step):
    /// where a step's time went. Varies from run to run.
    pub stage_times: Option<femdem_solver::StageTimes>,
    /// Host wall-clock time around the device's read-backs, by kind and
    /// part, over the whole run (empty on the CPU). Varies from run to run.
    pub read_backs: Vec<femdem_solver::Phase>,
}
