//! Running `femdem run` on a generated case, as a user would, and reusing a
//! run that already finished with the same case text.

use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Instant;

use anyhow::{Context, Result, bail};

/// The `femdem` binary this validation uses.
#[derive(Debug, Clone)]
pub struct Femdem {
    bin: PathBuf,
}

/// What one run left behind.
#[derive(Debug, Clone)]
pub struct RunOutput {
    /// The run's output directory (`history.csv`, `failures.csv`, frames).
    pub dir: PathBuf,
    /// The case file's stem (the frames are `<stem>_*.vtu`).
    pub stem: String,
    /// Wall time of the run, s (of the earlier run when reused).
    pub wall: f64,
    /// Whether the results are those of an earlier, finished run.
    pub reused: bool,
}

impl Femdem {
    /// Builds `femdem` in release mode and returns it; or, when the
    /// environment names a prebuilt binary in `FEMDEM_BIN` (a machine
    /// without cargo, a cluster node), returns that one unbuilt.
    pub fn build() -> Result<Femdem> {
        if let Some(bin) = std::env::var_os("FEMDEM_BIN") {
            let bin = PathBuf::from(bin);
            if !bin.is_file() {
                bail!("FEMDEM_BIN = {} is not a file", bin.display());
            }
            eprintln!("validate: using the prebuilt {} (FEMDEM_BIN)", bin.display());
            return Ok(Femdem { bin });
        }
        let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
        crate::run_in_root(Command::new(cargo).args(["build", "--release", "--quiet", "-p", "femdem-cli"]))?;
        let target = std::env::var_os("CARGO_TARGET_DIR").map_or_else(|| crate::root().join("target"), PathBuf::from);
        let bin = target.join("release").join(if cfg!(windows) { "femdem.exe" } else { "femdem" });
        if !bin.exists() {
            bail!("{} was not built", bin.display());
        }
        Ok(Femdem { bin })
    }

    /// Writes `case` to `dir/<stem>.toml` and runs it with `--out dir/out`,
    /// logging to `dir/run.log`. A run that finished before with the same
    /// case text is not repeated (its results are reused): an interrupted
    /// validation resumes at the first unfinished run.
    pub fn run(&self, dir: &Path, stem: &str, case: &str) -> Result<RunOutput> {
        std::fs::create_dir_all(dir)?;
        let case_path = dir.join(format!("{stem}.toml"));
        let out = dir.join("out");
        let stamp = dir.join("finished");
        let same = std::fs::read_to_string(&case_path).is_ok_and(|c| c == case);
        let done = same.then(|| std::fs::read_to_string(&stamp).ok()?.trim().parse::<f64>().ok()).flatten();
        if let Some(wall) = done {
            eprintln!("validate: reusing the finished run in {}", dir.display());
            return Ok(RunOutput { dir: out, stem: stem.into(), wall, reused: true });
        }
        let _ = std::fs::remove_file(&stamp);
        std::fs::write(&case_path, case)?;
        let log = std::fs::File::create(dir.join("run.log"))?;
        eprintln!("validate: femdem run {}", case_path.display());
        let start = Instant::now();
        let status = Command::new(&self.bin)
            .arg("run")
            .arg(&case_path)
            .arg("--out")
            .arg(&out)
            .arg("--overwrite")
            .stdout(log.try_clone()?)
            .stderr(log)
            .status()
            .with_context(|| format!("starting {}", self.bin.display()))?;
        let wall = start.elapsed().as_secs_f64();
        if !status.success() {
            bail!("femdem run {} failed ({status}); see {}", case_path.display(), dir.join("run.log").display());
        }
        std::fs::write(&stamp, format!("{wall}\n"))?;
        Ok(RunOutput { dir: out, stem: stem.into(), wall, reused: false })
    }
}
