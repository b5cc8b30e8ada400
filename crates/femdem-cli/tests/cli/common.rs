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

pub use femdem_post::table::Table;

/// The `history.csv` in `dir`, read by `femdem_post` (as `femdem plot` and
/// the validation read it).
pub fn history(dir: &Path) -> Table {
    Table::history(dir).expect("read history.csv")
}

/// The index of column `name` of `table`; panics naming it when there is
/// none.
pub fn col(table: &Table, name: &str) -> usize {
    table.index(name).unwrap_or_else(|e| panic!("{e}"))
}

/// How many joints `failures.csv` in `dir` lists, read by `femdem_post`.
pub fn failures(dir: &Path) -> usize {
    femdem_post::failures::Failure::read_all(dir).expect("read failures.csv").len()
}
