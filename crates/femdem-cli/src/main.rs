//! `femdem`: the command-line driver of the femdem FEMDEM simulator.
//!
//! Argument parsing over the case library (`femdem_case`), the run driver
//! (`femdem_run`) and the results library (`femdem_post`); the only crate
//! (with xtask) that knows the terminal.

mod commands;

use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Parser, Subcommand};

/// Combined finite–discrete element simulation of fracture in quasi-brittle
/// materials.
#[derive(Parser)]
#[command(name = "femdem", version, about)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Build a case's mesh with joints and print its statistics.
    Check {
        /// The TOML case file.
        case: PathBuf,
        /// Print one JSON object instead of text.
        #[arg(long)]
        json: bool,
        /// Worker threads (overrides `[solver] threads`; default: all cores).
        #[arg(long)]
        threads: Option<usize>,
        /// Override a value of the case, e.g. `--set solver.end_time=1e-3`
        /// or `--set materials.0.young=30e9` (repeatable; the value is a
        /// TOML value: quote strings). Checked as a value in the file is.
        #[arg(long = "set", value_name = "KEY.PATH=VALUE")]
        set: Vec<String>,
        /// Check even if the mesh's estimated memory exceeds what is
        /// available.
        #[arg(long)]
        force: bool,
        /// For tests: the memory available, bytes (instead of MemAvailable).
        #[arg(long, value_name = "BYTES", hide = true)]
        memory_available: Option<f64>,
    },
    /// Run a case to its end time, writing VTU frames, a PVD series and a
    /// CSV history.
    Run {
        /// The TOML case file.
        case: PathBuf,
        /// Output directory (default: `[output] dir`, else `out/<case stem>`).
        #[arg(long)]
        out: Option<PathBuf>,
        /// Worker threads (overrides `[solver] threads`; default: all
        /// cores). Results do not depend on it.
        #[arg(long)]
        threads: Option<usize>,
        /// Override a value of the case, e.g. `--set solver.end_time=1e-3`
        /// or `--set materials.0.young=30e9` (repeatable; the value is a
        /// TOML value: quote strings). Checked as a value in the file is.
        /// `--resume` needs the same overrides as the run it continues.
        #[arg(long = "set", value_name = "KEY.PATH=VALUE")]
        set: Vec<String>,
        /// Continue from the latest complete checkpoint in DIR (default:
        /// the output directory), after a signal or a crash; the results
        /// are those of an uninterrupted run. The case must be the one
        /// that wrote it.
        #[arg(long, value_name = "DIR", num_args = 0..=1)]
        resume: Option<Option<PathBuf>>,
        /// For tests: stop as SIGTERM would once N steps are done (a
        /// checkpoint, the last frame, a non-zero exit status).
        #[arg(long, value_name = "N", hide = true)]
        stop_after_steps: Option<u64>,
        /// For tests: the checkpoint of step N stops between writing its
        /// temporary file and renaming it, for a test to kill the run
        /// there (`femdem_run::checkpoint::PAUSED`).
        #[arg(long, value_name = "N", hide = true)]
        pause_checkpoint: Option<u64>,
        /// For tests: seconds of wall time between plain progress lines
        /// (when stderr is not a terminal; default 10).
        #[arg(long, value_name = "SECONDS", hide = true)]
        progress_interval: Option<f64>,
        /// Run even if the mesh's estimated memory exceeds what is available.
        #[arg(long)]
        force: bool,
        /// For tests: the memory available, bytes (instead of MemAvailable).
        #[arg(long, value_name = "BYTES", hide = true)]
        memory_available: Option<f64>,
        /// Where the step runs: `cpu` or `gpu` (a Vulkan device with 64-bit
        /// floats runs the tets, joints, surface loads and update; contact,
        /// failures and the account stay on the CPU). Overrides `[solver]
        /// device`.
        #[arg(long, value_name = "DEVICE")]
        device: Option<String>,
        /// Remove the results of an earlier run from the output directory
        /// first (only femdem's own files: history.csv, failures.csv,
        /// .pvd series with their .vtu frames, checkpoints, plot_*.png;
        /// anything else is kept). Without it, a run refuses a directory
        /// holding such results.
        #[arg(long, conflicts_with = "resume")]
        overwrite: bool,
    },
    /// Plot columns of a run's history.csv into PNG files. Without --y:
    /// the energies and the failed joints against time, and the load
    /// against the strain when the run recorded them, as plot_*.png in
    /// the results directory.
    Plot {
        /// The output directory of `femdem run` (or a history.csv).
        results: PathBuf,
        /// The column along x (default: time).
        #[arg(long, value_name = "COL", requires = "y")]
        x: Option<String>,
        /// A column to draw against x (repeatable: one line each).
        #[arg(long, value_name = "COL")]
        y: Vec<String>,
        /// The PNG file (default: plot_<y>_vs_<x>.png in the results
        /// directory).
        #[arg(long, value_name = "FILE", requires = "y")]
        out: Option<PathBuf>,
    },
}

/// The memory a run or check may use once its mesh is built: none checked
/// with `--force`, else `--memory-available` or `MemAvailable`.
fn memory_limit(force: bool, memory_available: Option<f64>) -> Option<femdem_case::memory::Available> {
    if force { None } else { femdem_case::memory::Available::of(memory_available) }
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Check { case, json, threads, set, force, memory_available } => {
            femdem_case::memory::refuse_if_too_big(&case, &set, threads, force, memory_available, "check")
                .and_then(|()| commands::check::run(&case, json, threads, &set, memory_limit(force, memory_available)))
        }
        Command::Run {
            case,
            out,
            threads,
            set,
            resume,
            stop_after_steps,
            pause_checkpoint,
            progress_interval,
            force,
            memory_available,
            device,
            overwrite,
        } => femdem_case::memory::refuse_if_too_big(&case, &set, threads, force, memory_available, "run").and_then(
            |()| {
                let options = femdem_run::RunOptions {
                    out,
                    threads,
                    set,
                    resume,
                    stop_after_steps,
                    pause_checkpoint,
                    device,
                    overwrite,
                    memory: memory_limit(force, memory_available),
                };
                commands::run::run(&case, options, progress_interval)
            },
        ),
        Command::Plot { results, x, y, out } => {
            commands::plot::run(&results, commands::plot::PlotOptions { x, y, out })
        }
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e:#}");
            ExitCode::FAILURE
        }
    }
}
