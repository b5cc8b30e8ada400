//! `cargo xtask fixtures`: regenerates the Gmsh-written test fixture with
//! Gmsh's Python API. Tests never need Gmsh: they read the committed file.

use std::process::Command;

use anyhow::Result;

/// Runs `crates/femdem-mesh/tests/data/regenerate.py`.
pub fn run() -> Result<()> {
    crate::run_in_root(Command::new("python3").arg("crates/femdem-mesh/tests/data/regenerate.py"))
}
