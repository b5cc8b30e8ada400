//! What every CLI test module needs: the workspace root and the `femdem`
//! binary run from it.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// The workspace root, where the tests' case paths start.
pub fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// Runs `femdem ARGS…` in the workspace root.
pub fn femdem(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_femdem")).args(args).current_dir(root()).output().expect("run femdem")
}

/// The text of the `history.csv` in `dir` without the comment lines
/// `femdem run` writes before the header (`# case: …`): the header, then
/// the rows.
pub fn history_csv(dir: &Path) -> String {
    let text = std::fs::read_to_string(dir.join("history.csv")).expect("read history.csv");
    text.lines().skip_while(|l| l.starts_with('#')).map(|l| format!("{l}\n")).collect()
}

/// The `history.csv` in `dir` as numbers: its column names and its rows.
pub struct History {
    /// The column names, in order.
    pub header: Vec<String>,
    /// One row of values per recorded step.
    pub rows: Vec<Vec<f64>>,
}

impl History {
    /// Reads the history of the run written to `dir`.
    pub fn read(dir: &Path) -> History {
        let text = history_csv(dir);
        let mut lines = text.lines();
        let header = lines.next().expect("a header").split(',').map(str::to_owned).collect();
        let rows = lines.map(|l| l.split(',').map(|v| v.parse().expect("a number")).collect()).collect();
        History { header, rows }
    }

    /// The index of the column `name`; panics naming it when there is none.
    pub fn col(&self, name: &str) -> usize {
        self.header.iter().position(|c| c == name).unwrap_or_else(|| panic!("no column {name}"))
    }
}
