//! `cargo xtask fixtures`: regenerates the Gmsh-written test fixtures (the
//! ASCII `gmsh_two_volumes.msh` and its binary twin
//! `gmsh_two_volumes_binary.msh`) and the paper cases' unstructured meshes
//! with Gmsh's Python API. Tests and cases never need Gmsh: they read the
//! committed files.

use std::process::Command;

use anyhow::Result;

/// Runs `crates/femdem-mesh/tests/data/regenerate.py` and
/// `cases/paper/meshes/regenerate.py`.
pub fn run() -> Result<()> {
    crate::run_in_root(Command::new("python3").arg("crates/femdem-mesh/tests/data/regenerate.py"))?;
    crate::run_in_root(Command::new("python3").arg("cases/paper/meshes/regenerate.py"))
}
